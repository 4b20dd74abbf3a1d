//! Settling-time bounds of the paper's corollaries, in seconds. The full
//! bound on the time to reach `|z1| < eps_z` is `T_s` plus these.
//!
//! ```
//! use famcc_core::bounds;
//! // Example 1: k_c = 1, p = 0.5, z1(0) = -1  =>  T_fn' = 2 s, T_fn < 3 s.
//! assert_eq!(bounds::finite_time(1.0_f64, 0.5, -1.0), 2.0);
//! ```

use crate::Real;

/// `T_fn' = |z1(0)|^(1-p) / (k_c (1-p))` (Corollary 1, eq. (42) (fnT)).
#[inline]
pub fn finite_time<T: Real>(k: T, p: T, z1_0: T) -> T {
    z1_0.abs().powf(T::one() - p) / (k * (T::one() - p))
}

/// `T_fxe' = 1/(k (r_1 - 1)) + 1/(k e^{-a/(2e)} (1 - r_b))` with
/// `a = (r_t - r_b)(r_1 - r_b)/(r_t - r_1)` (Corollary 2, eq. (53) (fxeT)).
///
/// ```
/// use famcc_core::bounds::variable_exponent;
/// let t = variable_exponent(1.5_f64, 0.5, 2.0, 3.0);
/// assert!((t - 3.32).abs() < 0.005); // T_fxe = 1 + 3.32 = 4.3 s
/// ```
#[inline]
pub fn variable_exponent<T: Real>(k: T, r_b: T, r_1: T, r_t: T) -> T {
    let one = T::one();
    let b = (r_1 - r_b) / (r_t - r_1);
    let a = (r_t - r_b) * b;
    let damp = (-a / (T::from_f64(2.0) * T::E())).exp();
    one / (k * (r_1 - one)) + one / (k * damp * (one - r_b))
}

/// One stage's term of `T_fr'`: `1/(alpha (1-p)) + 1/(beta (q-1))`
/// (Corollary 3, eq. (63) (fxTho)).
#[inline]
pub fn fixed_time_stage<T: Real>(alpha: T, p: T, beta: T, q: T) -> T {
    let one = T::one();
    one / (alpha * (one - p)) + one / (beta * (q - one))
}

/// `T_fr' = sum_i (1/(alpha_i (1-p_i)) + 1/(beta_i (q_i-1)))` for stages given
/// as `(alpha, p, beta, q)` (Corollary 3, eq. (63) (fxTho)).
///
/// ```
/// use famcc_core::bounds::fixed_time;
/// // Example 3: 4 s + 2 s = 6 s, so T_fr < 1 + 6 = 7 s.
/// assert_eq!(fixed_time(&[(1.0_f64, 0.5, 0.5, 2.0), (2.0, 0.5, 1.0, 2.0)]), 6.0);
/// ```
#[inline]
pub fn fixed_time<T: Real>(stages: &[(T, T, T, T)]) -> T {
    stages
        .iter()
        .fold(T::zero(), |acc, &(a, p, b, q)| acc + fixed_time_stage(a, p, b, q))
}
