//! Truncated Taylor arithmetic ("jets") in time.
//!
//! A [`Jet<T, K>`] carries a signal `x(t)` and its first `K - 1` time
//! derivatives at one instant, stored as normalized Taylor coefficients
//! `c_k = x^(k)(t) / k!`. Sums are coefficient-wise, products are Cauchy
//! convolutions (the Leibniz rule), and `exp`, `ln` and powers follow the
//! standard recurrences (Griewank & Walther, *Evaluating Derivatives*, ch. 13).
//!
//! The paper's iterative manifold (eq. IS) needs `d^j/dt^j h_mi(s_i)` up to
//! order `n-1-i` (eq. ISFM). The error vector `Z = (z1, ..., zn)` is exactly
//! the derivative list of `z1`, so `s_1 = z1` is a jet, every `h` is evaluated
//! on jets, and `s_{i+1} = d/dt s_i - h_mi(s_i)` is a [`Jet::shift`] and a
//! subtraction: no hand-derived derivative formulas for any order.
//!
//! Every operation is causal: coefficient `k` of a result depends only on
//! coefficients `0..=k` of its operands. A value that is singular in a high
//! coefficient therefore never contaminates a lower one.
//!
//! ```
//! use famcc_core::Jet;
//! // x(t) = 2 + 3t  =>  (x^2)' = 2 x x' = 12, (x^2)'' = 2 x'^2 = 18
//! let x = Jet::<f64, 3>::from_derivatives([2.0, 3.0, 0.0]);
//! let y = x * x;
//! assert_eq!(y.derivatives(), [4.0, 12.0, 18.0]);
//! ```

use crate::Real;
use core::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};

/// A signal's value and its first `K - 1` time derivatives (docs/design.md
/// §4.1: derivatives of nonlinear manifolds by jets).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Jet<T, const K: usize> {
    /// Normalized Taylor coefficients `x^(k) / k!`.
    c: [T; K],
}

impl<T: Real, const K: usize> Default for Jet<T, K> {
    fn default() -> Self {
        Self::constant(T::zero())
    }
}

#[inline(always)]
fn at<T: Real, const K: usize>(c: &[T; K], i: usize) -> T {
    c.get(i).copied().unwrap_or_else(T::zero)
}

#[inline(always)]
fn set<T: Real, const K: usize>(c: &mut [T; K], i: usize, v: T) {
    if let Some(slot) = c.get_mut(i) {
        *slot = v;
    }
}

/// `lead * r_k` for every coefficient, where `lead = exp(log_lead())`. When
/// `lead` is not a normal number (it overflowed or underflowed) each nonzero
/// coefficient is computed as `sign(r_k) exp(log_lead + ln|r_k|)` instead, and
/// exact zeros stay zero (no `0 * inf`).
#[inline]
fn scale_by_exp<T: Real, const K: usize>(r: [T; K], lead: T, log_lead: impl Fn() -> T) -> [T; K] {
    let mut out = r;
    if lead.is_normal() {
        out.iter_mut().for_each(|v| *v = *v * lead);
        return out;
    }
    let l = log_lead();
    for (k, v) in out.iter_mut().enumerate() {
        *v = if k == 0 {
            lead
        } else if *v == T::zero() {
            T::zero()
        } else {
            let m = (l + v.abs().ln()).exp();
            if *v < T::zero() {
                -m
            } else {
                m
            }
        };
    }
    out
}

impl<T: Real, const K: usize> Jet<T, K> {
    /// A constant signal: all derivatives zero.
    #[inline(always)]
    pub fn constant(v: T) -> Self {
        let mut c = [T::zero(); K];
        set(&mut c, 0, v);
        Self { c }
    }

    /// Builds a jet from the value and derivatives `[x, x', x'', ...]`.
    #[inline]
    pub fn from_derivatives(d: [T; K]) -> Self {
        let mut c = d;
        let mut fact = T::one();
        for (k, ck) in c.iter_mut().enumerate().skip(1) {
            fact = fact * T::c(k as f64);
            *ck = *ck / fact;
        }
        Self { c }
    }

    /// Builds a jet from normalized Taylor coefficients `x^(k)/k!`.
    #[inline(always)]
    pub fn from_taylor(c: [T; K]) -> Self {
        Self { c }
    }

    /// The normalized Taylor coefficients `x^(k)/k!`.
    #[inline(always)]
    pub fn taylor(&self) -> [T; K] {
        self.c
    }

    /// The value `x(t)`.
    #[inline(always)]
    pub fn value(&self) -> T {
        at(&self.c, 0)
    }

