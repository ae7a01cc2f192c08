// Dobashi et al. 2002 per pixel (seed 000 sections 5.2-5.3): the GPU twin of
// atmosphere-core's `Dobashi::radiance`. Eq. 12 along the pixel's ray through the
// sampling planes, or the sample spheres for a camera far out (`sky/dobashi/trace.wgsl`),
// with the ambient term, ending on the frame's surface where it has one (lit by the
// transmitted sun and the ambient sky, `Dobashi::surface_irradiance`); the transmitted
// sun disk where the ray reaches space. Writes spectral radiance (W m^-2 sr^-1 nm^-1)
// to the HDR target.

#import sky/dobashi/trace.wgsl
#import common/surface.wgsl

@group(0) @binding(12) var hdr: texture_storage_2d<rgba16float, write>;

// `Dobashi::surface_irradiance` (`Tracer::element_light`): the transmitted sun g_l
// (Eq. 11) and the ambient sky, pi psi on a horizontal element, psi at the element's sun
// angle, times the share of the ground's vertical optical depth above the element.
fn dobashi_surface_irradiance(point: vec3<f32>, normal: vec3<f32>) -> vec3<f32> {
    let e = surface_element(point, normal);
    let bottom = atmosphere.bottom_radius_m;
    let q = (e.r - bottom) * (e.r + bottom);
    var t = vec3<f32>(0.0);
    if e.sun_cosine > 0.0 {
        t = sunlight_at(q, e.mu_s);
    }
    let whole = optical_depth(read_table_columns(g_l, 0.0, 1.0));
    let share = select(vec3<f32>(1.0), optical_depth(read_table_columns(g_l, q, 1.0)) / whole,
        whole > vec3<f32>(0.0));
    let sky = PI * ambient_at(e.mu_s) * share * atmosphere.solar_irradiance.xyz;
    return element_irradiance(e, t, sky);
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= frame.size_px.xy) {
        return;
    }
    let direction = pixel_direction(id.xy);
    let surface = frame_surface(id.xy);
    let s = view_segment(direction, surface.distance);
    var r = radiance_of_empty(s, direction);
    if s.hit {
        let terms = trace(make_ray(s, direction, frame.sun_direction.xyz), dobashi.use_spheres != 0u);
        r.radiance = atmosphere.solar_irradiance.xyz * (terms.single + terms.ambient);
        r.transmittance = terms.transmittance;
    }
    if surface.present {
        let e = dobashi_surface_irradiance(r.end, surface.normal);
        r = add_surface(r, surface, e);
    }
    textureStore(hdr, id.xy, hdr_pixel(direction, r));
}
