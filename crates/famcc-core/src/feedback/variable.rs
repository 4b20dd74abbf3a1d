//! The variable-exponent laws' functions (paper eq. (45) (fxe), and the
//! discontinuous law of eq. (58) (fvec)): the exponent `r(s)`, the signed
//! power with that exponent on a jet, and the monotonicity check of
//! [`super::Feedback::VariableExponent`]. Compiled with the feature
//! `variable-exponent` only (src/compiled.rs).

use crate::{Jet, Real};

/// The variable exponent `r(s) = a s^2/(1 + b s^2) + r0`, written as
/// `a/(b + (1/s)^2) + r0` for `|s| > 1` so that `s^2` cannot overflow (the
/// law must stay defined, e.g. `-inf`, not NaN, at `|s| = 1e200`).
#[inline]
pub(super) fn var_exponent<T: Real>(s: T, a: T, b: T, r0: T) -> T {
    if s.abs() <= T::one() {
        let s2 = s * s;
        a * s2 / (T::one() + b * s2) + r0
    } else {
        let w = s.recip();
        a / (b + w * w) + r0
    }
}

/// `|s|^{r(s)} sign(s)` on a jet, with `r(s) = a s^2/(1 + b s^2) + r0`.
///
/// `s^2` is never formed alone: it underflows below `|s| = 1e-154` (which would
/// drop the `r(s)/s` term of the derivative) and overflows above `1e154`
/// (NaN). For `|s| <= 1` the magnitude is `|s|^{r0} exp(g(s) s ln|s|)` with
/// `g(s) = a s/(1 + b s^2)`: the exponential factor lies in `(0, 1]` and the
/// singular power is a plain [`Jet::powf`]. For `|s| > 1` it is
/// `exp((a/(b + w^2) + r0) ln|s|)` with `w = 1/s`.
#[inline]
pub(super) fn variable_signed_pow_jet<T: Real, const K: usize>(s: Jet<T, K>, a: T, b: T, r0: T) -> Jet<T, K> {
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

/// `min_{0<u<1} phi(u)` with `phi(u) = r_b (1 + b u)^2 + a u (1 + b u + ln u)`.
///
/// For `s = sqrt(u)` in `(0, 1)`, `d/ds |s|^{r(s)} > 0` (the variable-exponent
/// law strictly decreasing, paper Step B1 property 1) is equivalent to
/// `phi(u) > 0`; for `|s| >= 1` it always holds. `phi'(u) = a psi(ln u)` with
/// `psi(v) = v + 2 + 2 b e^v + c (1 + b e^v)`, `c = 2 r_b b / a`, increasing in
/// `v`, so the minimum is at the unique root of `psi`, found by bisection on
/// `[-3 - c - 2b - c b, -2 - c]` (`psi` is negative at the left end, positive
/// at the right end). Not finite (so the law is rejected) for invalid inputs.
pub(super) fn ve_monotonicity_margin<T: Real>(a: T, b: T, r_b: T) -> T {
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

/// The left end of [`ve_monotonicity_margin`]'s bisection, `hi - 1 - (2 +
/// c) b`, where `psi < 0`: for `v <= hi = -2 - c`, `psi(v) <= v + 2 + c +
/// (2 + c) b e^(-2-c)`, and `(2 + c) e^(-2-c) < 1` for `c >= 0` (a, b, c > 0
/// for every valid law: `0 < r_b < 1 < r_1 < r_t`).
fn ve_left_end<T: Real>(hi: T, b: T, c: T) -> T {
    hi - T::one() - (T::from_f64(2.0) + c) * b
}

#[cfg(test)]
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
