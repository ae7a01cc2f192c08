//! A camera path's camera from a glTF 2.0 file (docs/camera-paths.md, "glTF camera"): a
//! camera node's translation, rotation and scale animation with its parents', sampled at
//! any time, and its scene placed on the planet (glTF's x east, y up, -z north at the
//! placement, turned by its heading).

use std::path::{Path, PathBuf};

use anyhow::{Context, anyhow, bail};
use atmosphere_core::atmosphere::limits::MAX_ALTITUDE_M;
use glam::{DAffine3, DMat3, DQuat, DVec3};
use gltf::animation::Interpolation;
use gltf::animation::util::ReadOutputs;
use gltf::animation::{Channel, Property};
use gltf::camera::Projection;
use render_wgpu::frame::location_rotation;
use render_wgpu::terrain::geo_grid;

use crate::camera_path::file::GltfFile;
use crate::camera_path::keyframe::{TIME_S, within};
use crate::render::scene::AZIMUTH_DEG;

/// The largest glTF file read, bytes (buffers it names are read as they are).
pub const MAX_FILE_BYTES: u64 = 64 << 20;

/// How a sampler moves between its keyframes.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Kind {
    Step,
    Linear,
    /// Hermite with each keyframe's in-tangent, value and out-tangent.
    Cubic,
}

/// One animated property: times, s, and values (x, y, z, w; w unused for vectors).
#[derive(Clone, Debug)]
struct Track {
    kind: Kind,
    times: Vec<f64>,
    values: Vec<[f64; 4]>,
    rotation: bool,
}

impl Track {
    /// The value at `t`, held before the first keyframe and after the last.
    fn at(&self, t: f64) -> [f64; 4] {
        let n = self.times.len();
        let value = |k: usize| match self.kind {
            Kind::Cubic => self.values[3 * k + 1],
            _ => self.values[k],
        };
        if t <= self.times[0] {
            return value(0);
        }
        if t >= self.times[n - 1] {
            return value(n - 1);
        }
        let k = self.times.partition_point(|&x| x <= t) - 1;
        let dt = self.times[k + 1] - self.times[k];
        let s = (t - self.times[k]) / dt;
        let (a, b) = (value(k), value(k + 1));
        match self.kind {
            Kind::Step => a,
            Kind::Linear if self.rotation => {
                let q = quat(a).slerp(quat(b), s);
                [q.x, q.y, q.z, q.w]
            }
            Kind::Linear => std::array::from_fn(|i| a[i] + (b[i] - a[i]) * s),
            Kind::Cubic => {
                let (out_a, in_b) = (self.values[3 * k + 2], self.values[3 * (k + 1)]);
                let (s2, s3) = (s * s, s * s * s);
                let v = std::array::from_fn(|i| {
                    (2.0 * s3 - 3.0 * s2 + 1.0) * a[i]
                        + dt * (s3 - 2.0 * s2 + s) * out_a[i]
                        + (-2.0 * s3 + 3.0 * s2) * b[i]
                        + dt * (s3 - s2) * in_b[i]
                });
                if self.rotation {
                    let q = quat(v).normalize();
                    [q.x, q.y, q.z, q.w]
                } else {
                    v
                }
            }
        }
    }
}

fn quat(v: [f64; 4]) -> DQuat {
    DQuat::from_xyzw(v[0], v[1], v[2], v[3])
}

/// One node of the chain from the scene's root to the camera: its rest transform and the
/// tracks that move it.
#[derive(Clone, Debug)]
struct NodeMotion {
    translation: DVec3,
    rotation: DQuat,
    scale: DVec3,
    tracks: [Option<Track>; 3],
}

impl NodeMotion {
    fn local(&self, t: f64) -> DAffine3 {
        let v = |i: usize| self.tracks[i].as_ref().map(|tr| tr.at(t));
        let translation = v(0).map_or(self.translation, |a| DVec3::new(a[0], a[1], a[2]));
        let rotation = v(1).map_or(self.rotation, |a| quat(a).normalize());
        let scale = v(2).map_or(self.scale, |a| DVec3::new(a[0], a[1], a[2]));
        DAffine3::from_scale_rotation_translation(scale, rotation, translation)
    }
}

