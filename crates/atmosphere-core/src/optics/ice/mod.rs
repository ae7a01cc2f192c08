//! Hexagonal ice crystals (columns and plates) and their phase functions by geometric
//! optics: rays on the crystal's projected area, Fresnel reflection and refraction at
//! every face, internal reflections, absorption along the path, plus Fraunhofer
//! diffraction of the projected area (Macke, Mueller and Raschke 1996; Takano and Liou
//! 1989). Falling plates scatter by azimuth around the sun too: `sky_table.rs` bins them
//! over the sky's two angles (sundogs).
//!
//! Conventions, once: the crystal frame has the c-axis along z; the radius is the
//! distance from the axis to a prism edge (a hexagon's side equals it); the aspect
//! ratio is length / (2 radius); directions are unit vectors of travel; scattering
//! angles are measured from the incident direction (0: forward); phase functions are in
//! sr^-1 with unit integral over the sphere.

pub mod crystal;
pub mod diffraction;
pub mod fresnel;
pub mod orientation;
pub mod phase_table;
pub mod ray_tracer;
pub mod sky_table;
