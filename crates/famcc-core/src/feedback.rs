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

    #[cfg(feature = "variable-exponent")]
    /// The variable-exponent coefficients `(a, b)` of eq. (45) (fxe).
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

#[cfg(feature = "variable-exponent")]
/// The variable exponent `r(s) = a s^2/(1 + b s^2) + r0`, written as
/// `a/(b + (1/s)^2) + r0` for `|s| > 1` so that `s^2` cannot overflow (the
/// law must stay defined, e.g. `-inf`, not NaN, at `|s| = 1e200`).
#[inline]
fn var_exponent<T: Real>(s: T, a: T, b: T, r0: T) -> T {
    if s.abs() <= T::one() {
        let s2 = s * s;
        a * s2 / (T::one() + b * s2) + r0
    } else {
        let w = s.recip();
        a / (b + w * w) + r0
    }
}

#[cfg(feature = "variable-exponent")]
/// `|s|^{r(s)} sign(s)` on a jet, with `r(s) = a s^2/(1 + b s^2) + r0`.
///
/// `s^2` is never formed alone: it underflows below `|s| = 1e-154` (which would
/// drop the `r(s)/s` term of the derivative) and overflows above `1e154`
/// (NaN). For `|s| <= 1` the magnitude is `|s|^{r0} exp(g(s) s ln|s|)` with
/// `g(s) = a s/(1 + b s^2)`: the exponential factor lies in `(0, 1]` and the
/// singular power is a plain [`Jet::powf`]. For `|s| > 1` it is
/// `exp((a/(b + w^2) + r0) ln|s|)` with `w = 1/s`.
#[inline]
fn variable_signed_pow_jet<T: Real, const K: usize>(s: Jet<T, K>, a: T, b: T, r0: T) -> Jet<T, K> {
    let s0 = s.value();
    if s0 == T::zero() {
        // Only the exponent's value matters at 0 (see `Jet::signed_pow_jet`).
        return s.signed_pow_jet(&Jet::constant(r0));
    }
    let m = s.abs();
    let mag = if s0.abs() <= T::one() {
        let g = (s * a) / (s * s * b + T::one());
        let var = (g * x_ln_abs_x(s)).exp();
        if r0 == T::zero() {
            var
        } else {
            m.powf(r0) * var
        }
    } else {
        let w = s.recip();
        (((w * w + b).recip() * a + r0) * m.ln()).exp()
    };
    if s0 > T::zero() {
        mag
    } else {
        -mag
    }
}

#[cfg(feature = "variable-exponent")]
/// `s ln|s|` on a jet (`s != 0`), built from its derivative `s' (1 + ln|s|)`:
/// its first derivative stays finite even for a subnormal `s`, where the
/// `s'/s` inside `ln|s|` overflows.
#[inline]
fn x_ln_abs_x<T: Real, const K: usize>(s: Jet<T, K>) -> Jet<T, K> {
    let s0 = s.value();
    let rate = (s.shift() * (s.abs().ln() + T::one())).taylor();
    let mut c = [T::zero(); K];
    for (k, ck) in c.iter_mut().enumerate() {
        *ck = if k == 0 {
            s0 * s0.abs().ln()
        } else {
            rate.get(k - 1).copied().unwrap_or_else(T::zero) / T::from_f64(k as f64)
        };
    }
    Jet::from_taylor(c)
}