    /// The `k`-th time derivative `x^(k)(t)` (zero for `k >= K`).
    #[inline]
    pub fn derivative(&self, k: usize) -> T {
        let mut fact = T::one();
        for i in 2..=k {
            fact = fact * T::c(i as f64);
        }
        at(&self.c, k) * fact
    }

    /// All derivatives `[x, x', ..., x^(K-1)]`.
    #[inline]
    pub fn derivatives(&self) -> [T; K] {
        let mut d = self.c;
        let mut fact = T::one();
        for (k, dk) in d.iter_mut().enumerate().skip(1) {
            fact = fact * T::c(k as f64);
            *dk = *dk * fact;
        }
        d
    }

    /// True when the value and every derivative are exactly zero.
    #[inline(always)]
    pub fn is_zero(&self) -> bool {
        self.c.iter().all(|v| *v == T::zero())
    }

    /// True when every coefficient is finite.
    #[inline(always)]
    pub fn is_finite(&self) -> bool {
        self.c.iter().all(|v| v.is_finite())
    }

    /// The time derivative `d/dt`: the jet of `x'(t)`. Its last derivative is
    /// unknown at this truncation and set to zero.
    #[inline(always)]
    pub fn shift(&self) -> Self {
        let mut c = [T::zero(); K];
        for (k, (dst, src)) in c.iter_mut().zip(self.c.iter().skip(1)).enumerate() {
            *dst = *src * T::c((k + 1) as f64);
        }
        Self { c }
    }

    /// Multiplies every coefficient by a scalar.
    #[inline(always)]
    pub fn scale(&self, a: T) -> Self {
        let mut c = self.c;
        c.iter_mut().for_each(|v| *v = *v * a);
        Self { c }
    }

    /// `exp(x)`.
    ///
    /// The recurrence runs on `exp(x - x0)` (leading coefficient 1) and is
    /// scaled by `exp(x0)` at the end, so the derivatives stay accurate (and
    /// exactly zero where the signal's are) even where `exp(x0)` itself
    /// overflows or underflows.
    #[inline]
    pub fn exp(&self) -> Self {
        let mut r = [T::zero(); K];
        set(&mut r, 0, T::one());
        for k in 1..K {
            let mut acc = T::zero();
            for j in 1..=k {
                acc = acc + T::c(j as f64) * at(&self.c, j) * at(&r, k - j);
            }
            set(&mut r, k, acc / T::c(k as f64));
        }
        let x0 = self.value();
        Self {
            c: scale_by_exp(r, x0.exp(), || x0),
        }
    }

    /// `ln(x)`, for a positive value.
    #[inline]
    pub fn ln(&self) -> Self {
        let x0 = self.value();
        let mut l = [T::zero(); K];
        set(&mut l, 0, x0.ln());
        for k in 1..K {
            let mut acc = T::zero();
            for j in 1..k {
                acc = acc + T::c(j as f64) * at(&l, j) * at(&self.c, k - j);
            }
            set(&mut l, k, (at(&self.c, k) - acc / T::c(k as f64)) / x0);
        }
        Self { c: l }
    }

    /// `x^p` for a positive value and a constant exponent.
    ///
    /// Where `x0^p` itself overflows or underflows (e.g. `x^2` at `x = 1e200`:
    /// value `inf`, first derivative `2e200 x'`), the recurrence runs on
    /// `(x/x0)^p` and each coefficient is rescaled by `x0^p` through logs, so
    /// the first derivative stays finite and accurate (and exact zeros stay
    /// zero); higher derivatives stay finite but may lose accuracy there.
    #[inline]
    pub fn powf(&self, p: T) -> Self {
        if p == T::c(2.0) {
            return *self * *self;
        }
        if p == T::one() {
            return *self;
        }
        if p == T::c(0.5) {
            if let Some(r) = self.sqrt_normal() {
                return r;
            }
        }
        let x0 = self.value();
        let y0 = x0.powr(p);
        if y0.is_normal() {
            let mut y = [T::zero(); K];
            set(&mut y, 0, y0);
            for k in 1..K {
                let mut acc = T::zero();
                for j in 1..=k {
                    let w = p * T::c(j as f64) - T::c((k - j) as f64);
                    acc = acc + w * at(&self.c, j) * at(&y, k - j);
                }
                set(&mut y, k, acc / (T::c(k as f64) * x0));
            }
            return Self { c: y };
        }
        let mut r = [T::zero(); K];
        set(&mut r, 0, T::one());
        for k in 1..K {
            let mut acc = T::zero();
            for j in 1..=k {
                let w = p * T::c(j as f64) - T::c((k - j) as f64);
                acc = acc + w * (at(&self.c, j) / x0) * at(&r, k - j);
            }
            set(&mut r, k, acc / T::c(k as f64));
        }
        Self {
            c: scale_by_exp(r, y0, || p * x0.ln()),
        }
    }

