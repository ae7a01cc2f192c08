//! Scripted camera paths (docs/camera-paths.md): a TOML file of keyframes, and the frame
//! at any time between them, every field interpolated.

pub mod file;
pub mod gltf_camera;
pub mod keyframe;
pub mod orientation;
pub mod position;
pub mod spline;
pub mod sun;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use anyhow::{Context, anyhow, bail};
use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::atmosphere::limits::MAX_ALTITUDE_M;
use atmosphere_core::atmosphere::text_file::{TOML_LIMITS, read_text};
use render_wgpu::Frame;
use render_wgpu::frame::{MAX_SIDE_PX, TerrainOptions};

use crate::camera_path::file::{
    GltfFile, KeyframeFile, PathHeader, location, parse_file, write_file,
};
use crate::camera_path::gltf_camera::GltfCamera;
use crate::camera_path::keyframe::{
    Key, aim_at, local_orientation, place_rotation, resolve, within,
};
use crate::camera_path::orientation::OrientationSpline;
use crate::camera_path::position::PositionSpline;

/// Frame rates a path may ask for, frames per second.
pub const FPS: [f64; 2] = [0.001, 1000.0];
/// The most keyframes in one path.
pub const MAX_KEYFRAMES: usize = 10_000;
/// The default frame rate and image size.
pub const DEFAULT_FPS: f64 = 30.0;
pub const DEFAULT_SIZE_PX: (u32, u32) = (1280, 720);

/// A checked camera path; see the module documentation.
#[derive(Clone, Debug)]
pub struct CameraPath {
    origin: PathBuf,
    fps: f64,
    log_altitude_base_m: f64,
    size_px: (u32, u32),
    written: Vec<KeyframeFile>,
    keys: Vec<Key>,
    atmospheres: BTreeMap<String, Atmosphere>,
    position: PositionSpline,
    orientation: OrientationSpline,
    /// The camera from a glTF animation, if the path has a `[gltf]` table.
    gltf: Option<(GltfFile, GltfCamera)>,
}

/// A keyframe's camera, in the form frames are built from.
struct Camera {
    up: glam::DVec3,
    altitude_m: f64,
    local_orientation: glam::DQuat,
}

impl CameraPath {
    /// Reads and checks a path file; errors name the file, line and column, the field.
    pub fn load(path: &Path) -> anyhow::Result<CameraPath> {
        let text = read_text(path, TOML_LIMITS)
            .with_context(|| format!("camera path {}", path.display()))?;
        CameraPath::parse(&text, path)
    }

