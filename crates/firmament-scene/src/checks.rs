//! The checks every rule of the scene format is written with: each error names the key path, the
//! value and the rule. A leaf: the validation and the conversion code both use it.

use firmament_core::TimeOfDay;

use crate::error::SceneError;

/// Checks `ok`, or fails with `key = value: rule`.
pub(crate) fn check(ok: bool, key: &str, value: impl std::fmt::Display, rule: &str) -> Result<(), SceneError> {
    if ok {
        Ok(())
    } else {
        Err(SceneError::invalid(key, value, rule))
    }
}

/// Checks that `value` is finite and inside `[lo, hi]`.
pub(crate) fn in_range(key: &str, value: f64, lo: f64, hi: f64, unit: &str) -> Result<(), SceneError> {
    check(
        value.is_finite() && (lo..=hi).contains(&value),
        key,
        value,
        &format!("must be in [{lo}, {hi}]{unit}"),
    )
}

/// Checks that `value` is finite and > 0.
pub(crate) fn positive(key: &str, value: f64, unit: &str) -> Result<(), SceneError> {
    check(
        value.is_finite() && value > 0.0,
        key,
        value,
        &format!("must be a finite number > 0{unit}"),
    )
}

/// Checks that `value` is finite and >= 0.
pub(crate) fn non_negative(key: &str, value: f64) -> Result<(), SceneError> {
    check(
        value.is_finite() && value >= 0.0,
        key,
        value,
        "must be a finite number >= 0",
    )
}

/// Parses a time of day, naming `key` in the error.
pub(crate) fn time_of_day(key: &str, text: &str) -> Result<TimeOfDay, SceneError> {
    text.parse::<TimeOfDay>()
        .map_err(|e| SceneError::invalid(key, format!("\"{text}\""), e.rule))
}
