//! What goes wrong on the GPU side. Each message says what was being done and, where the
//! user can fix it, how.

use thiserror::Error;

/// Errors of device creation, shader composition, pipelines and read-back.
#[derive(Debug, Error)]
pub enum GpuError {
    #[error(
        "no GPU adapter atmos can use (backends tried: {backends}):\n{refused}\n\
         Install a Vulkan driver; without a GPU, Mesa's software Vulkan (lavapipe): \
         `apt-get install mesa-vulkan-drivers libvulkan1` (Debian). WGPU_BACKEND limits \
         the backends tried: leave it unset, or set WGPU_BACKEND=vulkan"
    )]
    NoAdapter {
        backends: String,
        /// One line per adapter found, with why it was passed over.
        refused: String,
    },
    #[error(
        "WGPU_BACKEND={value} names no backend (known: vulkan, metal, dx12, gl, webgpu; \
         several separated by commas)"
    )]
    UnknownBackend { value: String },
    #[error("WGPU_ADAPTER_NAME={wanted} matches no adapter (available: {available})")]
    NoAdapterNamed { wanted: String, available: String },
    #[error("unknown shader '{0}' (no such file below shaders/)")]
    UnknownShader(String),
    #[error("shader {shader} imports '{import}', which is no file below shaders/")]
    UnknownImport { shader: String, import: String },
    #[error("{what} failed GPU validation: {source}")]
    Validation {
        what: &'static str,
        #[source]
        source: wgpu::Error,
    },
    #[error("{species} density profile has {layers} layers; the GPU uniform holds at most 2")]
    TooManyDensityLayers {
        species: &'static str,
        layers: usize,
    },
    #[error(
        "Mie phase function {0} is not yet on the GPU (use cornette_shanks, henyey_greenstein or nishita_hazy)"
    )]
    UnsupportedPhase(String),
    #[error("waiting for the GPU failed: {0}")]
    Poll(#[from] wgpu::PollError),
    #[error("mapping a read-back buffer failed: {0}")]
    Map(#[from] wgpu::BufferAsyncError),
    #[error("reading a mapped buffer failed: {0}")]
    MapRange(#[from] wgpu::MapRangeError),
}

/// Errors of rendering a frame: the frame or model cannot be rendered, or the GPU failed.
#[derive(Debug, Error)]
pub enum RenderError {
    #[error("invalid frame: {0}")]
    Frame(String),
    #[error("model '{model}' is not yet on the GPU (models on the GPU: {on_gpu})")]
    NotOnGpu {
        model: atmosphere_core::models::id::ModelId,
        on_gpu: String,
    },
    #[error("not supported on the GPU: {0}")]
    Unsupported(String),
    #[error(transparent)]
    Model(#[from] atmosphere_core::models::error::ModelError),
    #[error(transparent)]
    Color(#[from] atmosphere_core::color::ColorError),
    #[error(transparent)]
    Gpu(#[from] GpuError),
    #[error("terrain: {0}")]
    Terrain(#[from] crate::terrain::MapError),
    /// A beams scene that cannot be prepared, or does not fit the device.
    #[error(transparent)]
    Beams(#[from] atmosphere_core::beams::error::BeamError),
    #[error("the beams scene does not fit the GPU: {0}")]
    BeamsTooLarge(String),
}
