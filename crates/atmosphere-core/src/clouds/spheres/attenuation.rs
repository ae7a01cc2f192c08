//! The attenuation textures G_i of Dobashi, Yamamoto and Nishita 2002, section 5.4: the
//! sunlight's attenuation by the clouds between the sun and each point of cloud sphere
//! i. The paper renders them from the sun, drawing the spheres from the outermost in
//! with the frame buffer's blending; here each texel of an equirectangular grid of
//! sphere k (its radius the middle of shell k) holds the optical depth towards the sun,
//! summed over every interval of the sun's ray inside a shell (`shells.rs`) of that
//! shell's mean extinction (`cloud_textures.rs`) times its length, the same sum the
//! paper's blending forms, computed on the sphere's texture grid. A texel whose sun ray
//! meets the ground lies in the planet's shadow and holds exp(-[`SHADOWED_DEPTH`]). As
//! in the paper the texels hold the attenuation ratio exp(-tau): where a texel's
//! neighbours are clear and it is opaque, the ratio's interpolation passes light and the
//! optical depth's would not (at 1,024 texels around the planet, a cloud's edge spans
//! 40 km of one texel). The ratio is read by a quadratic B-spline of 3 x 3 texels
//! (`geo/equirectangular.rs`'s `bspline_taps`), not bilinearly: inside a deck tau runs to
//! tens within a texel or two, and light that goes as exp(-b tau) showed a bilinear
//! read's creases, along the lines between texel centres, as streaks along meridians
//! and parallels (docs/clouds.md, "Limits of the spheres"). The octaves of the light
//! (`field.rs`) read tau = -ln of the interpolated ratio.

use glam::DVec3;
use rayon::prelude::*;

use super::cloud_textures::CloudTextures;
use super::settings::SphereSettings;
use super::shells::Shells;
use crate::clouds::error::CloudError;
use crate::geo::equirectangular::{bspline_taps, direction, lat_lon, texel_centre};

/// The optical depth held in the planet's shadow: exp(-80) is no light, and still a
/// normal f32 on the GPU.
pub const SHADOWED_DEPTH: f64 = 80.0;

/// The m attenuation textures of one sun direction.
#[derive(Clone, Debug, PartialEq)]
pub struct AttenuationTextures {
    width: usize,
    height: usize,
    count: usize,
    sun_direction: DVec3,
    /// `[k][j][i]`: the sun's attenuation ratio exp(-tau) at texel (i, j) of sphere k.
    ratios: Vec<f32>,
}

impl AttenuationTextures {
    /// The textures of `shells` with their `clouds`, for the unit `sun_direction`
    /// (planet-fixed), on grids of `settings.attenuation_width` texels.
    pub fn render(
        shells: &Shells,
        clouds: &CloudTextures,
        sun_direction: DVec3,
        settings: &SphereSettings,
    ) -> Result<AttenuationTextures, CloudError> {
        settings.check()?;
        if !sun_direction.is_finite() || (sun_direction.length() - 1.0).abs() > 1e-6 {
            return Err(CloudError(format!(
                "cloud spheres: the sun direction {sun_direction} is not a unit vector"
            )));
        }
        let (width, height) = (settings.attenuation_width, settings.attenuation_height());
        let count = shells.count as usize;
        let ratios = (0..count * width * height)
            .into_par_iter()
            .map(|n| {
                let k = n / (width * height);
                let texel = n % (width * height);
                let (lat, lon) = texel_centre(width, height, texel % width, texel / width);
                let point = direction(lat, lon) * shells.sphere_radius_m(k);
                (-sun_depth(shells, clouds, point, sun_direction)).exp() as f32
            })
            .collect();
        Ok(AttenuationTextures {
            width,
            height,
            count,
            sun_direction,
            ratios,
        })
    }

    pub fn width(&self) -> usize {
        self.width
    }

    pub fn height(&self) -> usize {
        self.height
    }

    pub fn sun_direction(&self) -> DVec3 {
        self.sun_direction
    }

    /// The texels, `[k][j][i]`, row-major, north first: what the GPU's buffer holds.
    pub fn values(&self) -> &[f32] {
        &self.ratios
    }

    /// The optical depth towards the sun of sphere `k` at the planet-fixed `point`'s
    /// direction: -ln of the ratio read by the quadratic B-spline, at most
    /// [`SHADOWED_DEPTH`].
    pub fn depth(&self, k: usize, point: DVec3) -> f64 {
        let (lat, lon) = lat_lon(point);
        let layer = &self.ratios[k.min(self.count - 1) * self.width * self.height..];
        let ratio: f64 = bspline_taps(self.width, self.height, lat, lon)
            .iter()
            .map(|&(n, w)| w * f64::from(layer[n]))
            .sum();
        (-ratio.max((-SHADOWED_DEPTH).exp()).ln()).min(SHADOWED_DEPTH)
    }
}

/// The optical depth from `point` towards the sun through every shell, or
/// [`SHADOWED_DEPTH`] when the sun's ray meets the ground.
pub fn sun_depth(shells: &Shells, clouds: &CloudTextures, point: DVec3, sun: DVec3) -> f64 {
    let (found, ground) = shells.crossings(point, sun, f64::INFINITY);
    if ground {
        return SHADOWED_DEPTH;
    }
    let depth: f64 = found
        .iter()
        .map(|c| {
            let middle = point + sun * ((c.t0 + c.t1) / 2.0);
            clouds.extinction(c.shell, middle) * (c.t1 - c.t0)
        })
        .sum();
    depth.min(SHADOWED_DEPTH)
}
