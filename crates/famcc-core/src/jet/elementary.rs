//! Elementary functions on jets: `exp`, `ln`, powers (constant, signed and
//! variable exponents), `sin`/`cos`, the logistic function and the reciprocal,
//! by the standard Taylor-coefficient recurrences (Griewank & Walther,
//! *Evaluating Derivatives*, ch. 13). Every one is causal: coefficient `k` of
//! the result depends on coefficients `0..=k` of the argument only.

use super::{at, set, Jet};
use crate::Real;

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
                acc = acc + T::from_f64(j as f64) * at(&self.c, j) * at(&r, k - j);
            }
            set(&mut r, k, acc / T::from_f64(k as f64));
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
                acc = acc + T::from_f64(j as f64) * at(&l, j) * at(&self.c, k - j);
            }
            set(&mut l, k, (at(&self.c, k) - acc / T::from_f64(k as f64)) / x0);
        }
        Self { c: l }
    }

    /// `x^p` for a positive value and a constant exponent.
    ///
    /// Where `x0^p` itself overflows or underflows (e.g. `x^2` at `x = 1e200`:
    /// value `inf`, first derivative `2e200 x'`), the recurrence runs on
    /// `(x/x0)^p` and each coefficient is rescaled by `x0^p` through logs, so
    /// the first derivative stays finite and accurate (and exact zeros stay
    /// zero); higher derivatives may lose accuracy there, or overflow where
    /// `(x'/x0)^k` does (e.g. `x^1.6` at `x = 1e-200`, `x' = 1`: the second
    /// derivative `0.96e80` comes out infinite).
    #[inline]
    pub fn powf(&self, p: T) -> Self {
        if p == T::from_f64(2.0) {
            return *self * *self;
        }
        if p == T::one() {
            return *self;
        }
        if p == T::from_f64(0.5) {
            if let Some(r) = self.sqrt_normal() {
                return r;
            }
        }
        let x0 = self.value();
        let y0 = x0.pow_nonneg(p);
        if y0.is_normal() {
            let mut y = [T::zero(); K];
            set(&mut y, 0, y0);
            for k in 1..K {
                let mut acc = T::zero();
                for j in 1..=k {
                    let w = p * T::from_f64(j as f64) - T::from_f64((k - j) as f64);
                    acc = acc + w * at(&self.c, j) * at(&y, k - j);
                }
                set(&mut y, k, acc / (T::from_f64(k as f64) * x0));
            }
            return Self { c: y };
        }
        let mut r = [T::zero(); K];
        set(&mut r, 0, T::one());
        for k in 1..K {
            let mut acc = T::zero();
            for j in 1..=k {
                let w = p * T::from_f64(j as f64) - T::from_f64((k - j) as f64);
                acc = acc + w * (at(&self.c, j) / x0) * at(&r, k - j);
            }
            set(&mut r, k, acc / T::from_f64(k as f64));
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
        let inv = (T::from_f64(2.0) * y0).recip();
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
            self.singular_at_zero(|k| p > T::from_f64(k as f64))
        }
    }

    /// `|x|^{q(x)} sign(x)` for an exponent that is itself a jet of the
    /// signal (the variable-exponent laws). `q` must be positive at 0.
    #[inline]
    pub fn signed_pow_jet(&self, q: &Self) -> Self {
        let x0 = self.value();
        if x0 == T::zero() {
            let q0 = q.value();
            return self.singular_at_zero(|k| q0 > T::from_f64(k as f64));
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
        self.sin_cos_from(self.value().sin_cos())
    }

    /// [`Jet::sin_cos`] for `|x| <= pi/4` only ([`Real::sin_cos_octant`]).
    #[inline]
    pub fn sin_cos_octant(&self) -> (Self, Self) {
        self.sin_cos_from(self.value().sin_cos_octant())
    }

    /// The jets of `sin(x)` and `cos(x)` from their values `(s0, c0)`, by
    /// the recurrences of `s' = c x'` and `c' = -s x'`.
    #[inline]
    fn sin_cos_from(&self, (s0, c0): (T, T)) -> (Self, Self) {
        let mut s = [T::zero(); K];
        let mut c = [T::zero(); K];
        set(&mut s, 0, s0);
        set(&mut c, 0, c0);
        for k in 1..K {
            let mut as_ = T::zero();
            let mut ac = T::zero();
            for j in 1..=k {
                let w = T::from_f64(j as f64) * at(&self.c, j);
                as_ = as_ + w * at(&c, k - j);
                ac = ac + w * at(&s, k - j);
            }
            let kk = T::from_f64(k as f64);
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
                acc = acc + T::from_f64(j as f64) * at(&self.c, j) * at(&g, k - j);
            }
            let yk = acc / T::from_f64(k as f64);
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
