//! The observer option of a configuration (feature `observer`, beyond the
//! paper; docs/observer.md "In the law"): the extended high-gain
//! differentiator replaces the plain one, and its estimate of the lumped
//! term is cancelled, bounded, inside the law:
//!
//! ```text
//! u_k = v_k - c_k,      c_k = clip(Lhat_k / b0, -delta, delta)
//! ```
//!
//! `v_k = -k_u Gamma(xi_k)` on the same manifold, envelopes and flexible
//! boundaries, computed on the observer's `Zhat_k`; the output limits apply
//! to the total `u_k` (so saturation is judged on what the actuator gets).
//!
//! ```
//! use famcc_core::{Config, Constraint, Controller, ExtendedHighGain, Feedback};
//! let cfg = Config::<f64, 2>::builder(1e-3, &[(Feedback::FiniteTime { k: 1.0, p: 0.7 }, None)],
//!                                     Constraint::Lateral { eps: 0.1 }, 5.0)
//!     .observer(Some(ExtendedHighGain::binomial(0.02, 1.5))) // b0 = 1.5
//!     .output_limits(Some((-8.0, 8.0)))                       // delta = 8 by default
//!     .build()
//!     .unwrap();
//! assert_eq!(cfg.cancellation_limit(), Some(8.0));
//! let mut ctrl = Controller::new(cfg);
//! let u = ctrl.step(-0.5).unwrap();
//! assert!(u > 0.0 && ctrl.diagnostics().cancellation == 0.0); // Lhat starts at 0
//! ```

use super::builder::ConfigBuilder;
use crate::error::positive;
use crate::{Config, ConfigError, DiscreteExtended, ExtendedHighGain, Real};

/// The share of the output range `(lo, hi)` that bounds the cancellation
/// by default: `delta = DEFAULT_CANCELLATION_SHARE (hi - lo)` (`U` for
/// limits `±U`).
pub const DEFAULT_CANCELLATION_SHARE: f64 = 0.5;

/// The observer as a configuration holds it: its parameters, its recursion
/// at the nominal period and the cancellation's bound.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Observed<T, const N: usize> {
    pub spec: ExtendedHighGain<T, N>,
    pub discrete: DiscreteExtended<T, N>,
    pub delta: T,
}

impl<T: Real, const N: usize> ConfigBuilder<T, N> {
    /// The extended high-gain differentiator (docs/observer.md), or `None`
    /// (the default: the paper's law). It replaces the differentiator
    /// (which must then be `None`) and needs integral action off (its
    /// estimate of the lumped term removes the steady error instead).
    pub fn observer(mut self, observer: Option<ExtendedHighGain<T, N>>) -> Self {
        self.observer = observer;
        self
    }

    /// The bound `delta > 0` of the cancellation `|c| <= delta` (input
    /// units). `None` (the default): [`DEFAULT_CANCELLATION_SHARE`] of the
    /// output range; required without finite output limits.
    pub fn cancellation_limit(mut self, delta: Option<T>) -> Self {
        self.cancellation_limit = delta;
        self
    }

    /// The observer's rules, and its recursion at `dt` (`None` without one).
    pub(super) fn observed(&self) -> Result<Option<Observed<T, N>>, ConfigError> {
        let Some(spec) = self.observer else {
            if self.cancellation_limit.is_some() {
                return Err(ConfigError::new(
                    "cancellation_limit",
                    "needs an observer (it bounds the observer's cancellation)",
                ));
            }
            return Ok(None);
        };
        if self.differentiator.is_some() {
            return Err(ConfigError::new(
                "differentiator",
                "must be None with an observer: the observer's estimates replace it",
            ));
        }
        if crate::Direction::of(spec.b0).is_some_and(|d| d != self.direction) {
            return Err(ConfigError::new(
                "b0",
                "must have the sign of the control direction: a negative b0 needs direction \
                 Negative, a positive one Positive (both are the sign of the plant's input gain)",
            ));
        }
        if self.integral {
            return Err(ConfigError::new(
                "integral",
                "must be off with an observer: its estimate of the lumped term removes the steady error",
            ));
        }
        let delta = match (self.cancellation_limit, self.output_limits) {
            (Some(d), _) => d,
            (None, Some((lo, hi))) if (hi - lo).is_finite() => {
                T::from_f64(DEFAULT_CANCELLATION_SHARE) * (hi - lo)
            }
            (None, _) => {
                return Err(ConfigError::new(
                    "cancellation_limit",
                    "is required without finite output limits: e.g. the largest holding input you \
                     expect, doubled",
                ))
            }
        };
        positive(delta, "cancellation_limit")?;
        crate::compiled::discretization(spec.discretization)?;
        let discrete = spec.discretize(self.dt)?;
        Ok(Some(Observed {
            spec,
            discrete,
            delta,
        }))
    }
}

impl<T: Real, const N: usize> Config<T, N> {
    /// The extended high-gain differentiator, if configured.
    pub fn observer(&self) -> Option<&ExtendedHighGain<T, N>> {
        self.observed.as_ref().map(|o| &o.spec)
    }

    /// The cancellation's bound `delta`, with an observer.
    pub fn cancellation_limit(&self) -> Option<T> {
        self.observed.as_ref().map(|o| o.delta)
    }

    /// The observer as the step runs it.
    #[inline(always)]
    pub(crate) fn observed(&self) -> Option<&Observed<T, N>> {
        self.observed.as_ref()
    }
}
