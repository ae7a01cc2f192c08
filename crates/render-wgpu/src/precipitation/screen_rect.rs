//! The pixels a frame's rain and ice volumes may cover: the rectangle the volumes pass
//! runs over, the rest of the frame keeping the model's pixels. A rain shaft's is the
//! projection of the box around its cylinder (its eight corners; the whole frame when a
//! corner is not in front of the camera). A cirrus layer or a droplet deck seen from
//! below its base is reached only by rays that miss the ground, d . up > -s |d| with s
//! the sine of the horizon's dip: its rectangle bounds the frame's part of the
//! half-plane d . up >= -s max |d| (linear in the pixel's position); seen from inside or
//! above, the whole frame. A pixel of margin all round.

use atmosphere_core::clouds::layer::shell::Shell;
use atmosphere_core::hydrometeors::render::LitVolume;
use atmosphere_core::hydrometeors::volumes::Shape;

use crate::frame::Frame;

/// A rectangle of pixels: its top-left corner and its size.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PixelRect {
    pub origin: [u32; 2],
    pub size: [u32; 2],
}

impl PixelRect {
    /// Whether pixel (column, row) lies inside.
    pub fn contains(&self, column: u32, row: u32) -> bool {
        (self.origin[0]..self.origin[0] + self.size[0]).contains(&column)
            && (self.origin[1]..self.origin[1] + self.size[1]).contains(&row)
    }
}

/// Bounds (x0, y0, x1, y1) holding none.
const EMPTY: [f64; 4] = [
    f64::INFINITY,
    f64::INFINITY,
    f64::NEG_INFINITY,
    f64::NEG_INFINITY,
];

fn extend(b: [f64; 4], (x, y): (f64, f64)) -> [f64; 4] {
    [b[0].min(x), b[1].min(y), b[2].max(x), b[3].max(y)]
}

/// The pixel bounds (x0, y0, x1, y1) of `volume` in `frame`, unclamped; `None`: any.
fn bounds(frame: &Frame, volume: &LitVolume) -> Option<[f64; 4]> {
    match volume.volume.shape {
        Shape::Shaft {
            axis,
            ground_radius_m,
            radius_m,
            height_m,
        } => shaft_bounds(frame, (axis, ground_radius_m), radius_m, height_m),
        Shape::Layer(shell) => layer_bounds(frame, &shell),
    }
}

/// A layer's bounds: the frame's part where d . up >= -s max |d|, from below its base.
fn layer_bounds(frame: &Frame, shell: &Shell) -> Option<[f64; 4]> {
    let r = frame.camera_position_m.length();
    if r >= shell.base_radius_m || r <= shell.ground_radius_m {
        return None;
    }
    let up = frame.camera_position_m / r;
    let dip = (1.0 - (shell.ground_radius_m / r).powi(2)).sqrt();
    let (half_w, half_h) = frame.half_extent();
    let longest = (1.0 + half_w * half_w + half_h * half_h).sqrt();
    let side = |(x, y): (f64, f64)| frame.direction_through(x, y).dot(up) + dip * longest;
    let (width, height) = (f64::from(frame.width), f64::from(frame.height));
    let corners = [(0.0, 0.0), (width, 0.0), (width, height), (0.0, height)];
    let mut b = EMPTY;
    for k in 0..4 {
        let (p, q) = (corners[k], corners[(k + 1) % 4]);
        let (fp, fq) = (side(p), side(q));
        if fp >= 0.0 {
            b = extend(b, p);
        }
        if (fp >= 0.0) != (fq >= 0.0) {
            let s = fp / (fp - fq);
            b = extend(b, (p.0 + s * (q.0 - p.0), p.1 + s * (q.1 - p.1)));
        }
    }
    Some(b)
}

/// A shaft's bounds: the projection of the box around its cylinder.
fn shaft_bounds(
    frame: &Frame,
    (axis, ground_radius_m): (glam::DVec3, f64),
    radius_m: f64,
    height_m: f64,
) -> Option<[f64; 4]> {
    let [right, up, forward] = frame.axes();
    let (half_w, half_h) = frame.half_extent();
    let (width, height) = (f64::from(frame.width), f64::from(frame.height));
    let u = axis.any_orthonormal_vector();
    let v = axis.cross(u);
    let foot = axis * ground_radius_m - frame.camera_position_m;
    let mut b = [
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    ];
    for k in 0..8 {
        let side = |bit: u32| if k & bit == 0 { -radius_m } else { radius_m };
        let along = if k & 4 == 0 { 0.0 } else { height_m };
        let corner = foot + axis * along + u * side(1) + v * side(2);
        let z = corner.dot(forward);
        if z <= 1e-3 * corner.length() {
            return None;
        }
        let x = 0.5 * (1.0 + corner.dot(right) / (z * half_w)) * width;
        let y = 0.5 * (1.0 - corner.dot(up) / (z * half_h)) * height;
        b = extend(b, (x, y));
    }
    Some(b)
}

