// Dobashi et al. 2002 per pixel (seed 000 sections 5.2-5.3): the GPU twin of
// atmosphere-core's `Dobashi::radiance`. Eq. 12 along the pixel's ray through the
// sampling planes, or the sample spheres for a camera far out (`dobashi_trace.wgsl`),
// with the ambient term; the transmitted sun disk where the ray reaches space. Writes
// spectral radiance (W m^-2 sr^-1 nm^-1) to the HDR target.

#import dobashi_trace.wgsl

@group(0) @binding(12) var hdr: texture_storage_2d<rgba16float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= frame.size_px.xy) {
        return;
    }
    let direction = pixel_direction(id.xy);
    let s = view_segment(direction, 0.0);
    var r = Radiance(vec3<f32>(0.0), vec3<f32>(1.0), !s.hit || !s.on_ground, vec3<f32>(0.0));
    if s.hit {
        let terms = trace(make_ray(s, direction, frame.sun_direction.xyz, false),
            dobashi.use_spheres != 0u);
        r.radiance = atmosphere.solar_irradiance.xyz * (terms.single + terms.ambient);
        r.transmittance = terms.transmittance;
    }
    textureStore(hdr, id.xy, hdr_pixel(direction, r));
}
