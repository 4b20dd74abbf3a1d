//! The public step methods of [`Controller`]: output feedback from `e`
//! (or from `y` and `y_d`), with a one-off period, and state feedback. The
//! sign convention of every one is `e = y - y_d` (output minus reference).

use super::{Controller, Measured};
use crate::error::StepError;
use crate::Real;

impl<T: Real, const N: usize> Controller<T, N> {
    /// One output-feedback step at the nominal `dt` (eq. (35)): the error
    /// sample `e = y - y_d` (output minus reference, the opposite of a PID's
    /// `setpoint - y`) in, the output to hold until the next sample out.
    #[inline]
    pub fn step(&mut self, e: T) -> Result<T, StepError> {
        self.control_then_advance(Measured::Error(e), None, None)
    }

    /// [`Controller::step`], telling the controller the input the actuator
    /// really applied at the previous sample (diagnostics report the gap; an
    /// applied input that differs from the previous output marks the
    /// actuator as limited, for the integral separation and the health
    /// count). `e = y - y_d`.
    #[inline]
    pub fn step_applied(&mut self, e: T, applied: Option<T>) -> Result<T, StepError> {
        self.control_then_advance(Measured::Error(e), None, applied)
    }

    /// One step from the measured output `y` and the reference `y_d`: the
    /// error is `e = y - y_d` (output minus reference, the opposite of a
    /// PID's `setpoint - y`). A non-finite `y` or `y_d` is
    /// [`StepError::NonFiniteInput`]; a difference that overflows is
    /// [`StepError::Overflow`] (state unchanged).
    ///
    /// ```
    /// use famcc_core::{Config, Constraint, Controller, Feedback, HighGain};
    /// let cfg = Config::<f64, 2>::builder(1e-3, &[(Feedback::Linear { k: 1.0 }, None)],
    ///                                     Constraint::Lateral { eps: 0.1 }, 5.0)
    ///     .differentiator(Some(HighGain::paper())).build().unwrap();
    /// let (mut a, mut b) = (Controller::new(cfg), Controller::new(cfg));
    /// assert_eq!(a.step_output(0.25, 1.0, None), b.step(-0.75));
    /// ```
    #[inline]
    pub fn step_output(&mut self, y: T, y_d: T, applied: Option<T>) -> Result<T, StepError> {
        if !(y.is_finite() && y_d.is_finite()) {
            return Err(StepError::NonFiniteInput);
        }
        let e = y - y_d;
        if !e.is_finite() {
            return Err(StepError::Overflow);
        }
        self.control_then_advance(Measured::Error(e), None, applied)
    }

    /// One step with a one-off sample period `dt` (the differentiator is
    /// rediscretized for it; the nominal discretization is kept). `e = y - y_d`.
    pub fn step_dt(&mut self, e: T, dt: T, applied: Option<T>) -> Result<T, StepError> {
        self.control_then_advance(Measured::Error(e), Some(dt), applied)
    }

    /// One state-feedback step with a measured error vector (paper Theorems
    /// 1-2), `z1 = y - y_d` and its derivatives, in the law's coordinates:
    /// `z = (z1, ..., zn)`, or with integral action `z[1..N] = (z1, ...,
    /// zn)` and `z[0]` ignored (the controller's own integral is used). A
    /// configured differentiator keeps tracking `z1`.
    pub fn step_state(&mut self, z: [T; N]) -> Result<T, StepError> {
        self.control_then_advance(Measured::State(z), None, None)
    }

    /// [`Controller::step_state`] with the applied input of the previous
    /// sample; `z1 = y - y_d`.
    pub fn step_state_applied(&mut self, z: [T; N], applied: Option<T>) -> Result<T, StepError> {
        self.control_then_advance(Measured::State(z), None, applied)
    }

    /// The number of steps so far at which the bounds were expanded while
    /// the actuator was known to have headroom (cheap; also in
    /// [`super::Diagnostics::unsaturated_expansions`]).
    pub fn unsaturated_expansions(&self) -> u64 {
        self.state.diag.unsaturated_expansions
    }
}
