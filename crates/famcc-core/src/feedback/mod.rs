//! Negative feedback laws `h_p` (paper Step B2 and sections V-VI).
//!
//! Every law maps a manifold value `s` to a desired rate `ds/dt = h_p(s)`, is
//! odd, zero at zero and strictly decreasing (except the discontinuous
//! Moulay law, kept for comparison only). Units: `s` in the unit of the
//! stage's signal, `h_p` in that unit per second.
//!
//! ```
//! use famcc_core::Feedback;
//! let h = Feedback::FiniteTime { k: 1.0_f64, p: 0.5 };
//! assert_eq!(h.eval(4.0), -2.0);
//! assert_eq!(h.eval(-4.0), 2.0);
//! ```

use crate::error::{positive, ConfigError};
use crate::{Jet, Real};

#[cfg(feature = "variable-exponent")]
mod variable;
#[cfg(feature = "variable-exponent")]
use variable::{var_exponent, variable_signed_pow_jet, ve_monotonicity_margin};

/// A negative feedback law `h_p`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Feedback<T> {
    /// `h(s) = -k s` (eq. (59) (lfmi)), `k > 0`.
    Linear {
        /// Gain, 1/s.
        k: T,
    },
    /// `h(s) = -k |s|^p sign(s)`, `k > 0`, `0 < p < 1` (eq. (37) (fn)).
    FiniteTime {
        /// Gain.
        k: T,
        /// Exponent, `0 < p < 1`.
        p: T,
    },
    /// `h(s) = -alpha |s|^p sign(s) - beta |s|^q sign(s)`, `0 < p < 1 < q`
    /// (eq. (61) (RFCs)).
    FixedTime {
        /// Low-power gain, > 0.
        alpha: T,
        /// Low power, `0 < p < 1`.
        p: T,
        /// High-power gain, > 0.
        beta: T,
        /// High power, `q > 1`.
        q: T,
    },
    /// The paper's continuous variable-exponent law (eq. (45) (fxe)):
    /// `h(s) = -k |s|^{r(s)} sign(s)`, `r(s) = a s^2/(1 + b s^2) + r_b`,
    /// `b = (r_1 - r_b)/(r_t - r_1)`, `a = (r_t - r_b) b`, so that the exponent
    /// is `r_b` at 0, `r_1` at `|s| = 1` and tends to `r_t` at infinity;
    /// `0 < r_b < 1 < r_1 < r_t`.
    VariableExponent {
        /// Gain, > 0.
        k: T,
        /// Exponent at `s = 0`.
        r_b: T,
        /// Exponent at `|s| = 1`.
        r_1: T,
        /// Exponent as `|s| -> infinity`.
        r_t: T,
    },
    /// The discontinuous original of Moulay et al. (paper Remark after
    /// Corollary 2, eq. (58) (fvec)): `h(s) = -beta |s|^{p(s)} sign(s)` with
    /// `p(s) = lambda s^2/(1 + mu s^2)`. Its exponent is 0 at `s = 0`, so
    /// `h` jumps from +beta to -beta across zero. For comparison only.
    MoulayDiscontinuous {
        /// Gain, > 0.
        beta: T,
        /// Exponent numerator coefficient, > 0.
        lambda: T,
        /// Exponent denominator coefficient, >= 0.
        mu: T,
    },
}

impl<T: Real> Feedback<T> {
    /// Checks the parameter rules of the law.
    pub fn validate(&self) -> Result<(), ConfigError> {
        crate::compiled::law(self)?;
        let one = T::one();
        match *self {
            Feedback::Linear { k } => positive(k, "k"),
            Feedback::FiniteTime { k, p } => {
                positive(k, "k")?;
                if !(p > T::zero() && p < one) {
                    return Err(ConfigError::new("p", "must satisfy 0 < p < 1"));
                }
                Ok(())
            }
            #[cfg(feature = "fixed-time")]
            Feedback::FixedTime { alpha, p, beta, q } => {
                positive(alpha, "alpha")?;
                positive(beta, "beta")?;
                if !(p > T::zero() && p < one) {
                    return Err(ConfigError::new("p", "must satisfy 0 < p < 1"));
                }
                if !(q > one && q.is_finite()) {
                    return Err(ConfigError::new("q", "must be finite and > 1"));
                }
                Ok(())
            }
            #[cfg(feature = "variable-exponent")]
            Feedback::VariableExponent { k, r_b, r_1, r_t } => {
                positive(k, "k")?;
                if !(r_b > T::zero() && r_b < one) {
                    return Err(ConfigError::new("r_b", "must satisfy 0 < r_b < 1"));
                }
                if r_1.is_nan() || r_1 <= one {
                    return Err(ConfigError::new("r_1", "must be > 1"));
                }
                if !(r_t > r_1 && r_t.is_finite()) {
                    return Err(ConfigError::new("r_t", "must be finite and > r_1"));
                }
                let (a, b) = Self::exponent_coeffs(r_b, r_1, r_t);
                let margin = ve_monotonicity_margin(a, b, r_b);
                if margin.is_nan() || margin <= T::zero() {
                    return Err(ConfigError::new(
                        "r_b",
                        "too small for this r_1, r_t: h must be strictly decreasing (paper Step B1, \
                         property 1); raise r_b or lower (r_1 - r_b)/(r_t - r_1)",
                    ));
                }
                Ok(())
            }
            #[cfg(feature = "variable-exponent")]
            Feedback::MoulayDiscontinuous { beta, lambda, mu } => {
                positive(beta, "beta")?;
                positive(lambda, "lambda")?;
                if !(mu >= T::zero() && mu.is_finite()) {
                    return Err(ConfigError::new("mu", "must be finite and >= 0"));
                }
                Ok(())
            }
            // Compiled out: rejected above.
            #[allow(unreachable_patterns)]
            _ => Ok(()),
        }
    }

