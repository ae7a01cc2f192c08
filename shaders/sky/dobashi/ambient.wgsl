// Entry pass: the ambient table of the dobashi model, `main` (render-wgpu's
// `sky/dobashi/`). CPU twin: atmosphere-core's `models/dobashi/ambient.rs`
// (`AmbientTable::build`). Paper: none for the term itself (Dobashi, Yamamoto and Nishita
// 2002 has no multiple scattering; docs/models/dobashi.md), estimated as Hillaire 2020,
// section 5.5, does with the model's own Eq. 12 (`sky/dobashi/trace.wgsl`). Workgroup i
// takes the sun at cosine -1 + 2 i / (n - 1); its 64 lanes share `ambient_directions`^2
// rays from the ground (equal steps of the zenith cosine times equal steps of azimuth),
// so that no invocation runs more loop trips than every GPU allows, each traced with a
// unit ambient radiance: psi_1, the mean single-scattered and sunlit-ground radiance, and f,
// the mean transfer of a unit isotropic radiance; psi = psi_1 (1 + f + ... + f^(N-2)) for
// N orders, or psi_1 / (1 - f) for all. Writes psi per unit solar irradiance into
// `ambient_out`.

#import sky/dobashi/trace.wgsl

// psi per unit solar irradiance (rgb) at equal steps of the sun's cosine from -1 to 1,
// an n x 1 texture read by the per-pixel pass (as `ambient_table`). The rays traced here
// see a unit ambient radiance: `ambient_table` is a table of ones.
@group(0) @binding(12) var ambient_out: texture_storage_2d<rgba32float, write>;

const LANES: u32 = 64u;

// The rays of the ambient term see no terrain: orders two and up stay unshadowed
// (`Dobashi::build_ambient`).
fn terrain_visible(position: vec3<f32>, altitude: f32) -> f32 {
    return 1.0;
}

var<workgroup> psi_1_sum: array<vec3<f32>, 64>;
var<workgroup> transfer_sum: array<vec3<f32>, 64>;

@compute @workgroup_size(64)
fn main(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) lane: u32) {
    let n_sun = textureDimensions(ambient_out).x;
    let bottom = atmosphere.bottom_radius_m;
    let mu_sun = -1.0 + 2.0 * f32(group.x) / f32(n_sun - 1u);
    let sun = vec3<f32>(sqrt(max(1.0 - mu_sun * mu_sun, 0.0)), 0.0, mu_sun);
    let n = dobashi.ambient_directions;
    let weight = 1.0 / f32(n * n);
    var psi_1 = vec3<f32>(0.0);
    var transfer = vec3<f32>(0.0);
    for (var index = lane; index < n * n; index += LANES) {
        let mu = -1.0 + 2.0 * (f32(index / n) + 0.5) / f32(n);
        let phi = 2.0 * PI * (f32(index % n) + 0.5) / f32(n);
        let sin_zenith = sqrt(max(1.0 - mu * mu, 0.0));
        let direction = vec3<f32>(sin_zenith * cos(phi), sin_zenith * sin(phi), mu);
        // From the ground at (0, 0, bottom): q = 0, r mu = bottom mu; a ray below the
        // horizon ends where it starts, on the ground.
        var s: Segment;
        s.hit = true;
        s.q = 0.0;
        s.r_mu = bottom * mu;
        s.start = vec3<f32>(0.0, 0.0, bottom);
        s.start_dot_sun = bottom * mu_sun;
        s.on_ground = mu < 0.0;
        s.end = select(END_SPACE, END_GROUND, s.on_ground);
        let horizon_sq = (atmosphere.top_radius_m - bottom) * (atmosphere.top_radius_m + bottom);
        let root = sqrt(s.r_mu * s.r_mu + horizon_sq);
        s.length = select(horizon_sq / (max(s.r_mu, 0.0) + root), 0.0, s.on_ground);
        let terms = trace(make_ray(s, direction, sun), false);
        psi_1 += weight * terms.single;
        transfer += weight * terms.ambient;
    }
    psi_1_sum[lane] = psi_1;
    transfer_sum[lane] = transfer;
    workgroupBarrier();
    for (var stride = LANES / 2u; stride > 0u; stride /= 2u) {
        if lane < stride {
            psi_1_sum[lane] += psi_1_sum[lane + stride];
            transfer_sum[lane] += transfer_sum[lane + stride];
        }
        workgroupBarrier();
    }
    if lane != 0u {
        return;
    }
    let f = clamp(transfer_sum[0], vec3<f32>(0.0), vec3<f32>(1.0 - 1e-6));
    var series = 1.0 / (1.0 - f);
    if dobashi.max_orders > 0u {
        series = vec3<f32>(0.0);
        var power = vec3<f32>(1.0);
        for (var i = 0u; i + 1u < dobashi.max_orders; i++) {
            series += power;
            power *= f;
        }
    }
    textureStore(ambient_out, vec2<u32>(group.x, 0u), vec4<f32>(psi_1_sum[0] * series, 1.0));
}
