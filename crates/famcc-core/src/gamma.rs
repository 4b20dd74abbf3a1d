//! The odd maps `Gamma: (-1, 1) -> R` of the control law `v = -k_u Gamma(xi)`
//! (paper eq. (29) (uT)).
//!
//! ```
//! use famcc_core::Gamma;
//! assert_eq!(Gamma::Log.eval(0.0_f64), 0.0);
//! assert!((Gamma::Log.eval(0.5_f64) - 3.0_f64.ln()).abs() < 1e-15);
//! assert!((Gamma::Rational.eval(0.5_f64) - 0.5 / 0.75).abs() < 1e-15);
//! ```

use crate::Real;

/// The map `Gamma` of eq. (29) (uT).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Gamma {
    /// `ln((1 + xi)/(1 - xi)) = 2 atanh(xi)`.
    #[default]
    Log,
    /// `xi / ((1 + xi)(1 - xi))`.
    Rational,
}

impl Gamma {
    /// `Gamma(xi)` for `|xi| < 1` (infinite at `|xi| = 1`).
    ///
    /// The log map is evaluated on `|xi|` and the sign restored, so it is
    /// exactly odd and equally accurate near `-1` and `+1` whichever `atanh`
    /// backs the float type (std's `atanh` is `ln_1p(2x/(1-x))/2`, which
    /// cancels for `x` near `-1`).
    #[inline]
    pub fn eval<T: Real>(self, xi: T) -> T {
        match self {
            Gamma::Log => {
                let g = T::from_f64(2.0) * xi.abs().atanh();
                if xi < T::zero() {
                    -g
                } else {
                    g
                }
            }
            Gamma::Rational => xi / ((T::one() + xi) * (T::one() - xi)),
        }
    }

    /// The inverse `Gamma^-1(y)`: the `xi` in `(-1, 1)` with `Gamma(xi) = y`
    /// (the constraint value that makes `v = -k_u Gamma(xi)` equal a given
    /// output, for a bumpless start). Log: `tanh(y / 2)`; rational: the root
    /// of `y xi^2 + xi - y = 0` in `(-1, 1)`, `2 y / (1 + sqrt(1 + 4 y^2))`.
    /// Infinite `y` gives `+-1`.
    ///
    /// ```
    /// use famcc_core::Gamma;
    /// for g in [Gamma::Log, Gamma::Rational] {
    ///     assert!((g.eval(g.inverse(1.5_f64)) - 1.5).abs() < 1e-12);
    ///     assert_eq!(g.inverse(0.0_f64), 0.0);
    /// }
    /// ```
    #[inline]
    pub fn inverse<T: Real>(self, y: T) -> T {
        let two = T::from_f64(2.0);
        match self {
            Gamma::Log => (y / two).tanh(),
            Gamma::Rational => {
                if y == T::zero() {
                    return y;
                }
                // 2 y / (1 + sqrt(1 + 4 y^2)), written with r = 1/|y| so that it
                // neither overflows nor loses the limit 1 for large |y|.
                let r = T::one() / y.abs();
                let xi = two / (r + (r * r + two * two).root());
                if y < T::zero() {
                    -xi
                } else {
                    xi
                }
            }
        }
    }
}
