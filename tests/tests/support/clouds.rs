//! What the cloud tests share: multiple-scattering tables, the CPU's sun map of a
//! renderer frame, the CPU's march of a pixel's segment and its composite with the
//! model's pixel.

use atmosphere_core::clouds::layer::composite::composite;
use atmosphere_core::clouds::layer::field::CloudLayer;
use atmosphere_core::clouds::layer::march::{
    CloudLight, CloudSegment, MarchRay, march, march_in_sun_map,
};
use atmosphere_core::clouds::layer::orders::ScatteringOrders;
use atmosphere_core::clouds::layer::segment_upsample::Segment;
use atmosphere_core::clouds::layer::settings::SunLight;
use atmosphere_core::clouds::layer::shadowed_surface::radiance_with_shadowed_surface as shaded;
use atmosphere_core::clouds::layer::sun_map::{CloudSunMap, SunMapResolution};
use atmosphere_core::models::sky_model::{RayRadiance, SkyModel, ViewRay};
use atmosphere_core::optics::legendre_series::LegendreSeries;
use atmosphere_core::optics::surface_lighting::SurfaceHit;
use glam::DVec3;
use render_wgpu::frame::Frame;
use render_wgpu::frame::surface_buffer::SurfaceTexel;

/// Henyey-Greenstein tables, another g at each wavelength so that a swapped channel
/// shows.
pub fn orders() -> ScatteringOrders {
    let series: Vec<LegendreSeries> = [0.84, 0.85, 0.86]
        .iter()
        .map(|&g| LegendreSeries::henyey_greenstein(g, 300))
        .collect();
    ScatteringOrders::new(&series).unwrap()
}

/// The sun map the renderer makes for `layer` in `frame` (its grid under the camera,
/// the default resolution, or `SunMapResolution::LIT` when the layer is lit by it), on
/// the CPU.
pub fn frame_sun_map(layer: &CloudLayer, frame: &Frame) -> CloudSunMap {
    let resolution = match layer.settings().sun_light {
        SunLight::March => SunMapResolution::default(),
        SunLight::Map => SunMapResolution::LIT,
    };
    let grid = CloudSunMap::grid_for(layer.shell(), frame.camera_position_m, &resolution);
    let sun = frame.sun_direction.normalize();
    CloudSunMap::new(layer, grid.unwrap(), sun, &resolution).unwrap()
}

/// The CPU march of `segment` of the ray from `o` along `d`, lit through `map` where the
/// layer's settings say `sun_light = map`: [radiance x 3, transmittance].
pub fn cpu_march(
    layer: &CloudLayer,
    orders: &ScatteringOrders,
    (light, map): (&CloudLight, &CloudSunMap),
    (o, d): (DVec3, DVec3),
    (t0, t1): (f64, f64),
) -> [f64; 4] {
    let light = CloudLight {
        up: (o + d * t0).normalize(),
        ..light.clone()
    };
    let ray = MarchRay {
        origin: o,
        direction: d,
        t0,
        t1,
    };
    let s = layer.settings();
    let c = match s.sun_light {
        SunLight::March => march(layer, &ray, &light, orders, s),
        SunLight::Map => march_in_sun_map(layer, &ray, &light, orders, s, map),
    };
    [
        c.radiance[0],
        c.radiance[1],
        c.radiance[2],
        c.transmittance[0],
    ]
}

/// The segment of the layer that pixel (column, row)'s ray crosses before `texel`.
pub fn pixel_segment(
    layer: &CloudLayer,
    frame: &Frame,
    (column, row): (u32, u32),
    texel: &SurfaceTexel,
) -> Segment {
    let ray = frame.pixel_ray(column, row);
    let end = if texel.distance_m > 0.0 {
        f64::from(texel.distance_m)
    } else {
        f64::INFINITY
    };
    layer
        .shell()
        .first_segment(ray.origin_m, ray.direction, end)
}

/// The CPU's composite of pixel (column, row) with `cloud` (where its ray enters the
/// cloud and the cloud's [radiance x 3, transmittance]): `composite.rs` with the model's
/// answers for the whole ray (ended on the surface, in the shadow of `map`) and for the
/// ray ended at the cloud.
pub fn cpu_pixel(
    model: &dyn SkyModel,
    frame: &Frame,
    (column, row): (u32, u32),
    (texel, map): (&SurfaceTexel, &CloudSunMap),
    cloud: Option<(f64, [f64; 4])>,
) -> RayRadiance {
    let ray = frame.pixel_ray(column, row);
    let full = if texel.distance_m > 0.0 {
        let hit = SurfaceHit {
            distance_m: f64::from(texel.distance_m),
            normal: glam::Vec3::from_array(texel.normal).as_dvec3(),
            albedo: texel.stored_albedo().map(f64::from).to_vec(),
        };
        shaded(model, &frame.atmosphere, &ray, &hit, map).unwrap()
    } else {
        model.radiance(&ray).unwrap()
    };
    let Some((t0, [r, g, b, t])) = cloud else {
        return full;
    };
    let front = if t0 > 0.0 {
        model
            .radiance(&ViewRay {
                max_distance_m: Some(t0),
                ..ray
            })
            .unwrap()
    } else {
        RayRadiance::unattenuated(3)
    };
    let cloud = CloudSegment {
        radiance: vec![r, g, b],
        transmittance: vec![t; 3],
    };
    composite(&full, &front, &cloud)
}
