//! How wrong a model is: error statistics over many rays, the CIEDE2000 colour
//! difference, and the sweep over stiff and extreme cases.

pub mod color_difference;
pub mod error_statistics;
pub mod stability;
