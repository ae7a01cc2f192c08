// Library: reads of Riley et al. 2004's tables A_n and F_n (atmosphere-core's
// `clouds::layer::orders::ScatteringOrders`) from the including pass's storage buffer
// `orders` (A_1..A_26 at ANGLES angles per wavelength, then F_1..F_26 per wavelength),
// with its constants ANGLES, ORDERS, WAVES and PI.

// A_n (n clamped to 1..26) at the scattering angle of cosine `nu`, each wavelength.
fn distribution(n: u32, nu: f32) -> vec3<f32> {
    let row = clamp(n, 1u, ORDERS) - 1u;
    let x = acos(clamp(nu, -1.0, 1.0)) / PI * f32(ANGLES - 1u);
    let k = min(u32(floor(x)), ANGLES - 2u);
    let f = x - f32(k);
    var a = vec3<f32>(0.0);
    for (var w = 0u; w < WAVES; w++) {
        let base = (w * ORDERS + row) * ANGLES + k;
        a[w] = mix(orders[base], orders[base + 1u], f);
    }
    return a;
}

// F_n (n clamped to 1..26), each wavelength.
fn forward_fraction(n: u32) -> vec3<f32> {
    let row = clamp(n, 1u, ORDERS) - 1u;
    let base = WAVES * ORDERS * ANGLES + row;
    return vec3<f32>(orders[base], orders[base + ORDERS], orders[base + 2u * ORDERS]);
}
