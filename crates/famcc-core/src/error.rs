//! Error values. famcc-core never panics: invalid configurations and invalid
//! inputs come back as these values. Both implement [`core::error::Error`]
//! (no `std` needed), so `?` converts them into any error type that wraps one.

use core::fmt;

/// A rejected configuration value: which parameter, at which stage (for
/// per-stage lists), and the rule it broke.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ConfigError {
    /// The parameter's name, as in the paper and the Python API (`eps`, `p`, `k_u`, ...).
    pub parameter: &'static str,
    /// Zero-based stage index for per-stage parameters (stage `i` builds `h_m(i+1)`).
    pub stage: Option<usize>,
    /// The rule the value broke, e.g. `"must be > 0"`.
    pub rule: &'static str,
}

impl ConfigError {
    /// An error for a global parameter.
    pub const fn new(parameter: &'static str, rule: &'static str) -> Self {
        Self {
            parameter,
            stage: None,
            rule,
        }
    }

    /// The same error, attributed to a stage.
    pub const fn at_stage(mut self, stage: usize) -> Self {
        self.stage = Some(stage);
        self
    }
}

impl fmt::Display for ConfigError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.stage {
            Some(i) => write!(f, "stage {}: {} {}", i + 1, self.parameter, self.rule),
            None => write!(f, "{} {}", self.parameter, self.rule),
        }
    }
}

impl core::error::Error for ConfigError {}

/// Checks `x > 0` (and finite), and that it is a scale the controller can
/// compute with: within `[1 / S, S]`, `S` = [`crate::Real::scale_limit`]
/// (docs/design.md §3.9).
pub(crate) fn positive<T: crate::Real>(x: T, name: &'static str) -> Result<(), ConfigError> {
    if !(x.is_finite() && x > T::zero()) {
        return Err(ConfigError::new(name, "must be finite and > 0"));
    }
    scale(x, name)
}

/// Checks `1 / S <= |x| <= S` for a nonzero scale parameter (docs/design.md §3.9).
pub(crate) fn scale<T: crate::Real>(x: T, name: &'static str) -> Result<(), ConfigError> {
    let s = T::scale_limit();
    if x.abs() <= s && x.abs() >= T::one() / s {
        Ok(())
    } else {
        Err(ConfigError::new(
            name,
            "must be within [2^-256, 2^256] in f64 and [2^-32, 2^32] (2.3e-10 to 4.3e9) in f32, \
             so that the law stays far from overflow (the paper's values are near 1)",
        ))
    }
}

/// A step that could not be taken. The controller's state is unchanged.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StepError {
    /// The measurement (or an element of the state vector) was NaN or infinite.
    NonFiniteInput,
    /// The `applied` input was NaN or infinite.
    NonFiniteApplied,
    /// A one-off sample period was not finite and > 0, or outside the scale
    /// range of the configuration (docs/design.md §3.9).
    InvalidDt,
    /// `step(e)` at order >= 2 needs a differentiator; without one use
    /// `step_state` with the measured error vector.
    NoDifferentiator,
    /// The input was finite but so large that an internal quantity overflowed.
    /// Before the first step, or when the estimate itself overflowed, nothing
    /// changed; otherwise the sample was consumed (estimate and clock
    /// advanced) and the caller should hold its previous output.
    Overflow,
}

impl fmt::Display for StepError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            StepError::NonFiniteInput => "input must be finite (got NaN or infinity); state unchanged",
            StepError::NonFiniteApplied => "applied input must be finite; state unchanged",
            StepError::InvalidDt => "dt must be finite and > 0; state unchanged",
            StepError::NoDifferentiator => {
                "step(e) at order >= 2 needs a differentiator; use step_state(z) for state feedback"
            }
            StepError::Overflow => "input too large: an internal value overflowed; hold the previous output",
        })
    }
}

impl core::error::Error for StepError {}
