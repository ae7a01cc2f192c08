//! The cost baseline every GPU frame time is given against: nishita with 16 view
//! samples, the cost baseline the issues measure against.

use atmosphere_core::models::id::ModelId;

use super::variant::Variant;

/// The baseline's label: nishita with 16 view samples.
pub const BASELINE: &str = "nishita samples=16";

/// The cost baseline: nishita with 16 view samples.
pub fn baseline() -> Variant {
    Variant::new(ModelId::Nishita, None, &["samples=16"])
}
