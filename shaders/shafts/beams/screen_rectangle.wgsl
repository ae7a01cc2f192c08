// A light's screen rectangle as two triangles: the clip-space position of vertex `v`
// (0 to 5) of the rectangle [x0, y0, x1, y1] = `bounds`, its corners (0, 0), (1, 0),
// (1, 1), (0, 0), (1, 1), (0, 1) between them.
fn screen_rectangle_position(bounds: vec4<f32>, v: u32) -> vec4<f32> {
    let corners = array<vec2<f32>, 6>(
        vec2<f32>(0.0, 0.0), vec2<f32>(1.0, 0.0), vec2<f32>(1.0, 1.0),
        vec2<f32>(0.0, 0.0), vec2<f32>(1.0, 1.0), vec2<f32>(0.0, 1.0),
    );
    return vec4<f32>(mix(bounds.xy, bounds.zw, corners[v]), 0.0, 1.0);
}
