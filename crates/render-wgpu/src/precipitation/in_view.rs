//! The planner's rule for rain and ice volumes: a frame runs the volumes pass only when
//! some volume may be in view. A rain shaft is out of view when its bounding sphere lies
//! outside the cone around the view direction that holds every pixel's ray; and the
//! volumes are when the rectangle of pixels they may cover (`screen_rect.rs`) is empty
//! (a layer's too: seen from below, when every pixel's ray meets the ground first).
//! Conservative: a frame it prunes has no pixel whose ray meets a volume.

use atmosphere_core::hydrometeors::render::LitVolume;
use atmosphere_core::hydrometeors::volumes::Shape;

use crate::frame::Frame;
use crate::frame::plan::{FramePlan, StepKind};

use super::screen_rect::volumes_rect;

/// Why the planner leaves the volumes pass out when no volume is in view.
pub const NO_VOLUME_IN_VIEW: &str = "no rain or ice volume in view";

/// Whether `volume` may show in `frame`.
pub fn in_view(frame: &Frame, volume: &LitVolume) -> bool {
    let Shape::Shaft {
        axis,
        ground_radius_m,
        radius_m,
        height_m,
    } = volume.volume.shape
    else {
        return true;
    };
    let centre = axis * (ground_radius_m + 0.5 * height_m) - frame.camera_position_m;
    let bound = radius_m.hypot(0.5 * height_m);
    let distance = centre.length();
    if distance <= bound {
        return true;
    }
    let [_, _, forward] = frame.axes();
    let (half_w, half_h) = frame.half_extent();
    let cone = half_w.hypot(half_h).atan();
    let off_axis = forward
        .normalize()
        .dot(centre / distance)
        .clamp(-1.0, 1.0)
        .acos();
    // A margin of 1e-6 rad keeps rays that graze the sphere in.
    off_axis - cone <= (bound / distance).asin() + 1e-6
}

/// Why `frame` needs no volumes pass, if it does not.
pub fn why_no_volumes(frame: &Frame, volumes: &[LitVolume]) -> Option<&'static str> {
    let none = !volumes.iter().any(|v| in_view(frame, v)) || volumes_rect(frame, volumes).is_none();
    none.then_some(NO_VOLUME_IN_VIEW)
}

/// The volumes' step of `frame` in `plan`: its index, or `None` when there are no
/// volumes or none is in view (the reason recorded).
pub fn plan_volumes(frame: &Frame, volumes: &[LitVolume], plan: &mut FramePlan) -> Option<u32> {
    if volumes.is_empty() {
        return None;
    }
    if let Some(why) = why_no_volumes(frame, volumes) {
        plan.skip("volumes", why);
        return None;
    }
    plan.run("volumes", StepKind::Pass);
    Some(plan.steps.len() as u32 - 1)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::precipitation::test_scene;
    use glam::DVec3;

    fn frame(forward: DVec3) -> Frame {
        test_scene::frame(forward, 50.0)
    }

    fn shaft(ground_m: f64) -> LitVolume {
        test_scene::shaft(ground_m, 5_000.0, 3_000.0)
    }

    /// Whether the ray through any of a grid of points over the image (its edges
    /// included) meets the volume.
    fn any_ray_meets(frame: &Frame, volume: &LitVolume) -> bool {
        (0..=32).any(|i| {
            (0..=18).any(|j| {
                let x = f64::from(frame.width) * f64::from(i) / 32.0;
                let y = f64::from(frame.height) * f64::from(j) / 18.0;
                let d = frame.direction_through(x, y).normalize();
                volume
                    .volume
                    .segment(frame.camera_position_m, d, f64::INFINITY)
                    .is_some()
            })
        })
    }

    #[test]
    fn a_pruned_frame_has_no_ray_that_meets_the_shaft() {
        let (mut pruned, mut kept) = (0, 0);
        for k in 0..72 {
            let angle = f64::from(k) * 5f64.to_radians();
            let forward = DVec3::new(0.2, angle.cos(), angle.sin()).normalize();
            let f = frame(forward);
            let volumes = [shaft(f.atmosphere.bottom_radius_m)];
            match why_no_volumes(&f, &volumes) {
                Some(why) => {
                    assert_eq!(why, NO_VOLUME_IN_VIEW);
                    assert!(!any_ray_meets(&f, &volumes[0]), "{k}");
                    pruned += 1;
                }
                None => kept += 1,
            }
        }
        assert!(pruned > 20 && kept > 5, "{pruned} pruned, {kept} kept");
        assert_eq!(
            why_no_volumes(&frame(DVec3::Y), &[]),
            Some(NO_VOLUME_IN_VIEW)
        );
    }
}
