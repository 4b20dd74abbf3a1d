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
}