/// A glTF camera node's animation, placed on the planet.
#[derive(Clone, Debug)]
pub struct GltfCamera {
    /// The glTF file as read (resolved against the path file).
    pub file: PathBuf,
    /// The camera's vertical field of view (its `yfov`), degrees.
    pub fov_deg: f64,
    /// The animation's last keyframe time, s.
    pub duration_s: f64,
    /// The animation's frame rate, if the table gives one (checked by the path).
    pub fps: Option<f64>,
    /// The unit vector from the planet's centre to the placement.
    pub up: DVec3,
    /// The placement's altitude above the ground sphere, m.
    pub altitude_m: f64,
    /// FNV-1a 64 of the file and its buffers: what the frames' fingerprints see of it.
    pub digest: u64,
    /// The rotation from glTF scene axes to planet axes.
    scene_to_planet: DQuat,
    /// From the scene's root to the camera node.
    chain: Vec<NodeMotion>,
}

/// The rotation from glTF axes (x east, y up, z south) to a place's local frame (x north,
/// y west, z up), the scene's -z turned `heading_deg` from north towards east.
pub fn scene_to_local(heading_deg: f64) -> DQuat {
    let axes = DQuat::from_mat3(&DMat3::from_cols(-DVec3::Y, DVec3::Z, -DVec3::X));
    DQuat::from_rotation_z(-heading_deg.to_radians()) * axes
}

impl GltfCamera {
    /// Reads the `[gltf]` table's file (relative to `origin`, the path file) and checks it;
    /// errors name the file and what is missing or out of range.
    pub fn load(table: &GltfFile, origin: &Path) -> anyhow::Result<GltfCamera> {
        let lat = within("latitude_deg", table.latitude_deg, [-90.0, 90.0])?;
        let lon = within("longitude_deg", table.longitude_deg, [-180.0, 180.0])?;
        let altitude_m = within("altitude_m", table.altitude_m, [0.0, MAX_ALTITUDE_M])?;
        let heading = within("heading_deg", table.heading_deg.unwrap_or(0.0), AZIMUTH_DEG)?;
        let file = match origin.parent() {
            Some(dir) if Path::new(&table.file).is_relative() => dir.join(&table.file),
            _ => PathBuf::from(&table.file),
        };
        let named = || format!("glTF {}", file.display());
        let (fov_deg, duration_s, chain, digest) = read(&file, table).with_context(named)?;
        Ok(GltfCamera {
            fov_deg,
            duration_s,
            fps: table.fps,
            up: geo_grid::direction(lat.to_radians(), lon.to_radians()),
            altitude_m,
            digest,
            scene_to_planet: location_rotation(lat, lon) * scene_to_local(heading),
            chain,
            file,
        })
    }

    /// The camera's position and rotation in the glTF scene's axes at `t` s.
    pub fn scene_pose(&self, t: f64) -> (DVec3, DQuat) {
        let world = self
            .chain
            .iter()
            .fold(DAffine3::IDENTITY, |m, node| m * node.local(t));
        let (_, rotation, translation) = world.to_scale_rotation_translation();
        (translation, rotation.normalize())
    }

    /// The camera's planet-fixed position, m, and rotation (camera axes to planet axes) at
    /// `t` s on a ground sphere of `radius_m`.
    pub fn pose(&self, t: f64, radius_m: f64) -> (DVec3, DQuat) {
        let (p, q) = self.scene_pose(t);
        let origin = self.up * (radius_m + self.altitude_m);
        (
            origin + self.scene_to_planet * p,
            (self.scene_to_planet * q).normalize(),
        )
    }
}

/// FNV-1a 64 of byte slices one after another.
fn fnv1a(parts: &[&[u8]]) -> u64 {
    let mut hash = 0xcbf2_9ce4_8422_2325u64;
    for &byte in parts.iter().flat_map(|p| p.iter()) {
        hash = (hash ^ u64::from(byte)).wrapping_mul(0x0100_0000_01b3);
    }
    hash
}

