// Library: a frame's cloud composited with its sky model at one pixel, into the HDR
// target (render-wgpu's `clouds/frame_pass.rs`). Per channel, as atmosphere-core's
// `clouds/layer/composite.rs` specifies (Riley et al. 2004, section 5: the atmosphere
// in front of and behind the volume),
//     L = L_front + T_front L_cloud + T_cloud (L_full - L_front),
// with L_full the model's pixel (its surface and sun disk included), L_front the model's
// second run ended where the ray enters the cloud, L_cloud and T_cloud the cloud, and
// T_front the atmosphere's transmittance from the camera to the cloud's entry, exp(-tau)
// of the columns integrated by the midpoint rule over FRONT_STEPS steps. Pixels without
// cloud (T_cloud = 1) keep L_full exactly. From above the layer with the cloud at a
// reduced resolution, L_front is the model's run at reduced rays, ended where each
// enters the layer's top (`clouds/frame_front.rs`), and T_front that of the same rays,
// both read at the pixel by `reduced_front` (CPU twin: atmosphere-core's
// `clouds/layer/front_upsample.rs`). The composite pass (`frame_composite.wgsl`) and the
// spheres' upsample (`spheres/frame_upsample.wgsl`) store their pixels through it.

#import clouds/front_transmittance.wgsl

@group(0) @binding(2) var full_image: texture_2d<f32>;
@group(0) @binding(3) var front_image: texture_2d<f32>;
@group(0) @binding(6) var hdr: texture_storage_2d<rgba16float, write>;
// y: 1 when the model's second run wrote `front_image`, 0 when the camera is inside the
// layer and it did not run (no air in front of the cloud; x is the march's); z: 1 when
// `front_image` holds every pixel, the divisor k when it holds the reduced rays (one per
// k x k pixels) whose entries `reduced_entries` holds.
@group(0) @binding(7) var<uniform> composite_flags: vec4<u32>;
// w: where each reduced ray enters the layer, m (0: it does not).
@group(0) @binding(8) var reduced_entries: texture_2d<f32>;
// rgb: each reduced ray's transmittance to its entry (`clouds/front_rays.wgsl`).
@group(0) @binding(9) var reduced_transmittance: texture_2d<f32>;

// How far (in reduced pixels, each way) `reduced_front` looks for a reduced ray that
// enters the layer where none of the pixel's bilinear taps does.
const FRONT_SEARCH: i32 = 2;
// A tap whose entry lies further than this share of the pixel's own from it marks a
// pixel whose depth in front changes too fast across the taps to be read from them:
// near the limb of the layer's top, which it integrates itself (FRONT_STEPS).
const FRONT_ENTRY_TOLERANCE: f32 = 0.1;

// The air in front of the cloud at a pixel: its transmittance and radiance.
struct AirInFront {
    transmittance: vec3<f32>,
    radiance: vec3<f32>,
}

// A reduced ray's optical depth in front of the cloud and its mean source, its radiance
// per unit of opacity 1 - T_front, which changes across the image more slowly than the
// radiance where the rays graze the layer's top.
struct FrontTap {
    depth: vec3<f32>,
    source: vec3<f32>,
}

fn front_tap(texel: vec2<i32>) -> FrontTap {
    let t = textureLoad(reduced_transmittance, texel, 0).rgb;
    let l = textureLoad(front_image, texel, 0).rgb;
    return FrontTap(-log(max(t, vec3<f32>(1e-30))), l / max(1.0 - t, vec3<f32>(1e-6)));
}

// The kept bilinear taps of a pixel's air in front: their mean, their weight (0: none
// enters the layer) and whether one enters too far from the pixel's own entry.
struct FrontTaps {
    mean: FrontTap,
    weight: f32,
    steep: bool,
}

// Where full pixel `px` lies on the reduced run's grid (`layer/upsample.rs`'s map).
fn reduced_position(px: vec2<u32>) -> vec2<f32> {
    let low = vec2<f32>(textureDimensions(front_image));
    return (vec2<f32>(px) + 0.5) * low / vec2<f32>(frame.size_px.xy) - 0.5;
}

// The four bilinear taps about full pixel `px`, whose ray enters the layer at `entry_m`,
// kept where the reduced ray enters the layer.
fn bilinear_front_taps(px: vec2<u32>, entry_m: f32) -> FrontTaps {
    let low = vec2<i32>(textureDimensions(front_image));
    let uv = clamp(reduced_position(px), vec2<f32>(0.0), vec2<f32>(low - vec2<i32>(1)));
    let i0 = vec2<i32>(floor(uv));
    let f = uv - vec2<f32>(i0);
    var taps = FrontTaps(FrontTap(vec3<f32>(0.0), vec3<f32>(0.0)), 0.0, false);
    for (var k = 0; k < 4; k++) {
        let step = vec2<i32>(k & 1, k >> 1u);
        let texel = min(i0 + step, low - vec2<i32>(1));
        let w = select(1.0 - f.x, f.x, step.x == 1) * select(1.0 - f.y, f.y, step.y == 1);
        let entry = textureLoad(reduced_entries, texel, 0).w;
        if w > 0.0 && entry > 0.0 {
            taps.steep = taps.steep || abs(entry - entry_m) > FRONT_ENTRY_TOLERANCE * entry_m;
            let tap = front_tap(texel);
            taps.mean.depth += w * tap.depth;
            taps.mean.source += w * tap.source;
            taps.weight += w;
        }
    }
    if taps.weight > 0.0 {
        taps.mean.depth /= taps.weight;
        taps.mean.source /= taps.weight;
    }
    return taps;
}

