//! The memory a model's tables may take on the CPU, checked from the settings before
//! anything is allocated, so that large table sizes end in an error rather than an abort.

use crate::models::error::ModelError;

/// The most bytes the tables a model keeps may take: 1 GiB.
pub const TABLE_BUDGET_BYTES: u64 = 1 << 30;

/// Nothing, or an error naming the model, the settings (e.g. "table_heights=64 x
/// table_angles=256") and the bytes their tables need when over [`TABLE_BUDGET_BYTES`].
pub fn check_table_bytes(model: &str, settings: &str, bytes: u64) -> Result<(), ModelError> {
    if bytes <= TABLE_BUDGET_BYTES {
        return Ok(());
    }
    Err(ModelError::Settings(format!(
        "{model} tables of {settings} need {bytes} bytes, over the budget of \
         {TABLE_BUDGET_BYTES} bytes (1 GiB)"
    )))
}

/// The product of `factors` (saturating: a size too large to count is over any budget).
pub fn product(factors: &[usize]) -> u64 {
    factors
        .iter()
        .fold(1u64, |p, &f| p.saturating_mul(f as u64))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tables_over_the_budget_are_named_with_their_bytes() {
        assert!(check_table_bytes("nishita", "x", TABLE_BUDGET_BYTES).is_ok());
        let e = check_table_bytes("nishita", "table_heights=9 x table_angles=9", 1 << 31)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("nishita tables of table_heights=9 x table_angles=9 need 2147483648 bytes"),
            "{e}"
        );
        assert_eq!(product(&[usize::MAX, usize::MAX]), u64::MAX);
        assert_eq!(product(&[3, 4, 5]), 60);
    }
}
