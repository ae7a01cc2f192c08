// Entry pass: the aerial-perspective volume of the hillaire model, `main` (render-wgpu's
// `sky/hillaire/`). CPU twin: atmosphere-core's `models/hillaire/aerial_perspective.rs`.
// Paper: Hillaire 2020, section 5.4. As on the CPU the slices are laid over directions
// around the camera in the latitude-longitude mapping rather than the frustum, so the
// volume depends only on the view (camera radius, sun zenith cosine) and is kept while
// the view stays. Each direction is marched once through all slices,
// `ap_samples_per_slice` segments each, as a straight line past the ground (through the
// ground-level medium); slice k holds depth (k + 1) range / slices. Two 3D textures:
// radiance per unit solar irradiance and transmittance from the camera to the slice, rgb
// per channel, a = 1.

#import sky/hillaire/march.wgsl
#import sky/hillaire/directions.wgsl

@group(0) @binding(5) var radiance_out: texture_storage_3d<rgba32float, write>;
@group(0) @binding(6) var transmittance_out: texture_storage_3d<rgba32float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(radiance_out);
    if any(id.xy >= size.xy) {
        return;
    }
    let q = hillaire.view_q;
    let r = hillaire.view_r;
    let mu_s = hillaire.view_mu_s;
    let d = texel_direction(size.xy, q, r, id.x, id.y);
    let ray = view_ray(q, r * d.mu, r * mu_s, view_sun_cosine(d.mu, d.phi, mu_s));
    let samples = hillaire.ap_samples_per_slice;
    let slice_m = hillaire.aerial_range_m / f32(size.z);
    let dt = slice_m / f32(samples);
    var m = view_march();
    for (var k = 0u; k < size.z; k++) {
        for (var s = 0u; s < samples; s++) {
            march_segment(ray, &m, f32(k) * slice_m + (f32(s) + 0.5) * dt, dt);
        }
        textureStore(radiance_out, vec3<u32>(id.xy, k), vec4<f32>(m.radiance, 1.0));
        textureStore(transmittance_out, vec3<u32>(id.xy, k), vec4<f32>(march_throughput(m), 1.0));
    }
}
