// Library: the delta-M four-stream slab of the cloud layer's `four-stream` method, twin
// of atmosphere-core's `clouds/layer/four_stream.rs` (its documentation holds the
// equations: Liou 1974, Wiscombe 1977, Stamnes and Swanson 1981, the source-function
// technique of Toon et al. 1989), one wavelength at a time. A 2 x 2 matrix is a
// mat2x2<f32> built from its columns.

const FOUR_STREAM_MU: vec2<f32> = vec2<f32>(0.33998104, 0.86113631);
const FOUR_STREAM_W: vec2<f32> = vec2<f32>(0.65214515, 0.34785485);
const FOUR_STREAM_MIN_ABSORPTION: f32 = 1e-6;
const FOUR_STREAM_MIN_SUN_COSINE: f32 = 0.02;

// P_0..P_3 at `x`.
fn four_stream_legendre(x: f32) -> vec4<f32> {
    return vec4<f32>(1.0, x, 0.5 * (3.0 * x * x - 1.0), 0.5 * x * (5.0 * x * x - 3.0));
}

// The scaled phase function p'(mu, mu') of moments `chi` (chi'_0..chi'_3), azimuth-averaged.
fn four_stream_phase(chi: vec4<f32>, mu: f32, mu_prime: f32) -> f32 {
    return dot(vec4<f32>(1.0, 3.0, 5.0, 7.0) * chi, four_stream_legendre(mu) * four_stream_legendre(mu_prime));
}

// (1 - e^(-k x)) / k without the cancellation of small k x.
fn four_stream_one_minus_exp_over(k: f32, x: f32) -> f32 {
    let kx = k * x;
    if kx < 1e-2 {
        return x * (1.0 - kx * (0.5 - kx * (1.0 / 6.0 - kx / 24.0)));
    }
    return (1.0 - exp(-kx)) / k;
}

// (S, D) of solution `kind` (0: sigma, 1: delta) of eigenvalue `k` at scaled depth `tau`,
// S in .xy, D in .zw.
fn four_stream_mode(k: f32, total: f32, tau: f32, kind: u32, b: vec2<f32>, d: vec2<f32>) -> vec4<f32> {
    let falling = exp(-k * tau);
    let rising = exp(-k * (total - tau));
    let sigma = falling + rising;
    var delta = -falling * four_stream_one_minus_exp_over(k, total - 2.0 * tau);
    if 2.0 * tau >= total {
        delta = rising * four_stream_one_minus_exp_over(k, 2.0 * tau - total);
    }
    if kind == 0u {
        return vec4<f32>(b * sigma, k * k * d * delta);
    }
    return vec4<f32>(b * delta, d * sigma);
}

// A solved slab (atmosphere-core's `FourStreamSlab`): the scaled moments, the peak's
// share f, tau'/tau, the (perturbed) sun cosine, the scaled optical depth, the
// eigenvalues, the eigenvectors d and B d of each, the beam's particular solution and the
// constants of the beam's (.x) and the sky's (.y) solutions.
struct FourStreamSlab {
    chi: vec4<f32>,
    f: f32,
    scale: f32,
    mu0: f32,
    total: f32,
    k: vec2<f32>,
    d0: vec2<f32>,
    d1: vec2<f32>,
    b0: vec2<f32>,
    b1: vec2<f32>,
    zs: vec2<f32>,
    zd: vec2<f32>,
    c0: vec2<f32>,
    c1: vec2<f32>,
    c2: vec2<f32>,
    c3: vec2<f32>,
}

