//! Truncated Taylor arithmetic ("jets") in time.
//!
//! A [`Jet<T, K>`] carries a signal `x(t)` and its first `K - 1` time
//! derivatives at one instant, stored as normalized Taylor coefficients
//! `c_k = x^(k)(t) / k!`. Sums are coefficient-wise, products are Cauchy
//! convolutions (the Leibniz rule), and `exp`, `ln` and powers follow the
//! standard recurrences (Griewank & Walther, *Evaluating Derivatives*, ch. 13).
//!
//! The paper's iterative manifold (eq. (11) (IS)) needs `d^j/dt^j h_mi(s_i)` up to
//! order `n-1-i` (eq. (12) (ISFM)). The error vector `Z = (z1, ..., zn)` is exactly
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

mod elementary;

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
            fact = fact * T::from_f64(k as f64);
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
            fact = fact * T::from_f64(i as f64);
        }
        at(&self.c, k) * fact
    }

    /// All derivatives `[x, x', ..., x^(K-1)]`.
    #[inline]
    pub fn derivatives(&self) -> [T; K] {
        let mut d = self.c;
        let mut fact = T::one();
        for (k, dk) in d.iter_mut().enumerate().skip(1) {
            fact = fact * T::from_f64(k as f64);
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
            *dst = *src * T::from_f64((k + 1) as f64);
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
    fn powf_keeps_a_normal_first_derivative_where_its_value_is_subnormal() {
        // x(t) = 1e-200 + t (+ t^2 / 2): x^1.6 = 1e-320 is subnormal, but its
        // first derivative by hand, p x^(p-1) x' = 1.6e-120, is normal.
        let y = Jet::<f64, 2>::from_derivatives([1e-200, 1.0])
            .powf(1.6)
            .derivatives();
        assert!(!y[0].is_normal() && y[0] > 0.0, "{}", y[0]);
        assert!((y[1] / 1.6e-120 - 1.0).abs() < 1e-12, "{}", y[1]);
        let y = Jet::<f64, 3>::from_derivatives([1e-200, 1.0, 1.0])
            .powf(1.6)
            .derivatives();
        assert!((y[1] / 1.6e-120 - 1.0).abs() < 1e-12, "{}", y[1]);
    }

    #[test]
    fn powf_keeps_finite_derivatives_where_its_value_overflows() {
        // x(t) = 1e124 + 1e121 t: x^2.5 = 1e310 overflows, while by hand
        // y' = 2.5 x^1.5 x' = 2.5e307 and y'' = 3.75 x^0.5 x'^2 = 3.75e304.
        let y = Jet::<f64, 3>::from_derivatives([1e124, 1e121, 0.0])
            .powf(2.5)
            .derivatives();
        assert_eq!(y[0], f64::INFINITY);
        assert!((y[1] / 2.5e307 - 1.0).abs() < 1e-12, "{}", y[1]);
        assert!((y[2] / 3.75e304 - 1.0).abs() < 1e-12, "{}", y[2]);
    }

    #[test]
    fn shift_is_time_derivative() {
        let x = Jet::<f64, 3>::from_derivatives([1.0, 2.0, 3.0]);
        assert_eq!(x.shift().derivatives(), [2.0, 3.0, 0.0]);
    }
}
