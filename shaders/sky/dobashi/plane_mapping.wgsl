// Library: the mapping of the dobashi model's plane tables, shared by their build
// (`planes` in `sky/dobashi/tables.wgsl`) and their lookup (`sky/dobashi/trace.wgsl`).
// CPU twin: atmosphere-core's `models/dobashi/plane_tables.rs` (`texel_ray`,
// `PlaneTables::coordinates`). Paper: Dobashi, Yamamoto and Nishita 2002, section 5.2 and
// appendix A.2 (the tables dI_r, dI_m, dg_v over height and direction); the mapping of
// the direction axis is this project's, after Bruneton 2017's transmittance table.

#import common/atmosphere_params.wgsl

// The range (d_min, d_max) of the distance to where a ray leaves the atmosphere, over the
// rays from the point at radius `r` (r^2 - bottom^2 = `q`, horizon length `rho` =
// sqrt(q)) that meet the ground (`ground`: from straight down to the horizon) or the top
// (from straight up to the horizon); each half of a row's direction axis spans its range.
fn plane_distance_range(q: f32, r: f32, rho: f32, ground: bool) -> vec2<f32> {
    let bottom = atmosphere.bottom_radius_m;
    let top = atmosphere.top_radius_m;
    let horizon = sqrt((top - bottom) * (top + bottom));
    if ground {
        return vec2<f32>(q / (r + bottom), rho);
    }
    return vec2<f32>((horizon - rho) * (horizon + rho) / (top + r), rho + horizon);
}