#[cfg(feature = "variable-exponent")]
/// `min_{0<u<1} phi(u)` with `phi(u) = r_b (1 + b u)^2 + a u (1 + b u + ln u)`.
///
/// For `s = sqrt(u)` in `(0, 1)`, `d/ds |s|^{r(s)} > 0` (the variable-exponent
/// law strictly decreasing, paper Step B1 property 1) is equivalent to
/// `phi(u) > 0`; for `|s| >= 1` it always holds. `phi'(u) = a psi(ln u)` with
/// `psi(v) = v + 2 + 2 b e^v + c (1 + b e^v)`, `c = 2 r_b b / a`, increasing in
/// `v`, so the minimum is at the unique root of `psi`, found by bisection on
/// `[-3 - c - 2b - c b, -2 - c]` (`psi` is negative at the left end, positive
/// at the right end). Not finite (so the law is rejected) for invalid inputs.
fn ve_monotonicity_margin<T: Real>(a: T, b: T, r_b: T) -> T {
    let one = T::one();
    let two = T::from_f64(2.0);
    let c = two * r_b * b / a;
    let psi = |v: T| v + two + two * b * v.exp() + c * (one + b * v.exp());
    let mut hi = -two - c;
    let mut lo = ve_left_end(hi, b, c);
    for _ in 0..200 {
        let mid = (lo + hi) / two;
        if !(mid > lo && mid < hi) {
            break;
        }
        if psi(mid) < T::zero() {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let u = hi.exp();
    // u underflows to 0 only when the minimum sits at u -> 0, where phi -> r_b.
    let dip = if u > T::zero() {
        a * u * (one + b * u + u.ln())
    } else {
        T::zero()
    };
    r_b * (one + b * u) * (one + b * u) + dip
}

#[cfg(feature = "variable-exponent")]
/// The left end of [`ve_monotonicity_margin`]'s bisection, `hi - 1 - (2 +
/// c) b`, where `psi < 0`: for `v <= hi = -2 - c`, `psi(v) <= v + 2 + c +
/// (2 + c) b e^(-2-c)`, and `(2 + c) e^(-2-c) < 1` for `c >= 0` (a, b, c > 0
/// for every valid law: `0 < r_b < 1 < r_1 < r_t`).
fn ve_left_end<T: Real>(hi: T, b: T, c: T) -> T {
    hi - T::one() - (T::from_f64(2.0) + c) * b
}

#[cfg(all(test, feature = "variable-exponent"))]
mod tests {
    use super::ve_monotonicity_margin;

    /// `min phi(u)` over a fine grid of `(0, 1)` (uniform, and log-spaced
    /// down to `1e-12`), `phi(u) = r_b (1 + b u)^2 + a u (1 + b u + ln u)`.
    fn grid_min(a: f64, b: f64, r_b: f64) -> f64 {
        let uniform = (1..200_000).map(|i| i as f64 / 200_000.0);
        let logs = (0..200_000).map(|i| 10f64.powf(-12.0 * i as f64 / 200_000.0));
        uniform
            .chain(logs)
            .map(|u| r_b * (1.0 + b * u) * (1.0 + b * u) + a * u * (1.0 + b * u + u.ln()))
            .fold(f64::INFINITY, f64::min)
    }

    #[test]
    fn the_monotonicity_margin_is_the_minimum_of_phi() {
        for (a, b, r_b) in [
            (1.0, 0.5, 0.5),
            (4.0, 2.0, 0.1),
            (0.5, 0.1, 1.0),
            (8.0, 0.0, 0.2),
            (3.0, 5.0, 0.05),
        ]
        .into_iter()
        .chain(
            // Valid laws (r_b, r_1, r_t) at the extremes of b = (r_1 - r_b) /
            // (r_t - r_1) and c = 2 r_b b / a: b = 1e4 with c = 0.02 or 2e-5,
            // b = 0.01 with c = 0.01, c = 15 with b = 11, and c = 2.2 (> 2)
            // with an interior minimum.
            [
                (0.01, 1.01, 1.0101),
                (0.001, 100.0, 100.01),
                (0.5, 1.5, 101.0),
                (0.9, 1.01, 1.02),
                (0.6, 1.05, 1.15),
            ]
            .map(|(r_b, r_1, r_t): (f64, f64, f64)| {
                let b = (r_1 - r_b) / (r_t - r_1);
                ((r_t - r_b) * b, b, r_b)
            }),
        ) {
            let m = ve_monotonicity_margin(a, b, r_b);
            let g = grid_min(a, b, r_b);
            assert!(
                m <= g + 1e-12 && g - m < 1e-6 * (1.0 + g.abs()),
                "({a}, {b}, {r_b}): {m} vs grid {g}"
            );
        }
    }
}
