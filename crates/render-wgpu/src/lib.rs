//! render-wgpu: the GPU side of atmos, one folder per thing it renders.
//!
//! - [`gpu`]: the device ([`GpuContext`]), errors, pipeline helpers, read-back, timers and
//!   the embedded shaders;
//! - [`frame`]: what one frame is ([`Frame`]), its plan, its uniforms and the surface its
//!   rays end on;
//! - [`sky`]: each scattering model's tables and per-pixel pass behind one trait, and the
//!   registry that makes them;
//! - [`terrain`]: the planet's relief and colour, drawn into the frame's surface;
//! - [`clouds`]: the cloud layer's ray march;
//! - [`precipitation`]: rain shafts and cirrus layers composited over a frame;
//! - [`post`]: tone mapping and the luminance measured for exposure;
//! - [`Renderer`] ties them: tables are kept between frames and rebuilt only when an
//!   input they depend on changed, as the frame's plan says (docs/rendering.md).
//!
//! Every shader has a CPU twin in atmosphere-core and matches it within a tolerance
//! checked by a parity test in `tests/`.

pub mod clouds;
pub mod frame;
pub mod frame_targets;
pub mod gpu;
pub mod post;
pub mod precipitation;
pub mod renderer;
pub mod shafts;
pub mod sky;
pub mod terrain;

pub use frame::Frame;
pub use gpu::context::GpuContext;
pub use gpu::error::{GpuError, RenderError};
pub use renderer::Renderer;
