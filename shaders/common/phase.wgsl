// Library: the phase functions, per steradian. CPU twin: atmosphere-core's
// `optics/phase.rs`. Papers: Rayleigh's; for Mie, Cornette and Shanks 1992 (Bruneton and
// Neyret 2008, Eq. 4), Henyey and Greenstein 1941, or Nishita's hazy-atmosphere function
// (Dobashi et al. 2000, Eq. 4) (`PhaseFunction`).

#import common/atmosphere_params.wgsl

const PI: f32 = 3.14159265358979;

// Rayleigh: 3 / (16 pi) (1 + nu^2).
fn rayleigh_phase(nu: f32) -> f32 {
    return 3.0 / (16.0 * PI) * (1.0 + nu * nu);
}

// The atmosphere's Mie phase function at the cosine `nu` (`PhaseFunction::eval`).
fn mie_phase(nu: f32) -> f32 {
    let g = atmosphere.mie_g;
    let g2 = g * g;
    let denom = max(1.0 + g2 - 2.0 * g * nu, 1e-30);
    switch atmosphere.mie_phase_kind {
        case 0u: {
            return 3.0 / (8.0 * PI) * (1.0 - g2) * (1.0 + nu * nu) / ((2.0 + g2) * denom * sqrt(denom));
        }
        case 1u: {
            return (1.0 - g2) / (4.0 * PI * denom * sqrt(denom));
        }
        default: {
            let c = 0.5 * (1.0 + nu);
            let c2 = c * c;
            let c4 = c2 * c2;
            return (1.0 + 9.0 * c4 * c4) / (8.0 * PI);
        }
    }
}
