// Reading the model's tables while building and rendering: the GPU twins of
// atmosphere-core's `bruneton/tables.rs` (`Table4::lookup`, `IrradianceTable::lookup`,
// `DensityTable::at`) and of the transmittance helpers of `bruneton/precompute.rs`.
//
// The tables and the store are bound as `sky/bruneton/bindings.wgsl` declares.

#import sky/bruneton/parameterization.wgsl
#import common/transmittance_lookup.wgsl

// Trilinear interpolation over (r, mu, mu_s) in nu slice `inu` (`Table4::slice`), along
// mu_s geometric where `geometric_pair` says so.
fn table4_slice(base: u32, p: Position, inu: u32) -> vec3<f32> {
    let geometric = geometric_pair(p.mu_s.i);
    var out = vec3<f32>(0.0);
    for (var dm = 0u; dm < 2u; dm++) {
        let wm = select(1.0 - p.mu.w, p.mu.w, dm == 1u);
        for (var dr = 0u; dr < 2u; dr++) {
            let w_r = select(1.0 - p.r.w, p.r.w, dr == 1u);
            let i = base + table_index(p.r.i + dr, p.mu.i + dm, p.mu_s.i, inu);
            out += (wm * w_r) * along_mu_s(store_read(i).xyz, store_read(i + 1u).xyz, p.mu_s.w, geometric);
        }
    }
    return out;
}

// Quadrilinear interpolation of the 4D table at `base` (`Table4::at_position`).
fn table4(base: u32, p: Position) -> vec3<f32> {
    let lo = table4_slice(base, p, p.nu.i);
    if p.nu.w == 0.0 {
        return lo;
    }
    return mix(lo, table4_slice(base, p, p.nu.i + 1u), p.nu.w);
}

// Bilinear interpolation of the irradiance table at `base` at (q, r, mu_s)
// (`IrradianceTable::lookup`).
fn irradiance_at(base: u32, q: f32, r: f32, mu_s: f32) -> vec3<f32> {
    let bottom = atmosphere.bottom_radius_m;
    let x_r = clamp(q / (r + bottom) / (atmosphere.top_radius_m - bottom), 0.0, 1.0);
    let x_mu_s = irradiance_x_mu_s(mu_s);
    let ar = axis(x_r, bruneton.irradiance_r_size);
    let am = axis(x_mu_s, bruneton.irradiance_mu_s_size);
    let i = base + ar.i * bruneton.irradiance_mu_s_size + am.i;
    let geometric = irradiance_geometric_pair(am.i);
    let lower = along_mu_s(store_read(i).xyz, store_read(i + 1u).xyz, am.w, geometric);
    let upper = along_mu_s(store_read(i + bruneton.irradiance_mu_s_size).xyz, store_read(i + bruneton.irradiance_mu_s_size + 1u).xyz, am.w, geometric);
    return mix(lower, upper, ar.w);
}

// Samples of the density table (`DensityTable::SAMPLES`), evenly spaced over the
// atmosphere's thickness.
const DENSITY_SAMPLES: u32 = 8192u;

// Relative densities at `altitude_m` from the density table (`DensityTable::at`), read
// from its copy in a 1D texture: the trapezoid nodes read it twice per node and texel.
fn density_at(altitude_m: f32) -> vec3<f32> {
    let f = clamp(altitude_m / bruneton.density_step_m, 0.0, f32(DENSITY_SAMPLES - 1u));
    let i = min(u32(f), DENSITY_SAMPLES - 2u);
    return mix(textureLoad(density_table, i, 0).xyz, textureLoad(density_table, i + 1u, 0).xyz, f - f32(i));
}

// Columns of matter of the segment of length d from (q, r mu): differences of the
// columns table, from the far end for rays that meet the ground (`segment_column`). The
// two ends are chosen before the two look-ups, so that a shader whose pixels take both
// kinds of ray (which lavapipe runs for every pixel) reads the table twice, not four
// times.
fn segment_column(q: f32, r: f32, r_mu: f32, d: f32, ground: bool) -> vec3<f32> {
    let ends = segment_ends(q, r, r_mu, d, ground);
    let a = table_columns(transmittance_columns, ends.x, ends.y);
    let b = table_columns(transmittance_columns, ends.z, ends.w);
    return max(a - b, vec3<f32>(0.0));
}

// The two rays of `segment_column`, (q, mu) of the one whose columns are added, then of
// the one whose columns are subtracted.
fn segment_ends(q: f32, r: f32, r_mu: f32, d: f32, ground: bool) -> vec4<f32> {
    let q_d = clamp(q + d * (d + 2.0 * r_mu), 0.0, horizon_sq());
    let r_d = radius_of_q(q_d);
    let mu_d = clamp((r_mu + d) / r_d, -1.0, 1.0);
    let mu = clamp(r_mu / r, -1.0, 1.0);
    return vec4<f32>(select(q, q_d, ground), select(mu, -mu_d, ground), select(q_d, q, ground),
        select(mu_d, -mu, ground));
}

// The visible part of the sun seen from (q, r) with its centre at zenith cosine mu_s
// (`visible_sun` of atmosphere-core's `bruneton/sun_disk.rs`): the fraction of the disk
// above the geometric horizon (0 when none of it is) and the zenith cosine of that part's
// centroid. With the centre y disk radii above the horizon, c = -y, the segment has area
// (acos c - c sqrt(1 - c^2)) / pi of the disk and its centroid lies
// (2/3) (1 - c^2)^(3/2) / (acos c - c sqrt(1 - c^2)) radii above the centre.
fn visible_sun(q: f32, r: f32, mu_s: f32) -> vec2<f32> {
    let alpha = bruneton.sun_angular_radius;
    let theta_s = acos(clamp(mu_s, -1.0, 1.0));
    let theta_h = acos(-safe_sqrt(q) / r);
    let height = (theta_h - theta_s) / alpha;
    if height >= 1.0 {
        return vec2<f32>(1.0, mu_s);
    }
    if height <= -1.0 {
        return vec2<f32>(0.0, mu_s);
    }
    let c = -height;
    let s = safe_sqrt(1.0 - c * c);
    let segment = acos(c) - c * s;
    if segment <= 0.0 {
        return vec2<f32>(0.0, mu_s);
    }
    let centroid = 2.0 / 3.0 * s * s * s / segment;
    return vec2<f32>(segment / PI, cos(theta_s - centroid * alpha));
}

// Transmittance to the sun from (q, r) at sun cosine mu_s, interpolated in the
// transmittance table (`Builder::sun_transmittance`): to a point, zero behind the planet,
// or with `sun_disk` to the disk's visible part along its centroid.
fn sun_transmittance(q: f32, r: f32, mu_s: f32) -> vec3<f32> {
    if bruneton.sun_disk == 1u {
        let visible = visible_sun(q, r, mu_s);
        if visible.x <= 0.0 {
            return vec3<f32>(0.0);
        }
        return visible.x * table_columns(transmittance, q, visible.y);
    }
    if hits_ground(q, r * mu_s) {
        return vec3<f32>(0.0);
    }
    return table_columns(transmittance, q, mu_s);
}
