use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::model::{ModelSettings, ViewRay, prepare};
use std::time::Instant;
fn main() {
    let earth = Atmosphere::preset("earth").unwrap();
    let settings = ModelSettings::default();
    let m = prepare("reference", &earth, &settings).unwrap();
    const ALTITUDES_M: [f64; 6] = [0.0, 1.0, 2_000.0, 10_000.0, 40_000.0, 200_000.0];
    let phi = [
        0.618_033_988_749_895,
        0.754_877_666_246_693,
        0.569_840_290_998_053,
    ];
    for i in 0..200 {
        let f = |k: usize| (0.5 + phi[k] * i as f64).fract();
        let altitude = ALTITUDES_M[i % ALTITUDES_M.len()];
        let (vz, sz, az) = (180.0 * f(0), 100.0 * f(1), 180.0 * f(2));
        let ray = ViewRay::from_angles(earth.bottom_radius_m, altitude, vz, sz, az, None).unwrap();
        let t0 = Instant::now();
        let r = m.radiance(&ray).unwrap();
        let el = t0.elapsed().as_secs_f64();
        let rel: f64 = r
            .radiance
            .iter()
            .zip(&r.radiance_std_error)
            .map(|(l, e)| if *l > 0.0 { e / l } else { 0.0 })
            .fold(0.0, f64::max);
        if el > 0.2 || rel > 0.01 {
            println!(
                "{altitude} vz={vz:.1} sz={sz:.1} az={az:.1}: L={:.3e} rel={rel:.4} t={el:.2}",
                r.radiance[1]
            );
        }
    }
}