    /// The same from text (`origin` names it in errors and resolves relative files).
    pub fn parse(text: &str, origin: &Path) -> anyhow::Result<CameraPath> {
        let file = parse_file(text, origin)?;
        let gltf = match &file.gltf {
            Some(table) => Some(gltf_camera(table, &file.keyframe, origin, text)?),
            None => None,
        };
        let gltf_fps = gltf.as_ref().and_then(|(_, g)| g.fps);
        let fps = within("fps", file.fps.or(gltf_fps).unwrap_or(DEFAULT_FPS), FPS)
            .map_err(|e| anyhow!("camera path {}: {e}", origin.display()))?;
        let size_px = (
            file.width.unwrap_or(DEFAULT_SIZE_PX.0),
            file.height.unwrap_or(DEFAULT_SIZE_PX.1),
        );
        for (side, field) in [(size_px.0, "width"), (size_px.1, "height")] {
            if !(1..=MAX_SIDE_PX).contains(&side) {
                bail!(
                    "camera path {}: {field} {side} must be 1 to {MAX_SIDE_PX} px",
                    origin.display()
                );
            }
        }
        if file.keyframe.is_empty() || file.keyframe.len() > MAX_KEYFRAMES {
            bail!(
                "camera path {}: {} keyframes; a path has 1 to {MAX_KEYFRAMES} [[keyframe]] tables",
                origin.display(),
                file.keyframe.len()
            );
        }
        let mut atmospheres = BTreeMap::new();
        let mut keys: Vec<Key> = Vec::with_capacity(file.keyframe.len());
        for (n, spanned) in file.keyframe.iter().enumerate() {
            // With a glTF camera the first keyframe is placed at the scene's origin.
            let placed = match &gltf {
                Some((table, camera)) if n == 0 => Some(KeyframeFile {
                    latitude_deg: Some(table.latitude_deg),
                    longitude_deg: Some(table.longitude_deg),
                    altitude_m: Some(table.altitude_m),
                    fov_deg: Some(camera.fov_deg),
                    ..spanned.get_ref().clone()
                }),
                _ => None,
            };
            let written = placed.as_ref().unwrap_or(spanned.get_ref());
            let key = resolve(written, keys.last(), origin, &mut atmospheres).map_err(|e| {
                anyhow!(
                    "camera path {}: keyframe {} (time_s {}): {e:#}",
                    location(origin, text, spanned.span().start),
                    n + 1,
                    spanned.get_ref().time_s
                )
            })?;
            keys.push(key);
        }
        for (n, pair) in keys.windows(2).enumerate() {
            let degrees = pair[0].up.angle_between(pair[1].up).to_degrees();
            if degrees > MAX_ARC_DEG {
                bail!(
                    "camera path {}: keyframes {} and {} are {degrees:.1} degrees apart round the planet; at most {MAX_ARC_DEG} (add a keyframe between them)",
                    location(origin, text, file.keyframe[n + 1].span().start),
                    n + 1,
                    n + 2
                );
            }
        }
        let base_m = within(
            "log_altitude_base_m",
            file.log_altitude_base_m.unwrap_or(0.0),
            [0.0, MAX_ALTITUDE_M],
        )
        .map_err(|e| anyhow!("camera path {}: {e}", origin.display()))?;
        if let Some(k) = keys.iter().position(|k| k.altitude_m < base_m) {
            bail!(
                "camera path {}: keyframe {}'s altitude_m {} is below log_altitude_base_m {base_m}",
                location(origin, text, file.keyframe[k].span().start),
                k + 1,
                keys[k].altitude_m
            );
        }
        let times: Vec<f64> = keys.iter().map(|k| k.time_s).collect();
        let ups: Vec<_> = keys.iter().map(|k| k.up).collect();
        let altitudes: Vec<f64> = keys.iter().map(|k| k.altitude_m).collect();
        let rotations: Vec<_> = keys.iter().map(|k| k.local_orientation).collect();
        Ok(CameraPath {
            origin: origin.to_path_buf(),
            fps,
            log_altitude_base_m: base_m,
            size_px,
            // Written back with atmosphere files as resolved, so the text stands alone.
            written: file
                .keyframe
                .iter()
                .zip(&keys)
                .map(|(s, k)| KeyframeFile {
                    atmosphere: s
                        .get_ref()
                        .atmosphere
                        .as_ref()
                        .map(|_| k.atmosphere.clone()),
                    ..s.get_ref().clone()
                })
                .collect(),
            position: PositionSpline::new(&times, &ups, &altitudes, base_m),
            orientation: OrientationSpline::new(&times, &rotations),
            keys,
            atmospheres,
            // Written back with the glTF file as resolved, as atmosphere files are.
            gltf: gltf.map(|(table, g)| {
                let file = g.file.display().to_string();
                (GltfFile { file, ..table }, g)
            }),
        })
    }

    /// A path of keyframes as written in a file with `header` (each checked as [`parse`]
    /// checks a file; `origin` names it in errors and resolves relative atmosphere files).
    ///
    /// [`parse`]: CameraPath::parse
    pub fn from_keyframes(
        header: &PathHeader,
        keyframes: &[KeyframeFile],
        origin: &Path,
    ) -> anyhow::Result<CameraPath> {
        CameraPath::parse(&write_file(header, None, keyframes)?, origin)
    }

    /// The keyframes as written (atmosphere files as resolved).
    pub fn keyframes(&self) -> &[KeyframeFile] {
        &self.written
    }

    /// The frame rate, image size and log altitude base.
    pub fn header(&self) -> PathHeader {
        PathHeader {
            fps: self.fps,
            size_px: self.size_px,
            log_altitude_base_m: self.log_altitude_base_m,
        }
    }

    /// Time of the last keyframe, s (the first is at 0 or later; frames start at time 0).
    pub fn duration_s(&self) -> f64 {
        let keys = self.keys.last().map_or(0.0, |k| k.time_s);
        self.gltf
            .as_ref()
            .map_or(keys, |(_, g)| keys.max(g.duration_s))
    }

    /// The path file's frame rate (default 30 fps).
    pub fn fps(&self) -> f64 {
        self.fps
    }

    /// The path file's image size (default 1280x720).
    pub fn size_px(&self) -> (u32, u32) {
        self.size_px
    }

    /// Frames at `fps` from time 0 to the last keyframe inclusive: floor(duration * fps +
    /// 1e-9) + 1.
    pub fn frame_count(&self, fps: f64) -> usize {
        (self.duration_s() * fps + 1e-9).floor() as usize + 1
    }

    /// The keyframes with every field known.
    pub fn keys(&self) -> &[Key] {
        &self.keys
    }

