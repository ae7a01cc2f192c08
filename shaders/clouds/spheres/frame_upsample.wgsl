// Entry passes: a frame's reduced cloud spheres (`frame_reduced.wgsl`) brought to full
// size by the span each ray crossed (render-wgpu's `clouds/spheres/frame_spheres.rs`;
// CPU twin: atmosphere-core's `clouds/spheres/reduced.rs`, with the rule of
// `clouds/layer/segment_upsample.rs`). A pixel whose ray has no span of the layer is
// clear; otherwise it interpolates bilinearly between the reduced rays whose span is its
// own (`clouds/segment_taps.wgsl`). `main` writes each pixel as `frame_image.wgsl` does;
// `composite` composites it with the model's runs (`frame_composite_pixel.wgsl`) where
// the air in front is read from the bilinear taps of the reduced run in front. Where
// the taps weigh too little (the planet's limb, the edge of terrain in front of the
// cloud), or the air in front needs more, the pixel is listed (`common/pixel_list.wgsl`)
// and `listed` or `listed_composite` takes it, by an indirect dispatch over the list
// alone: shaded along its own ray, composited with the composite's whole rule. On a
// software rasteriser a group of invocations pays for a branch any of them takes, and a
// march compiled into a pass costs even where none runs it (docs/clouds.md, "At a
// reduced resolution").

#import clouds/spheres/frame_composite_pixel.wgsl
#import clouds/segment_taps.wgsl
#import common/pixel_list.wgsl

// The reduced spheres and the spans their rays crossed.
@group(0) @binding(29) var reduced_image: texture_2d<f32>;
@group(0) @binding(30) var reduced_segments: texture_2d<f32>;
// The listed pixels, and their dispatch.
@group(0) @binding(31) var<storage, read_write> march_list: MarchList;
@group(0) @binding(32) var<storage, read_write> list_dispatch: ListDispatch;

// The spheres at a full pixel: its ray, their radiance (rgb) and transmittance (a), the
// span's start (-1: clear), and whether the taps weigh too little to give them.
struct SpheresAtPixel {
    d: vec3<f32>,
    cloud: vec4<f32>,
    first_m: f32,
    unread: bool,
}

// The spheres at full pixel `px` from the reduced rays of its span.
fn spheres_from_taps(px: vec2<u32>) -> SpheresAtPixel {
    let o = spheres.camera_m.xyz;
    let d = pixel_ray(px);
    let t = sphere_span(o, d, surface_end(px));
    var p = SpheresAtPixel(d, vec4<f32>(0.0, 0.0, 0.0, 1.0), -1.0, false);
    if t.x < t.y {
        let taps = same_span_taps(reduced_image, reduced_segments, px, spheres.counts.zw, t,
            frame_spheres.w);
        p.unread = taps.weight < MIN_SAME_WEIGHT;
        if !p.unread {
            p.cloud = taps.sum / taps.weight;
            p.first_m = t.x;
        }
    }
    return p;
}

// The spheres at listed pixel `px`: from the taps where they give them, else shaded
// along its ray.
fn spheres_at_listed(px: vec2<u32>) -> SpheresAtPixel {
    var p = spheres_from_taps(px);
    if p.unread {
        let along = spheres_along(spheres.camera_m.xyz, p.d, surface_end(px));
        p.cloud = along.cloud;
        p.first_m = along.first_m;
    }
    return p;
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= spheres.counts.zw) {
        return;
    }
    let p = spheres_from_taps(id.xy);
    if p.unread {
        list_pixel(id.xy);
    } else {
        store_frame_pixel(id.xy, p.d, p.cloud, p.first_m);
    }
}

@compute @workgroup_size(8, 8)
fn composite(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= spheres.counts.zw) {
        return;
    }
    let p = spheres_from_taps(id.xy);
    if p.unread || !store_composited_from_taps(id.xy, p.cloud, p.first_m) {
        list_pixel(id.xy);
    }
}

@compute @workgroup_size(256)
fn listed(
    @builtin(global_invocation_id) id: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    let count = atomicLoad(&march_list.count);
    for (var i = id.x; i < count; i += groups.x * LIST_GROUP) {
        let px = listed_pixel(i);
        let p = spheres_at_listed(px);
        store_frame_pixel(px, p.d, p.cloud, p.first_m);
    }
}

@compute @workgroup_size(256)
fn listed_composite(
    @builtin(global_invocation_id) id: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    let count = atomicLoad(&march_list.count);
    for (var i = id.x; i < count; i += groups.x * LIST_GROUP) {
        let px = listed_pixel(i);
        let p = spheres_at_listed(px);
        store_composited_pixel(px, p.cloud, p.first_m);
    }
}
