// Library: the cloud layer pass's parameters and bindings (render-wgpu's
// `clouds/layer_uniform.rs`, whose layout the naga test checks). Positions are in
// metres from the planet's centre; spectral quantities at the renderer's three
// wavelengths (680, 550, 440 nm) in xyz.

struct LayerParams {
    // xyz: the camera; w: tan of half the vertical field of view.
    camera_m: vec4<f32>,
    // The camera's unit forward, right and up vectors (xyz).
    forward: vec4<f32>,
    right: vec4<f32>,
    up: vec4<f32>,
    // Unit vector towards the sun (xyz).
    sun_direction: vec4<f32>,
    // The sun's irradiance through the atmosphere and the sky's horizontal irradiance
    // where the layer is, W m^-2 nm^-1 (xyz).
    sun_irradiance: vec4<f32>,
    sky_irradiance: vec4<f32>,
    // Radii of the ground, the layer's base and top, and the layer's thickness, m.
    radii_m: vec4<f32>,
    // extinction_per_m, albedo, coverage_scale, backscatter_xi.
    medium: vec4<f32>,
    // detail_scale_m, detail_strength, min_transmittance (w unused).
    detail: vec4<f32>,
    // steps, shadow_steps, method (0 riley, 1 octaves, 2 eddington, 3 four-stream), octaves; the
    // method picks the pipeline (its LAYER_METHOD constant) and is not read here.
    counts: vec4<u32>,
    // The cover grid's width and height, the image's width and height.
    sizes: vec4<u32>,
    // Octaves of detail noise read by the view march and by the shadow march, the
    // resolution divisor, the sun's light (0: a shadow march, 1: the sun map; it picks
    // the pipeline, its SUN_FROM_MAP constant, and is not read here).
    noise: vec4<u32>,
}

@group(0) @binding(0) var<uniform> layer: LayerParams;
// The cover, equirectangular, north up, the first column at 180 W (`CoverGrid`).
@group(0) @binding(1) var cover: texture_2d<f32>;
// A_1..A_26 at ANGLES angles per wavelength, then F_1..F_26 per wavelength, then the
// asymmetry g per wavelength (`clouds::layer::orders::ScatteringOrders`).
@group(0) @binding(2) var<storage, read> orders: array<f32>;
// rgb: the cloud's radiance towards the camera; a: its transmittance; the full image,
// or the reduced one that `layer_upsample.wgsl` brings to full size.
@group(0) @binding(3) var cloud_image: texture_storage_2d<rgba32float, write>;

const ANGLES: u32 = 1024u;
const ORDERS: u32 = 26u;
const WAVES: u32 = 3u;
const PI: f32 = 3.14159265358979;
