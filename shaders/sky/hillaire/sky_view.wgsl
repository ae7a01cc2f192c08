// Entry pass: the sky-view LUT of the hillaire model, `main` (render-wgpu's
// `sky/hillaire/`). CPU twin: atmosphere-core's `models/hillaire/sky_view.rs`. Paper:
// Hillaire 2020, section 5.3. For the frame's view (camera radius and sun zenith cosine
// of `HillaireParams`) each texel's direction in the latitude-longitude mapping
// (`sky/hillaire/directions.wgsl`) is marched with the sky view's segment count to where
// it leaves the atmosphere or meets the ground (the ground's own light is added by the
// pass). rgb = radiance per unit solar irradiance (sr^-1) per channel, a = 1.

#import sky/hillaire/march.wgsl
#import sky/hillaire/directions.wgsl

@group(0) @binding(5) var sky_view_out: texture_storage_2d<rgba32float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(sky_view_out);
    if any(id.xy >= size) {
        return;
    }
    let q = hillaire.view_q;
    let r = hillaire.view_r;
    let mu_s = hillaire.view_mu_s;
    let d = texel_direction(size, q, r, id.x, id.y);
    let r_mu = r * d.mu;
    let length = select(exit_distance(q, r_mu), ground_distance(q, r_mu), d.ground);
    let nu = view_sun_cosine(d.mu, d.phi, mu_s);
    let m = march_run(view_ray(q, r_mu, r * mu_s, nu), length, hillaire.sky_view_samples);
    textureStore(sky_view_out, id.xy, vec4<f32>(m.radiance, 1.0));
}
