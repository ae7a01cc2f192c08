//! The Rust twin of `VolumesParams` in `shaders/precipitation/volume_params.wgsl` (the
//! naga test checks the layout): a frame's lit volumes relative to its camera in f32, and
//! their phase tables at the frame's wavelengths, the probes of the sun's light
//! scattered more than once and their lobe tables (`hydrometeors/sun_orders.rs`) packed
//! in one buffer.

use atmosphere_core::hydrometeors::render::LitVolume;
use atmosphere_core::hydrometeors::sun_orders::{LOBE_ANGLES, LOBE_G_MAX, LOBE_G_STEPS};
use atmosphere_core::hydrometeors::volumes::Shape;
use bytemuck::{Pod, Zeroable};
use glam::DVec3;

use crate::gpu::error::RenderError;

/// The most volumes a frame holds.
pub const MAX_VOLUMES: usize = 2;
const KIND_SHAFT: u32 = 1;
const KIND_LAYER: u32 = 2;

/// WGSL `VolumeParams`, 144 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct VolumeUniform {
    /// x: kind (1 shaft, 2 layer); y: its first bin in the phase buffer; z: its bins;
    /// w: 0 for a table by scattering angle, else its azimuth columns (a table over the
    /// sky, row-major, elevation rows).
    pub kind: [u32; 4],
    /// Shaft: xyz the unit axis, w the radius, m.
    pub axis: [f32; 4],
    /// Shaft: xyz the camera relative to the axis's foot, w the height, m. Layer: r^2 -
    /// R^2 of the camera for the base, top and ground radii, m^2.
    pub place: [f32; 4],
    /// x: the bins' width (over the sky: the elevation bins'), y: over the sky, the
    /// azimuth bins' width, degrees.
    pub bin_deg: [f32; 4],
    /// The march's extinction per channel, beta (1 - f_c) (the forward peak out of it
    /// where it counts as no scattering), m^-1.
    pub extinction: [f32; 4],
    pub sun_irradiance: [f32; 4],
    /// The radiance the march scatters as the sky's light, W m^-2 sr^-1 nm^-1.
    pub sky_radiance: [f32; 4],
    /// x: the probes' first entry in the buffer (per probe one J, H_x, H_y, H_z per
    /// channel); y, z, w: probes across radius, azimuth and height (w = 0: none).
    pub probes: [u32; 4],
    /// x: the lobe table's first entry (rgb, rows of G); y: its G steps; z: its angles;
    /// w: its largest G as f32 bits.
    pub lobes: [u32; 4],
}

/// WGSL `VolumesParams`, 320 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct VolumesUniform {
    /// x: how many volumes; y: 1 when the frame's rays end on its surface; z, w: the
    /// column and row of the first pixel the pass runs over.
    pub count: [u32; 4],
    /// x: the divisor N (1: every pixel marched); y, z: the first reduced pixel the
    /// reduced pass runs over.
    pub reduction: [u32; 4],
    pub volumes: [VolumeUniform; MAX_VOLUMES],
}

fn rgb(v: [f64; 3]) -> [f32; 4] {
    [v[0] as f32, v[1] as f32, v[2] as f32, 0.0]
}

/// The uniform of `volumes` seen from `camera_m`, and the phase buffer's bins (rgb, 0).
pub fn pack(
    volumes: &[LitVolume],
    camera_m: DVec3,
    has_surface: bool,
) -> Result<(VolumesUniform, Vec<[f32; 4]>), RenderError> {
    if volumes.len() > MAX_VOLUMES {
        return Err(RenderError::Frame(format!(
            "{} rain and ice volumes; a frame holds at most {MAX_VOLUMES}",
            volumes.len()
        )));
    }
    let mut uniform = VolumesUniform {
        count: [volumes.len() as u32, u32::from(has_surface), 0, 0],
        ..Default::default()
    };
    let mut bins = Vec::new();
    for (slot, lit) in uniform.volumes.iter_mut().zip(volumes) {
        let values = &lit.phase.values;
        if values.len() < 2 {
            return Err(RenderError::Frame(
                "a volume's phase table has fewer than 2 bins".into(),
            ));
        }
        let r2 = camera_m.length_squared();
        let (kind, axis, place) = match lit.volume.shape {
            Shape::Shaft {
                axis,
                ground_radius_m,
                radius_m,
                height_m,
            } => {
                let p = camera_m - axis * ground_radius_m;
                (
                    KIND_SHAFT,
                    [axis.x as f32, axis.y as f32, axis.z as f32, radius_m as f32],
                    [p.x as f32, p.y as f32, p.z as f32, height_m as f32],
                )
            }
            Shape::Layer(shell) => (
                KIND_LAYER,
                [0.0; 4],
                [
                    (r2 - shell.base_radius_m.powi(2)) as f32,
                    (r2 - shell.top_radius_m.powi(2)) as f32,
                    (r2 - shell.ground_radius_m.powi(2)) as f32,
                    0.0,
                ],
            ),
        };
        let (bin_deg, columns, azimuth_bin_deg) = match lit.phase.sky {
            None => (lit.phase.bin_deg, 0, 0.0),
            Some(grid) => {
                if grid.elevation_bins() < 2
                    || grid.azimuth_bins() < 2
                    || values.len() != grid.elevation_bins() * grid.azimuth_bins()
                {
                    return Err(RenderError::Frame(
                        "a volume's sky phase table does not fill its grid of at least 2 x 2"
                            .into(),
                    ));
                }
                (
                    grid.elevation_bin_deg,
                    grid.azimuth_bins() as u32,
                    grid.azimuth_bin_deg,
                )
            }
        };
        let first = bins.len() as u32;
        bins.extend(values.iter().map(|v| rgb(*v)));
        let (probes, lobes) = match &lit.orders {
            None => ([0; 4], [0; 4]),
            Some(orders) => {
                let probes = bins.len() as u32;
                bins.extend(
                    orders
                        .moments
                        .iter()
                        .flat_map(|probe| probe.iter().map(|m| m.map(|x| x as f32))),
                );
                let lobes = bins.len() as u32;
                bins.extend(orders.lobes.iter().map(|v| rgb(*v)));
                let [r, a, h] = orders.dims.map(|n| n as u32);
                (
                    [probes, r, a, h],
                    [
                        lobes,
                        LOBE_G_STEPS as u32,
                        LOBE_ANGLES as u32,
                        (LOBE_G_MAX as f32).to_bits(),
                    ],
                )
            }
        };
        *slot = VolumeUniform {
            kind: [kind, first, values.len() as u32, columns],
            axis,
            place,
            bin_deg: [bin_deg as f32, azimuth_bin_deg as f32, 0.0, 0.0],
            extinction: rgb(lit.extinction_per_m()),
            sun_irradiance: rgb(lit.light.sun_irradiance),
            sky_radiance: rgb(lit.light.sky_radiance),
            probes,
            lobes,
        };
    }
    if bins.is_empty() {
        bins.push([0.0; 4]);
    }
    Ok((uniform, bins))
}
