//! The hillaire model (Hillaire 2020) on the GPU: its tables in compute shaders named like
//! their CPU twins in atmosphere-core's `hillaire/`, and the per-pixel pass of
//! `shaders/sky/hillaire/pixel.wgsl`. The CPU model is the specification; the steps and
//! the inputs each table depends on are those of `Hillaire::update`:
//! - `transmittance` (section 5.1): the columns of `sky/transmittance_table.wgsl` (the
//!   CPU's shared table holds columns; transmittance is exp(-tau) of the interpolated
//!   columns on both sides), rebuilt when the columns' inputs change;
//! - `multiple_scattering` (Psi_ms, section 5.5) when extinction, scattering or the ground's albedo
//!   change; `ground_irradiance` (E_sky) when those or the Mie phase function change;
//!   neither for single scattering (`max_orders = 1`);
//! - `sky_view` (section 5.3) when the view (camera radius to the millimetre, sun zenith cosine:
//!   `view_cache::view_key`), the Mie phase function or the Psi_ms inputs change; not for
//!   a camera above the atmosphere, whose rays are marched;
//! - `aerial_perspective` (section 5.4) likewise, and only when some pixel may see the
//!   ground within the volume's range (`ground_in_view`);
//! - `hillaire`: the pass, every frame. It reads the transmittance table, the sky view
//!   and the volume through the texture unit's filter where the device can
//!   (`table_sampling`): one read per look-up instead of 4 (8 for the volume's trilinear
//!   one); where the cloud's sun map shades the air it subtracts the cloud's shadow
//!   there, per pixel, as every model does (`clouds/air_shadow_pass.rs`).

pub mod pass;
pub mod step;
pub mod tables;
pub mod uniform;

pub use pass::HillairePass;
pub use step::HillaireStep;
pub use tables::Table;
pub use uniform::HillaireUniform;
