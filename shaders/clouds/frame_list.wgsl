// Library: the list of a frame's pixels that the upsample by segment
// (`frame_upsample_pixel.wgsl`) cannot interpolate (`common/pixel_list.wgsl`), and the
// march of one listed pixel, which `frame_march_list.wgsl` runs by an indirect dispatch
// over the list alone (render-wgpu's `clouds/frame_pass.rs`). CPU twin: atmosphere-core's
// `clouds/layer/segment_upsample.rs` (`upsample_by_segment`'s `march`).

#import clouds/frame_pixel_cloud.wgsl
#import common/pixel_list.wgsl

@group(0) @binding(9) var<storage, read_write> march_list: MarchList;
@group(0) @binding(10) var<storage, read_write> list_dispatch: ListDispatch;

// Pixel `px` marched along its segment.
fn march_pixel(px: vec2<u32>) -> PixelCloud {
    let d = frame_direction(vec2<f32>(px));
    let t = frame_segment(d, px);
    if t.x >= t.y {
        return CLEAR_PIXEL;
    }
    return pixel_cloud(march_layer(layer.camera_m.xyz, d, t.x, t.y), d, t.x);
}