// The slab of optical depth `tau_total` (unscaled) lit at the sun's cosine `mu0_in`, the
// droplets' moments chi_1..chi_4 in `moments`.
fn four_stream_solve(tau_total: f32, mu0_in: f32, albedo: f32, moments: vec4<f32>) -> FourStreamSlab {
    let absorption = max(1.0 - albedo, FOUR_STREAM_MIN_ABSORPTION);
    let f = clamp(moments.w, 0.0, 0.999);
    let scale = 1.0 - (1.0 - absorption) * f;
    let omega = 1.0 - absorption / scale;
    let chi = (vec4<f32>(1.0, moments.xyz) - f) / (1.0 - f);
    let total = max(tau_total, 0.0) * scale;
    let mu = FOUR_STREAM_MU;
    let weights = FOUR_STREAM_W;
    // A (even moments) and B (odd), by their elements a_ij.
    var a: array<vec2<f32>, 2>;
    var b: array<vec2<f32>, 2>;
    for (var i = 0u; i < 2u; i++) {
        for (var j = 0u; j < 2u; j++) {
            let same = four_stream_phase(chi, mu[i], mu[j]);
            let opposite = four_stream_phase(chi, mu[i], -mu[j]);
            let identity = select(0.0, 1.0, i == j);
            a[i][j] = (identity - 0.5 * omega * (same + opposite) * weights[j]) / mu[i];
            b[i][j] = (identity - 0.5 * omega * (same - opposite) * weights[j]) / mu[i];
        }
    }
    let ma = mat2x2<f32>(a[0][0], a[1][0], a[0][1], a[1][1]);
    let mb = mat2x2<f32>(b[0][0], b[1][0], b[0][1], b[1][1]);
    let ab = ma * mb;
    let det = absorption / scale * (1.0 - omega * chi.z) * (1.0 - omega * chi.y)
        * (1.0 - omega * chi.w) / ((mu.x * mu.y) * (mu.x * mu.y));
    let trace = ab[0][0] + ab[1][1];
    let large = 0.5 * (trace + sqrt(max(trace * trace - 4.0 * det, 0.0)));
    let k2 = vec2<f32>(det / large, large);
    let k = sqrt(k2);
    var d: array<vec2<f32>, 2>;
    var bd: array<vec2<f32>, 2>;
    for (var q = 0u; q < 2u; q++) {
        // Rows of A B - k^2 (ab[column][row]); the longer gives the eigenvector.
        let first = vec2<f32>(ab[1][0], k2[q] - ab[0][0]);
        let second = vec2<f32>(k2[q] - ab[1][1], ab[0][1]);
        d[q] = normalize(select(second, first, length(first) >= length(second)));
        bd[q] = mb * d[q];
    }
    var mu0 = clamp(mu0_in, FOUR_STREAM_MIN_SUN_COSINE, 1.0);
    if any(abs(k * mu0 - 1.0) < vec2<f32>(1e-3)) {
        mu0 *= 1.002;
    }
    // The beam's particular solution.
    let q_up = omega / (4.0 * PI) * vec2<f32>(
        four_stream_phase(chi, mu.x, -mu0),
        four_stream_phase(chi, mu.y, -mu0),
    );
    let q_down = omega / (4.0 * PI) * vec2<f32>(
        four_stream_phase(chi, -mu.x, -mu0),
        four_stream_phase(chi, -mu.y, -mu0),
    );
    let qs = (q_up + q_down) / mu;
    let qd = (q_up - q_down) / mu;
    let inv = 1.0 / (mu0 * mu0);
    let m = mb * ma - mat2x2<f32>(inv, 0.0, 0.0, inv);
    let rhs = mb * qs - qd / mu0;
    let m_det = (k2.x - inv) * (k2.y - inv);
    let zs = vec2<f32>(rhs.x * m[1][1] - m[1][0] * rhs.y, m[0][0] * rhs.y - m[0][1] * rhs.x) / m_det;
    let zd = mu0 * (qs - ma * zs);
    // The conditions at the top (S - D) and the base (S + D); rows 0-1 and 2-3.
    var rows: array<vec4<f32>, 4>;
    for (var column = 0u; column < 4u; column++) {
        let q = column / 2u;
        let top = four_stream_mode(k[q], total, 0.0, column % 2u, bd[q], d[q]);
        let base = four_stream_mode(k[q], total, total, column % 2u, bd[q], d[q]);
        rows[0][column] = top.x - top.z;
        rows[1][column] = top.y - top.w;
        rows[2][column] = base.x + base.z;
        rows[3][column] = base.y + base.w;
    }
    let bottom = exp(-total / mu0);
    let sky_radiance = 1.0 / (2.0 * PI * dot(FOUR_STREAM_W, mu));
    // Right-hand sides: the beam's in .x, the sky's in .y.
    var r = array<vec2<f32>, 4>(
        vec2<f32>(-(zs.x - zd.x), 2.0 * sky_radiance),
        vec2<f32>(-(zs.y - zd.y), 2.0 * sky_radiance),
        vec2<f32>(-(zs.x + zd.x) * bottom, 0.0),
        vec2<f32>(-(zs.y + zd.y) * bottom, 0.0),
    );
    // Gaussian elimination with partial pivoting.
    for (var col = 0u; col < 4u; col++) {
        var pivot = col;
        for (var row = col + 1u; row < 4u; row++) {
            if abs(rows[row][col]) > abs(rows[pivot][col]) {
                pivot = row;
            }
        }
        let row_swap = rows[col];
        rows[col] = rows[pivot];
        rows[pivot] = row_swap;
        let r_swap = r[col];
        r[col] = r[pivot];
        r[pivot] = r_swap;
        for (var row = col + 1u; row < 4u; row++) {
            let factor = rows[row][col] / rows[col][col];
            rows[row] -= factor * rows[col];
            r[row] -= factor * r[col];
        }
    }
    for (var i = 0u; i < 4u; i++) {
        let row = 3u - i;
        var known = vec2<f32>(0.0);
        for (var c = row + 1u; c < 4u; c++) {
            known += rows[row][c] * r[c];
        }
        r[row] = (r[row] - known) / rows[row][row];
    }
    return FourStreamSlab(chi, f, scale, mu0, total, k, d[0], d[1], bd[0], bd[1], zs, zd, r[0], r[1], r[2], r[3]);
}

