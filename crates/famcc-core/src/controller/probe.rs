//! The validation probe (docs/design.md §3.9): a configuration is accepted
//! only when its first steps succeed for moderate inputs, so that no valid
//! configuration fails on its first sample and the recovery rule
//! (recover.rs) always has an estimate to restart from.
//!
//! For each probe error `e` of [`probe_errors`] (zero, and both signs of
//! [`PROBE_PER_DECADE`] magnitudes a decade from `1e-3` to [`PROBE_LIMIT`]:
//! a law can overflow in a band of moderate errors and not at its ends, e.g.
//! Moulay's exponent `lambda/mu` of order 100) a fresh controller takes
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
use super::{Controller, Measured};
use crate::{differentiator, Config, ConfigError, Real};

/// The largest probe error: `|e| <= 1e3` is "moderate".
pub const PROBE_LIMIT: f64 = 1e3;

/// Probe magnitudes per decade (from `1e-3` to [`PROBE_LIMIT`]).
pub const PROBE_PER_DECADE: usize = 8;

/// The number of probe errors: zero and `±m` for `6 PROBE_PER_DECADE + 1`
/// magnitudes `m`.
pub const PROBE_COUNT: usize = 2 * (6 * PROBE_PER_DECADE + 1) + 1;

/// The `i`-th probe error (`i < PROBE_COUNT`): `0`, then `+m_j`, `-m_j` for
/// `m_j = 1e-3 · 10^(j / PROBE_PER_DECADE)`, `j = 0, ..., 6 PROBE_PER_DECADE`
/// (the last is exactly [`PROBE_LIMIT`]).
///
/// ```
/// use famcc_core::{probe_error, PROBE_COUNT, PROBE_LIMIT};
/// assert_eq!(probe_error(0), 0.0);
/// assert_eq!(probe_error(PROBE_COUNT - 2), PROBE_LIMIT);
/// assert_eq!(probe_error(PROBE_COUNT - 1), -PROBE_LIMIT);
/// assert!((probe_error(1) - 1e-3).abs() < 1e-18);
/// ```
pub fn probe_error(i: usize) -> f64 {
    /// `10^(1/8)`.
    const STEP: f64 = 1.333_521_432_163_324;
    if i == 0 || i >= PROBE_COUNT {
        return 0.0;
    }
    let j = (i - 1) / 2;
    let last = 6 * PROBE_PER_DECADE;
    let m = if j >= last {
        PROBE_LIMIT
    } else {
        (0..j).fold(1e-3, |m, _| m * STEP)
    };
    if i % 2 == 1 {
        m
    } else {
        -m
    }
}

/// All probe errors, in the order of [`probe_error`].
pub fn probe_errors() -> impl Iterator<Item = f64> {
    (0..PROBE_COUNT).map(probe_error)
}

/// Checks that the first steps of `c` succeed for every probe error.
pub(crate) fn probe<T: Real, const N: usize>(c: &Config<T, N>) -> Result<(), ConfigError> {
    if runs(c, true) {
        return Ok(());
    }
    if c.initial_derivatives().is_some() && runs(&c.without_initial_derivatives(), true) {
        return Err(ConfigError::new(
            "initial_derivatives",
            "are so large that the first step overflows for |e| <= 1e3 (use moderate \
             values, e.g. 0)",
        ));
    }
    let largest = c.gamma().eval(T::one() - T::epsilon() * T::from_f64(0.5));
    if !(c.k_u() * largest).is_finite() {
        return Err(ConfigError::new(
            "k_u",
            "is so large that k_u Gamma(xi) overflows (the paper uses k_u between 2 and 30)",
        ));
    }
    if c.observing() && runs(c, false) {
        return Err(ConfigError::new(
            "observer_mu",
            "(with dt) gives observer gains so large that the first steps overflow for |e| <= 1e3 \
             (raise observer_mu, e.g. to 20 dt)",
        ));
    }
    if c.recursion().is_some() && runs(c, false) {
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
    let by_error =
        output && (c.recursion().is_some() || c.observing() || !differentiator::needed_at(c.plant_order()));
    probe_errors().all(|e| {
        let e = T::from_f64(e);
        let z = c.initial_estimate(e);
        let mut ctrl = Controller::new(*c);
        let step = |ctrl: &mut Controller<T, N>| step_ok(ctrl, by_error, e, z);
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

/// One probe step: of the error `e` when `by_error`, else of the measured
/// vector `z`, through the general step, which every configuration can take
/// (the unlimited steady step is its specialization, equal bit for bit:
/// tests/suite/fast_path.rs). So the probe adds no copy of the step to a
/// program (a microcontroller's flash).
fn step_ok<T: Real, const N: usize>(ctrl: &mut Controller<T, N>, by_error: bool, e: T, z: [T; N]) -> bool {
    let measured = if by_error {
        Measured::Error(e)
    } else {
        Measured::State(z)
    };
    ctrl.control_then_advance_general(measured, None, None).is_ok()
}