/// The rectangle of `frame`'s pixels that `volumes` may cover; `None` when they cover
/// none.
pub fn volumes_rect(frame: &Frame, volumes: &[LitVolume]) -> Option<PixelRect> {
    let (width, height) = (f64::from(frame.width), f64::from(frame.height));
    let whole = [0.0, 0.0, width, height];
    let mut b = [
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    ];
    for volume in volumes {
        let v = bounds(frame, volume).unwrap_or(whole);
        b = [
            b[0].min(v[0]),
            b[1].min(v[1]),
            b[2].max(v[2]),
            b[3].max(v[3]),
        ];
    }
    // A pixel of margin, then the frame.
    let x0 = (b[0] - 1.0).floor().clamp(0.0, width);
    let y0 = (b[1] - 1.0).floor().clamp(0.0, height);
    let x1 = (b[2] + 1.0).ceil().clamp(0.0, width);
    let y1 = (b[3] + 1.0).ceil().clamp(0.0, height);
    (x1 > x0 && y1 > y0).then_some(PixelRect {
        origin: [x0 as u32, y0 as u32],
        size: [(x1 - x0) as u32, (y1 - y0) as u32],
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::precipitation::test_scene;
    use atmosphere_core::hydrometeors::scene::CirrusSettings;
    use glam::DVec3;

    fn frame(forward: DVec3) -> Frame {
        test_scene::frame(forward, 60.0)
    }

    fn shaft(ground_m: f64) -> LitVolume {
        test_scene::shaft(ground_m, 3_000.0, 2_000.0)
    }

    /// Turning the camera round a shaft: every pixel whose ray meets it lies in the
    /// rectangle, and looking at it from the side the rectangle leaves pixels out.
    #[test]
    fn every_pixel_that_meets_the_shaft_is_in_the_rectangle() {
        let mut narrowed = 0;
        for k in 0..24 {
            let angle = f64::from(k) * 15f64.to_radians();
            let forward = DVec3::new(0.1, angle.cos(), angle.sin()).normalize();
            let f = frame(forward);
            let volumes = [shaft(f.atmosphere.bottom_radius_m)];
            let rect = volumes_rect(&f, &volumes);
            let mut met = 0;
            for row in 0..f.height {
                for column in 0..f.width {
                    let d = f.pixel_ray(column, row).direction;
                    let meets = volumes[0]
                        .volume
                        .segment(f.camera_position_m, d, f64::INFINITY)
                        .is_some();
                    if meets {
                        met += 1;
                        assert!(rect.is_some_and(|r| r.contains(column, row)), "{k}");
                    }
                }
            }
            if let Some(r) = rect
                && met > 0
                && r.size[0] * r.size[1] < f.width * f.height
            {
                narrowed += 1;
            }
        }
        assert!(narrowed >= 3, "{narrowed}");
    }

    /// Pitching the camera from 40 degrees down to 40 up under a cirrus layer: every
    /// pixel whose ray meets the layer lies in the rectangle, which leaves out the rows
    /// under the horizon, and none when every ray meets the ground.
    #[test]
    fn every_pixel_that_meets_a_layer_from_below_is_in_the_rectangle() {
        let mut narrowed = 0;
        for k in -8..=8 {
            let pitch = f64::from(k) * 5f64.to_radians();
            let f = frame(DVec3::new(pitch.sin(), pitch.cos(), 0.0));
            let ground = f.atmosphere.bottom_radius_m;
            let cirrus = CirrusSettings::default().volume(ground, 20.0).unwrap();
            let volumes = [LitVolume {
                volume: cirrus,
                ..shaft(ground)
            }];
            let rect = volumes_rect(&f, &volumes);
            for row in 0..f.height {
                for column in 0..f.width {
                    let d = f.pixel_ray(column, row).direction;
                    if volumes[0]
                        .volume
                        .segment(f.camera_position_m, d, f64::INFINITY)
                        .is_some()
                    {
                        assert!(rect.is_some_and(|r| r.contains(column, row)), "{k}");
                    }
                }
            }
            if rect.is_none_or(|r| r.size[1] < f.height) {
                narrowed += 1;
            }
        }
        assert!(narrowed >= 8, "{narrowed}");
        let down = frame(DVec3::new(-1.0, 0.01, 0.0).normalize());
        let ground = down.atmosphere.bottom_radius_m;
        let volumes = [LitVolume {
            volume: CirrusSettings::default().volume(ground, 20.0).unwrap(),
            ..shaft(ground)
        }];
        assert_eq!(volumes_rect(&down, &volumes), None);
    }
}
