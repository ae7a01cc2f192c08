//! Bruneton's nodes along each texel's ray placed by density (`density_nodes`): on the
//! hazy preset, whose aerosol lies in a boundary layer 1.2 km thick, single scattering
//! of the sunlit texels in the layer with N nodes by density is closer to 4N crowded
//! nodes than N crowded nodes are (measured: RMS 0.31 against 0.41 for Rayleigh, 0.32
//! against 0.47 for Mie, at N = 8).

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::bruneton::Bruneton;
use atmosphere_core::models::bruneton::parameterization::{
    AngleMapping, Radii, ScatteringSize, texel_parameters,
};
use atmosphere_core::models::sky_model::ModelSettings;

/// Single scattering (Rayleigh, Mie) of reduced tables of the hazy preset.
fn single(options: &[&str]) -> (Vec<[f32; 3]>, Vec<[f32; 3]>) {
    let mut settings = ModelSettings {
        max_orders: Some(1),
        ..ModelSettings::default()
    };
    for item in ["r=8", "mu=32", "mu_s=8", "nu=4"].iter().chain(options) {
        let (k, v) = item.split_once('=').unwrap();
        settings.options.set(k, v);
    }
    let model = Bruneton::prepare(&Atmosphere::preset("hazy").unwrap(), &settings).unwrap();
    let t = &model.tables()[0];
    let mie = t.single_mie.as_ref().expect("the hazy preset has aerosol");
    (t.single_rayleigh.data.clone(), mie.data.clone())
}

/// Whether the texel at `index` of the reduced tables has the sun at least 10 deg above
/// the horizon and a ray that starts in the boundary layer (below 1 km).
fn sunlit_in_the_layer(index: usize) -> bool {
    let a = Atmosphere::preset("hazy").unwrap();
    let radii = Radii {
        bottom_m: a.bottom_radius_m,
        top_m: a.top_radius_m,
    };
    let size = ScatteringSize {
        r: 8,
        mu: 32,
        mu_s: 8,
        nu: 4,
        angles: AngleMapping::PAPER,
    };
    let (ir, imu, imus, inu) = size.coords(index);
    let (r, _, mu_s, _, _) = texel_parameters(&radii, &size, ir, imu, imus, inu);
    mu_s > 0.17 && r - a.bottom_radius_m < 1e3
}

/// RMS and largest relative difference of `a` from `b` over the sunlit texels of the
/// boundary layer, green channel.
fn difference(a: &[[f32; 3]], b: &[[f32; 3]]) -> (f64, f64) {
    let (mut sum, mut n, mut worst) = (0.0, 0, 0.0f64);
    for (i, (x, y)) in a.iter().zip(b).enumerate() {
        if sunlit_in_the_layer(i) && y[1] > 0.0 {
            let e = f64::from(x[1]) / f64::from(y[1]) - 1.0;
            sum += e * e;
            n += 1;
            worst = worst.max(e.abs());
        }
    }
    ((sum / n as f64).sqrt(), worst)
}

#[test]
fn density_nodes_converge_faster_on_a_boundary_layer() {
    let n = 8;
    let crowded = single(&[&format!("view_samples={n}")]);
    let density = single(&[&format!("view_samples={n}"), "density_nodes=true"]);
    let fine = single(&[&format!("view_samples={}", 4 * n)]);
    for (name, c, d, f) in [
        ("rayleigh", &crowded.0, &density.0, &fine.0),
        ("mie", &crowded.1, &density.1, &fine.1),
    ] {
        let (c_rms, c_max) = difference(c, f);
        let (d_rms, d_max) = difference(d, f);
        eprintln!(
            "{name}: against {} crowded nodes, {n} crowded: RMS {c_rms:.4} max {c_max:.4}; {n} by density: RMS {d_rms:.4} max {d_max:.4}",
            4 * n
        );
        assert!(d_rms < 0.8 * c_rms && d_max < c_max, "{name}");
    }
}
