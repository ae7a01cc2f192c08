// Library: the medium's phase function at the cosine of the scattering angle, sr^-1.
// CPU twin: atmosphere-core's `optics/phase.rs` (`PhaseFunction::eval`): Rayleigh's;
// Cornette and Shanks 1992 (Bruneton and Neyret 2008 Eq. 4); Henyey and Greenstein
// 1941; Nishita's hazy function (Dobashi, Yamamoto and Nishita 2000 Eq. 4); a table
// linear in angle, its values normalised on the CPU.

#import shafts/beams/bindings.wgsl

const PI_PHASE: f32 = 3.14159265358979;

fn tabulated_phase(nu: f32) -> f32 {
    let angle = degrees(acos(nu));
    let rows = params.counts.w;
    if angle <= phase_table[0].x {
        return phase_table[0].y;
    }
    for (var i = 1u; i < rows; i++) {
        let b = phase_table[i];
        if angle <= b.x {
            let a = phase_table[i - 1u];
            return a.y + (b.y - a.y) * (angle - a.x) / (b.x - a.x);
        }
    }
    return phase_table[rows - 1u].y;
}

fn beams_phase(nu_in: f32) -> f32 {
    let nu = clamp(nu_in, -1.0, 1.0);
    let g = params.phase.x;
    let g2 = g * g;
    let denom = max(1.0 + g2 - 2.0 * g * nu, 1e-30);
    switch params.counts.z {
        case 0u: {
            return 3.0 / (16.0 * PI_PHASE) * (1.0 + nu * nu);
        }
        case 1u: {
            return 3.0 / (8.0 * PI_PHASE) * (1.0 - g2) * (1.0 + nu * nu) / ((2.0 + g2) * denom * sqrt(denom));
        }
        case 2u: {
            return (1.0 - g2) / (4.0 * PI_PHASE * denom * sqrt(denom));
        }
        case 3u: {
            let c = 0.5 * (1.0 + nu);
            let c2 = c * c;
            let c4 = c2 * c2;
            return (1.0 + 9.0 * c4 * c4) / (8.0 * PI_PHASE);
        }
        default: {
            return tabulated_phase(nu);
        }
    }
}