    /// Whether the exposure at `time_s` is metered from the frame (`auto_exposure`, a
    /// discrete field: the keyframe's in effect) rather than the path's `exposure`.
    pub fn auto_exposure_at(&self, time_s: f64) -> bool {
        let t = time_s.clamp(self.keys[0].time_s, self.duration_s());
        self.keys[self.segment(t)].auto_exposure
    }

    /// The index of the keyframe that starts the segment holding `t`, or that `t` falls on.
    fn segment(&self, t: f64) -> usize {
        self.keys
            .partition_point(|k| k.time_s <= t)
            .saturating_sub(1)
    }

    /// The frame at `time_s` (clamped to [0, duration]) at `width` x `height`: camera,
    /// sun, atmosphere, model and settings, exposure, terrain, all interpolated.
    pub fn frame_at(&self, time_s: f64, width: u32, height: u32) -> anyhow::Result<Frame> {
        if !time_s.is_finite() {
            bail!(
                "camera path {}: time {time_s} s must be finite",
                self.origin.display()
            );
        }
        let t = time_s.clamp(self.keys[0].time_s, self.duration_s());
        // The segment [keys[i], keys[i + 1]] holding t, or the keyframe t falls on.
        let i = self.segment(t);
        let key = &self.keys[i];
        let pose = self.gltf.as_ref().map(|(_, g)| {
            g.pose(
                time_s.clamp(0.0, self.duration_s()),
                self.atmospheres[&key.atmosphere].bottom_radius_m,
            )
        });
        // The sun by angles is at the camera: the glTF camera's place when it has one.
        let sun_place = |up: glam::DVec3| {
            place_rotation(pose.and_then(|(p, _)| p.try_normalize()).unwrap_or(up))
        };
        let mut frame = if i + 1 == self.keys.len() || key.time_s == t {
            let camera = Camera {
                up: key.up,
                altitude_m: key.altitude_m,
                local_orientation: key.local_orientation,
            };
            let sun = sun::direction(key.sun, sun_place(key.up))?;
            self.build(key, &camera, sun, Blend::none(key), width, height)?
        } else {
            let next = &self.keys[i + 1];
            let h = (t - key.time_s) / (next.time_s - key.time_s);
            let e = next.easing.apply(h);
            let (up, altitude_m) = self.position.at(i, h).with_context(|| {
                format!(
                    "camera path {}: between keyframes {} and {} the camera passes the planet's centre",
                    self.origin.display(),
                    i + 1,
                    i + 2
                )
            })?;
            let local_orientation = match (key.target_m, next.target_m) {
                // Both ends look at one target: track it all the way.
                (Some(a), Some(b)) if a == b => {
                    let radius_m = self.atmospheres[&key.atmosphere].bottom_radius_m;
                    let (heading, pitch) = aim_at(up, up * (radius_m + altitude_m), a)
                        .with_context(|| {
                            format!(
                                "camera path {}: at {t} s the camera is at its look-at target",
                                self.origin.display()
                            )
                        })?;
                    let roll = key.roll_deg + (next.roll_deg - key.roll_deg) * e;
                    local_orientation(heading, pitch, roll)
                }
                _ => self.orientation.at(i, h),
            };
            let camera = Camera {
                up,
                altitude_m,
                local_orientation,
            };
            let sun = sun::between(
                (key.sun, place_rotation(key.up)),
                (next.sun, place_rotation(next.up)),
                (h, e),
                sun_place(up),
            )?;
            self.build(
                key,
                &camera,
                sun,
                Blend::between(key, next, e),
                width,
                height,
            )?
        };
        if let Some((position_m, orientation)) = pose {
            frame.camera_position_m = position_m;
            frame.orientation = orientation;
        }
        frame
            .validate()
            .with_context(|| format!("camera path {} at {t} s", self.origin.display()))?;
        Ok(frame)
    }

    /// The frame of a camera, a sun and blended parameters; the discrete fields
    /// (atmosphere, model, settings, terrain) are `key`'s.
    fn build(
        &self,
        key: &Key,
        camera: &Camera,
        sun_direction: glam::DVec3,
        blend: Blend,
        width: u32,
        height: u32,
    ) -> anyhow::Result<Frame> {
        let mut atmosphere =
            self.atmospheres[&key.atmosphere].with_aerosol_scale(blend.aerosol_scale);
        if let Some(albedo) = blend.ground_albedo {
            atmosphere.ground_albedo = albedo;
        }
        let ground_m = atmosphere.bottom_radius_m;
        let mut camera_m = camera.up * (ground_m + camera.altitude_m);
        // Rounding may put a camera on the ground a hair below it.
        if camera_m.length() < ground_m {
            camera_m *= ground_m / camera_m.length() * (1.0 + 4.0 * f64::EPSILON);
        }
        Ok(Frame {
            camera_position_m: camera_m,
            orientation: place_rotation(camera.up) * camera.local_orientation,
            vertical_fov_deg: blend.fov_deg,
            sun_direction,
            atmosphere,
            model: key.model,
            settings: key.settings.clone(),
            exposure_ev100: blend.exposure_ev100,
            width,
            height,
            terrain: key.terrain.then_some(TerrainOptions {
                exaggeration: blend.exaggeration,
                ..TerrainOptions::default()
            }),
        })
    }

