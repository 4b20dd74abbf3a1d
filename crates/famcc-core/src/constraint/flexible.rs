//! Error-driven flexible boundaries (paper eqs. (30) WxyUxyL and (31) Wxi;
//! for LaMC and LoMC they reduce to eqs. (41) WxUxL and (51) WyUyL).
//!
//! With `d_sc` the distance of the state from the zero manifold along the
//! gradient line and `d_U = sqrt(x_U^2 + y_U^2)` the nominal half-width,
//!
//! `T_s = S((d_sc - (d_U - rho_e)) / rho_e)`,
//! `x~_U = ((1 - T_s) + T_s (d_sc + rho_e)/d_U) x_U` (same factor for `y~_U`).
//!
//! The factor is exactly 1 while the state is at least `rho_e` inside the
//! nominal boundary (then `S` is exactly 0), so the nominal boundaries return
//! exactly once the state is back inside. Outside, the boundary keeps the
//! distance `rho_e` from the state, so `|xi~| = d_sc/(d_sc + rho_e) < 1`
//! (eq. (88), |xi|). The boundary needs no knowledge of the input limits.
//!
//! ```
//! use famcc_core::constraint::expansion;
//! use famcc_core::Transition;
//! let s = Transition::Exponential;
//! assert_eq!(expansion(s, 0.5_f64, 1.0, 0.01), 1.0);           // well inside: nominal
//! assert!((expansion(s, 2.0_f64, 1.0, 0.01) - 2.01).abs() < 1e-15); // outside: d_sc + rho_e
//! ```

use crate::{Real, Transition};

/// The expansion factor `x~_U / x_U = y~_U / y_U >= 1` of eq. (30) (WxyUxyL) for
/// distance `d_sc >= 0`, nominal half-width `d_u > 0` and margin `rho_e > 0`.
#[inline(always)]
pub fn expansion<T: Real>(transition: Transition, d_sc: T, d_u: T, rho_e: T) -> T {
    let ts = transition.double_ended((d_sc - (d_u - rho_e)) / rho_e);
    if ts == T::zero() {
        return T::one();
    }
    (T::one() - ts) + ts * (d_sc + rho_e) / d_u
}
