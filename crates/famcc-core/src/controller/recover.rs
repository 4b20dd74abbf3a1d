//! The recovery rule (docs/design.md §3.7): the one place that decides what
//! a step whose finite sample could not be used leaves behind.
//!
//! The estimate is kept in range, `|z_hat_i| <= R` with `R` =
//! [`Real::estimate_range`] (`2^512` in `f64`, `2^64` in `f32`). A step
//! after the first fails with [`crate::StepError::Overflow`] when the law
//! overflowed on its estimate, or when the update would take the estimate
//! (or the integral) out of range. The sample is then consumed: the clock
//! advances, the latched envelopes, the diagnostics and the last output stay,
//! and the estimate *restarts* as at the first step (§3.4), from this
//! step's sample: `Phi (e, d_2, ..., d_n) + Gamma e` (the integral at 0; the
//! measured vector for `step_state`). When that is out of range too (the
//! sample itself is the outlier), or when the update overflowed on a sample
//! beyond the probe's range (`|e| > 1e3`), it restarts from a zero error.
//!
//! With the first-order hold ([`crate::Discretization::Foh`]) the next
//! sample adds no feedthrough to the restarted estimate (its clock starts a
//! run at count 0 to say so): otherwise every restart would meet the
//! increment of a moving error with zero derivatives, and a law that
//! overflows on that peaking would fail every sample.
//!
//! So the stored estimate is always in range, and a sample that the first
//! step could use (validation guarantees that for `|e| <= 1e3`, §3.9) makes
//! the next step's estimate one the law can use: after any finite input,
//! the second moderate sample returns `Ok` (at most one `Overflow` among
//! the moderate samples: [`RECOVERY_SAMPLES`]).

use super::probe::PROBE_LIMIT;
use super::Measured;
use crate::differentiator::Recursion;
use crate::{Config, Real};

/// The number of moderate samples (`|e| <= 1e3`, docs/design.md §3.9)
/// after which a controller returns `Ok` again, whatever came before: the
/// first may still return `Overflow` (and restarts the estimate), the
/// second is `Ok`.
pub const RECOVERY_SAMPLES: usize = 2;

/// True when every entry is within the estimate's range (NaN is not).
#[inline(always)]
pub(super) fn in_range<T: Real, const N: usize>(z: &[T; N]) -> bool {
    let r = T::estimate_range();
    // Without short-circuit, so that the comparisons vectorize.
    z.iter().fold(true, |ok, v| ok & (v.abs() <= r))
}

/// True when a latched envelope width can be used: finite (the oblique
/// constraint's `sqrt(x_U^2 + y_U^2)` is scaled when the squares overflow).
#[inline(always)]
pub(super) fn width_in_range<T: Real>(w: T) -> bool {
    w.is_finite()
}

/// Why a step could not use its sample.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Cause {
    /// The law overflowed on the stored estimate: the sample may be fine.
    Law,
    /// The update would take the estimate or the integral out of range: the
    /// sample is (or drove) the outlier.
    Update,
}

/// The estimate the next step uses after this step's sample could not be
/// used: restarted from the sample, else from a zero error (the module
/// docs), with the differentiator's input it restarted from (the prefilter
/// restarts at that sample). `hgd` is this step's discretization.
pub(super) fn restarted<T: Real, const N: usize>(
    c: &Config<T, N>,
    measured: &Measured<T, N>,
    hgd: Option<&Recursion<T, N>>,
    cause: Cause,
) -> ([T; N], T) {
    let zero = Measured::Error(T::zero());
    // After an update overflow the sample is (or drove) the outlier: the
    // estimate restarts from a zero error, unless the sample is moderate
    // (the probe's range, §3.9), where a zero restart could overflow again
    // on the same moderate sample for good (f32, high differentiator gains)
    // while the first step's estimate from it is one the probe stepped from.
    let from_sample = match cause {
        Cause::Law => Some(measured),
        Cause::Update => moderate(measured).then_some(measured),
    };
    for m in from_sample.into_iter().chain([&zero]) {
        let (seed, e) = seed(c, m);
        let next = match hgd {
            Some(d) => d.advance(&seed, e),
            None => seed,
        };
        if in_range(&next) {
            return (next, e);
        }
    }
    // Unreachable for a validated configuration (the zero error's estimate
    // is in range, §3.9); zeros are in range in any case.
    ([T::zero(); N], T::zero())
}

/// True when the measurement lies in the probe's range (`|.| <= PROBE_LIMIT`).
fn moderate<T: Real, const N: usize>(m: &Measured<T, N>) -> bool {
    let limit = T::from_f64(PROBE_LIMIT);
    match m {
        Measured::Error(e) => e.abs() <= limit,
        Measured::State(z) => z.iter().all(|v| v.abs() <= limit),
    }
}

/// The first step's estimate for a measurement, with the integral at 0,
/// and the measured error.
fn seed<T: Real, const N: usize>(c: &Config<T, N>, m: &Measured<T, N>) -> ([T; N], T) {
    let off = c.estimate_offset();
    match m {
        Measured::Error(e) => (c.initial_estimate(*e), *e),
        Measured::State(z) => {
            let mut z = *z;
            z.iter_mut().take(off).for_each(|i| *i = T::zero());
            (z, z.get(off).copied().unwrap_or_else(T::zero))
        }
    }
}
