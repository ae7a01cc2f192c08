//! The rain shaft's and the cirrus layer's geometry against closed forms, the march's
//! transmittance and sky light against the homogeneous slab's closed forms, rain's
//! extinction against the Marshall-Palmer integral, the sky's light averaged over the
//! sphere against another rule, and bad settings named.

use std::f64::consts::PI;

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::hydrometeors::channel_phase::ChannelPhase;
use atmosphere_core::hydrometeors::error::HydrometeorError;
use atmosphere_core::hydrometeors::render::{LitVolume, VolumeLight, march};
use atmosphere_core::hydrometeors::sky_light::sphere_mean_radiance;
use atmosphere_core::hydrometeors::spectral_phase::Particles;
use atmosphere_core::hydrometeors::volumes::{Volume, rain_extinction_per_m};
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::models::sky_model::ViewRay;
use atmosphere_core::optics::mie::marshall_palmer::MarshallPalmer;
use glam::DVec3;

const GROUND_M: f64 = 6_360_000.0;

fn shaft() -> Volume {
    Volume::rain_shaft(DVec3::X * GROUND_M, GROUND_M, 1_000.0, 3_000.0, 5.0).unwrap()
}

fn cirrus(optical_depth: f64) -> Volume {
    let ice = Particles::Ice {
        radius_m: 2e-5,
        length_m: 8e-5,
        rays: 10_000,
    };
    Volume::cirrus(GROUND_M, 8_000.0, 1_000.0, optical_depth, ice).unwrap()
}

#[test]
fn rays_cross_the_shaft_and_the_layer_where_geometry_says() {
    let v = shaft();
    // Level through the axis, 500 m up, from 5 km away: enters at 4 km, leaves at 6 km.
    let origin = DVec3::X * (GROUND_M + 500.0) - DVec3::Y * 5_000.0;
    let (t0, t1) = v.segment(origin, DVec3::Y, f64::INFINITY).unwrap();
    assert!(
        (t0 - 4_000.0).abs() < 1e-6 && (t1 - 6_000.0).abs() < 1e-6,
        "{t0} {t1}"
    );
    // Ended by a surface at 4.5 km; missed above the top and beside it.
    assert_eq!(v.segment(origin, DVec3::Y, 4_500.0).unwrap().1, 4_500.0);
    let above = origin + DVec3::X * 3_000.0;
    assert!(v.segment(above, DVec3::Y, f64::INFINITY).is_none());
    assert!(
        v.segment(origin + DVec3::Z * 1_001.0, DVec3::Y, f64::INFINITY)
            .is_none()
    );
    // From inside, straight up: 2500 m to the top.
    let inside = DVec3::X * (GROUND_M + 500.0);
    assert!((v.exit_distance(inside, DVec3::X) - 2_500.0).abs() < 1e-6);
    // The layer straight up from the ground: 8 to 9 km; from inside, down to its base.
    let c = cirrus(0.3);
    let ground = DVec3::X * (GROUND_M + 2.0);
    let (t0, t1) = c.segment(ground, DVec3::X, f64::INFINITY).unwrap();
    assert!(
        (t0 - 7_998.0).abs() < 1e-6 && (t1 - 8_998.0).abs() < 1e-6,
        "{t0} {t1}"
    );
    let mid = DVec3::X * (GROUND_M + 8_400.0);
    assert!((c.exit_distance(mid, -DVec3::X) - 400.0).abs() < 1e-6);
    assert!((c.extinction_per_m - 3e-4).abs() < 1e-15);
}

#[test]
fn the_march_keeps_the_slabs_closed_forms() {
    // No sun: the sky's light alone, L_sky (1 - e^(-tau_c)), and T_c =
    // e^(-tau_c) whatever the steps, for the vertical crossing of a layer of tau = 2,
    // each channel with its own extinction beta (1 - f_c) (the forward peak out of it).
    let volume = cirrus(2.0);
    let peak_fraction = [0.0, 0.5, 0.75];
    let lit = LitVolume {
        volume,
        phase: ChannelPhase {
            bin_deg: 0.05,
            sky: None,
            values: vec![[1.0 / (4.0 * PI); 3]; 3600],
        },
        peak_fraction,
        light: VolumeLight {
            sun_direction: DVec3::Y,
            sun_irradiance: [0.0; 3],
            sky_radiance: [1.0, 2.0, 3.0],
        },
        orders: None,
    };
    let origin = DVec3::X * (GROUND_M + 2.0);
    let s = march(&lit, origin, DVec3::X, f64::INFINITY).unwrap();
    for c in 0..3 {
        let t = (-2.0 * (1.0 - peak_fraction[c])).exp();
        assert!(
            (s.transmittance[c] / t - 1.0).abs() < 1e-12,
            "{c}: {}",
            s.transmittance[c]
        );
        let exact = lit.light.sky_radiance[c] * (1.0 - t);
        assert!(
            (s.radiance[c] / exact - 1.0).abs() < 1e-12,
            "{c}: {}",
            s.radiance[c]
        );
    }
    // A ray that misses meets nothing.
    assert!(march(&lit, origin, -DVec3::X, f64::INFINITY).is_none());
}

