// Library: 3D gradient noise and its fractal sum (Perlin 2002, "Improving noise"), the
// twin of atmosphere-core's `numerics/gradient_noise.rs`: the same lowbias32 integer
// hash of the lattice point and seed, the same 12 cube-edge gradients and quintic fade,
// so a value depends only on (seed, point) on either side. The hash of a lattice point
// (i, j, k) is mix(seed ^ mix(i ^ mix(j ^ mix(k)))); a cell's eight corners share its
// inner rounds (2 of mix(k), 4 of mix(j ^ .)), 22 rounds instead of 32, the same values.

fn noise_mix(x_in: u32) -> u32 {
    var x = x_in;
    x = x ^ (x >> 16u);
    x = x * 0x7feb352du;
    x = x ^ (x >> 15u);
    x = x * 0x846ca68bu;
    x = x ^ (x >> 16u);
    return x;
}

// The dot product of `o` with cube-edge gradient `hash % 12`: (+-1, +-1, 0) for 0..3,
// (+-1, 0, +-1) for 4..7, (0, +-1, +-1) for 8..11, bit 0 the first sign and bit 1 the
// second. Picked by selects, not by a switch: a software rasteriser runs every case
// that some lane of a SIMD group takes.
fn gradient_dot(hash: u32, o: vec3<f32>) -> f32 {
    let h = hash % 12u;
    let a = select(o.y, o.x, h < 8u);
    let b = select(o.z, o.y, h < 4u);
    return select(a, -a, (h & 1u) != 0u) + select(b, -b, (h & 2u) != 0u);
}

fn noise_fade(t: vec3<f32>) -> vec3<f32> {
    return t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
}

// Gradient noise at `point`: 0 on the lattice, within about [-1, 1].
fn gradient_noise(seed: u32, point: vec3<f32>) -> f32 {
    let cell = floor(point);
    let f = point - cell;
    let c = bitcast<vec3<u32>>(vec3<i32>(cell));
    let u = noise_fade(f);
    var hz = array<u32, 2>(noise_mix(c.z), noise_mix(c.z + 1u));
    var corners: array<f32, 8>;
    for (var k = 0u; k < 4u; k++) {
        let dy = k & 1u;
        let dz = k >> 1u;
        let hyz = noise_mix((c.y + dy) ^ hz[dz]);
        for (var dx = 0u; dx < 2u; dx++) {
            let hash = noise_mix(seed ^ noise_mix((c.x + dx) ^ hyz));
            let d = vec3<u32>(dx, dy, dz);
            corners[dx + 2u * k] = gradient_dot(hash, f - vec3<f32>(d));
        }
    }
    let x00 = mix(corners[0], corners[1], u.x);
    let x10 = mix(corners[2], corners[3], u.x);
    let x01 = mix(corners[4], corners[5], u.x);
    let x11 = mix(corners[6], corners[7], u.x);
    return mix(mix(x00, x10, u.y), mix(x01, x11, u.y), u.z);
}

// The fractal sum of `octaves` octaves (frequency doubling, amplitude times `gain`, each
// octave seeded by noise_mix(seed + octave)), normalised by the sum of the amplitudes.
fn fractal_noise(seed: u32, point: vec3<f32>, octaves: u32, gain: f32) -> f32 {
    var sum = 0.0;
    var norm = 0.0;
    var amplitude = 1.0;
    var frequency = 1.0;
    for (var octave = 0u; octave < octaves; octave++) {
        sum += amplitude * gradient_noise(noise_mix(seed + octave), point * frequency);
        norm += amplitude;
        amplitude *= gain;
        frequency *= 2.0;
    }
    return select(0.0, sum / norm, norm > 0.0);
}
