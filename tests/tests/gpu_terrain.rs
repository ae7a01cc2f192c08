//! The terrain pass on the GPU.

mod support;

use render_wgpu::frame::{LocalView, TerrainOptions, location_rotation};
use support::{frame, renderer_or_skip};

#[test]
fn debug_alps() {
    let Some(mut renderer) = renderer_or_skip("terrain") else {
        return;
    };
    let view = LocalView {
        altitude_m: 5600.0,
        view_zenith_deg: 93.0,
        view_azimuth_deg: -240.0,
        sun_zenith_deg: 84.6,
        sun_azimuth_deg: -251.0,
    };
    let mut f = frame("nishita", view, 60.0, 64, 36);
    let place = location_rotation(46.0, 7.8);
    f.camera_position_m = place * f.camera_position_m;
    f.orientation = place * f.orientation;
    f.sun_direction = place * f.sun_direction;
    f.terrain = Some(TerrainOptions::default());
    let plan = renderer.render(&f).unwrap();
    println!("{plan}");
    let s = renderer.read_surface().unwrap();
    for row in (0..36).step_by(4) {
        let line: Vec<String> = (0..64).step_by(8).map(|c| {
            let t = s[row * 64 + c];
            format!("{:.0}/{:.2}", t.distance_m, t.albedo[1])
        }).collect();
        println!("{row}: {}", line.join(" "));
    }
}
