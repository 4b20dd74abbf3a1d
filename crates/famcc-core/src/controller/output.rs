//! What happens to the law's output `v` inside a step (docs/design.md §3.8):
//! the output limits (magnitude and rate), what is known about the
//! actuator's limits, the integral separation (anti-windup) and the health
//! count.
//!
//! The limits are applied rate first, then magnitude, so the returned output
//! is always within `(lo, hi)`, and within the rate window whenever the
//! previous output was within `(lo, hi)`.

use crate::Real;

/// The limits a step applies and knows of.
#[derive(Clone, Copy, Debug)]
pub(super) struct Limits<T> {
    /// Configured magnitude limits.
    pub magnitude: Option<(T, T)>,
    /// Configured rate limit (units per second) and this step's period.
    pub rate: Option<(T, T)>,
    /// The previous output (the last one returned, or the configured
    /// initial output before the first step).
    pub previous: Option<T>,
    /// The input the actuator applied at the previous sample, when told.
    pub applied: Option<T>,
    /// The output scale `k_u` (for the tolerance of `applied`).
    pub k_u: T,
}

/// The limited output and the actuator's known limits at this step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Limited<T> {
    /// The output to return (limited).
    pub u: T,
    /// The law's output beyond a known upper limit (`+1`), a known lower one
    /// (`-1`), or neither (`0`).
    pub beyond: i8,
    /// True when anything is known about the actuator's limits (limits
    /// configured, or `applied` passed).
    pub known: bool,
}

/// The relative tolerance under which `applied` counts as the previous
/// output: `|v_prev - applied| <= 1e-6 (|v_prev| + k_u)`.
const APPLIED_TOLERANCE: f64 = 1e-6;

impl<T: Real> Limits<T> {
    /// Limits `v`, and says where it stands against what is known.
    #[inline]
    pub fn apply(&self, v: T) -> Limited<T> {
        let inf = T::infinity();
        let (mut lo, mut hi) = (-inf, inf);
        let mut u = v;
        if let (Some((r, dt)), Some(p)) = (self.rate, self.previous) {
            let step = r * dt;
            let (w_lo, w_hi) = (p - step, p + step);
            u = u.max(w_lo).min(w_hi);
            lo = lo.max(w_lo);
            hi = hi.min(w_hi);
        }
        if let Some((m_lo, m_hi)) = self.magnitude {
            u = u.max(m_lo).min(m_hi);
            lo = lo.max(m_lo);
            hi = hi.min(m_hi);
        }
        // An actuator that did not apply the previous output was at a limit
        // in the direction it fell short.
        if let (Some(a), Some(p)) = (self.applied, self.previous) {
            let tol = T::from_f64(APPLIED_TOLERANCE) * (p.abs() + self.k_u);
            if a < p - tol {
                hi = hi.min(a);
            } else if a > p + tol {
                lo = lo.max(a);
            }
        }
        // Above and below at once (an applied input short of the rate
        // window: `hi < lo`) says nothing about the side: 0, so that the
        // mirrored limits give the mirrored answer (src/direction.rs).
        let beyond = i8::from(v > hi) - i8::from(v < lo);
        Limited {
            u,
            beyond,
            known: self.magnitude.is_some() || self.rate.is_some() || self.applied.is_some(),
        }
    }
}

impl<T: Real> Limited<T> {
    /// What [`Limits::apply`] gives with no limit configured and no input
    /// told: `v` itself, beyond no limit, none known.
    #[inline(always)]
    pub fn unlimited(v: T) -> Self {
        Self {
            u: v,
            beyond: 0,
            known: false,
        }
    }

    /// True when the actuator is known to have headroom: limits known and
    /// the law's output within them.
    #[inline]
    pub fn headroom(&self) -> bool {
        self.known && self.beyond == 0
    }

