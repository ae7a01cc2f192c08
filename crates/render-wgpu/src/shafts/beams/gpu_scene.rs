//! A beams scene as the GPU reads it: the lights, their light maps and shadow maps, the
//! occluders (primitives, and the triangles of meshes with their bounding volume
//! hierarchy) and the phase function, packed into plain structs laid out byte for byte
//! as `shaders/shafts/beams/bindings.wgsl` declares them.
//!
//! Positions are relative to the camera (the camera sits at the origin), so that f32
//! keeps the scene's detail wherever it is; the CPU twins are atmosphere-core's
//! `beams/methods/march.rs` and `beams/methods/planes2000.rs` with everything they read: `light.rs`, `light_map.rs`,
//! `shadow_map.rs`, `occluder.rs`, `bvh.rs`, `optics/phase.rs`.

use atmosphere_core::beams::in_scattering::InScattering;
use atmosphere_core::beams::light::LightShape;
use atmosphere_core::beams::methods::march::March;
use atmosphere_core::beams::occluder::Primitive;
use atmosphere_core::beams::shadow_map::{Projection, ShadowMap};
use atmosphere_core::optics::phase::PhaseFunction;
use bytemuck::{Pod, Zeroable};
use glam::DVec3;

/// What the march pass reads besides its buffers: the camera, the medium, the loop
/// counts (WGSL `BeamsParams`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct BeamsUniform {
    /// The camera's right vector (xyz), w = tan(half the vertical field of view) times
    /// the image's aspect ratio.
    pub camera_right: [f32; 4],
    /// The camera's up vector (xyz), w = tan(half the vertical field of view).
    pub camera_up: [f32; 4],
    /// The camera's forward vector (xyz), w = where the medium has extinguished the
    /// light, m (0 in a medium that neither scatters nor absorbs).
    pub camera_forward: [f32; 4],
    /// Scattering coefficient at each wavelength, m^-1 (xyz).
    pub scattering_per_m: [f32; 4],
    /// Extinction coefficient at each wavelength, m^-1 (xyz).
    pub extinction_per_m: [f32; 4],
    /// The red, green and blue weights of a light map's texel at each wavelength (one
    /// row per wavelength, w = 0).
    pub channel_weights: [[f32; 4]; 3],
    /// Width and height of the image, px; steps along each ray; lights.
    pub size_steps_lights: [u32; 4],
    /// Primitives; BVH nodes; phase function kind (0 Rayleigh, 1 Cornette-Shanks,
    /// 2 Henyey-Greenstein, 3 Nishita's hazy, 4 tabulated); rows of its table.
    pub counts: [u32; 4],
    /// The phase function's asymmetry g (x), 0 elsewhere.
    pub phase: [f32; 4],
}

/// A light (WGSL `BeamLight`), 144 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct LightUniform {
    /// Position relative to the camera (xyz), w = radius, m; a parallel light: a
    /// point of its plane, w = 0.
    pub position: [f32; 4],
    /// The light's frame (`LightFrame`): x, y, z (its axis or direction of travel).
    pub frame_x: [f32; 4],
    pub frame_y: [f32; 4],
    pub frame_z: [f32; 4],
    /// A spot: cos and tan of the cone's half-angle, falloff exponent. A parallel
    /// light: its beam's half sides, m, and 1 when it has them.
    pub beam: [f32; 4],
    /// Intensity (W sr^-1 nm^-1) or irradiance (W m^-2 nm^-1) at each wavelength.
    pub emission: [f32; 4],
    /// 0 point, 1 spot, 2 parallel.
    pub kind: u32,
    /// First texel of its light map; the map's width (0: no map) and height.
    pub map_offset: u32,
    pub map_width: u32,
    pub map_height: u32,
    /// Its shadow views: the first and how many (0: nothing shadows it).
    pub first_view: u32,
    pub view_count: u32,
    pub pad0: u32,
    pub pad1: u32,
}

/// One depth image of a shadow map (WGSL `ShadowView`), 96 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct ShadowViewUniform {
    /// The apex (perspective) or the rectangle's centre (orthographic), relative to
    /// the camera; w = the tangent of half the view (perspective).
    pub origin: [f32; 4],
    pub frame_x: [f32; 4],
    pub frame_y: [f32; 4],
    pub frame_z: [f32; 4],
    /// Orthographic: the rectangle's half sides, m.
    pub half: [f32; 4],
    /// 0 perspective, 1 orthographic; texels a side; first depth.
    pub kind: u32,
    pub size: u32,
    pub offset: u32,
    pub pad: u32,
}

