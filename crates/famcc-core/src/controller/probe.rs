//! The validation probe (docs/design.md §3.9): a configuration is accepted
//! only when its first steps succeed for moderate inputs, so that no valid
//! configuration fails on its first sample and the recovery rule
//! (recover.rs) always has an estimate to restart from.
//!
//! For each probe error `e` in [`PROBE_ERRORS`] a fresh controller takes
//! the first step (the latch), a second step (the latched envelopes and the
//! advanced estimate, i.e. the estimate the recovery rule restarts from),
//! and a third with the envelopes at their final widths after `T_s`, all on
//! the sample `e` (with the measured vector `(e, d_2, ..., d_n)` when the
//! configuration has no differentiator). Every step must return `Ok`.
//!
//! When a step fails, the error names the parameter found responsible: the
//! initial derivatives when the probe passes without them, `k_u` when its
//! product with the largest Gamma overflows, `mu` when the same law passes
//! with state feedback, the stage laws otherwise.

use super::clock::Clock;
use super::recover::initial_estimate;
use super::Controller;
use crate::{differentiator, Config, ConfigError, Real};

/// The errors the probe steps with (`|e| <= 1e3`: "moderate").
pub const PROBE_ERRORS: [f64; 4] = [0.0, 1.0, 1e3, -1e3];

/// Checks that the first steps of `c` succeed for every probe error.
pub(crate) fn probe<T: Real, const N: usize>(c: &Config<T, N>) -> Result<(), ConfigError> {
    if runs(c, true) {
        return Ok(());
    }
    if c.initial_derivatives().is_some() {
        if let Ok(plain) = c.to_builder().initial_derivatives(None).build_unprobed() {
            if runs(&plain, true) {
                return Err(ConfigError::new(
                    "initial_derivatives",
                    "are so large that the first step overflows for |e| <= 1e3 (use moderate \
                     values, e.g. 0)",
                ));
            }
        }
    }
    let largest = c.gamma().eval(T::one() - T::epsilon() * T::from_f64(0.5));
    if !(c.k_u() * largest).is_finite() {
        return Err(ConfigError::new(
            "k_u",
            "is so large that k_u Gamma(xi) overflows (the paper uses k_u between 2 and 30)",
        ));
    }
    if c.discretized().is_some() && runs(c, false) {
        return Err(ConfigError::new(
            "mu",
            "(with dt) gives differentiator gains so large that the first steps overflow for \
             |e| <= 1e3 (the paper's mu = 0.01 at dt = 1e-3)",
        ));
    }
    Err(ConfigError::new(
        "feedback",
        "(the stage laws with their skews) overflows at moderate errors |e| <= 1e3: lower the \
         gains, widths or exponents (the paper's are near 1)",
    ))
}

/// True when the probe's steps all succeed, stepping the output error when
/// `output` and the configuration allows it, the measured vector otherwise.
fn runs<T: Real, const N: usize>(c: &Config<T, N>, output: bool) -> bool {
    let by_error = output && (c.discretized().is_some() || !differentiator::needed_at(c.plant_order()));
    PROBE_ERRORS.iter().all(|&e| {
        let e = T::from_f64(e);
        let z = initial_estimate(c, e);
        let mut ctrl = Controller::new(*c);
        let step = |ctrl: &mut Controller<T, N>| {
            if by_error {
                ctrl.step(e).is_ok()
            } else {
                ctrl.step_state(z).is_ok()
            }
        };
        if !(step(&mut ctrl) && step(&mut ctrl)) {
            return false;
        }
        let st = &mut ctrl.state;
        for w in [&mut st.envelopes.x, &mut st.envelopes.y] {
            w.rho0 = w.eps;
        }
        let settle = c.settle_time();
        st.clock = Clock::at(settle.to_f64_lossless(), 0, c.dt(), settle);
        step(&mut ctrl)
    })
}
