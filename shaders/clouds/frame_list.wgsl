// Library: the list of a frame's pixels that the upsample by segment
// (`frame_upsample.wgsl`) cannot interpolate (`common/pixel_list.wgsl`), which
// `frame_march_list.wgsl` marches by an indirect dispatch over the list alone
// (render-wgpu's `clouds/frame_pass.rs`). CPU twin: atmosphere-core's
// `clouds/layer/segment_upsample.rs` (`upsample_by_segment`'s `march`).

#import clouds/frame_rays.wgsl
#import common/pixel_list.wgsl

// As in `frame_march.wgsl`.
@group(0) @binding(5) var cloud_front: texture_storage_2d<rgba32float, write>;
@group(0) @binding(9) var<storage, read_write> march_list: MarchList;
@group(0) @binding(10) var<storage, read_write> list_dispatch: ListDispatch;

// Marches pixel `px` along its segment; writes its cloud and where the ray enters it.
fn march_pixel(px: vec2<u32>) {
    let d = frame_direction(vec2<f32>(px));
    let t = frame_segment(d, px);
    let o = layer.camera_m.xyz;
    var result = vec4<f32>(0.0, 0.0, 0.0, 1.0);
    var front = vec4<f32>(0.0);
    if t.x < t.y {
        result = march_layer(o, d, t.x, t.y);
        if result.a < 1.0 {
            front = vec4<f32>(normalize(o + d * t.x), t.x);
        }
    }
    textureStore(cloud_image, px, result);
    textureStore(cloud_front, px, front);
}
