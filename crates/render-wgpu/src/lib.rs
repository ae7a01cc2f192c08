//! render-wgpu: the GPU side of atmos.
//!
//! A [`device::GpuContext`] lives for the program; passes are made once from it and run
//! when their inputs change. A [`Renderer`] owns the context, tables and passes and
//! renders a [`Frame`] (camera, sun, atmosphere, model, exposure) into an HDR target
//! and a tone-mapped image, as its [`frame_plan::FramePlan`] says (docs/rendering.md). Every table is built by a compute shader from `shaders/`
//! (embedded, see [`shader_source`]) that matches its CPU twin in atmosphere-core within
//! a tolerance checked by a parity test in `tests/`.

pub mod atmosphere_uniform;
pub mod bruneton_pass;
pub mod device;
pub mod dobashi_pass;
pub mod error;
pub mod frame;
pub mod frame_plan;
pub mod frame_uniform;
pub mod gpu_timer;
pub mod ground_in_view;
pub mod hillaire_pass;
pub mod luminance_pass;
pub mod model_pass;
pub mod nishita_pass;
pub mod oneil_pass;
pub mod pipeline;
pub mod readback;
pub mod renderer;
pub mod riley_pass;
pub mod shader_source;
pub mod surface_buffer;
pub mod table_sampling;
pub mod terrain;
pub mod terrain_pass;
pub mod tone_map;
pub mod tone_map_pass;
pub mod transmittance_pass;

pub use device::GpuContext;
pub use error::{GpuError, RenderError};
pub use frame::Frame;
pub use renderer::Renderer;