// The diffuse field's source towards the eye (1 - f) (1/2) sum_j w_j (p'(mu, mu_j)
// I(+mu_j) + p'(mu, -mu_j) I(-mu_j)), sr^-1, per unit sun irradiance (.x) and per unit
// sky irradiance (.y), at optical depth `tau_above` (unscaled, clamped to the slab)
// below the top of `slab`, towards a direction of cosine `mu_out` from the upward vertical.
fn four_stream_source(slab: FourStreamSlab, tau_above: f32, mu_out: f32) -> vec2<f32> {
    let tau = min(max(tau_above, 0.0) * slab.scale, slab.total);
    let mu = FOUR_STREAM_MU;
    let chi = slab.chi;
    var s_beam = slab.zs * exp(-tau / slab.mu0);
    var d_beam = slab.zd * exp(-tau / slab.mu0);
    var s_sky = vec2<f32>(0.0);
    var d_sky = vec2<f32>(0.0);
    var constants = array<vec2<f32>, 4>(slab.c0, slab.c1, slab.c2, slab.c3);
    for (var column = 0u; column < 4u; column++) {
        var here = four_stream_mode(slab.k.x, slab.total, tau, column % 2u, slab.b0, slab.d0);
        if column >= 2u {
            here = four_stream_mode(slab.k.y, slab.total, tau, column % 2u, slab.b1, slab.d1);
        }
        s_beam += constants[column].x * here.xy;
        d_beam += constants[column].x * here.zw;
        s_sky += constants[column].y * here.xy;
        d_sky += constants[column].y * here.zw;
    }
    let to_eye_up = FOUR_STREAM_W * vec2<f32>(
        four_stream_phase(chi, mu_out, mu.x),
        four_stream_phase(chi, mu_out, mu.y),
    );
    let to_eye_down = FOUR_STREAM_W * vec2<f32>(
        four_stream_phase(chi, mu_out, -mu.x),
        four_stream_phase(chi, mu_out, -mu.y),
    );
    // I(+mu) = (S + D) / 2, I(-mu) = (S - D) / 2.
    let beam = dot(to_eye_up, s_beam + d_beam) + dot(to_eye_down, s_beam - d_beam);
    let sky = dot(to_eye_up, s_sky + d_sky) + dot(to_eye_down, s_sky - d_sky);
    return max((1.0 - slab.f) * 0.25 * vec2<f32>(beam, sky), vec2<f32>(0.0));
}

// The source of `four_stream_source` at optical depth `tau_above` below the top of a
// slab of optical depth `tau_above + tau_below`, sun cosine `mu0_in`.
fn four_stream_diffuse(
    tau_above: f32,
    tau_below: f32,
    mu0_in: f32,
    albedo: f32,
    moments: vec4<f32>,
    mu_out: f32,
) -> vec2<f32> {
    let above = max(tau_above, 0.0);
    let slab = four_stream_solve(above + max(tau_below, 0.0), mu0_in, albedo, moments);
    return four_stream_source(slab, above, mu_out);
}