    /// The path as TOML (for the EXR header of each frame, so a frame says what made it).
    pub fn to_toml(&self) -> String {
        let gltf = self.gltf.as_ref().map(|(table, _)| table);
        let text =
            write_file(&self.header(), gltf, &self.written).unwrap_or_else(|e| format!("# {e}\n"));
        // The glTF file's contents, so that frames of a changed file differ in fingerprint.
        match &self.gltf {
            Some((_, g)) => format!(
                "{text}# [gltf] file and buffers: FNV-1a 64 {:016x}\n",
                g.digest
            ),
            None => text,
        }
    }
}

/// The largest arc round the planet between two keyframes' places, degrees.
pub const MAX_ARC_DEG: f64 = 150.0;

/// The continuous parameters of a frame.
struct Blend {
    fov_deg: f64,
    exposure_ev100: f64,
    aerosol_scale: f64,
    ground_albedo: Option<f64>,
    exaggeration: f64,
}

impl Blend {
    fn none(k: &Key) -> Blend {
        Blend {
            fov_deg: k.fov_deg,
            exposure_ev100: k.exposure_ev100,
            aerosol_scale: k.aerosol_scale,
            ground_albedo: k.ground_albedo,
            exaggeration: k.exaggeration,
        }
    }

    fn between(a: &Key, b: &Key, e: f64) -> Blend {
        let lerp = |x: f64, y: f64| x + (y - x) * e;
        Blend {
            fov_deg: lerp(a.fov_deg, b.fov_deg),
            exposure_ev100: lerp(a.exposure_ev100, b.exposure_ev100),
            aerosol_scale: lerp(a.aerosol_scale, b.aerosol_scale),
            ground_albedo: match (a.ground_albedo, b.ground_albedo) {
                (Some(x), Some(y)) => Some(lerp(x, y)),
                (x, _) => x,
            },
            exaggeration: lerp(a.exaggeration, b.exaggeration),
        }
    }
}

/// Keyframe fields that place or aim the camera: a glTF camera gives them all.
const CAMERA_FIELDS: [&str; 10] = [
    "latitude_deg",
    "longitude_deg",
    "altitude_m",
    "position_m",
    "heading_deg",
    "pitch_deg",
    "roll_deg",
    "look_at",
    "look_at_m",
    "fov_deg",
];

/// The `[gltf]` table's camera, read and checked, and no keyframe placing or aiming the
/// camera besides it; errors name the path file's line and the glTF file.
fn gltf_camera(
    table: &toml::Spanned<GltfFile>,
    keyframes: &[toml::Spanned<KeyframeFile>],
    origin: &Path,
    text: &str,
) -> anyhow::Result<(GltfFile, GltfCamera)> {
    let at = location(origin, text, table.span().start);
    let camera = GltfCamera::load(table.get_ref(), origin)
        .map_err(|e| anyhow!("camera path {at}: [gltf]: {e:#}"))?;
    if let Some(fps) = camera.fps {
        within("[gltf] fps", fps, FPS).map_err(|e| anyhow!("camera path {at}: {e}"))?;
    }
    for (n, spanned) in keyframes.iter().enumerate() {
        let k = spanned.get_ref();
        let given = [
            k.latitude_deg.is_some(),
            k.longitude_deg.is_some(),
            k.altitude_m.is_some(),
            k.position_m.is_some(),
            k.heading_deg.is_some(),
            k.pitch_deg.is_some(),
            k.roll_deg.is_some(),
            k.look_at.is_some(),
            k.look_at_m.is_some(),
            k.fov_deg.is_some(),
        ];
        if let Some(field) = given.iter().position(|&g| g) {
            bail!(
                "camera path {}: keyframe {} (time_s {}): {} is given by the [gltf] camera; a keyframe of a glTF path sets the sun, atmosphere, model, exposure and terrain",
                location(origin, text, spanned.span().start),
                n + 1,
                k.time_s,
                CAMERA_FIELDS[field]
            );
        }
    }
    Ok((table.get_ref().clone(), camera))
}
