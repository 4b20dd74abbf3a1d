//! The FAMCC law on the extended differentiator's estimates, with the
//! estimated lumped term cancelled, bounded (beyond the paper;
//! docs/observer.md "In the law").
//!
//! [`ObservedController`] composes a [`Controller`] in state feedback (its
//! configuration without a differentiator) with an [`ExtendedHighGain`]:
//! at sample `k` the law gets the observer's `Zhat_k` as the measured error
//! vector and gives `v_k = -k_u Gamma(xi_k)` on the same manifold, envelopes
//! and flexible boundaries, and the command is
//!
//! ```text
//! u_k = v_k - c_k,      c_k = clip(Lhat_k / b0, -delta, delta)
//! ```
//!
//! so the barrier sees the bounded remainder `L - b0 c` of the lumped term
//! and holds only what `c` does not cancel. The observer advances at the
//! next sample with the input the actuator applied (`applied`, when the
//! caller knows it: a saturated actuator; else `u_k` itself).
//!
//! ```
//! use famcc_core::{Config, Constraint, ExtendedHighGain, Feedback, ObservedController};
//! let law = Config::<f64, 2>::builder(1e-3, &[(Feedback::FiniteTime { k: 1.0, p: 0.7 }, None)],
//!                                     Constraint::Lateral { eps: 0.1 }, 5.0)
//!     .build()
//!     .unwrap();
//! let obs = ExtendedHighGain::binomial(0.02, 1.5); // b0 = 1.5
//! let mut ctrl = ObservedController::new(law, obs, 4.0).unwrap(); // |c| <= 4
//! let u = ctrl.step(-0.5).unwrap();
//! assert!(u > 0.0 && ctrl.cancellation() == 0.0); // Lhat starts at 0
//! ```

use crate::error::positive;
use crate::{Config, ConfigError, Controller, DiscreteExtended, ExtendedHighGain, Real, StepError};

/// The law on the extended differentiator's estimates (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ObservedController<T, const N: usize> {
    law: Controller<T, N>,
    observer: DiscreteExtended<T, N>,
    b0: T,
    delta: T,
    /// The estimate the next step uses before its advance: `(Zhat, Lhat)_k`.
    zhat: [T; N],
    lhat: T,
    /// The last step's sample, command and cancellation (`None` before the first).
    last: Option<(T, T, T)>,
}

impl<T: Real, const N: usize> ObservedController<T, N> {
    /// The law `config` (state feedback: no differentiator, no integral
    /// action) on the observer `observer` discretized at `config.dt()`, the
    /// cancellation bounded by `delta` (input units, `> 0`: a stated share
    /// of the input range).
    ///
    /// Errors name the parameter: `differentiator` (the observer's
    /// estimates replace it), `integral` (the observer's `Lhat` takes its
    /// role), `delta`, or the observer's own.
    pub fn new(
        config: Config<T, N>,
        observer: ExtendedHighGain<T, N>,
        delta: T,
    ) -> Result<Self, ConfigError> {
        if config.recursion().is_some() {
            return Err(ConfigError::new(
                "differentiator",
                "must be None with an observer: the observer's estimates replace it",
            ));
        }
        if config.integral() {
            return Err(ConfigError::new(
                "integral",
                "must be off with an observer: its estimate of the lumped term removes the steady error",
            ));
        }
        positive(delta, "delta")?;
        let discrete = observer.discretize(config.dt())?;
        Ok(Self {
            law: Controller::new(config),
            observer: discrete,
            b0: observer.b0,
            delta,
            zhat: [T::zero(); N],
            lhat: T::zero(),
            last: None,
        })
    }

    /// One step: the error sample `e = y - y_d` in, the command `u` to hold
    /// until the next sample out.
    #[inline]
    pub fn step(&mut self, e: T) -> Result<T, StepError> {
        self.step_applied(e, None)
    }

    /// [`ObservedController::step`], told the input the actuator applied
    /// at the previous sample (it drives the observer; without it the last
    /// command is taken as applied). On an error the observer's state is
    /// unchanged, but for [`StepError::Overflow`] after the first step (the
    /// law consumed the sample: the estimate advances with it).
    pub fn step_applied(&mut self, e: T, applied: Option<T>) -> Result<T, StepError> {
        if !e.is_finite() || applied.is_some_and(|u| !u.is_finite()) {
            return Err(StepError::NonFiniteInput);
        }
        let (zhat, lhat) = match self.last {
            None => self.restart(e),
            Some((e_prev, u_prev, _)) => {
                let u = applied.unwrap_or(u_prev);
                let (v, vl) = self.observer.advance(&self.zhat, self.lhat, e_prev, u);
                let (z, l) = self.observer.current(&v, vl, e - e_prev);
                let range = T::estimate_range();
                if z.iter().all(|x| x.abs() <= range) && l.abs() <= range {
                    (z, l)
                } else {
                    self.restart(e) // an outlier drove the estimate out of range
                }
            }
        };
        // The law is told the part of the applied input that was its own.
        let told = match (applied, self.last) {
            (Some(u), Some((_, _, c))) => Some(u + c),
            _ => None,
        };
        let c = clamp(lhat / self.b0, self.delta);
        match self.law.step_state_applied(zhat, told) {
            Ok(v) => {
                let u = v - c;
                if !u.is_finite() {
                    return Err(StepError::Overflow);
                }
                (self.zhat, self.lhat, self.last) = (zhat, lhat, Some((e, u, c)));
                Ok(u)
            }
            Err(StepError::Overflow) if self.last.is_some() => {
                let held = self.last.map_or(T::zero(), |(_, u, _)| u);
                (self.zhat, self.lhat, self.last) = (zhat, lhat, Some((e, held, c)));
                Err(StepError::Overflow)
            }
            Err(err) => Err(err),
        }
    }

    /// The observer's estimate from `e` alone: `(e, 0, ..., 0)` and `Lhat = 0`.
    fn restart(&self, e: T) -> ([T; N], T) {
        let mut z = [T::zero(); N];
        if let Some(z1) = z.first_mut() {
            *z1 = e;
        }
        (z, T::zero())
    }

    /// Back to the state before the first step.
    pub fn reset(&mut self) {
        self.law.reset();
        (self.zhat, self.lhat, self.last) = ([T::zero(); N], T::zero(), None);
    }

    /// The law (its configuration and diagnostics: `xi`, the bounds, ...).
    pub fn law(&self) -> &Controller<T, N> {
        &self.law
    }

    /// The observer's estimate `(Zhat, Lhat)` the last step used.
    pub fn estimate(&self) -> (&[T; N], T) {
        (&self.zhat, self.lhat)
    }

    /// The last step's cancellation `c = clip(Lhat / b0, -delta, delta)`
    /// (0 before the first).
    pub fn cancellation(&self) -> T {
        self.last.map_or(T::zero(), |(_, _, c)| c)
    }
}

/// `x` clipped to `[-bound, bound]` (NaN to 0).
#[inline(always)]
fn clamp<T: Real>(x: T, bound: T) -> T {
    if x > bound {
        bound
    } else if x < -bound {
        -bound
    } else if x.is_nan() {
        T::zero()
    } else {
        x
    }
}