/// A primitive occluder (WGSL `Primitive`), 64 bytes: a sphere (a = centre, a.w =
/// radius), a box (a = min, b = max), a quad (a = corner, b and c = edges) or a plane
/// (a = point, b = normal).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct PrimitiveUniform {
    pub a: [f32; 4],
    pub b: [f32; 4],
    pub c: [f32; 4],
    /// 0 sphere, 1 box, 2 quad, 3 plane.
    pub kind: u32,
    pub pad0: u32,
    pub pad1: u32,
    pub pad2: u32,
}

/// A node of the triangles' hierarchy (WGSL `BvhNode`), 32 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct NodeUniform {
    pub min: [f32; 3],
    pub first: u32,
    pub max: [f32; 3],
    pub count: u32,
}

/// A beams scene packed for the march pass.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GpuScene {
    pub uniform: BeamsUniform,
    pub lights: Vec<LightUniform>,
    /// Every light map's linear RGB texels, one map after another (w = 0).
    pub light_texels: Vec<[f32; 4]>,
    pub views: Vec<ShadowViewUniform>,
    /// Every shadow view's depths, m, one after another; f32::MAX where nothing is met.
    pub depths: Vec<f32>,
    pub primitives: Vec<PrimitiveUniform>,
    pub nodes: Vec<NodeUniform>,
    /// Triangles' corners relative to the camera, three rows each (w = 0).
    pub triangles: Vec<[f32; 4]>,
    /// A tabulated phase function: (angle, degrees; value, sr^-1) per row.
    pub phase_table: Vec<[f32; 2]>,
}

fn v4(v: DVec3, w: f64) -> [f32; 4] {
    [v.x as f32, v.y as f32, v.z as f32, w as f32]
}

fn v3(v: DVec3) -> [f32; 3] {
    [v.x as f32, v.y as f32, v.z as f32]
}

fn per_wavelength(values: &[f64]) -> [f32; 4] {
    std::array::from_fn(|k| values.get(k).map_or(0.0, |&v| v as f32))
}

impl GpuScene {
    /// The scene of the prepared CPU march (its wavelengths three, its shadow maps
    /// built), its image the size of the scene's camera.
    pub fn new(march: &March) -> GpuScene {
        GpuScene::from_parts(
            march.scattering(),
            march.shadow_maps(),
            march.settings().steps as u32,
        )
    }

