// Library: a frame's rays through the cloud layer (render-wgpu's `clouds/frame_pass.rs`):
// the direction through a fractional pixel of the frame's camera, and the segment of the
// layer a ray crosses, ended where it meets the frame's surface (terrain in front of the
// cloud hides it; terrain inside the layer ends the march). CPU twins:
// `LayerCamera::direction_at` and atmosphere-core's `Shell::first_segment` ended at the
// surface's distance.

#import clouds/layer_march.wgsl

struct FrameCloudParams {
    // x: 1 when the frame has a surface (binding 4 holds it), 0 when it has none.
    flags: vec4<u32>,
}

// The frame's surface: xyz the normal, w the distance along the pixel's ray, m (0: none).
@group(0) @binding(4) var frame_surface: texture_2d<f32>;
@group(0) @binding(6) var<uniform> frame_clouds: FrameCloudParams;

// The unit direction through the full image's fractional pixel (x, y), pixel x's centre
// at x.
fn frame_direction(pixel: vec2<f32>) -> vec3<f32> {
    let size = layer.sizes.zw;
    let tan_half = layer.camera_m.w;
    let aspect = f32(size.x) / f32(size.y);
    let sx = (2.0 * (pixel.x + 0.5) / f32(size.x) - 1.0) * tan_half * aspect;
    let sy = (2.0 * (pixel.y + 0.5) / f32(size.y) - 1.0) * tan_half;
    return normalize(layer.forward.xyz + sx * layer.right.xyz - sy * layer.up.xyz);
}

// The segment (t0, t1) of the layer along `d` from the camera, ended on the surface of
// full pixel `surface_px`; t0 >= t1 where the ray meets no cloud before the surface.
fn frame_segment(d: vec3<f32>, surface_px: vec2<u32>) -> vec2<f32> {
    var t = layer_segment(layer.camera_m.xyz, d);
    if frame_clouds.flags.x == 1u {
        let surface_m = textureLoad(frame_surface, surface_px, 0).w;
        if surface_m > 0.0 {
            t.y = min(t.y, surface_m);
        }
    }
    return t;
}
