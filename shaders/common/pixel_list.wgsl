// Library: a list of a frame's pixels that an upsample could not interpolate, which a
// pass of its own marches by an indirect dispatch over the list alone (render-wgpu's
// `gpu/pixel_list.rs`). A software rasteriser such as lavapipe pays for a branch that any
// invocation of a group takes, and for a march compiled into a pass even where none runs
// it, so the upsample lists the pixel and stays a plain read. The shader that imports
// this declares `march_list: MarchList` and `list_dispatch: ListDispatch` at bindings of
// its own.

const LIST_GROUP: u32 = 256u;
// The most workgroups of one dispatch dimension; past that each invocation marches
// several listed pixels.
const MAX_GROUPS: u32 = 65535u;

struct MarchList {
    count: atomic<u32>,
    // x | y << 16 of each listed pixel.
    pixels: array<u32>,
}

// The indirect dispatch of the listed march: its own buffer, since a dispatch may not
// read its counts from a buffer it binds for writing.
struct ListDispatch {
    // Grows with the list; y and z are 1.
    groups: atomic<u32>,
    groups_y: u32,
    groups_z: u32,
}

// Adds pixel `px` to the list, which holds a place for every pixel of the frame.
fn list_pixel(px: vec2<u32>) {
    let i = atomicAdd(&march_list.count, 1u);
    if i % LIST_GROUP == 0u && i / LIST_GROUP < MAX_GROUPS {
        atomicAdd(&list_dispatch.groups, 1u);
    }
    march_list.pixels[i] = px.x | (px.y << 16u);
}

// The listed pixel at `i`.
fn listed_pixel(i: u32) -> vec2<u32> {
    let packed = march_list.pixels[i];
    return vec2<u32>(packed & 0xffffu, packed >> 16u);
}