    /// `sqrt(x)` by the recurrence `y_k = (x_k - sum_{j=1}^{k-1} y_j y_{k-j}) / (2 y_0)`,
    /// when `sqrt(x_0)` is a normal number (`None` otherwise: use `powf`).
    #[inline]
    fn sqrt_normal(&self) -> Option<Self> {
        let y0 = self.value().root();
        if !y0.is_normal() {
            return None;
        }
        let inv = (T::c(2.0) * y0).recip();
        let mut y = [T::zero(); K];
        set(&mut y, 0, y0);
        for k in 1..K {
            let mut acc = at(&self.c, k);
            for j in 1..k {
                acc = acc - at(&y, j) * at(&y, k - j);
            }
            set(&mut y, k, acc * inv);
        }
        Some(Self { c: y })
    }

    /// `|x|`. At a zero value the sign of the first nonzero coefficient is
    /// used (the right-hand derivative in time).
    #[inline]
    pub fn abs(&self) -> Self {
        if self.leading_sign() < T::zero() {
            -*self
        } else {
            *self
        }
    }

    /// The sign of the first nonzero coefficient (zero for the zero jet).
    #[inline]
    fn leading_sign(&self) -> T {
        for v in self.c.iter() {
            if *v > T::zero() {
                return T::one();
            }
            if *v < T::zero() {
                return -T::one();
            }
        }
        T::zero()
    }

    /// The signed power `|x|^p sign(x)` (the paper's `⌈x⌋^p`), `p > 0`.
    ///
    /// At a zero value the `k`-th derivative is zero when `p > k`, and
    /// infinite (a true singularity of the law, for example the finite-time
    /// law with `p < 1`) when `p < k` and the signal moves.
    #[inline]
    pub fn signed_pow(&self, p: T) -> Self {
        let x0 = self.value();
        if x0 > T::zero() {
            self.powf(p)
        } else if x0 < T::zero() {
            -((-*self).powf(p))
        } else {
            self.singular_at_zero(|k| p > T::c(k as f64))
        }
    }

    /// `|x|^{q(x)} sign(x)` for an exponent that is itself a jet of the
    /// signal (the variable-exponent laws). `q` must be positive at 0.
    #[inline]
    pub fn signed_pow_jet(&self, q: &Self) -> Self {
        let x0 = self.value();
        if x0 == T::zero() {
            let q0 = q.value();
            return self.singular_at_zero(|k| q0 > T::c(k as f64));
        }
        let a = self.abs();
        let mag = (*q * a.ln()).exp();
        if x0 > T::zero() {
            mag
        } else {
            -mag
        }
    }

    /// The jet of a power-like law at a zero value: value zero, derivative
    /// `k` zero when `smooth(k)`, otherwise signed infinity if the signal
    /// moves at all.
    #[inline]
    fn singular_at_zero(&self, smooth: impl Fn(usize) -> bool) -> Self {
        let mut c = [T::zero(); K];
        let s = self.leading_sign();
        if s != T::zero() {
            for (k, ck) in c.iter_mut().enumerate().skip(1) {
                if !smooth(k) {
                    *ck = s * T::infinity();
                }
            }
        }
        Self { c }
    }

    /// `(sin(x), cos(x))`.
    #[inline]
    pub fn sin_cos(&self) -> (Self, Self) {
        let (s0, c0) = self.value().sin_cos();
        let mut s = [T::zero(); K];
        let mut c = [T::zero(); K];
        set(&mut s, 0, s0);
        set(&mut c, 0, c0);
        for k in 1..K {
            let mut as_ = T::zero();
            let mut ac = T::zero();
            for j in 1..=k {
                let w = T::c(j as f64) * at(&self.c, j);
                as_ = as_ + w * at(&c, k - j);
                ac = ac + w * at(&s, k - j);
            }
            let kk = T::c(k as f64);
            set(&mut s, k, as_ / kk);
            set(&mut c, k, -ac / kk);
        }
        (Self { c: s }, Self { c })
    }

    /// The logistic function `1/(1 + exp(-x))`, by its ODE `y' = y (1 - y) x'`:
    /// one scalar `exp` and an O(K^2) recurrence, no jet `exp` or division.
    /// Accurate where `y <= 1/2` (`x <= 0`); near `y = 1` the factor `1 - y`
    /// cancels, so callers reflect (`1 - logistic(-x)`) there.
    #[inline]
    pub fn logistic(&self) -> Self {
        let x0 = self.value();
        let one = T::one();
        let y0 = if x0 >= T::zero() {
            one / (one + (-x0).exp())
        } else {
            let q = x0.exp();
            q / (one + q)
        };
        let mut y = [T::zero(); K];
        let mut g = [T::zero(); K];
        set(&mut y, 0, y0);
        set(&mut g, 0, y0 * (one - y0));
        for k in 1..K {
            let mut acc = T::zero();
            for j in 1..=k {
                acc = acc + T::c(j as f64) * at(&self.c, j) * at(&g, k - j);
            }
            let yk = acc / T::c(k as f64);
            set(&mut y, k, yk);
            let mut sq = T::zero();
            for i in 0..=k {
                sq = sq + at(&y, i) * at(&y, k - i);
            }
            set(&mut g, k, yk - sq);
        }
        Self { c: y }
    }

