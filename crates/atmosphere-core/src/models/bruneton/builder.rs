//! What the build of one set of tables (three wavelengths) needs, and the look-ups every
//! step of Bruneton and Neyret 2008, Algorithm 4.1 shares.

use crate::atmosphere::Atmosphere;
use crate::models::bruneton::channels::Channels;
use crate::models::bruneton::delta_m::DeltaM;
use crate::models::bruneton::mie_quadrature::MieQuadrature;
use crate::models::bruneton::parameterization::Radii;
use crate::models::bruneton::settings::BrunetonSettings;
use crate::models::bruneton::sun_disk::visible_sun;
use crate::models::bruneton::tables::DensityTable;
use crate::optics::geometry::{distance_to_entry, distance_to_exit, ray_hits_ground};
use crate::optics::transmittance_table::TransmittanceTable;

/// Everything the build of one set of tables needs.
#[derive(Debug)]
pub struct Builder<'a> {
    pub atmosphere: &'a Atmosphere,
    pub settings: &'a BrunetonSettings,
    pub radii: Radii,
    pub transmittance: &'a TransmittanceTable,
    pub densities: &'a DensityTable,
    pub channels: Channels,
    /// The channels' transmittance at each texel of `transmittance`: interpolated
    /// directly, it spares three exponentials per look-up.
    pub sun_transmittances: Vec<[f64; 3]>,
    /// The Mie phase function's delta-M form; `None` prunes all Mie work (no aerosol).
    pub delta_m: Option<DeltaM>,
    /// Mie's Delta J by quadrature about the view (`mie_directions` > 0) instead of
    /// `delta_m`.
    pub mie_quadrature: Option<MieQuadrature>,
    pub max_orders: u32,
}

/// A table value in the tables' single precision.
pub(crate) fn to_f32(a: [f64; 3]) -> [f32; 3] {
    [a[0] as f32, a[1] as f32, a[2] as f32]
}

impl Builder<'_> {
    /// Transmittance to the sun from (r, mu_s): to a point (zero behind the planet), or
    /// with `sun_disk` to the disk's visible part.
    pub fn sun_transmittance(&self, r: f64, mu_s: f64) -> [f64; 3] {
        let (fraction, mu) = if self.settings.sun_disk {
            match visible_sun(
                r,
                mu_s,
                self.radii.bottom_m,
                self.atmosphere.sun.angular_radius_rad,
            ) {
                Some(visible) => visible,
                None => return [0.0; 3],
            }
        } else if ray_hits_ground(r, mu_s, self.radii.bottom_m) {
            return [0.0; 3];
        } else {
            (1.0, mu_s)
        };
        self.transmittance
            .interpolate(&self.sun_transmittances, r, mu)
            .map(|t| fraction * t)
    }

    /// Direct sunlight on a horizontal surface at (r, mu_s), per unit solar irradiance.
    pub(crate) fn direct_irradiance(&self, r: f64, mu_s: f64) -> [f64; 3] {
        let t = self.sun_transmittance(r, mu_s);
        let c = mu_s.max(0.0);
        t.map(|t| t * c)
    }

    /// Transmittance of the segment of length d from (r, mu), from the column table.
    pub fn segment_transmittance(&self, r: f64, mu: f64, d: f64, ground: bool) -> [f64; 3] {
        self.channels
            .transmittance(self.transmittance.segment_column(r, mu, d, ground))
    }

    /// Distance from (r, mu) to the ground (`ground`) or to the top of the atmosphere.
    pub(crate) fn ray_length(&self, r: f64, mu: f64, ground: bool) -> f64 {
        if ground {
            distance_to_entry(r, mu, self.radii.bottom_m).unwrap_or(0.0)
        } else {
            distance_to_exit(r, mu, self.radii.top_m)
        }
    }
}
