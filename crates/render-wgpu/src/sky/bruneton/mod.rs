//! The bruneton model on the GPU (Bruneton and Neyret 2008): every table of
//! atmosphere-core's `bruneton` built in compute shaders as the CPU builds it, and the
//! per-pixel pass of `shaders/sky/bruneton/pixel.wgsl`.
//!
//! The steps ([`BrunetonStep`]), in the order of the plan: the columns of matter and the
//! sun's transmittances (`sky/transmittance_table.wgsl`), the density table, single
//! scattering (section 4, Eq. 5), the loop over orders of Algorithm 4.1 (`orders.rs`),
//! the copy of S into three `Rgba32Float` 3D textures (single Rayleigh, single Mie,
//! orders two and up) at (x = nu * mu_s_size + mu_s, y = mu, z = r) and of E into a 2D
//! texture (x = mu_s, y = r); then each frame, for a camera inside the atmosphere, the
//! view slice (S interpolated at the camera's r and mu_s for every (mu, nu) node, which
//! the `inside` entry point interpolates in mu and nu), and the per-pixel pass.
//!
//! Tables being built live in one storage buffer, the store (`store.rs`), indexed as the
//! CPU's, so a table read back compares texel by texel; it is bound as up to four ranges
//! (`store_chunks.rs`), so that it may exceed the device's largest storage binding.
//! Rebuilds follow the CPU's (`built.rs`); Mie work is left out when
//! `Spectra::needs_mie` says so. The loop over orders may be spread over frames
//! (`progressive.rs`).
//!
//! Files: `step.rs` the steps; `pass.rs` the [`crate::sky::model_pass::ModelPass`] and
//! the plan; `encode.rs` and `orders.rs` each step's dispatches; `pipelines.rs` and
//! `bindings.rs` the pipelines and their bindings; `tables.rs`, `store.rs`,
//! `store_chunks.rs`, `uniform.rs`, `order_state.rs` and `workgroups.rs` the GPU
//! resources; `readback.rs` and `standalone.rs` for tests and profiling.

mod bindings;
mod built;
mod encode;
pub mod order_state;
mod orders;
pub mod pass;
mod pipelines;
mod progressive;
mod readback;
mod standalone;
pub mod step;
pub mod store;
mod store_chunks;
mod tables;
pub mod uniform;
pub mod workgroups;

pub use order_state::{MAX_ORDERS, OrderState};
pub use pass::BrunetonPass;
pub use step::BrunetonStep;
pub use store::StoreTable;
pub use uniform::BrunetonUniform;
pub use workgroups::SLICE_TEXELS;