    /// `1 / x`.
    #[inline]
    pub fn recip(&self) -> Self {
        Self::constant(T::one()) / *self
    }
}

impl<T: Real, const K: usize> Add for Jet<T, K> {
    type Output = Self;
    #[inline(always)]
    fn add(mut self, rhs: Self) -> Self {
        self += rhs;
        self
    }
}

impl<T: Real, const K: usize> AddAssign for Jet<T, K> {
    #[inline(always)]
    fn add_assign(&mut self, rhs: Self) {
        self.c
            .iter_mut()
            .zip(rhs.c.iter())
            .for_each(|(a, b)| *a = *a + *b);
    }
}

impl<T: Real, const K: usize> Sub for Jet<T, K> {
    type Output = Self;
    #[inline(always)]
    fn sub(mut self, rhs: Self) -> Self {
        self -= rhs;
        self
    }
}

impl<T: Real, const K: usize> SubAssign for Jet<T, K> {
    #[inline(always)]
    fn sub_assign(&mut self, rhs: Self) {
        self.c
            .iter_mut()
            .zip(rhs.c.iter())
            .for_each(|(a, b)| *a = *a - *b);
    }
}

impl<T: Real, const K: usize> Neg for Jet<T, K> {
    type Output = Self;
    #[inline(always)]
    fn neg(mut self) -> Self {
        self.c.iter_mut().for_each(|v| *v = -*v);
        self
    }
}

impl<T: Real, const K: usize> Mul for Jet<T, K> {
    type Output = Self;
    #[inline]
    fn mul(self, rhs: Self) -> Self {
        let mut c = [T::zero(); K];
        for (k, ck) in c.iter_mut().enumerate() {
            let mut acc = T::zero();
            for (a, b) in self.c.iter().take(k + 1).zip(rhs.c.iter().take(k + 1).rev()) {
                acc = acc + *a * *b;
            }
            *ck = acc;
        }
        Self { c }
    }
}

impl<T: Real, const K: usize> MulAssign for Jet<T, K> {
    #[inline(always)]
    fn mul_assign(&mut self, rhs: Self) {
        *self = *self * rhs;
    }
}

impl<T: Real, const K: usize> Div for Jet<T, K> {
    type Output = Self;
    #[inline]
    fn div(self, rhs: Self) -> Self {
        let b0 = rhs.value();
        let mut q = [T::zero(); K];
        for k in 0..K {
            let mut acc = at(&self.c, k);
            for j in 1..=k {
                acc = acc - at(&rhs.c, j) * at(&q, k - j);
            }
            set(&mut q, k, acc / b0);
        }
        Self { c: q }
    }
}

impl<T: Real, const K: usize> Add<T> for Jet<T, K> {
    type Output = Self;
    #[inline(always)]
    fn add(mut self, rhs: T) -> Self {
        if let Some(c0) = self.c.first_mut() {
            *c0 = *c0 + rhs;
        }
        self
    }
}

impl<T: Real, const K: usize> Sub<T> for Jet<T, K> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, rhs: T) -> Self {
        self + (-rhs)
    }
}

impl<T: Real, const K: usize> Mul<T> for Jet<T, K> {
    type Output = Self;
    #[inline(always)]
    fn mul(self, rhs: T) -> Self {
        self.scale(rhs)
    }
}

impl<T: Real, const K: usize> Div<T> for Jet<T, K> {
    type Output = Self;
    #[inline(always)]
    fn div(self, rhs: T) -> Self {
        self.scale(T::one() / rhs)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exp_ln_roundtrip() {
        let x = Jet::<f64, 4>::from_derivatives([0.7, -1.3, 2.0, 0.5]);
        let y = x.exp().ln();
        for (a, b) in x.taylor().iter().zip(y.taylor().iter()) {
            assert!((a - b).abs() < 1e-13);
        }
    }

    #[test]
    fn shift_is_time_derivative() {
        let x = Jet::<f64, 3>::from_derivatives([1.0, 2.0, 3.0]);
        assert_eq!(x.shift().derivatives(), [2.0, 3.0, 0.0]);
    }
}
