//! The cloud layer on the planet: a cover grid, a shell and the droplets, answering the
//! extinction at any point ([`CloudMedium`]), so the march and the path tracer read the
//! same medium. Positions are planet-fixed, in metres from the planet's centre.

use glam::DVec3;

use super::profile::{density, detail_erosion, vertical_profile};
use super::settings::LayerSettings;
use super::shell::Shell;
use crate::clouds::cover::grid::CoverGrid;
use crate::clouds::error::{CloudError, check_range};
use crate::clouds::medium::CloudMedium;
use crate::clouds::phase::CloudPhase;

/// The layer: settings checked, cover, shell, phase function.
#[derive(Clone, Debug)]
pub struct CloudLayer {
    settings: LayerSettings,
    cover: CoverGrid,
    shell: Shell,
    phase: CloudPhase,
}

impl CloudLayer {
    /// The layer on a planet of radius `bottom_radius_m` (1e3 to 1e8 m) with `cover`;
    /// refuses settings out of their ranges by name.
    pub fn new(
        settings: LayerSettings,
        bottom_radius_m: f64,
        cover: CoverGrid,
        phase: CloudPhase,
    ) -> Result<CloudLayer, CloudError> {
        settings.check()?;
        check_range("planet bottom_radius_m", bottom_radius_m, 1e3, 1e8)?;
        let (base_radius_m, top_radius_m) = settings.radii_m(bottom_radius_m);
        Ok(CloudLayer {
            settings,
            cover,
            shell: Shell {
                ground_radius_m: bottom_radius_m,
                base_radius_m,
                top_radius_m,
            },
            phase,
        })
    }

    pub fn settings(&self) -> &LayerSettings {
        &self.settings
    }

    pub fn shell(&self) -> &Shell {
        &self.shell
    }

    pub fn cover(&self) -> &CoverGrid {
        &self.cover
    }

    /// The density, 0 to 1, at `point`: cover x profile x erosion by `detail_octaves`
    /// octaves of noise.
    pub fn density(&self, point: DVec3) -> f64 {
        self.density_with_octaves(point, self.settings.detail_octaves)
    }

    /// The density with `octaves` octaves of detail noise: the view march reads
    /// `detail_octaves`, the sun's shadow march `shadow_octaves`.
    pub fn density_with_octaves(&self, point: DVec3, octaves: u32) -> f64 {
        let s = &self.settings;
        let x = (point.length() - self.shell.base_radius_m) / s.thickness_m;
        if !(0.0..=1.0).contains(&x) {
            return 0.0;
        }
        let cover = (self.cover.sample(point) * s.coverage_scale).min(1.0);
        // Above the cloud's top (or at its base) no noise can give it density.
        if cover <= 0.0 || vertical_profile(x, cover) <= 0.0 {
            return 0.0;
        }
        density(
            x,
            cover,
            detail_erosion(point, s.detail_scale_m, s.detail_strength, octaves),
        )
    }
}

impl CloudMedium for CloudLayer {
    fn extinction(&self, position: DVec3) -> f64 {
        self.settings.extinction_per_m * self.density(position)
    }

    fn light_extinction(&self, position: DVec3) -> f64 {
        self.settings.extinction_per_m
            * self.density_with_octaves(position, self.settings.shadow_octaves)
    }

    fn single_scattering_albedo(&self, _position: DVec3) -> f64 {
        self.settings.albedo
    }

    fn phase(&self) -> &CloudPhase {
        &self.phase
    }

    fn majorant(&self) -> f64 {
        self.settings.extinction_per_m
    }

    fn distance_to_boundary(&self, position: DVec3, direction: DVec3) -> f64 {
        self.shell.exit_distance(position, direction)
    }
}
