//! The steps of the bruneton model, in the order of its plan: the table builds, then the
//! passes of each frame.

use crate::frame::plan::StepKind;
use crate::sky::steps::PassStep;

/// One step of the bruneton model's frame plan.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BrunetonStep {
    /// The columns of matter T(r, mu) (`sky/transmittance_table.wgsl`, `columns`), the
    /// CPU's `TransmittanceTable`.
    Transmittance,
    /// The density table (`DensityTable`), copied into a 1D texture for the shaders.
    Density,
    /// The columns table as transmittances, the CPU's `Builder::sun_transmittances`.
    SunTransmittance,
    /// Rayleigh and Mie without phase functions (Bruneton and Neyret 2008, Eq. 5).
    SingleScattering,
    /// The loop over orders of Algorithm 4.1 (`orders.rs`).
    ScatteringOrders,
    /// S into the three 3D textures and E into a 2D texture for the pass.
    ScatteringTexture,
    /// S at the camera's r and mu_s for every (mu, nu) node, for a camera inside the
    /// atmosphere (`sky/bruneton/view_slice.wgsl`).
    ViewSlice,
    /// The per-pixel pass (`sky/bruneton/pixel.wgsl`).
    Render,
}

impl PassStep for BrunetonStep {
    fn name(self) -> &'static str {
        match self {
            BrunetonStep::Transmittance => "transmittance",
            BrunetonStep::Density => "density",
            BrunetonStep::SunTransmittance => "sun_transmittance",
            BrunetonStep::SingleScattering => "single_scattering",
            BrunetonStep::ScatteringOrders => "scattering_orders",
            BrunetonStep::ScatteringTexture => "scattering_texture",
            BrunetonStep::ViewSlice => "view_slice",
            BrunetonStep::Render => "bruneton",
        }
    }

    fn kind(self) -> StepKind {
        match self {
            BrunetonStep::ViewSlice | BrunetonStep::Render => StepKind::Pass,
            BrunetonStep::Transmittance
            | BrunetonStep::Density
            | BrunetonStep::SunTransmittance
            | BrunetonStep::SingleScattering
            | BrunetonStep::ScatteringOrders
            | BrunetonStep::ScatteringTexture => StepKind::TableBuild,
        }
    }
}