/// The camera's field of view, the animation's duration, the node chain of `file` and
/// the digest of its bytes.
fn read(file: &Path, table: &GltfFile) -> anyhow::Result<(f64, f64, Vec<NodeMotion>, u64)> {
    let size = std::fs::metadata(file)?.len();
    if size > MAX_FILE_BYTES {
        bail!("{size} bytes; at most {MAX_FILE_BYTES}");
    }
    let bytes = std::fs::read(file)?;
    let gltf = gltf::Gltf::from_slice(&bytes).map_err(|e| match e.to_string() {
        s if s.contains("interpolation") => {
            anyhow!("{s} (a sampler's interpolation is STEP, LINEAR or CUBICSPLINE)")
        }
        s => anyhow!(s),
    })?;
    let document = &gltf.document;
    let buffers = gltf::import_buffers(document, file.parent(), gltf.blob.clone())?;
    let mut parts: Vec<&[u8]> = vec![&bytes];
    parts.extend(buffers.iter().map(|b| b.0.as_slice()));
    let digest = fnv1a(&parts);
    let node_name = |n: &gltf::Node| {
        n.name()
            .map_or_else(|| format!("node {}", n.index()), |s| format!("node {s:?}"))
    };
    let cameras: Vec<gltf::Node> = document.nodes().filter(|n| n.camera().is_some()).collect();
    let camera_node = match &table.camera {
        Some(name) => {
            let node = document
                .nodes()
                .find(|n| n.name() == Some(name.as_str()))
                .with_context(|| format!("no node named {name:?} (camera)"))?;
            if node.camera().is_none() {
                bail!("node {name:?} has no camera");
            }
            node
        }
        None => match cameras.as_slice() {
            [] => bail!("no node has a camera"),
            [one] => one.clone(),
            several => bail!(
                "{} nodes have a camera ({}): name one with camera = \"...\"",
                several.len(),
                several.iter().map(node_name).collect::<Vec<_>>().join(", ")
            ),
        },
    };
    let camera = camera_node
        .camera()
        .context("the camera node has no camera")?;
    let fov_deg = match camera.projection() {
        Projection::Perspective(p) => {
            let fov = f64::from(p.yfov()).to_degrees();
            if !(fov.is_finite() && fov > 0.0 && fov < 180.0) {
                bail!("the camera's yfov is {fov} degrees; it must lie strictly between 0 and 180");
            }
            fov
        }
        _ => bail!(
            "{}'s camera is orthographic; atmos needs a perspective camera",
            node_name(&camera_node)
        ),
    };
    // The chain from the root down to the camera node.
    let mut parent = vec![None; document.nodes().len()];
    for n in document.nodes() {
        for c in n.children() {
            parent[c.index()] = Some(n.index());
        }
    }
    let mut chain = vec![camera_node.index()];
    while let Some(p) = parent[*chain.last().unwrap_or(&0)] {
        if chain.contains(&p) || chain.len() > parent.len() {
            bail!("the node hierarchy has a cycle");
        }
        chain.push(p);
    }
    chain.reverse();
    let moves = |a: &gltf::Animation| {
        a.channels().any(|c| {
            chain.contains(&c.target().node().index())
                && !matches!(c.target().property(), Property::MorphTargetWeights)
        })
    };
    let animation_name = |a: &gltf::Animation| {
        a.name()
            .map_or_else(|| format!("animation {}", a.index()), |s| format!("{s:?}"))
    };
    let animation = match &table.animation {
        Some(name) => document
            .animations()
            .find(|a| a.name() == Some(name.as_str()))
            .with_context(|| format!("no animation named {name:?}"))?,
        None => {
            let found: Vec<_> = document.animations().filter(moves).collect();
            match found.as_slice() {
                [] => bail!(
                    "no animation moves the camera {} or its parents",
                    node_name(&camera_node)
                ),
                [one] => one.clone(),
                several => bail!(
                    "{} animations move the camera ({}): name one with animation = \"...\"",
                    several.len(),
                    several
                        .iter()
                        .map(animation_name)
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            }
        }
    };
    if !moves(&animation) {
        bail!(
            "animation {} does not move the camera {} or its parents",
            animation_name(&animation),
            node_name(&camera_node)
        );
    }
    let mut motions: Vec<NodeMotion> = chain
        .iter()
        .map(|&i| {
            let node = document.nodes().nth(i).expect("index from the document");
            let (t, r, s) = node.transform().decomposed();
            NodeMotion {
                translation: DVec3::from_array(t.map(f64::from)),
                rotation: quat(r.map(f64::from)).normalize(),
                scale: DVec3::from_array(s.map(f64::from)),
                tracks: [None, None, None],
            }
        })
        .collect();
    let mut duration_s: f64 = 0.0;
    for channel in animation.channels() {
        let Some(at) = chain
            .iter()
            .position(|&i| i == channel.target().node().index())
        else {
            continue;
        };
        let slot = match channel.target().property() {
            Property::Translation => 0,
            Property::Rotation => 1,
            Property::Scale => 2,
            Property::MorphTargetWeights => continue,
        };
        let track = track(&channel, &buffers).with_context(|| {
            format!(
                "animation {} channel {}",
                animation_name(&animation),
                channel.index()
            )
        })?;
        duration_s = duration_s.max(*track.times.last().unwrap_or(&0.0));
        motions[at].tracks[slot] = Some(track);
    }
    Ok((fov_deg, duration_s, motions, digest))
}

/// A channel's sampler read and checked.
fn track(channel: &Channel, buffers: &[gltf::buffer::Data]) -> anyhow::Result<Track> {
    let reader = channel.reader(|b| buffers.get(b.index()).map(|d| d.0.as_slice()));
    let times: Vec<f64> = reader
        .read_inputs()
        .context("its sampler's input (times) cannot be read")?
        .map(f64::from)
        .collect();
    let (values, rotation): (Vec<[f64; 4]>, bool) = match reader
        .read_outputs()
        .context("its sampler's output (values) cannot be read")?
    {
        ReadOutputs::Translations(v) | ReadOutputs::Scales(v) => (
            v.map(|a| [a[0], a[1], a[2], 0.0].map(f64::from)).collect(),
            false,
        ),
        ReadOutputs::Rotations(r) => (r.into_f32().map(|a| a.map(f64::from)).collect(), true),
        ReadOutputs::MorphTargetWeights(_) => bail!("morph target weights are not a camera's"),
    };
    let kind = match channel.sampler().interpolation() {
        Interpolation::Step => Kind::Step,
        Interpolation::Linear => Kind::Linear,
        Interpolation::CubicSpline => Kind::Cubic,
    };
    if times.is_empty() {
        bail!("its sampler has no keyframes");
    }
    for w in times.windows(2) {
        if w[1] <= w[0] {
            bail!("its times must increase: {} then {}", w[0], w[1]);
        }
    }
    for &t in &times {
        within("a keyframe time", t, TIME_S)?;
    }
    let per_key = if kind == Kind::Cubic { 3 } else { 1 };
    if values.len() != per_key * times.len() {
        bail!(
            "{} values for {} times; {:?} needs {per_key} a time",
            values.len(),
            times.len(),
            channel.sampler().interpolation()
        );
    }
    if values.iter().flatten().any(|v| !v.is_finite()) {
        bail!("its values must be finite");
    }
    Ok(Track {
        kind,
        times,
        values,
        rotation,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scene_axes_map_to_east_up_north() {
        let q = scene_to_local(0.0);
        // Local frame: x north, y west, z up.
        assert!((q * DVec3::X - -DVec3::Y).length() < 1e-15);
        assert!((q * DVec3::Y - DVec3::Z).length() < 1e-15);
        assert!((q * -DVec3::Z - DVec3::X).length() < 1e-15);
        // Heading 90: the scene's north (-z) points east.
        let q = scene_to_local(90.0);
        assert!((q * -DVec3::Z - -DVec3::Y).length() < 1e-15);
    }

    #[test]
    fn samplers_step_linear_and_cubic() {
        let track = |kind, values: Vec<[f64; 4]>| Track {
            kind,
            times: vec![0.0, 2.0],
            values,
            rotation: false,
        };
        let ends = vec![[0.0; 4], [10.0, 0.0, 0.0, 0.0]];
        assert_eq!(track(Kind::Step, ends.clone()).at(1.9)[0], 0.0);
        assert_eq!(track(Kind::Linear, ends.clone()).at(0.5)[0], 2.5);
        assert_eq!(track(Kind::Linear, ends).at(3.0)[0], 10.0);
        // Tangents of the straight line: cubic equals linear.
        let slope = [5.0, 0.0, 0.0, 0.0];
        let cubic = track(
            Kind::Cubic,
            vec![slope, [0.0; 4], slope, slope, [10.0, 0.0, 0.0, 0.0], slope],
        );
        assert!((cubic.at(0.5)[0] - 2.5).abs() < 1e-12);
        assert_eq!(cubic.at(2.0)[0], 10.0);
    }
}
