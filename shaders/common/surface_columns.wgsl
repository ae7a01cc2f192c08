// Library: the light on a surface element read from the columns table (the `columns`
// entry point of `sky/transmittance_table.wgsl`), shared by the models whose surface
// irradiance reads it: the transmitted sun, and the share of the ground's vertical
// optical depth above the element, which scales a sky irradiance tabulated on the ground
// only. CPU twin: the `surface_irradiance` of atmosphere-core's `models/hillaire/mod.rs`
// and `models/dobashi/trace.rs` (`Tracer::element_light`), over
// `optics/surface_lighting.rs`. Paper: the sun's transmittance T(x, sun) of Hillaire 2020,
// section 5.1; the scaling by the vertical depth is this project's, not a paper's.

#import common/atmosphere_params.wgsl
#import common/surface.wgsl
#import common/table_sampling.wgsl

// The sun's transmittance to element `e` through the columns table `columns`; none where
// the sun is behind the element or the planet hides its centre.
fn element_sun_transmittance(e: SurfaceElement, columns: texture_2d<f32>) -> vec3<f32> {
    if e.sun_cosine > 0.0 && !planet_hides_sun(e) {
        return exp(-optical_depth(read_table_columns(columns, e.q, e.mu_s)));
    }
    return vec3<f32>(0.0);
}

// The optical depth of the vertical column above r^2 - bottom^2 = `q` over that above the
// ground, per channel (1 where the atmosphere is empty), from the columns table `columns`.
fn vertical_depth_share_above(columns: texture_2d<f32>, q: f32) -> vec3<f32> {
    let whole = optical_depth(read_table_columns(columns, 0.0, 1.0));
    let above = optical_depth(read_table_columns(columns, q, 1.0));
    return select(vec3<f32>(1.0), above / whole, whole > vec3<f32>(0.0));
}
