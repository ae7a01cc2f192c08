//! The dobashi model (Dobashi, Yamamoto and Nishita 2002) on the GPU: the pre-integrated
//! segment tables of the sampling planes and of the sample spheres (sections 5.2-5.3)
//! built by `shaders/sky/dobashi/tables.wgsl` (the GPU twins of atmosphere-core's
//! `dobashi::PlaneTables` and `dobashi::SphereTables`), g_l (the `columns` of the
//! transmittance pass), the ambient term's table (`shaders/sky/dobashi/ambient.wgsl`,
//! `AmbientTable::build`) and the per-pixel pass (`shaders/sky/dobashi/pixel.wgsl`,
//! `Dobashi::radiance`). Each table is rebuilt only when what it depends on changed.

pub mod ambient;
pub mod pass;
pub mod step;
pub mod tables;

pub use pass::{DobashiPass, DobashiUniform, uses_spheres};
pub use step::DobashiStep;
pub use tables::{
    DobashiTableUniform, DobashiTables, PLANE_PANELS, SPHERE_PANELS, SegmentTextures,
    plane_interval_m, sphere_rows,
};
