//! The sample clock (docs/design.md §3.1, §3.10): an integer sample count
//! and an `f64` time base, so the time never stalls or drifts, in `f32` as
//! in `f64`.
//!
//! The clock counts the samples of the current *run*, a stretch of samples
//! at one period (the nominal `dt`, or a one-off period of `step_dt` given
//! repeatedly). The time of the next sample is `base + k * period`, one
//! `f64` product and one sum, exact to an `f64` rounding for any count up
//! to `u64::MAX` (the count saturates there). Only a change of period adds
//! a rounding (of `base`), so even `10^10` one-off periods stay within a
//! fraction of a sample.
//!
//! The law needs the time only while the envelopes shrink (eq. (4): `rho`
//! equals `eps` exactly from `T_s` on), so its time is `min(t, T_s)` in `T`,
//! computed without `f64` arithmetic on the nominal path (soft-float on an
//! FPU of single precision); the `f64` time is computed only when read.
//!
//! ```
//! use famcc_core::{Config, Constraint, Controller};
//! let cfg = Config::<f32, 1>::builder(1e-3, &[], Constraint::Longitudinal { eps: 0.1 }, 5.0)
//!     .build().unwrap();
//! let mut c = Controller::new(cfg);
//! let mut snap = c.snapshot();
//! snap.started = true;
//! snap.k = 100_000_000_000;         // 10^11 samples at 1 ms: 10^8 s
//! c.restore(&snap).unwrap();
//! c.step(0.0).unwrap();
//! assert_eq!(c.diagnostics().t, 1e11 * f64::from(1e-3_f32));
//! assert_eq!(c.samples(), 100_000_000_001);
//! ```

use crate::Real;

/// Position of the sample clock: `k` samples at `period` since `base`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Clock<T> {
    /// Time of sample 0 of the current run, seconds (exact `f64`).
    pub base: f64,
    /// Samples taken in the current run (saturating).
    pub k: u64,
    /// The period of the current run, seconds.
    pub period: T,
    /// `min(base, T_s)` in `T`: the law's time base.
    law_base: T,
    /// True once a sample of this run had the law's time `T_s`: every later
    /// one has it too (the time is non-decreasing in `k`), so the settled
    /// step skips the product.
    law_settled: bool,
}

impl<T: Real> Clock<T> {
    /// Sample 0 at time 0, nominal period `dt`.
    pub fn start(dt: T) -> Self {
        Self {
            base: 0.0,
            k: 0,
            period: dt,
            law_base: T::zero(),
            law_settled: false,
        }
    }

    /// A clock at `k` samples of `period` after `base` (a restored state;
    /// `base` finite and `>= 0`, `period` finite and `> 0`).
    pub fn at(base: f64, k: u64, period: T, settle_time: T) -> Self {
        Self {
            base,
            k,
            period,
            law_base: law_base(base, settle_time),
            law_settled: false,
        }
    }

    /// The time of the next sample, seconds.
    #[inline]
    pub fn time(&self) -> f64 {
        self.base + self.k as f64 * self.period.to_f64_lossless()
    }

    /// The law's time of the next sample: `min(t, T_s)` in `T`.
    #[inline(always)]
    fn law_time(&self, settle_time: T) -> T {
        // (A run that starts at or after `T_s` needs no test of its own:
        // `law_base >= T_s` makes every `t` below `>= T_s`.)
        if self.law_settled {
            return settle_time;
        }
        let t = self.law_base + T::from_u64(self.k) * self.period;
        // `t.min(settle_time)` without its NaN handling (`t` is never NaN).
        if t < settle_time {
            t
        } else {
            settle_time
        }
    }

    /// The next sample, taken with period `dt`: the law's time of this sample
    /// (`min(t, T_s)` in `T`, bit for bit `k * dt` while a run at the nominal
    /// period starts at 0, the paper's sampled law, and `t < T_s`), and the
    /// clock after it. The run goes on when `dt` is its period, otherwise a
    /// new run starts at this sample. `None` when the time would not be finite.
    #[inline(always)]
    pub fn sample(&self, dt: T, settle_time: T) -> Option<(T, Self)> {
        let t = self.law_time(settle_time);
        if crate::compiled::continues_run(dt, self.period) {
            let next = Self {
                k: self.k.saturating_add(1),
                law_settled: t >= settle_time,
                ..*self
            };
            return Some((t, next));
        }
        let base = self.time();
        let end = base + dt.to_f64_lossless();
        end.is_finite().then(|| {
            let next = Self {
                base,
                k: 1,
                period: dt,
                law_base: law_base(base, settle_time),
                law_settled: false,
            };
            (t, next)
        })
    }
}

/// `min(base, T_s)` rounded to `T`.
fn law_base<T: Real>(base: f64, settle_time: T) -> T {
    T::from_f64(base.min(settle_time.to_f64_lossless()))
}
