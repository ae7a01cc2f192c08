//! Bruneton and Neyret 2008, Algorithm 4.1: single scattering into S, then each order in
//! turn: Delta J from the previous order's radiance (scattered light plus light reflected
//! by the ground), Delta S by integrating T Delta J along every texel's ray, Delta E from
//! the previous order's sky radiance; added to S and E, until an order adds less than a
//! threshold.
//!
//! The integrals over directions (Delta J, Delta E) are in `sphere_integrals`, those
//! along the texels' rays (single scattering, Delta S) in `view_integrals`; this file
//! holds the loop over orders. See docs/models/bruneton.md.

use std::time::Instant;

use crate::models::bruneton::builder::Builder;
use crate::models::bruneton::channels::Channels;
use crate::models::bruneton::parameterization::{IrradianceMapping, texel_parameters};
use crate::models::bruneton::sphere_integrals::{Previous, PreviousIrradiance};
use crate::models::bruneton::tables::{IrradianceTable, Table4};
use crate::optics::phase::rayleigh;

/// How long an order took and how much it added.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OrderStats {
    /// 1 = single scattering.
    pub order: u32,
    /// max over channels of (sum over texels of the order's radiance) / (sum of all
    /// orders so far, this one included); NaN for an order left out because it held more
    /// light than the one before (the iteration would diverge).
    pub share: f64,
    pub seconds: f64,
}

/// The tables of three wavelengths.
#[derive(Clone, Debug)]
pub struct Tables {
    pub channels: Channels,
    /// Single Rayleigh scattering without its phase function (C* of the paper minus the
    /// multiple part).
    pub single_rayleigh: Table4,
    /// Single Mie scattering without its phase function (C_M of the paper); `None` when
    /// pruned (no aerosol).
    pub single_mie: Option<Table4>,
    /// All orders from two up, full radiance.
    pub multiple: Table4,
    /// Ground irradiance from the sky, orders one up to the last but one (direct
    /// sunlight is added when rendering).
    pub irradiance: IrradianceTable,
    pub orders: Vec<OrderStats>,
}

impl Builder<'_> {
    /// for single scattering).
    fn sums(&self, previous: Previous) -> [f64; 3] {
        let size = self.settings.scattering_size;
        let mut out = [0.0; 3];
        for index in 0..size.texels() {
            let v = match previous {
                Previous::Single { rayleigh: ray, mie } => {
                    let (ir, imu, imus, inu) = size.coords(index);
                    let (_, _, _, nu, _) = texel_parameters(&self.radii, &size, ir, imu, imus, inu);
                    let pr = rayleigh(nu);
                    let mut v = ray.data[index].map(|a| pr * a as f64);
                    if let Some(mie) = mie {
                        let pm = self.atmosphere.mie.phase.eval(nu);
                        for k in 0..3 {
                            v[k] += pm * mie.data[index][k] as f64;
                        }
                    }
                    v
                }
                Previous::Multiple(t) => t.data[index].map(f64::from),
            };
            for k in 0..3 {
                out[k] += v[k];
            }
        }
        out
    }

    /// Algorithm 4.1.
    pub fn build(&self) -> Tables {
        let start = Instant::now();
        let (single_rayleigh, single_mie) = self.single_scattering();
        let first = OrderStats {
            order: 1,
            share: 1.0,
            seconds: start.elapsed().as_secs_f64(),
        };
        self.multiple_orders(single_rayleigh, single_mie, first)
    }

    /// Algorithm 4.1 from its loop on, given the single-scattering tables (built by
    /// [`Builder::single_scattering`] and timed in `first`): orders two and up and the
    /// irradiance table.
    pub fn multiple_orders(
        &self,
        single_rayleigh: Table4,
        single_mie: Option<Table4>,
        first: OrderStats,
    ) -> Tables {
        let size = self.settings.scattering_size;
        let mut orders = vec![first];
        let mut totals = self.sums(Previous::Single {
            rayleigh: &single_rayleigh,
            mie: single_mie.as_ref(),
        });
        let mapping = IrradianceMapping {
            radii: self.radii,
            angles: self.settings.scattering_size.angles,
            mu_s_size: self.settings.irradiance_size.0,
            r_size: self.settings.irradiance_size.1,
        };
        let mut multiple = Table4::zeros(size);
        let mut irradiance = IrradianceTable::zeros(mapping);
        let mut previous_table: Option<Table4> = None;
        let mut previous_e: Option<IrradianceTable> = None;
        let mut previous_added: Option<[f64; 3]> = None;
        for order in 2..=self.max_orders {
            let start = Instant::now();
            let previous = match &previous_table {
                None => Previous::Single {
                    rayleigh: &single_rayleigh,
                    mie: single_mie.as_ref(),
                },
                Some(t) => Previous::Multiple(t),
            };
            let previous_irradiance = match &previous_e {
                None => PreviousIrradiance::Direct,
                Some(e) => PreviousIrradiance::Table(e),
            };
            // Delta E of order - 1 lights the ground for this order's reflection.
            let delta_e = self.irradiance_of(previous);
            let density = self.scattering_density(previous, previous_irradiance);
            let delta_s = self.scattering_of(&density);
            let added = self.sums(Previous::Multiple(&delta_s));
            // No order can hold more light than the one before it: growth means the
            // approximations of the order step amplify (optically thick atmospheres), so
            // stop without it rather than diverge.
            if let Some(before) = previous_added
                && (0..3).any(|k| added[k] > before[k])
            {
                orders.push(OrderStats {
                    order,
                    share: f64::NAN,
                    seconds: start.elapsed().as_secs_f64(),
                });
                break;
            }
            previous_added = Some(added);
            irradiance.add(&delta_e);
            multiple.add(&delta_s);
            let mut share: f64 = 0.0;
            for k in 0..3 {
                totals[k] += added[k];
                if totals[k] > 0.0 {
                    share = share.max(added[k] / totals[k]);
                }
            }
            orders.push(OrderStats {
                order,
                share,
                seconds: start.elapsed().as_secs_f64(),
            });
            previous_table = Some(delta_s);
            previous_e = Some(delta_e);
            if share < self.settings.order_threshold {
                break;
            }
        }
        Tables {
            channels: self.channels,
            single_rayleigh,
            single_mie,
            multiple,
            irradiance,
            orders,
        }
    }
}
