// Library: the list of a frame's pixels that the upsample by segment
// (`frame_upsample.wgsl`) cannot interpolate, which `frame_march_list.wgsl` marches by
// an indirect dispatch over the list alone (render-wgpu's `clouds/frame_pass.rs`). A software
// rasteriser such as lavapipe pays for a branch that any pixel of a group takes, so a
// march inside the upsample would cost every group with one edge pixel a march; the
// list keeps the upsample a plain read. CPU twin: atmosphere-core's
// `clouds/layer/segment_upsample.rs` (`upsample_by_segment`'s `march`).

#import clouds/frame_rays.wgsl

const LIST_GROUP: u32 = 256u;
// The most workgroups of one dispatch dimension; past that each invocation marches
// several listed pixels.
const MAX_GROUPS: u32 = 65535u;

struct MarchList {
    count: atomic<u32>,
    // x | y << 16 of each listed pixel.
    pixels: array<u32>,
}

// The indirect dispatch of `frame_march_list.wgsl`: its own buffer, since a dispatch
// may not read its counts from a buffer it binds for writing.
struct ListDispatch {
    // Grows with the list; y and z are 1.
    groups: atomic<u32>,
    groups_y: u32,
    groups_z: u32,
}

// As in `frame_march.wgsl`.
@group(0) @binding(5) var cloud_front: texture_storage_2d<rgba32float, write>;
@group(0) @binding(9) var<storage, read_write> march_list: MarchList;
@group(0) @binding(10) var<storage, read_write> list_dispatch: ListDispatch;

// Adds pixel `px` to the list, which holds a place for every pixel of the frame.
fn list_pixel(px: vec2<u32>) {
    let i = atomicAdd(&march_list.count, 1u);
    if i % LIST_GROUP == 0u && i / LIST_GROUP < MAX_GROUPS {
        atomicAdd(&list_dispatch.groups, 1u);
    }
    march_list.pixels[i] = px.x | (px.y << 16u);
}

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
