//! A frame's cloud spheres shaded at a reduced resolution and brought to full size by
//! segment, as the layer's interactive march is (`layer/upsample.rs`,
//! `layer/segment_upsample.rs`): the GPU's `clouds/spheres/frame_reduced.wgsl` and
//! `frame_upsample.wgsl` follow this. With `resolution_divisor` k, one ray per k x k
//! pixels is shaded (`spheres_only`), through the full image's fractional pixel of
//! `upsample.rs` and ended on the surface of the full pixel nearest to it, and keeps its
//! span of the layer (`span`: where it runs inside the layer's top sphere, ended on the
//! ground and the surface). A full pixel with no span is clear; otherwise it takes the
//! bilinear taps whose span matches its own (`segment_upsample.rs`'s rule, with the
//! layer's densest extinction), or is shaded itself where none do: the planet's limb,
//! the edge of terrain in front of the cloud. From orbit a texel of the cloud textures
//! spans tens of kilometres, many pixels, so the interpolation loses little there.

use glam::DVec3;

use super::composite::spheres_only;
use super::field::CloudSpheres;
use super::shells::{Shells, roots};
use crate::clouds::error::CloudError;
use crate::clouds::layer::march::CloudLight;
use crate::clouds::layer::orders::ScatteringOrders;
use crate::clouds::layer::segment_upsample::{ReducedMarch, Segment, upsample_by_segment};
use crate::clouds::layer::upsample::{marched_coordinate, nearest_pixel, reduced_size};

/// The stretch (t0, t1) of the ray from `origin` along the unit `direction` inside the
/// sphere of the layer's top, t0 clamped to the origin, ended at `max_distance_m` and
/// where the ray meets the ground (as `Shells::crossings` ends its crossings); `None`
/// when it is empty: the ray crosses no shell.
pub fn span(shells: &Shells, origin: DVec3, direction: DVec3, max_distance_m: f64) -> Segment {
    let r = origin.length();
    let mu = (origin.dot(direction) / r).clamp(-1.0, 1.0);
    let (near, far) = roots(r, mu, shells.base_radius_m + shells.thickness_m)?;
    let ground = match roots(r, mu, shells.ground_radius_m) {
        Some((hit, _)) if hit >= 0.0 && mu < 0.0 => hit,
        _ => f64::INFINITY,
    };
    let (t0, t1) = (near.max(0.0), far.min(max_distance_m).min(ground));
    (t0 < t1).then_some((t0, t1))
}

/// How a frame sees the spheres: its camera's position, its size in pixels, the unit
/// ray through a fractional pixel (pixel x's centre at x), and where the ray of each
/// full pixel ends (its surface's distance, or infinity).
pub struct SphereView<'a> {
    pub origin: DVec3,
    pub size: (u32, u32),
    pub direction: &'a dyn Fn(f64, f64) -> DVec3,
    pub end_m: &'a dyn Fn(u32, u32) -> f64,
}

impl std::fmt::Debug for SphereView<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SphereView")
            .field("origin", &self.origin)
            .field("size", &self.size)
            .finish_non_exhaustive()
    }
}

/// The spheres' image of `view` lit by `light` (three wavelengths), row-major,
/// [radiance at each wavelength, transmittance] per pixel, shaded at `divisor` (the
/// module's rule; 1 shades every pixel).
pub fn spheres_image(
    spheres: &CloudSpheres,
    orders: &ScatteringOrders,
    light: &CloudLight,
    view: &SphereView<'_>,
    divisor: u32,
) -> Result<Vec<[f64; 4]>, CloudError> {
    if light.sun_irradiance.len() != 3 || light.sky_irradiance.len() != 3 {
        return Err(CloudError(format!(
            "cloud spheres' image: a light at {} wavelengths, the image holds 3",
            light.sun_irradiance.len()
        )));
    }
    if divisor == 0 {
        return Err(CloudError(
            "cloud spheres' image: resolution divisor 0".into(),
        ));
    }
    let shade = |direction: DVec3, end_m: f64| {
        let (cloud, _) = spheres_only(spheres, orders, light, view.origin, direction, end_m);
        let r = &cloud.radiance;
        [r[0], r[1], r[2], cloud.transmittance[0]]
    };
    let (width, height) = view.size;
    let full_ray = |x: u32, y: u32| (view.direction)(f64::from(x), f64::from(y));
    if divisor == 1 {
        let pixel = |i: u32| (i % width, i / width);
        return Ok((0..width * height)
            .map(|i| {
                let (x, y) = pixel(i);
                shade(full_ray(x, y), (view.end_m)(x, y))
            })
            .collect());
    }
    let (lw, lh) = reduced_size(width, height, divisor);
    let mut image = Vec::with_capacity((lw * lh) as usize);
    let mut segments = Vec::with_capacity((lw * lh) as usize);
    for j in 0..lh {
        let y = marched_coordinate(j, lh, height);
        for i in 0..lw {
            let x = marched_coordinate(i, lw, width);
            let direction = (view.direction)(x, y);
            let end = (view.end_m)(nearest_pixel(x, width), nearest_pixel(y, height));
            image.push(shade(direction, end));
            segments.push(span(spheres.shells(), view.origin, direction, end));
        }
    }
    let full_segments: Vec<Segment> = (0..height)
        .flat_map(|y| (0..width).map(move |x| (x, y)))
        .map(|(x, y)| {
            span(
                spheres.shells(),
                view.origin,
                full_ray(x, y),
                (view.end_m)(x, y),
            )
        })
        .collect();
    let reduced = ReducedMarch {
        image: &image,
        segments: &segments,
        size: (lw, lh),
        extinction_per_m: spheres.extinction_per_m(),
    };
    Ok(upsample_by_segment(
        &reduced,
        (width, height),
        &full_segments,
        |x, y, _| shade(full_ray(x, y), (view.end_m)(x, y)),
    ))
}
