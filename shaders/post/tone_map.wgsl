// Entry pass: from the HDR target (spectral radiance at the three wavelengths) to the
// display, `vertex` and `fragment` (render-wgpu's `post/tone_map_pass.rs`). CPU twin:
// render-wgpu's `post/tone_map.rs`. Paper: Narkowicz 2016, "ACES filmic tone mapping
// curve". The radiance is converted to linear sRGB in cd/m^2 and scaled by the exposure
// in one 3x3 matrix, negative (out-of-gamut) values are clipped, and Narkowicz's fit of
// the ACES filmic curve maps each channel to [0, 1]; the Rgba8UnormSrgb target applies
// the sRGB transfer function.

struct ToneMapParams {
    // Rows of the matrix from radiance to exposed linear sRGB (xyz; w = 0).
    red: vec4<f32>,
    green: vec4<f32>,
    blue: vec4<f32>,
}

@group(0) @binding(0) var<uniform> tone_map: ToneMapParams;
@group(0) @binding(1) var hdr: texture_2d<f32>;

// Narkowicz 2016, "ACES Filmic Tone Mapping Curve": a rational fit of the ACES
// reference rendering and output transforms.
fn aces_filmic(x: vec3<f32>) -> vec3<f32> {
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), vec3<f32>(0.0), vec3<f32>(1.0));
}

// A triangle that covers the whole target.
@vertex
fn vertex(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    let xy = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    return vec4<f32>(xy * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn fragment(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let radiance = textureLoad(hdr, vec2<u32>(position.xy), 0).xyz;
    let srgb = vec3<f32>(dot(tone_map.red.xyz, radiance), dot(tone_map.green.xyz, radiance),
        dot(tone_map.blue.xyz, radiance));
    return vec4<f32>(aces_filmic(max(srgb, vec3<f32>(0.0))), 1.0);
}
