//! Multiple scattering as a constant ambient term. The paper has single scattering only
//! (its conclusion leaves multiple scattering to future work); the model adds a uniform,
//! isotropic ambient radiance ψ that every segment scatters towards the camera,
//! ψ Σ_k (dI_r + dI_m)(t_k) Π_{j<k} dg_v(t_j), and the ground reflects, r ψ Π dg_v. Both
//! reuse the tables of Eq. 12 (an isotropic radiance scatters with a phase integral of 1).
//! The table is built in `ambient_build`.

use crate::atmosphere::table_inputs::Inputs;
use crate::models::dobashi::grid::Grid;

/// ψ per unit solar irradiance (sr^-1) over the sun's cosine, one channel per wavelength.
#[derive(Clone, Debug, PartialEq)]
pub struct AmbientTable {
    /// `ambient_sun_angles` x 1 nodes at equal steps of mu_sun from -1 to 1.
    pub radiance: Grid,
    /// f, the mean transfer of a unit isotropic radiance at the ground, per wavelength.
    pub transfer: Vec<f64>,
}

impl AmbientTable {
    /// Every table of Eq. 12 (all extinction inputs), the Mie phase and the ground.
    pub const INPUTS: Inputs = Inputs::EXTINCTION
        .union(Inputs::MIE_PHASE)
        .union(Inputs::GROUND_ALBEDO);

    /// Bytes of the table.
    pub fn bytes(&self) -> usize {
        self.radiance.bytes()
    }

    /// ψ per unit solar irradiance for a sun of cosine `mu_sun` to the local zenith.
    pub fn lookup(&self, mu_sun: f64, out: &mut [f64]) {
        let x = 0.5 * (mu_sun.clamp(-1.0, 1.0) + 1.0) * (self.radiance.width - 1) as f64;
        self.radiance.sample(x, 0.0, out);
    }
}