    /// The integral separation (anti-windup): integrate the sample `e` only
    /// while the state is inside the final band, and not while the output is
    /// beyond a known limit in the direction `e` would push it further
    /// (`dv/dI < 0`: `e < 0` raises `v`).
    #[inline]
    pub fn integrates(&self, e: T, inside_final_band: bool) -> bool {
        let pushing = (self.beyond > 0 && e < T::zero()) || (self.beyond < 0 && e > T::zero());
        inside_final_band && !pushing
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn limits(magnitude: Option<(f64, f64)>, rate: Option<f64>, previous: Option<f64>) -> Limits<f64> {
        Limits {
            magnitude,
            rate: rate.map(|r| (r, 0.1)),
            previous,
            applied: None,
            k_u: 1.0,
        }
    }

    #[test]
    fn magnitude_then_rate() {
        let l = limits(Some((-1.0, 2.0)), Some(5.0), Some(1.8));
        assert_eq!(
            l.apply(10.0),
            Limited {
                u: 2.0,
                beyond: 1,
                known: true
            }
        );
        assert_eq!(l.apply(-10.0).u, 1.3);
        assert_eq!(
            l.apply(1.5),
            Limited {
                u: 1.5,
                beyond: 0,
                known: true
            }
        );
        let none = limits(None, Some(5.0), None);
        assert_eq!(
            none.apply(-10.0),
            Limited {
                u: -10.0,
                beyond: 0,
                known: true
            }
        );
        let free = limits(None, None, Some(0.0));
        assert!(!free.apply(3.0).known && !free.apply(3.0).headroom());
    }

    #[test]
    fn applied_reveals_a_limit() {
        let mut l = limits(None, None, Some(5.0));
        l.applied = Some(3.0);
        assert_eq!(l.apply(4.0).beyond, 1);
        assert_eq!(l.apply(2.0).beyond, 0);
        l.applied = Some(5.0 - 1e-7);
        assert_eq!(l.apply(5.5).beyond, 0);
        let sat = l.apply(0.0);
        assert!(sat.integrates(1.0, true) && !sat.integrates(1.0, false));
        l.applied = Some(3.0);
        let high = l.apply(4.0);
        assert!(!high.integrates(-1.0, true) && high.integrates(1.0, true));
    }

    #[test]
    fn an_applied_input_short_of_the_rate_window_names_no_side() {
        // window [p - 0.5, p + 0.5] = [1.5, 2.5], applied 1.0: hi = 1.0 < lo = 1.5
        let mut l = limits(None, Some(5.0), Some(2.0));
        l.applied = Some(1.0);
        assert_eq!(l.apply(1.2).beyond, 0); // above hi and below lo at once
        assert_eq!(l.apply(3.0).beyond, 1);
        assert_eq!(l.apply(0.5).beyond, -1);
        let sat = l.apply(1.2);
        assert!(sat.integrates(1.0, true) && sat.integrates(-1.0, true));
        // exactly at a limit is within it, on either side
        let at = limits(Some((-1.0, 2.0)), None, None);
        assert_eq!((at.apply(2.0).beyond, at.apply(-1.0).beyond), (0, 0));
    }

    #[test]
    fn integrates_unless_pushing_beyond_either_limit() {
        // Beyond the lower limit, e > 0 lowers v further: no integration; e < 0
        // and e = 0 bring it back or hold it: integrate. Mirrored above.
        let l = limits(Some((-1.0, 2.0)), None, None);
        let low = l.apply(-3.0);
        assert_eq!(low.beyond, -1);
        assert!(!low.integrates(1.0, true));
        assert!(low.integrates(-1.0, true) && low.integrates(0.0, true));
        let high = l.apply(3.0);
        assert_eq!(high.beyond, 1);
        assert!(!high.integrates(-1.0, true));
        assert!(high.integrates(1.0, true) && high.integrates(0.0, true));
        assert!(!low.integrates(-1.0, false) && !high.integrates(1.0, false));
    }
}
