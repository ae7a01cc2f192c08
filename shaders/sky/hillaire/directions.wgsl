// Library: the latitude-longitude mapping of directions around a camera inside the
// atmosphere, shared by the sky view, the aerial-perspective volume and the per-pixel
// pass of the hillaire model. CPU twin: atmosphere-core's `models/hillaire/directions.rs`.
// Paper: Hillaire 2020, section 5.3 (the sky-view LUT's mapping). Longitude is the
// azimuth from the sun's vertical plane, 0 to pi in equal steps; latitude is measured
// from the geometric horizon of the camera's altitude and mapped by a square root,
// v = sqrt(|l| / l_max); the rows are two halves (ground first, nadir at row 0, then sky,
// zenith last), each starting on the horizon, so that no texel mixes rays ending in space
// with rays ending on the ground.

#import common/phase.wgsl

// `horizon_zenith`: zenith angle of the geometric horizon at radius r (r^2 - bottom^2 = q).
fn horizon_zenith(q: f32, r: f32) -> f32 {
    return acos(horizon_cosine(q, r));
}

// `horizon_mu`: -sqrt(r^2 - bottom^2) / r, 0 on the ground.
fn horizon_cosine(q: f32, r: f32) -> f32 {
    return select(-sqrt(q) / r, 0.0, q <= 0.0);
}

// A texel's direction: zenith cosine, azimuth from the sun, and whether it is in the
// ground half.
struct TexelDirection {
    mu: f32,
    phi: f32,
    ground: bool,
}

// `LatLong::texel_direction` of texel (i, storage row j) of a `size` grid for a camera at
// radius r.
fn texel_direction(size: vec2<u32>, q: f32, r: f32, i: u32, j: u32) -> TexelDirection {
    let h = size.y / 2u;
    var d: TexelDirection;
    d.ground = j < h;
    let k = select(j - h, h - 1u - j, d.ground);
    let s = f32(k) / f32(h - 1u);
    let theta_h = horizon_zenith(q, r);
    var theta = theta_h * (1.0 - s * s);
    if d.ground {
        theta = theta_h + (PI - theta_h) * s * s;
    }
    // The horizon row takes the horizon's cosine itself, without the round trip of acos.
    d.mu = select(cos(theta), horizon_cosine(q, r), k == 0u);
    d.phi = PI * f32(i) / f32(size.x - 1u);
    return d;
}

// `view_sun_cosine`: view-sun cosine of a direction (mu, phi) with the sun at mu_s.
fn view_sun_cosine(mu: f32, phi: f32, mu_s: f32) -> f32 {
    let sin_v = safe_sqrt(1.0 - mu * mu);
    let sin_s = safe_sqrt(1.0 - mu_s * mu_s);
    return clamp(mu * mu_s + sin_v * sin_s * cos(phi), -1.0, 1.0);
}

// Where a direction falls in a grid: the texel column below, the storage rows of the
// two rows (from the horizon) around it, and the weights of the second column and row.
struct GridPosition {
    column: u32,
    column_weight: f32,
    row0: u32,
    row1: u32,
    row_weight: f32,
}

// `LatLong::position` of the direction at zenith angle `theta` (the CPU's acos(mu)) and
// azimuth `phi` in the ground or sky half, for a horizon at zenith angle `theta_h`.
fn grid_position(size: vec2<u32>, theta_h: f32, theta: f32, phi: f32, ground: bool) -> GridPosition {
    var s = safe_sqrt(1.0 - theta / theta_h);
    if ground {
        s = select(0.0, sqrt(clamp((theta - theta_h) / (PI - theta_h), 0.0, 1.0)), PI - theta_h > 0.0);
    }
    s = min(s, 1.0);
    let h = size.y / 2u;
    let fy = s * f32(h - 1u);
    let row = min(u32(fy), h - 2u);
    let fx = clamp(phi, 0.0, PI) / PI * f32(size.x - 1u);
    var p: GridPosition;
    p.column = min(u32(fx), size.x - 2u);
    p.column_weight = fx - f32(p.column);
    p.row_weight = fy - f32(row);
    // `LatLong::storage_row`.
    p.row0 = select(h + row, h - 1u - row, ground);
    p.row1 = select(h + row + 1u, h - 2u - row, ground);
    return p;
}
