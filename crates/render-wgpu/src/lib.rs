//! render-wgpu: the GPU side of atmos.
//!
//! A [`device::GpuContext`] lives for the program; passes are made once from it and run
//! when their inputs change. Every table is built by a compute shader from `shaders/`
//! (embedded, see [`shader_source`]) that matches its CPU twin in atmosphere-core within
//! a tolerance checked by a parity test in `tests/`.

pub mod atmosphere_uniform;
pub mod device;
pub mod error;
pub mod shader_source;
pub mod transmittance_pass;

pub use device::GpuContext;
pub use error::GpuError;
