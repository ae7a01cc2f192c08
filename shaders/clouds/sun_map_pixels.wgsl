// Entry pass: the sun's transmittance through the cloud layer at each pixel's surface
// point, from the sun map (render-wgpu's `clouds/sun_map_pass.rs`; CPU twin:
// atmosphere-core's `CloudSunMap::transmittance` at the point where
// `clouds/layer/shadowed_surface.rs` lights the surface). Every model's pixel pass
// multiplies its surface's sun by it (`common/surface.wgsl`); 1 where the pixel has no
// surface. The other channels are the cloud's shadow in the air, 0 here
// (`clouds/air_shadow.wgsl` writes them).

#import common/frame_params.wgsl
#import clouds/sun_map_read.wgsl

// xyz: the surface's normal; w: its distance along the pixel's ray, m (0: none).
@group(0) @binding(30) var pixel_geometry: texture_2d<f32>;
@group(0) @binding(34) var pixel_cloud_sun: texture_storage_2d<rgba32float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= frame.size_px.xy) {
        return;
    }
    let distance = textureLoad(pixel_geometry, id.xy, 0).w;
    var t = 1.0;
    if distance > 0.0 {
        t = cloud_sun_transmittance(frame.camera_m.xyz + pixel_direction(id.xy) * distance);
    }
    textureStore(pixel_cloud_sun, id.xy, vec4<f32>(t, 0.0, 0.0, 0.0));
}
