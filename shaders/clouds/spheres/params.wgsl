// Library: the cloud spheres pass's parameters and bindings (render-wgpu's
// `clouds/spheres/sphere_uniform.rs`, whose layout the naga test checks). Positions in
// metres from the planet's centre; spectral quantities at the renderer's three
// wavelengths (680, 550, 440 nm) in xyz.

struct SphereParams {
    // xyz: the camera; w: tan of half the vertical field of view.
    camera_m: vec4<f32>,
    // The camera's unit forward, right and up vectors (xyz).
    forward: vec4<f32>,
    right: vec4<f32>,
    up: vec4<f32>,
    // Unit vector towards the sun (xyz).
    sun_direction: vec4<f32>,
    // The sun's irradiance through the atmosphere and the sky's horizontal irradiance
    // on the clouds, W m^-2 nm^-1 (xyz).
    sun_irradiance: vec4<f32>,
    sky_irradiance: vec4<f32>,
    // Radii of the ground and the layer's base, the layer's thickness, one shell's
    // thickness, m.
    radii_m: vec4<f32>,
    // The droplets' single-scattering albedo (x; yzw unused).
    medium: vec4<f32>,
    // The number of spheres m, the light's octaves, the image's width and height.
    counts: vec4<u32>,
    // The cloud textures' width and height, the attenuation textures' width and height.
    grids: vec4<u32>,
}

@group(0) @binding(20) var<uniform> spheres: SphereParams;
// Cloud textures T_k: the vertical optical depth of shell k, [k][j][i] on the cover's
// equirectangular grid (`clouds::spheres::cloud_textures`).
@group(0) @binding(21) var<storage, read> cloud_depths: array<f32>;
// Attenuation textures G_k: the sun's attenuation ratio exp(-tau) at sphere k,
// [k][j][i] (`clouds::spheres::attenuation`).
@group(0) @binding(22) var<storage, read> sun_ratios: array<f32>;
// The droplets' phase function A_1 at ANGLES angles from 0 to 180 degrees, per
// wavelength (`clouds::layer::orders::ScatteringOrders`'s first row).
@group(0) @binding(23) var<storage, read> single_phase: array<f32>;
// rgb: the spheres' radiance towards the camera; a: their transmittance.
@group(0) @binding(24) var sphere_image: texture_storage_2d<rgba32float, write>;

const ANGLES: u32 = 1024u;
const PI: f32 = 3.14159265358979;
// The optical depth of the planet's shadow (`attenuation::SHADOWED_DEPTH`).
const SHADOWED_DEPTH: f32 = 80.0;