// The nearest reduced ray within FRONT_SEARCH of full pixel `px`'s nearest one that
// enters the layer; no depth and no source where there is none.
fn nearest_front_tap(px: vec2<u32>) -> FrontTap {
    let low = vec2<i32>(textureDimensions(front_image));
    let p = reduced_position(px);
    let nearest = vec2<i32>(floor(clamp(p, vec2<f32>(0.0), vec2<f32>(low - vec2<i32>(1))) + 0.5));
    var found = FrontTap(vec3<f32>(0.0), vec3<f32>(0.0));
    var best = 1e30;
    for (var j = -FRONT_SEARCH; j <= FRONT_SEARCH; j++) {
        for (var i = -FRONT_SEARCH; i <= FRONT_SEARCH; i++) {
            let texel = nearest + vec2<i32>(i, j);
            let inside = all(texel >= vec2<i32>(0)) && all(texel < low);
            let offset = vec2<f32>(texel) - p;
            let distance2 = dot(offset, offset);
            if inside && distance2 < best && textureLoad(reduced_entries, texel, 0).w > 0.0 {
                best = distance2;
                found = front_tap(texel);
            }
        }
    }
    return found;
}

// The air in front of the cloud at full pixel `px`, whose ray enters the layer at
// `entry_m`, from the reduced rays: the mean optical depth and source of its four
// bilinear taps over those whose ray enters the layer (`bilinear_front_taps`), else
// those of the nearest such reduced ray (`nearest_front_tap`). Where a kept tap enters
// further than FRONT_ENTRY_TOLERANCE of `entry_m` from it, or no tap enters, the depth
// is the pixel's own. The radiance is (1 - T) times the source.
fn reduced_front(px: vec2<u32>, entry_m: f32) -> AirInFront {
    let taps = bilinear_front_taps(px, entry_m);
    var tap = taps.mean;
    var t = exp(-tap.depth);
    if taps.weight <= 0.0 {
        tap = nearest_front_tap(px);
    }
    if taps.steep || taps.weight <= 0.0 {
        t = front_transmittance(pixel_direction(px), entry_m);
    }
    return AirInFront(t, (1.0 - t) * tap.source);
}

// L_front + T_front L_cloud + T_cloud (L_full - L_front) of `cloud` (rgb radiance, a
// transmittance) with the air in front `air`, written to pixel `px` of the HDR target;
// L_full exactly where the pixel has no cloud (T_cloud = 1).
fn store_over(px: vec2<u32>, full: vec3<f32>, cloud: vec4<f32>, air: AirInFront) {
    var out = full;
    if cloud.a < 1.0 {
        let front = air.radiance;
        out = front + air.transmittance * cloud.rgb + cloud.a * max(full - front, vec3<f32>(0.0));
    }
    textureStore(hdr, px, vec4<f32>(min(out, vec3<f32>(F16_MAX)), 1.0));
}

// No air in front of a cloud: the camera is inside it, or the model's second run did not
// run (`composite_flags.y`).
const NO_AIR = AirInFront(vec3<f32>(1.0), vec3<f32>(0.0));

// Writes pixel `px` of the HDR target: `cloud` (rgb radiance, a transmittance), whose
// ray enters it at `entry_m` (0: the camera is inside it, or no cloud), composited with
// the model's runs.
fn store_composite(px: vec2<u32>, cloud: vec4<f32>, entry_m: f32) {
    let full = textureLoad(full_image, px, 0).rgb;
    var air = NO_AIR;
    if cloud.a < 1.0 && entry_m > 0.0 && composite_flags.y == 1u {
        if composite_flags.z > 1u {
            air = reduced_front(px, entry_m);
        } else {
            let t = front_transmittance(pixel_direction(px), entry_m);
            air = AirInFront(t, textureLoad(front_image, px, 0).rgb);
        }
    }
    store_over(px, full, cloud, air);
}

// `store_composite` where the model's run in front is reduced (`composite_flags.z` above
// 1) and the pixel's air in front is read from its bilinear taps alone; false, with
// nothing written, where it needs the nearest tap or its own depth, which the caller
// leaves to a pass that takes `store_composite`'s path: on a software rasteriser a
// group of invocations pays for a branch any of them takes.
fn store_composite_from_taps(px: vec2<u32>, cloud: vec4<f32>, entry_m: f32) -> bool {
    let full = textureLoad(full_image, px, 0).rgb;
    var air = NO_AIR;
    if cloud.a < 1.0 && entry_m > 0.0 && composite_flags.y == 1u {
        let taps = bilinear_front_taps(px, entry_m);
        if taps.weight <= 0.0 || taps.steep {
            return false;
        }
        let t = exp(-taps.mean.depth);
        air = AirInFront(t, (1.0 - t) * taps.mean.source);
    }
    store_over(px, full, cloud, air);
    return true;
}
