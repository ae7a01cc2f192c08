//! The frame planner's rule for light shafts: no shadow test where nothing casts a
//! shadow into the visible lit air. Conservative: a frame with any shadow in the air
//! that some pixel may see keeps the shafts.

use atmosphere_core::models::id::ModelId;
use atmosphere_core::shafts::ShadowMap;

use crate::frame::Frame;
use crate::frame::ground_in_view::ground_within;

/// Why `frame` needs no shafts with the shadow map `map`, or `None` when it may.
pub fn why_no_shafts(frame: &Frame, map: &ShadowMap) -> Option<&'static str> {
    if frame.model != ModelId::Hillaire {
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