    /// The scene of a prepared CPU method: its lights and medium at three wavelengths,
    /// each light's shadow map, and `steps` for the march (the planes ignore it).
    pub fn from_parts(
        scattering: &InScattering,
        shadow_maps: &[ShadowMap],
        steps: u32,
    ) -> GpuScene {
        let scene = &scattering.scene;
        let camera = &scene.camera;
        let eye = camera.position_m;
        let tan_half = (0.5 * camera.vertical_fov_deg.to_radians()).tan();
        let (width, height) = (camera.width_px, camera.height_px);
        let aspect = f64::from(width) / f64::from(height);
        let thinnest = scattering.medium.thinnest_extinction_per_m();
        let extinguished = if thinnest.is_finite() {
            atmosphere_core::beams::in_scattering::EXTINGUISHED_OPTICAL_DEPTH / thinnest
        } else {
            0.0
        };
        let mut out = GpuScene::default();
        for (i, light) in scene.lights.iter().enumerate() {
            let mut packed = LightUniform {
                emission: per_wavelength(&scattering.emission[i]),
                first_view: out.views.len() as u32,
                ..Default::default()
            };
            let (kind, position, radius, frame, beam) = match &light.shape {
                LightShape::Point {
                    position_m,
                    radius_m,
                    frame,
                } => (0, *position_m, *radius_m, frame, [0.0; 4]),
                LightShape::Spot {
                    position_m,
                    radius_m,
                    frame,
                    cos_cone,
                    tan_cone,
                    falloff_exponent,
                } => {
                    let beam = [*cos_cone, *tan_cone, *falloff_exponent, 0.0];
                    (1, *position_m, *radius_m, frame, beam.map(|v| v as f32))
                }
                LightShape::Parallel {
                    position_m,
                    frame,
                    half_size_m,
                } => {
                    let beam = half_size_m.map_or([0.0; 4], |[x, y]| [x, y, 1.0, 0.0]);
                    (2, *position_m, 0.0, frame, beam.map(|v| v as f32))
                }
            };
            packed.kind = kind;
            packed.position = v4(position - eye, radius);
            packed.frame_x = v4(frame.x, 0.0);
            packed.frame_y = v4(frame.y, 0.0);
            packed.frame_z = v4(frame.z, 0.0);
            packed.beam = beam;
            if let Some(map) = &light.light_map {
                packed.map_offset = out.light_texels.len() as u32;
                packed.map_width = map.width as u32;
                packed.map_height = map.height as u32;
                out.light_texels
                    .extend(map.texels.iter().map(|t| [t[0], t[1], t[2], 0.0]));
            }
            for view in shadow_maps[i].views() {
                out.views.push(shadow_view(
                    &view.projection,
                    eye,
                    view.size,
                    out.depths.len(),
                ));
                out.depths.extend(
                    view.depth_m
                        .iter()
                        .map(|&d| if d.is_finite() { d } else { f32::MAX }),
                );
            }
            packed.view_count = out.views.len() as u32 - packed.first_view;
            out.lights.push(packed);
        }
        out.primitives = scene
            .occluders
            .primitives
            .iter()
            .map(|p| primitive(p, eye))
            .collect();
        let bvh = &scene.occluders.triangles;
        out.nodes = bvh
            .nodes()
            .iter()
            .map(|n| NodeUniform {
                min: v3(n.min - eye),
                first: n.first as u32,
                max: v3(n.max - eye),
                count: n.count as u32,
            })
            .collect();
        out.triangles = bvh
            .triangles()
            .iter()
            .flat_map(|t| t.0.map(|c| v4(c - eye, 0.0)))
            .collect();
        let (phase_kind, g) = match &scene.medium.phase {
            PhaseFunction::Rayleigh => (0, 0.0),
            PhaseFunction::CornetteShanks { g } => (1, *g),
            PhaseFunction::HenyeyGreenstein { g } => (2, *g),
            PhaseFunction::NishitaHazy => (3, 0.0),
            PhaseFunction::Tabulated { angles_deg, .. } => {
                // The normalised value at each node is the function there; the shader
                // interpolates between nodes in angle as `PhaseFunction::eval` does.
                let phase = &scene.medium.phase;
                out.phase_table = angles_deg
                    .iter()
                    .map(|&a| [a as f32, phase.eval(a.to_radians().cos()) as f32])
                    .collect();
                (4, 0.0)
            }
        };
        let weights = &scattering.channel_weights;
        out.uniform = BeamsUniform {
            camera_right: v4(camera.right, tan_half * aspect),
            camera_up: v4(camera.up, tan_half),
            camera_forward: v4(camera.forward, extinguished),
            scattering_per_m: per_wavelength(&scattering.medium.scattering_per_m),
            extinction_per_m: per_wavelength(&scattering.medium.extinction_per_m),
            channel_weights: std::array::from_fn(|k| {
                weights
                    .get(k)
                    .map_or([0.0; 4], |w| [w[0] as f32, w[1] as f32, w[2] as f32, 0.0])
            }),
            size_steps_lights: [width, height, steps, out.lights.len() as u32],
            counts: [
                out.primitives.len() as u32,
                out.nodes.len() as u32,
                phase_kind,
                out.phase_table.len() as u32,
            ],
            phase: [g as f32, 0.0, 0.0, 0.0],
        };
        out
    }
}

fn shadow_view(
    projection: &Projection,
    eye: DVec3,
    size: usize,
    offset: usize,
) -> ShadowViewUniform {
    let (kind, origin, w, frame, half) = match *projection {
        Projection::Perspective {
            apex,
            frame,
            tan_half,
        } => (0, apex, tan_half, frame, [0.0; 4]),
        Projection::Orthographic {
            center,
            frame,
            half,
        } => (
            1,
            center,
            0.0,
            frame,
            [half[0] as f32, half[1] as f32, 0.0, 0.0],
        ),
    };
    ShadowViewUniform {
        origin: v4(origin - eye, w),
        frame_x: v4(frame.x, 0.0),
        frame_y: v4(frame.y, 0.0),
        frame_z: v4(frame.z, 0.0),
        half,
        kind,
        size: size as u32,
        offset: offset as u32,
        pad: 0,
    }
}

fn primitive(p: &Primitive, eye: DVec3) -> PrimitiveUniform {
    let (kind, a, b, c) = match *p {
        Primitive::Sphere { center, radius } => (0, v4(center - eye, radius), [0.0; 4], [0.0; 4]),
        Primitive::Box { min, max } => (1, v4(min - eye, 0.0), v4(max - eye, 0.0), [0.0; 4]),
        Primitive::Quad {
            corner,
            edge_u,
            edge_v,
        } => (2, v4(corner - eye, 0.0), v4(edge_u, 0.0), v4(edge_v, 0.0)),
        Primitive::Plane { point, normal } => (3, v4(point - eye, 0.0), v4(normal, 0.0), [0.0; 4]),
    };
    PrimitiveUniform {
        a,
        b,
        c,
        kind,
        ..Default::default()
    }
}
