//! The value checks of a configuration's run-time options (initial
//! derivatives, estimate, output and rate limits, initial output): each value
//! on its own; how they combine with the law is the builder's (builder.rs).

use crate::error::{positive, ConfigError};
use crate::Real;

/// Checks the estimate limits `|z_hat_i| <= limit_i` (docs/design.md §3.8):
/// every limit `> 0`, infinity allowed (no limit for that estimate).
///
/// ```
/// use famcc_core::config::check_estimate_limits;
/// assert!(check_estimate_limits(&[2.0_f64, f64::INFINITY]).is_ok());
/// assert!(check_estimate_limits(&[2.0_f64, 0.0]).is_err());
/// ```
pub fn check_estimate_limits<T: Real>(limits: &[T]) -> Result<(), ConfigError> {
    if limits.iter().any(|v| v.is_nan() || *v <= T::zero()) {
        return Err(ConfigError::new(
            "estimate_limits",
            "must all be > 0 (inf allowed)",
        ));
    }
    Ok(())
}

/// The run-time options' own rules, each error naming its parameter.
pub(super) fn check_options<T: Real, const N: usize>(
    initial_derivatives: Option<&[T; N]>,
    estimate_limits: Option<&[T; N]>,
    output_limits: Option<(T, T)>,
    rate_limit: Option<T>,
    initial_output: Option<T>,
) -> Result<(), ConfigError> {
    if let Some(d) = initial_derivatives {
        if d.iter().any(|v| !v.is_finite()) {
            return Err(ConfigError::new("initial_derivatives", "must be finite"));
        }
        if d.iter().any(|v| v.abs() > T::scale_limit()) {
            return Err(ConfigError::new(
                "initial_derivatives",
                "must be at most 2^256 in f64 and 2^32 in f32 in magnitude (moderate values, e.g. 0)",
            ));
        }
    }
    if let Some(l) = estimate_limits {
        check_estimate_limits(l)?;
    }
    if let Some((lo, hi)) = output_limits {
        if lo.partial_cmp(&hi) != Some(core::cmp::Ordering::Less) {
            return Err(ConfigError::new(
                "output_limits",
                "must be a pair lo < hi (infinite ends allowed, NaN not)",
            ));
        }
    }
    if let Some(r) = rate_limit {
        positive(r, "rate_limit")?;
    }
    if initial_output.is_some_and(|u| !u.is_finite()) {
        return Err(ConfigError::new("initial_output", "must be finite"));
    }
    Ok(())
}
