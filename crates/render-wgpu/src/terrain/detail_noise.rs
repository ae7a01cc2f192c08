//! Gradient noise on an integer lattice with the derivatives the relief refinement needs.
//!
//! Perlin's gradient noise with the quintic fade `f(x) = 6x^5 - 15x^4 + 10x^3` (Perlin
//! 2002, "Improving noise", section 3): at a point `(x, y)` of lattice cell `(i, j)` with
//! fractions `(u, v)`, each corner `c` contributes `g_c . ((u, v) - c)` (its pseudo-random
//! unit gradient dotted with the offset from it), blended by `f(u)` and `f(v)`:
//! `N = n00 + f(u) (n10 - n00) + f(v) (n01 - n00) + f(u) f(v) (n00 - n10 - n01 + n11)`.
//! The noise is 0 at every lattice point, C2 everywhere (the fade's first and second
//! derivatives vanish at 0 and 1), and [`Sample`] carries `N`, `dN/dx`, `dN/dy` and the
//! mixed derivative `d2N/dxdy` in closed form.
//!
//! Gradients are picked from 16 directions by a hash of the lattice point, the octave and
//! a seed: the noise is a pure function of its arguments (no state, no time, no thread
//! order). The lattice wraps in x with a given period, so a longitude circle closes.

/// A value of the noise with its first derivatives and mixed second derivative.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Sample {
    pub value: f64,
    pub dx: f64,
    pub dy: f64,
    pub dxdy: f64,
}

/// 16 unit gradients, evenly spaced in angle (offset by half a step, so none is along an
/// axis).
const GRADIENTS: [[f64; 2]; 16] = {
    let mut g = [[0.0; 2]; 16];
    // cos and sin of (k + 1/2) 2 pi / 16, written out (const fn has no trigonometry).
    const C: [f64; 4] = [
        0.980_785_280_403_230_4,
        0.831_469_612_302_545_2,
        0.555_570_233_019_602_2,
        0.195_090_322_016_128_27,
    ];
    let mut k = 0;
    while k < 16 {
        // Quadrant q, index m within it: angle (4q + m + 1/2) pi / 8.
        let (q, m) = (k / 4, k % 4);
        let (c, s) = (C[m], C[3 - m]);
        g[k] = match q {
            0 => [c, s],
            1 => [-s, c],
            2 => [-c, -s],
            _ => [s, -c],
        };
        k += 1;
    }
    g
};

/// A 64-bit mix of the lattice point, octave and seed (the finaliser of SplitMix64).
fn hash(ix: i64, iy: i64, octave: u32, seed: u64) -> u64 {
    let mut z = seed
        ^ (ix as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15)
        ^ (iy as u64).wrapping_mul(0xC2B2_AE3D_27D4_EB4F)
        ^ u64::from(octave).wrapping_mul(0x1656_67B1_9E37_79F9);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

fn gradient(ix: i64, iy: i64, octave: u32, seed: u64) -> [f64; 2] {
    GRADIENTS[(hash(ix, iy, octave, seed) >> 60) as usize]
}

/// The quintic fade and its derivative.
fn fade(t: f64) -> (f64, f64) {
    let f = t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
    let df = 30.0 * t * t * (t - 1.0) * (t - 1.0);
    (f, df)
}

/// Gradient noise at `(x, y)` on the unit lattice, wrapping in x with period
/// `period_x` lattice cells, for `octave` and `seed` (which pick independent gradients).
pub fn gradient_noise(x: f64, y: f64, period_x: i64, octave: u32, seed: u64) -> Sample {
    let (x0, y0) = (x.floor(), y.floor());
    let (u, v) = (x - x0, y - y0);
    let (ix, iy) = ((x0 as i64).rem_euclid(period_x), y0 as i64);
    let ix1 = (ix + 1).rem_euclid(period_x);
    let g00 = gradient(ix, iy, octave, seed);
    let g10 = gradient(ix1, iy, octave, seed);
    let g01 = gradient(ix, iy + 1, octave, seed);
    let g11 = gradient(ix1, iy + 1, octave, seed);
    let n00 = g00[0] * u + g00[1] * v;
    let n10 = g10[0] * (u - 1.0) + g10[1] * v;
    let n01 = g01[0] * u + g01[1] * (v - 1.0);
    let n11 = g11[0] * (u - 1.0) + g11[1] * (v - 1.0);
    // N = a + f(u) b + f(v) c + f(u) f(v) e, with a, b, c, e linear in (u, v).
    let (b, c, e) = (n10 - n00, n01 - n00, n00 - n10 - n01 + n11);
    let (b_u, b_v) = (g10[0] - g00[0], g10[1] - g00[1]);
    let (c_u, c_v) = (g01[0] - g00[0], g01[1] - g00[1]);
    let e_u = g00[0] - g10[0] - g01[0] + g11[0];
    let e_v = g00[1] - g10[1] - g01[1] + g11[1];
    let (fu, dfu) = fade(u);
    let (fv, dfv) = fade(v);
    Sample {
        value: n00 + fu * b + fv * c + fu * fv * e,
        dx: g00[0] + dfu * b + fu * b_u + fv * c_u + dfu * fv * e + fu * fv * e_u,
        dy: g00[1] + dfv * c + fv * c_v + fu * b_v + fu * dfv * e + fu * fv * e_v,
        dxdy: dfu * b_v + dfv * c_u + dfu * dfv * e + dfu * fv * e_v + fu * dfv * e_u,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gradients_are_unit_and_distinct() {
        for (k, g) in GRADIENTS.iter().enumerate() {
            assert!((g[0].hypot(g[1]) - 1.0).abs() < 1e-15, "{k}");
            for h in &GRADIENTS[k + 1..] {
                assert!((g[0] - h[0]).abs() + (g[1] - h[1]).abs() > 0.1);
            }
        }
    }

    /// Zero at lattice points; the derivatives match central differences; the lattice
    /// wraps with its period.
    #[test]
    fn derivatives_match_finite_differences_and_the_lattice_wraps() {
        for k in 0..5 {
            assert_eq!(gradient_noise(k as f64, -3.0, 7, 2, 9).value, 0.0);
        }
        let h = 1e-5;
        for &(x, y) in &[(0.3, 0.7), (5.91, -2.2), (13.5, 4.04), (0.999, 0.001)] {
            let s = gradient_noise(x, y, 16, 3, 42);
            let at = |x: f64, y: f64| gradient_noise(x, y, 16, 3, 42);
            let dx = (at(x + h, y).value - at(x - h, y).value) / (2.0 * h);
            let dy = (at(x, y + h).value - at(x, y - h).value) / (2.0 * h);
            let dxdy = (at(x + h, y).dy - at(x - h, y).dy) / (2.0 * h);
            assert!((dx - s.dx).abs() < 1e-7, "{dx} {}", s.dx);
            assert!((dy - s.dy).abs() < 1e-7, "{dy} {}", s.dy);
            assert!((dxdy - s.dxdy).abs() < 1e-6, "{dxdy} {}", s.dxdy);
            let wrapped = at(x + 16.0, y);
            assert!(
                (wrapped.value - s.value).abs() < 1e-12 && (wrapped.dxdy - s.dxdy).abs() < 1e-9
            );
            assert_ne!(gradient_noise(x, y, 16, 4, 42), s);
            assert_ne!(gradient_noise(x, y, 16, 3, 43), s);
        }
    }
}
