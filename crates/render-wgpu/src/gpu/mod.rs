//! The GPU itself: the device and queue ([`context::GpuContext`]), errors, pipeline and
//! resource helpers (pipelines compiled on first use among them), read-back, timestamp
//! queries and the embedded shaders.

pub mod adapter_choice;
pub mod context;
pub mod error;
pub mod formats;
pub mod lazy_pipeline;
pub mod pipeline;
pub mod pixel_list;
pub mod readback;
pub mod requirements;
pub mod shaders;
pub mod timer;
