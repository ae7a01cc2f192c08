//! The frame planner's rule for light shafts: no shadow test where nothing casts a
//! shadow into the visible lit air. Conservative: a frame with any shadow in the air
//! that some pixel may see keeps the shafts.

use atmosphere_core::models::id::ModelId;
use atmosphere_core::shafts::{Relief, ShadowMap};

use crate::frame::Frame;
use crate::frame::ground_in_view::ground_within;
use crate::frame::plan::FramePlan;
use crate::gpu::error::RenderError;
use crate::shafts::terrain::frame_map::FrameShadow;

/// The shadow map of the frame's drawn terrain (`relief`, `None` when none is drawn)
/// for its light shafts, or `None` with the reason recorded in `plan`: shafts off, no
/// terrain in view, or the planner's rule ([`why_no_shafts`], applied when `prune`).
pub fn plan_shafts<'a, R: Relief + Sync>(
    frame: &Frame,
    relief: Option<&R>,
    shadow: &'a mut FrameShadow,
    prune: bool,
    plan: &mut FramePlan,
) -> Result<Option<&'a ShadowMap>, RenderError> {
    let Some(options) = frame.terrain else {
        return Ok(None);
    };
    let relief = match relief {
        Some(relief) if options.shafts => relief,
        _ => {
            let why = if options.shafts {
                "no terrain in view"
            } else {
                "shafts off"
            };
            plan.skip("shafts", why);
            return Ok(None);
        }
    };
    let sun = frame.sun_direction.normalize();
    let radius_m = frame.atmosphere.bottom_radius_m;
    let map = shadow.update(frame.camera_position_m, sun, radius_m, relief)?;
    match why_no_shafts(frame, map).filter(|_| prune) {
        Some(why) => {
            plan.skip("shafts", why);
            Ok(None)
        }
        None => Ok(Some(map)),
    }
}

/// Why `frame` needs no shafts with the shadow map `map`, or `None` when it may.
pub fn why_no_shafts(frame: &Frame, map: &ShadowMap) -> Option<&'static str> {
    if !matches!(
        frame.model,
        ModelId::Hillaire
            | ModelId::Nishita
            | ModelId::Oneil
            | ModelId::Bruneton
            | ModelId::Dobashi
    ) {
        return Some("the model has no light shafts");
    }
    if map.shadowing_cells == 0 {
        return Some("nothing casts a shadow into the air");
    }
    // From above the shadow volume's top, rays that never dip below it see no shadow:
    // the ground test of a planet as large as that top.
    let top_m = frame.atmosphere.bottom_radius_m + f64::from(map.max_top_m);
    if frame.camera_position_m.length() > top_m {
        let mut shell = frame.clone();
        shell.atmosphere.bottom_radius_m = top_m;
        if !ground_within(&shell, f64::INFINITY) {
            return Some("no shadowed air in view");
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use atmosphere_core::atmosphere::Atmosphere;
    use atmosphere_core::models::sky_model::ModelSettings;
    use atmosphere_core::shafts::GnomonicGrid;
    use glam::DVec3;

    use super::*;
    use crate::frame::look_orientation;

    /// A hillaire frame at `altitude_m` on the z axis looking along `forward`.
    fn frame(altitude_m: f64, forward: DVec3) -> Frame {
        let a = Atmosphere::preset("earth").unwrap();
        let hint = if forward.z.abs() > 0.9 {
            DVec3::X
        } else {
            DVec3::Z
        };
        Frame {
            camera_position_m: DVec3::Z * (a.bottom_radius_m + altitude_m),
            orientation: look_orientation(forward, hint).unwrap(),
            vertical_fov_deg: 40.0,
            sun_direction: DVec3::new(0.1, 0.0, 0.05).normalize(),
            atmosphere: a,
            model: ModelId::Hillaire,
            settings: ModelSettings::default(),
            exposure_ev100: 14.0,
            width: 32,
            height: 18,
            terrain: None,
        }
    }

    /// The shadow of a 1 km block in the middle of a 64-cell grid under a low sun.
    fn block_map(sun: DVec3) -> ShadowMap {
        let grid = GnomonicGrid::new(DVec3::Z, 6_360_000.0, 100.0, 64).unwrap();
        let heights: Vec<f32> = (0..64 * 64)
            .map(|k| {
                if (k % 64, k / 64) == (32, 32) {
                    1_000.0
                } else {
                    0.0
                }
            })
            .collect();
        ShadowMap::new(grid, &heights, sun).unwrap()
    }

    #[test]
    fn shafts_run_only_where_shadowed_air_may_be_seen() {
        let sun = frame(0.0, DVec3::X).sun_direction;
        let map = block_map(sun);
        assert!(map.shadowing_cells > 0);
        // Below the shadow's top looking at the horizon: may see it.
        assert_eq!(why_no_shafts(&frame(500.0, DVec3::X), &map), None);
        // 20 km up looking at the zenith: no ray comes down to 1 km.
        let up = frame(20_000.0, DVec3::new(0.01, 0.0, 1.0));
        assert_eq!(why_no_shafts(&up, &map), Some("no shadowed air in view"));
        // 20 km up looking down: it may.
        assert_eq!(why_no_shafts(&frame(20_000.0, -DVec3::Z), &map), None);
        // The sun overhead: the block casts no shadow into the air.
        let overhead = block_map(DVec3::Z);
        assert_eq!(overhead.shadowing_cells, 0);
        assert_eq!(
            why_no_shafts(&frame(500.0, DVec3::X), &overhead),
            Some("nothing casts a shadow into the air")
        );
        // dobashi has shafts through its sampling planes.
        let mut dobashi = frame(500.0, DVec3::X);
        dobashi.model = ModelId::Dobashi;
        assert_eq!(why_no_shafts(&dobashi, &map), None);
        // A model without shafts.
        let mut riley = frame(500.0, DVec3::X);
        riley.model = ModelId::Riley;
        assert_eq!(
            why_no_shafts(&riley, &map),
            Some("the model has no light shafts")
        );
    }
}
