//! A light's own frame: z along its axis, x and y across it, the frame in which its
//! light map is laid out (Dobashi et al. 2000 Appendix A).

use glam::DVec3;

/// An orthonormal frame about a light's axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightFrame {
    pub x: DVec3,
    pub y: DVec3,
    pub z: DVec3,
}

impl LightFrame {
    /// The frame with z along `axis` and y toward `up` (or, when `up` is absent, toward
    /// +y, or +z for an axis along y). `None` when `axis` is zero or `up` is parallel
    /// to it.
    pub fn new(axis: DVec3, up: Option<DVec3>) -> Option<LightFrame> {
        let z = axis.try_normalize()?;
        let up = up.unwrap_or(if z.y.abs() > 0.99 { DVec3::Z } else { DVec3::Y });
        let x = up.cross(z).try_normalize()?;
        let y = z.cross(x);
        Some(LightFrame { x, y, z })
    }

    /// `v` in this frame's coordinates.
    pub fn local(&self, v: DVec3) -> DVec3 {
        DVec3::new(v.dot(self.x), v.dot(self.y), v.dot(self.z))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_is_orthonormal_and_follows_its_axis() {
        for axis in [DVec3::NEG_Y, DVec3::new(1.0, -2.0, 0.5), DVec3::X] {
            let f = LightFrame::new(axis, None).unwrap();
            assert!((f.z - axis.normalize()).length() < 1e-15);
            assert!(f.x.dot(f.y).abs() < 1e-15 && f.x.dot(f.z).abs() < 1e-15);
            assert!((f.x.cross(f.y) - f.z).length() < 1e-15);
        }
        assert!(LightFrame::new(DVec3::ZERO, None).is_none());
        assert!(LightFrame::new(DVec3::X, Some(DVec3::X)).is_none());
    }
}
