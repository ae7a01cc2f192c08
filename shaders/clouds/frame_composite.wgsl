// Entry pass: a frame's cloud composited with its sky model (render-wgpu's
// `clouds/frame_pass.rs`). Per pixel, per channel, as atmosphere-core's
// `clouds/layer/composite.rs` specifies (Riley et al. 2004, section 5: the atmosphere
// in front of and behind the volume),
//     L = L_front + T_front L_cloud + T_cloud (L_full - L_front),
// with L_full the model's pixel (its surface and sun disk included), L_front the model's
// second run ended where the ray enters the cloud, L_cloud and T_cloud the march
// (`clouds/frame_march.wgsl`), and T_front the atmosphere's transmittance from the
// camera to the cloud's entry, exp(-tau) of the columns integrated by the midpoint rule
// over FRONT_STEPS steps. Pixels without cloud (T_cloud = 1) keep L_full exactly.
// From above the layer with the spheres at a reduced resolution, L_front is the model's
// run at the spheres' reduced rays, ended where each enters the layer
// (`clouds/frame_front.rs`), and T_front that of the same rays, both read at the pixel
// by `reduced_front` (CPU twin: atmosphere-core's `clouds/layer/front_upsample.rs`).

#import clouds/front_transmittance.wgsl

@group(0) @binding(2) var full_image: texture_2d<f32>;
@group(0) @binding(3) var front_image: texture_2d<f32>;
// rgb: the cloud's radiance; a: its transmittance.
@group(0) @binding(4) var cloud_image: texture_2d<f32>;
// w: the cloud's entry distance, m (0: the camera is inside it, or no cloud).
@group(0) @binding(5) var cloud_front: texture_2d<f32>;
@group(0) @binding(6) var hdr: texture_storage_2d<rgba16float, write>;
// y: 1 when the model's second run wrote `front_image`, 0 when the camera is inside the
// layer and it did not run (no air in front of the cloud; x is the march's); z: 1 when
// `front_image` holds every pixel, the divisor k when it holds the reduced rays (one per
// k x k pixels) whose entries `reduced_entries` holds.
@group(0) @binding(7) var<uniform> composite_flags: vec4<u32>;
// w: where each reduced ray enters the layer, m (0: it does not).
@group(0) @binding(8) var reduced_entries: texture_2d<f32>;
// rgb: each reduced ray's transmittance to its entry
// (`clouds/front_reduced_transmittance.wgsl`).
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

// The air in front of the cloud at full pixel `px`, whose ray enters the layer at
// `entry_m`, from the reduced rays: the mean optical depth and source of its four
// bilinear taps (`layer/upsample.rs`'s map) over those whose ray enters the layer, else
// those of the nearest such reduced ray within FRONT_SEARCH of the pixel's nearest one;
// no source where there is none. Where that ray, or a kept tap's, enters further than
// FRONT_ENTRY_TOLERANCE of `entry_m` from it, or none is found, the depth is the pixel's
// own. The radiance is (1 - T) times the source.
fn reduced_front(px: vec2<u32>, entry_m: f32) -> AirInFront {
    let low = vec2<i32>(textureDimensions(front_image));
    let p = (vec2<f32>(px) + 0.5) * vec2<f32>(low) / vec2<f32>(frame.size_px.xy) - 0.5;
    let uv = clamp(p, vec2<f32>(0.0), vec2<f32>(low - vec2<i32>(1)));
    let i0 = vec2<i32>(floor(uv));
    let f = uv - vec2<f32>(i0);
    var sum = FrontTap(vec3<f32>(0.0), vec3<f32>(0.0));
    var weight = 0.0;
    var steep = false;
    for (var k = 0; k < 4; k++) {
        let step = vec2<i32>(k & 1, k >> 1u);
        let texel = min(i0 + step, low - vec2<i32>(1));
        let w = select(1.0 - f.x, f.x, step.x == 1) * select(1.0 - f.y, f.y, step.y == 1);
        let entry = textureLoad(reduced_entries, texel, 0).w;
        if w > 0.0 && entry > 0.0 {
            steep = steep || abs(entry - entry_m) > FRONT_ENTRY_TOLERANCE * entry_m;
            let tap = front_tap(texel);
            sum.depth += w * tap.depth;
            sum.source += w * tap.source;
            weight += w;
        }
    }
    if weight > 0.0 {
        sum.depth /= weight;
        sum.source /= weight;
    } else {
        steep = true;
        let nearest = vec2<i32>(floor(uv + 0.5));
        var best = 1e30;
        for (var j = -FRONT_SEARCH; j <= FRONT_SEARCH; j++) {
            for (var i = -FRONT_SEARCH; i <= FRONT_SEARCH; i++) {
                let texel = nearest + vec2<i32>(i, j);
                let inside = all(texel >= vec2<i32>(0)) && all(texel < low);
                let offset = vec2<f32>(texel) - p;
                let distance2 = dot(offset, offset);
                if inside && distance2 < best
                    && textureLoad(reduced_entries, texel, 0).w > 0.0 {
                    best = distance2;
                    sum = front_tap(texel);
                }
            }
        }
    }
    var t = exp(-sum.depth);
    if steep {
        t = front_transmittance(pixel_direction(px), entry_m);
    }
    return AirInFront(t, (1.0 - t) * sum.source);
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= frame.size_px.xy) {
        return;
    }
    let full = textureLoad(full_image, id.xy, 0).rgb;
    let cloud = textureLoad(cloud_image, id.xy, 0);
    var out = full;
    if cloud.a < 1.0 {
        let entry_m = textureLoad(cloud_front, id.xy, 0).w;
        var front = vec3<f32>(0.0);
        var t_front = vec3<f32>(1.0);
        if entry_m > 0.0 && composite_flags.y == 1u {
            if composite_flags.z > 1u {
                let air = reduced_front(id.xy, entry_m);
                t_front = air.transmittance;
                front = air.radiance;
            } else {
                t_front = front_transmittance(pixel_direction(id.xy), entry_m);
                front = textureLoad(front_image, id.xy, 0).rgb;
            }
        }
        out = front + t_front * cloud.rgb + cloud.a * max(full - front, vec3<f32>(0.0));
    }
    textureStore(hdr, id.xy, vec4<f32>(min(out, vec3<f32>(F16_MAX)), 1.0));
}