    /// True when some derivative of `h` is unbounded at `s = 0` (a power
    /// below 1): such a law cannot be used where the manifold needs its time
    /// derivatives unless the nonsingular skew removes the singularity.
    pub fn is_singular_at_zero(&self) -> bool {
        !matches!(self, Feedback::Linear { .. })
    }

    /// The variable-exponent coefficients `(a, b)` of eq. (45) (fxe).
    #[cfg(feature = "variable-exponent")]
    #[inline]
    fn exponent_coeffs(r_b: T, r_1: T, r_t: T) -> (T, T) {
        let b = (r_1 - r_b) / (r_t - r_1);
        ((r_t - r_b) * b, b)
    }

    /// `h(s)`.
    #[inline]
    pub fn eval(&self, s: T) -> T {
        match *self {
            Feedback::Linear { k } => -k * s,
            Feedback::FiniteTime { k, p } => -k * signed_pow(s, p),
            #[cfg(feature = "fixed-time")]
            Feedback::FixedTime { alpha, p, beta, q } => {
                -(alpha * signed_pow(s, p) + beta * signed_pow(s, q))
            }
            #[cfg(feature = "variable-exponent")]
            Feedback::VariableExponent { k, r_b, r_1, r_t } => {
                let (a, b) = Self::exponent_coeffs(r_b, r_1, r_t);
                -k * signed_pow(s, var_exponent(s, a, b, r_b))
            }
            #[cfg(feature = "variable-exponent")]
            Feedback::MoulayDiscontinuous { beta, lambda, mu } => {
                -beta * signed_pow(s, var_exponent(s, lambda, mu, T::zero()))
            }
            // Compiled out (src/compiled.rs): no configuration holds it.
            #[allow(unreachable_patterns)]
            _ => T::nan(),
        }
    }

    /// `h(s(t))` with its time derivatives, for a jet `s`.
    #[inline]
    pub fn eval_jet<const K: usize>(&self, s: Jet<T, K>) -> Jet<T, K> {
        match *self {
            Feedback::Linear { k } => s * (-k),
            Feedback::FiniteTime { k, p } => s.signed_pow(p) * (-k),
            #[cfg(feature = "fixed-time")]
            Feedback::FixedTime { alpha, p, beta, q } => -(s.signed_pow(p) * alpha + s.signed_pow(q) * beta),
            #[cfg(feature = "variable-exponent")]
            Feedback::VariableExponent { k, r_b, r_1, r_t } => {
                let (a, b) = Self::exponent_coeffs(r_b, r_1, r_t);
                variable_signed_pow_jet(s, a, b, r_b) * (-k)
            }
            #[cfg(feature = "variable-exponent")]
            Feedback::MoulayDiscontinuous { beta, lambda, mu } => {
                variable_signed_pow_jet(s, lambda, mu, T::zero()) * (-beta)
            }
            // Compiled out (src/compiled.rs): no configuration holds it.
            #[allow(unreachable_patterns)]
            _ => Jet::constant(T::nan()),
        }
    }

    /// `dh/ds` at `s` (infinite at 0 for powers below 1).
    #[inline]
    pub fn slope(&self, s: T) -> T {
        self.eval_jet(Jet::<T, 2>::from_derivatives([s, T::one()]))
            .derivative(1)
    }

    /// The inverse `h^{-1}(y)` in closed form, where one exists (linear and
    /// finite-time laws); `None` otherwise.
    ///
    /// ```
    /// use famcc_core::Feedback;
    /// let h = Feedback::FiniteTime { k: 2.0_f64, p: 0.5 };
    /// let x = h.inverse_closed_form(h.eval(0.3)).unwrap();
    /// assert!((x - 0.3).abs() < 1e-15);
    /// ```
    #[inline]
    pub fn inverse_closed_form(&self, y: T) -> Option<T> {
        match *self {
            Feedback::Linear { k } => Some(-y / k),
            // Erratum (docs/errata.md, eq. (39) (nfn)): s_fn = z1 + sign(z2) |z2 / k|^(1/p), not (1/k)|z2|^(1/p).
            Feedback::FiniteTime { k, p } => Some(-signed_pow(y / k, T::one() / p)),
            _ => None,
        }
    }
}

/// The signed power `|x|^p sign(x)` (the paper's `⌈x⌋^p`); 0 at 0.
///
/// ```
/// use famcc_core::feedback::signed_pow;
/// assert_eq!(signed_pow(-4.0_f64, 0.5), -2.0);
/// ```
#[inline]
pub fn signed_pow<T: Real>(x: T, p: T) -> T {
    if x > T::zero() {
        x.pow_nonneg(p)
    } else if x < T::zero() {
        -(-x).pow_nonneg(p)
    } else {
        T::zero()
    }
}