#[test]
fn rain_extinction_is_twice_the_drops_cross_section() {
    // sum n(D) 2 pi r^2 dD = (pi / 2) N0 int D^2 e^(-Lambda D) dD over 0.2 to 6 mm, in
    // closed form, mm^2 to m^2.
    let rain = MarshallPalmer::new(5.0).unwrap();
    let l = rain.slope_per_mm();
    let primitive = |d: f64| -(-l * d).exp() * (d * d / l + 2.0 * d / (l * l) + 2.0 / l.powi(3));
    let exact = PI / 2.0 * 8000.0 * (primitive(6.0) - primitive(0.2)) * 1e-6;
    let numeric = rain_extinction_per_m(&rain);
    assert!((numeric / exact - 1.0).abs() < 1e-4, "{numeric} vs {exact}");
}

#[test]
fn bad_volumes_are_named() {
    let err = |r: Result<Volume, HydrometeorError>| r.unwrap_err().to_string();
    let p = DVec3::X * GROUND_M;
    assert!(err(Volume::rain_shaft(p, GROUND_M, 5.0, 3_000.0, 5.0)).contains("rain shaft radius"));
    assert!(err(Volume::rain_shaft(p, GROUND_M, 1e3, 3e5, 5.0)).contains("rain shaft height"));
    assert!(err(Volume::rain_shaft(p, GROUND_M, 1e3, 3e3, 500.0)).contains("rain rate"));
    assert!(err(Volume::rain_shaft(DVec3::ZERO, GROUND_M, 1e3, 3e3, 5.0)).contains("position"));
    let ice = Particles::Ice {
        radius_m: 2e-5,
        length_m: 8e-5,
        rays: 10_000,
    };
    assert!(err(Volume::cirrus(GROUND_M, 500.0, 1e3, 0.3, ice)).contains("cirrus base"));
    assert!(err(Volume::cirrus(GROUND_M, 8e3, 1e3, f64::NAN, ice)).contains("optical depth"));
    let rain = Particles::Rain {
        rain_rate_mm_h: 5.0,
    };
    assert!(err(Volume::cirrus(GROUND_M, 8e3, 1e3, 0.3, rain)).contains("ice crystals only"));
}

#[test]
fn the_sky_light_is_the_models_radiance_averaged_over_the_sphere() {
    // The sphere's mean by the midpoint rule in the zenith cosine and the azimuth
    // against a Fibonacci lattice of 4096 directions (no symmetry assumed), 500 m up
    // with the sun 30 degrees high: the ground below, lit, and the sky above.
    let atmosphere = Atmosphere::preset("earth").unwrap();
    let model = prepare(ModelId::Nishita, &atmosphere, &Default::default()).unwrap();
    let point = DVec3::X * (atmosphere.bottom_radius_m + 500.0);
    let e = 30f64.to_radians();
    let sun = DVec3::new(e.sin(), e.cos(), 0.0);
    let mean = sphere_mean_radiance(model.as_ref(), point, sun).unwrap();
    let n = 4096;
    let golden = PI * (3.0 - 5f64.sqrt());
    let mut lattice = vec![0.0; mean.len()];
    for k in 0..n {
        let z = 1.0 - 2.0 * (k as f64 + 0.5) / n as f64;
        let r = (1.0 - z * z).sqrt();
        let phi = golden * k as f64;
        let direction = DVec3::new(z, r * phi.cos(), r * phi.sin());
        let answer = model
            .radiance(&ViewRay {
                origin_m: point,
                direction,
                sun_direction: sun,
                max_distance_m: None,
            })
            .unwrap();
        for (l, a) in lattice.iter_mut().zip(&answer.radiance) {
            *l += a / n as f64;
        }
    }
    for (m, l) in mean.iter().zip(&lattice) {
        assert!((m / l - 1.0).abs() < 0.02, "{m} against {l}");
    }
}
