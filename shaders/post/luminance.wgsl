// Entry pass: the frame's log-average luminance for automatic exposure, `main`
// (render-wgpu's `post/luminance.rs`, which is also its CPU twin,
// `log_average_luminance`). Paper: Reinhard et al. 2002, Eq. 1 (the log-average).
// Each of GRID x GRID workgroups of 8 x 8 invocations strides over the HDR target
// (spectral radiance at the three wavelengths), converts each pixel to luminance in
// cd/m^2 with the CIE weights of the uniform, and sums ln(L) and the count over the
// pixels brighter than the floor (black space and night do not count); the workgroup's
// sums go to one pair of the output. The CPU adds the pairs and takes
// exp(sum / count).

struct LuminanceParams {
    // Luminance (cd/m^2) per unit of radiance at each wavelength (xyz; w = the floor).
    weights: vec4<f32>,
}

// Workgroups along each side; must match GRID in render-wgpu's `post/luminance.rs`.
const GRID: u32 = 16u;
const SIDE: u32 = 8u;

@group(0) @binding(0) var<uniform> params: LuminanceParams;
@group(0) @binding(1) var hdr: texture_2d<f32>;
// Per workgroup: (sum of ln L, pixel count).
@group(0) @binding(2) var<storage, read_write> sums: array<vec2<f32>>;

var<workgroup> partial: array<vec2<f32>, 64>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) global: vec3<u32>,
        @builtin(local_invocation_index) local: u32,
        @builtin(workgroup_id) group: vec3<u32>) {
    let size = textureDimensions(hdr);
    let stride = GRID * SIDE;
    var sum = vec2<f32>(0.0);
    for (var y = global.y; y < size.y; y += stride) {
        for (var x = global.x; x < size.x; x += stride) {
            let radiance = textureLoad(hdr, vec2<u32>(x, y), 0).xyz;
            let luminance = dot(params.weights.xyz, radiance);
            if luminance > params.weights.w {
                sum += vec2<f32>(log(luminance), 1.0);
            }
        }
    }
    partial[local] = sum;
    workgroupBarrier();
    for (var span = 32u; span > 0u; span >>= 1u) {
        if local < span {
            partial[local] += partial[local + span];
        }
        workgroupBarrier();
    }
    if local == 0u {
        sums[group.y * GRID + group.x] = partial[0];
    }
}
