//! The observer inside the step (feature `observer`; config/observer.rs,
//! docs/observer.md "In the law"): the estimate the law uses at sample `k`,
//! and the cancellation `c_k = clip(Lhat_k / b0, -delta, delta)`.
//!
//! The state holds `(Zhat, Lhat)_(k-1)`, the sample `e_(k-1)` and the
//! output `u_(k-1)`. At sample `k` the estimate advances over the elapsed
//! period with `e_(k-1)` and the input applied over it (told, else
//! `u_(k-1)`), then takes the first-order hold's feedthrough of
//! `e_k - e_(k-1)` ([`crate::DiscreteExtended::current`]). The first step,
//! and any estimate out of range, (re)starts from `(e_k, d_2, ..., d_n)`
//! and `Lhat = 0` (the recovery rule, recover.rs).

use super::{Controller, Measured};
use crate::Real;

/// What the observer gives a step.
#[derive(Clone, Copy)]
pub(super) struct Observation<T, const N: usize> {
    /// The error sample.
    pub e: T,
    /// The vector the law uses: the estimate (after the estimate limits),
    /// or the measured one of a state-feedback step.
    pub law: [T; N],
    /// The estimate to store, `Zhat_k`.
    pub next: [T; N],
    /// `Lhat_k`.
    pub lumped: T,
}

impl<T: Real, const N: usize> Controller<T, N> {
    /// The observer's estimate for this step (`None` without an observer).
    #[inline(always)]
    pub(super) fn observe(
        &self,
        first: bool,
        measured: &Measured<T, N>,
        applied: Option<T>,
    ) -> Option<Observation<T, N>> {
        #[cfg(feature = "observer")]
        if let Some(o) = self.config.observed() {
            return Some(self.observation(o, first, measured, applied));
        }
        let _ = (first, measured, applied);
        None
    }

    #[cfg(feature = "observer")]
    #[inline]
    fn observation(
        &self,
        o: &crate::config::Observed<T, N>,
        first: bool,
        measured: &Measured<T, N>,
        applied: Option<T>,
    ) -> Observation<T, N> {
        let e = match measured {
            Measured::Error(e) => *e,
            Measured::State(z) => z.first().copied().unwrap_or_else(T::zero),
        };
        let c = &self.config;
        let restart = || (c.initial_estimate(e), T::zero());
        let (next, lumped) = if first {
            restart()
        } else {
            let st = &self.state;
            let period = st.clock.period;
            let rediscretized;
            let d = if crate::compiled::continues_run(c.dt(), period) {
                &o.discrete
            } else {
                match o.spec.discretize(period) {
                    Ok(d) => {
                        rediscretized = d;
                        &rediscretized
                    }
                    Err(_) => &o.discrete,
                }
            };
            let u = applied.unwrap_or(st.diag.v);
            let (v, vl) = d.advance(&st.zhat, st.lhat, st.filtered, u);
            let (z, l) = d.current(&v, vl, e - st.filtered);
            if super::recover::in_range(&z) && super::recover::in_range(&[l]) {
                (z, l)
            } else {
                restart() // an outlier drove the estimate out of range
            }
        };
        let law = match measured {
            Measured::Error(_) => self.limited(next),
            Measured::State(z) => *z,
        };
        Observation { e, law, next, lumped }
    }

    /// The observer's estimate `Lhat` of the lumped term that the next step
    /// advances (0 without an observer and before the first step).
    pub fn lumped(&self) -> T {
        #[cfg(feature = "observer")]
        return self.state.lhat;
        #[cfg(not(feature = "observer"))]
        T::zero()
    }

    /// The cancellation `clip(Lhat / b0, -delta, delta)` of the estimate
    /// `lumped` (0 without an observer; NaN to 0).
    #[inline(always)]
    pub(super) fn cancellation(&self, lumped: T) -> T {
        #[cfg(feature = "observer")]
        if let Some(o) = self.config.observed() {
            let x = lumped / o.spec.b0;
            return if x > o.delta {
                o.delta
            } else if x < -o.delta {
                -o.delta
            } else if x.is_nan() {
                T::zero()
            } else {
                x
            };
        }
        let _ = lumped;
        T::zero()
    }
}
