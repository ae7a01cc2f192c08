//! render-wgpu
