//! The bumpless start (docs/design.md §3.8): the first step's output equals
//! a given `u0` when that is feasible.
//!
//! The law gives `v_0 = -k_u Gamma(xi_0)` (`+k_u` for a negative direction,
//! src/direction.rs: read `k_u` as `sign(G) k_u` below), so the first step needs `xi_0 =
//! xi* = Gamma^-1(-u0 / k_u)`.
//!
//! - With integral action the state is free in one coordinate: the
//!   controller chooses `I_0` so that `xi_0(I_0) = xi*`, the envelopes
//!   latched as usual from that state. The latch keeps `|xi_0| <= 1/k0`
//!   (`rho_0 >= k0 |s_0|` in effect), so `u0` is feasible when `|xi*| <
//!   1/k0` (`|u0| < k_u Gamma(1/k0)`, `k_u ln 3` for `k0 = 2` and the log
//!   map); a larger `|u0|` gives the nearest feasible output.
//! - Without it the state is fixed; the latch is widened or narrowed
//!   instead: both envelopes' initial widths are scaled by one factor `c`
//!   (never below their final widths, at most [`MAX_WIDENING`] times the
//!   usual latch) so that `xi_0 = xi*`. That is feasible when `xi*` has the
//!   sign of the offset `sigma_0` and `|xi*| < 1` (and inside the nominal
//!   bounds, `|xi*| < 1 - rho_e / eps`); otherwise the nearest feasible `c`
//!   is used (the usual latch when `sigma_0 = 0`).
//!
//! Both are scalar root searches ([`crate::constraint::bracketed_root`]) on
//! the first step's own evaluation, run once.

use super::recover::width_in_range;
use super::Controller;
use crate::constraint::{bracketed_root, Envelopes};
use crate::manifold;
use crate::Real;

/// The largest factor by which the bumpless start widens the usual latch.
pub const MAX_WIDENING: f64 = 1e6;

/// Doublings of the search for an `I_0` bracket.
const DOUBLINGS: usize = 96;

impl<T: Real, const N: usize> Controller<T, N> {
    /// `xi*` for the configured initial output, at most `limit` in magnitude.
    fn target_xi(&self, u0: T, limit: T) -> T {
        let c = &self.config;
        let xi = c.gamma().inverse(-u0 / c.direction().apply(c.k_u()));
        xi.max(-limit).min(limit)
    }

    /// The first step's `xi` (the one the output uses) for the estimate `z`,
    /// with the envelopes `env` latched from it (`latch`) or taken as they are.
    fn first_xi(&self, z: &[T; N], mut env: Envelopes<T>, latch: bool, t: T, nominal: bool) -> T {
        let c = &self.config;
        let constraint = c.constraint();
        let m = if constraint.needs_s(true) {
            manifold::evaluate(z, c.laws())
        } else {
            manifold::evaluate_prev(z, c.laws())
        };
        let eval = constraint.evaluate(
            c.last_law(),
            &m,
            &mut env,
            latch.then(|| (c.latch(), c.k0())),
            t,
            c.rho_e().map(|rho_e| (rho_e, c.transition())),
        );
        if !(width_in_range(env.x.rho0) && width_in_range(env.y.rho0)) {
            // A latch the step would refuse (recover.rs): not a candidate.
            return T::nan();
        }
        if nominal {
            eval.xi_nominal
        } else {
            eval.xi
        }
    }

    /// The largest `|xi|` that keeps the bounds nominal (below 1, and below
    /// `1 - rho_e / eps` with the flexible boundary).
    fn nominal_limit(&self) -> T {
        let c = &self.config;
        let (ex, ey) = c.constraint().eps();
        let eps = match (c.constraint().uses_x(), c.constraint().uses_y()) {
            (true, true) => ex.min(ey),
            (true, false) => ex,
            _ => ey,
        };
        let below_one = T::one() - T::from_f64(9.5367431640625e-7);
        match c.rho_e() {
            Some(r) => below_one.min(T::one() - r / eps * T::from_f64(1.0 + 1e-6)),
            None => below_one,
        }
    }

    /// With integral action: the `I_0` whose first output is `u0` (or the
    /// nearest feasible), for the initial estimate `z` (slot 0 ignored).
    pub(super) fn initial_integral(&self, z: &[T; N], u0: T, t: T) -> T {
        let c = &self.config;
        let limit = (T::one() / c.k0()).min(self.nominal_limit()) * T::from_f64(1.0 - 1e-9);
        let target = self.target_xi(u0, limit);
        let env = self.state.envelopes;
        let f = |i: T| {
            let mut zz = *z;
            if let Some(z0) = zz.first_mut() {
                *z0 = i;
            }
            self.first_xi(&zz, env, true, t, false) - target
        };
        let f0 = f(T::zero());
        if !f0.is_finite() || f0 == T::zero() {
            return T::zero();
        }
        let (ex, ey) = c.constraint().eps();
        // 2^-20 times the widest final width, doubled DOUBLINGS times.
        let mut step = ex.max(ey) * T::from_f64(9.5367431640625e-7);
        let (mut best, mut best_f) = (T::zero(), f0.abs());
        for _ in 0..DOUBLINGS {
            step = step * T::from_f64(2.0);
            // I_0 stays within the estimate's range (docs/design.md §3.7).
            if step > T::estimate_range() * T::from_f64(0.5) {
                break;
            }
            for x in [step, -step] {
                let fx = f(x);
                if !fx.is_finite() {
                    continue;
                }
                if (fx > T::zero()) != (f0 > T::zero()) {
                    // A sign change across a jump (a discontinuous law) is
                    // no root: keep the root only when it is one.
                    let r = bracketed_root(f, T::zero(), x).unwrap_or(x);
                    return if f(r).abs() < f0.abs() { r } else { T::zero() };
                }
                if fx.abs() < best_f {
                    (best, best_f) = (x, fx.abs());
                }
            }
        }
        best
    }

    /// Without integral action: the envelopes, latched as usual in `env`,
    /// rescaled so that the first output is `u0` (or the nearest feasible).
    pub(super) fn bumpless_envelopes(&self, z: &[T; N], env: Envelopes<T>, u0: T, t: T) -> Envelopes<T> {
        let target = self.target_xi(u0, self.nominal_limit());
        let scaled = |x: T| {
            let k = x.exp();
            let mut e = env;
            for w in [&mut e.x, &mut e.y] {
                w.rho0 = (w.rho0 * k).max(w.eps);
            }
            e
        };
        let f = |x: T| self.first_xi(z, scaled(x), false, t, true) - target;
        // ln c: from where every used envelope is at its final width to MAX_WIDENING.
        let lowest = [env.x, env.y]
            .iter()
            .filter(|w| w.eps > T::zero())
            .map(|w| w.eps / w.rho0)
            .fold(T::one(), |a, b| a.min(b));
        let (lo, hi) = (lowest.ln(), T::from_f64(MAX_WIDENING).ln());
        let x = match bracketed_root(f, lo, hi) {
            Some(x) => x,
            None => {
                let (f_lo, f_hi, f_one) = (f(lo).abs(), f(hi).abs(), f(T::zero()).abs());
                if !(f_lo.is_finite() && f_hi.is_finite()) || (f_lo >= f_one && f_hi >= f_one) {
                    T::zero()
                } else if f_lo < f_hi {
                    lo
                } else {
                    hi
                }
            }
        };
        scaled(x)
    }
}
