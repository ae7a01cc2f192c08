//! The GPU itself: the device and queue ([`context::GpuContext`]), errors, pipeline and
//! resource helpers, read-back, timestamp queries and the embedded shaders.

pub mod context;
pub mod error;
pub mod formats;
pub mod pipeline;
pub mod readback;
pub mod shaders;
pub mod timer;
