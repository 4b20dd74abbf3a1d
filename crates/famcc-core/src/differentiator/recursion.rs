//! The sampled differentiator [`DiscreteHgd`], `Zhat_{k+1} = Phi Zhat_k + Gamma f_k`
//! with `f_k` the sample `e_k` (or its low-pass prefiltered value): one step
//! of it and its stability (the spectral radius of `Phi`).

use super::spectral_radius;
use crate::{ConfigError, Real};

/// The sampled differentiator `Zhat_{k+1} = Phi Zhat_k + Gamma e_k` of
/// eq. (34) for one sample period.
///
/// `phi` is row-major (`phi[row][col]`), `gamma[i]` multiplies the held input
/// `f_k`: the sample `e_k` of `z1`, or with a prefilter
/// ([`HighGain::with_prefilter`](super::HighGain::with_prefilter)) its
/// low-pass value `f_k = f_(k-1) + prefilter (e_k - f_(k-1))`
/// ([`DiscreteHgd::filter`]). Build it with
/// [`HighGain::discretize`](super::HighGain::discretize).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DiscreteHgd<T, const N: usize> {
    /// State transition over one period, row-major.
    pub phi: [[T; N]; N],
    /// Input vector over one period.
    pub gamma: [T; N],
    /// The prefilter's gain per period, `1 - exp(-dt / tau)` in `(0, 1]`;
    /// exactly 1 without a prefilter (the paper's differentiator: `f_k = e_k`).
    pub prefilter: T,
    /// The direct feedthrough `D` of the first-order hold
    /// ([`Discretization::Foh`](super::Discretization::Foh)); zeros for the
    /// other discretizations. With it `gamma` is the held input's (the exact
    /// hold's), the recursion stores `V_k = Phi Zhat_(k-1) + Gamma f_(k-1)`
    /// ([`DiscreteHgd::advance`]) and the estimate of sample `k` is
    /// `Zhat_k = V_k + D (f_k - f_(k-1))` ([`DiscreteHgd::current`]): the
    /// straight line through the samples adds to the held input's response
    /// only through the increment, so a constant input is the exact hold's,
    /// bit for bit, and a large level does not cancel in `f32`.
    pub feedthrough: [T; N],
}

impl<T: Real, const N: usize> DiscreteHgd<T, N> {
    /// One sample of eq. (34): `Zhat_{k+1} = Phi Zhat_k + Gamma e`, with `e`
    /// the sample of `z1` (held over the period). Allocation-free.
    ///
    /// ```
    /// use famcc_core::DiscreteHgd;
    /// let d = DiscreteHgd { phi: [[0.5_f64, 0.25], [0.0, 0.25]], gamma: [0.5, 2.0], prefilter: 1.0, feedthrough: [0.0; 2] };
    /// assert_eq!(d.advance(&[1.0, 2.0], 4.0), [3.0, 8.5]);
    /// ```
    #[inline]
    pub fn advance(&self, zhat: &[T; N], e: T) -> [T; N] {
        Recursion::new(self).advance(zhat, e)
    }

    /// The estimate of the sample whose (prefiltered) input changed by
    /// `df = f_k - f_(k-1)`, from the stored `v`: `v + D df` with the
    /// first-order hold's feedthrough `D`, and `v` itself (bit for bit) for
    /// the other discretizations.
    ///
    /// ```
    /// use famcc_core::DiscreteHgd;
    /// let d = DiscreteHgd { phi: [[0.5_f64]], gamma: [0.25], prefilter: 1.0, feedthrough: [0.25] };
    /// assert_eq!(d.current(&[1.0], 2.0), [1.5]);
    /// assert_eq!(d.current(&[1.0], 0.0), [1.0]); // a constant input: v itself
    /// let held = DiscreteHgd { feedthrough: [0.0], ..d };
    /// assert_eq!(held.current(&[-0.0], 2.0)[0].to_bits(), (-0.0_f64).to_bits());
    /// ```
    #[inline]
    pub fn current(&self, v: &[T; N], df: T) -> [T; N] {
        Recursion::new(self).current(v, df)
    }

    /// The differentiator's input for the sample `e` after the input `last`
    /// of the previous sample: `e` itself without a prefilter (`prefilter ==
    /// 1`, bit for bit), else the first-order low-pass
    /// `last + prefilter (e - last)`, whose DC gain is exactly 1.
    ///
    /// ```
    /// use famcc_core::DiscreteHgd;
    /// let d = DiscreteHgd { phi: [[0.5_f64]], gamma: [0.5], prefilter: 0.25, feedthrough: [0.0] };
    /// assert_eq!(d.filter(2.0, 6.0), 3.0);
    /// assert_eq!(d.filter(6.0, 6.0), 6.0);
    /// let plain = DiscreteHgd { prefilter: 1.0, ..d };
    /// assert_eq!(plain.filter(2.0, -0.0).to_bits(), (-0.0_f64).to_bits());
    /// ```
    #[inline(always)]
    pub fn filter(&self, last: T, e: T) -> T {
        filter(self.prefilter, last, e)
    }

    /// The spectral radius of `Phi` (computed in `f64` by [`spectral_radius`]):
    /// the recursion is stable iff it is below 1. A configuration whose
    /// discretized differentiator has a radius `>= 1` is rejected
    /// ([`crate::ConfigBuilder::build`]; e.g. Euler at `dt = 5 mu`).
    ///
    /// ```
    /// use famcc_core::{Discretization, HighGain};
    /// let h = |d| HighGain::new(0.01_f64, [4.0, 4.0], d);
    /// // exact: eigenvalue exp(-2 dt / mu), a double one (a defective
    /// // eigenvalue moves by ~sqrt(rounding): the radius is read to ~1e-6)
    /// let r = h(Discretization::Exact).discretize(1e-3).unwrap().spectral_radius();
    /// assert!((r - (-0.2_f64).exp()).abs() < 1e-5);
    /// assert!(h(Discretization::Euler).discretize(0.05).unwrap().spectral_radius() > 1.0);
    /// ```
    pub fn spectral_radius(&self) -> f64 {
        let mut m = [[0.0_f64; N]; N];
        for (row, src) in m.iter_mut().zip(self.phi.iter()) {
            for (x, p) in row.iter_mut().zip(src.iter()) {
                *x = p.to_f64_lossless();
            }
        }
        spectral_radius(&m)
    }

    /// The checks of [`crate::ConfigBuilder::build_discretized`] on a recursion
    /// precomputed elsewhere, whose leading `offset` slots (the integral's)
    /// must be unused.
    pub(crate) fn check_precomputed(&self, offset: usize) -> Result<(), ConfigError> {
        let entries = || {
            self.phi
                .iter()
                .flatten()
                .chain(self.gamma.iter())
                .chain(self.feedthrough.iter())
        };
        if !entries().all(|v| v.is_finite()) {
            return Err(ConfigError::new(
                "discretized",
                "must have finite Phi, Gamma and feedthrough",
            ));
        }
        if !(self.prefilter > T::zero() && self.prefilter <= T::one()) {
            return Err(ConfigError::new(
                "discretized",
                "must have a prefilter gain in (0, 1] (1 without a prefilter)",
            ));
        }
        let mut unused = self
            .gamma
            .iter()
            .take(offset)
            .chain(self.feedthrough.iter().take(offset))
            .chain(self.phi.iter().enumerate().flat_map(|(i, row)| {
                row.iter()
                    .enumerate()
                    .filter(move |(j, _)| i.min(*j) < offset)
                    .map(|(_, v)| v)
            }));
        if unused.any(|v| *v != T::zero()) {
            return Err(ConfigError::new(
                "discretized",
                "must leave the integral's slot 0 of Phi and Gamma zero (discretize_order at the plant order)",
            ));
        }
        if spectral_radius(&self.phi).partial_cmp(&T::one()) != Some(core::cmp::Ordering::Less) {
            return Err(ConfigError::new(
                "discretized",
                "is unstable (spectral radius of Phi >= 1): precompute it with HighGain::discretize_order",
            ));
        }
        if !crate::compiled::FIRST_ORDER_HOLD && self.feedthrough.iter().any(|v| *v != T::zero()) {
            return Err(ConfigError::new("discretized", crate::compiled::FOH_COMPILED_OUT));
        }
        Ok(())
    }
}

/// The recursion as the step runs it: [`DiscreteHgd`] with `Phi` stored by
/// columns, so that `Phi Zhat` is a sum of columns scaled by the entries of
/// `Zhat` and vectorizes across rows without transposing `Phi` at every
/// sample. Each entry of the result takes the same operations in the same
/// order as the row-major dot product (`Gamma_i e + Phi_i0 z_0 + ...`), so
/// the result is bit-identical.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Recursion<T, const N: usize> {
    /// `cols[j][i] = phi[i][j]`.
    cols: [[T; N]; N],
    gamma: [T; N],
    prefilter: T,
    /// `Some(D)` for the first-order hold (a nonzero feedthrough).
    feedthrough: Option<[T; N]>,
}

impl<T: Real, const N: usize> Recursion<T, N> {
    /// `d` stored by columns.
    pub(crate) fn new(d: &DiscreteHgd<T, N>) -> Self {
        Self {
            cols: transpose(&d.phi),
            gamma: d.gamma,
            prefilter: d.prefilter,
            feedthrough: d
                .feedthrough
                .iter()
                .any(|x| *x != T::zero())
                .then_some(d.feedthrough),
        }
    }

    /// The recursion by rows again (exact).
    pub(crate) fn hgd(&self) -> DiscreteHgd<T, N> {
        DiscreteHgd {
            phi: transpose(&self.cols),
            gamma: self.gamma,
            prefilter: self.prefilter,
            feedthrough: self.feedthrough.unwrap_or([T::zero(); N]),
        }
    }

    /// True for a first-order hold (a feedthrough to add).
    #[inline(always)]
    pub(crate) fn has_feedthrough(&self) -> bool {
        crate::compiled::FIRST_ORDER_HOLD && self.feedthrough.is_some()
    }

    /// [`DiscreteHgd::current`].
    #[inline(always)]
    pub(crate) fn current(&self, v: &[T; N], df: T) -> [T; N] {
        let mut z = *v;
        if let Some(d) = &self.feedthrough {
            z.iter_mut().zip(d.iter()).for_each(|(z, d)| *z = *z + *d * df);
        }
        z
    }

    /// [`DiscreteHgd::advance`].
    #[inline(always)]
    pub(crate) fn advance(&self, zhat: &[T; N], e: T) -> [T; N] {
        let mut out = self.gamma;
        out.iter_mut().for_each(|o| *o = *o * e);
        for (col, z) in self.cols.iter().zip(zhat.iter()) {
            for (o, p) in out.iter_mut().zip(col.iter()) {
                *o = *o + *p * *z;
            }
        }
        out
    }

    /// [`DiscreteHgd::filter`].
    #[inline(always)]
    pub(crate) fn filter(&self, last: T, e: T) -> T {
        filter(self.prefilter, last, e)
    }
}

impl<T: Real, const N: usize> From<DiscreteHgd<T, N>> for Recursion<T, N> {
    fn from(d: DiscreteHgd<T, N>) -> Self {
        Self::new(&d)
    }
}

/// `m` transposed (exact).
fn transpose<T: Real, const N: usize>(m: &[[T; N]; N]) -> [[T; N]; N] {
    let mut t = [[T::zero(); N]; N];
    for (i, row) in m.iter().enumerate() {
        for (col, v) in t.iter_mut().zip(row.iter()) {
            if let Some(c) = col.get_mut(i) {
                *c = *v;
            }
        }
    }
    t
}

/// `e` without a prefilter (`prefilter == 1`, bit for bit), else the
/// low-pass `last + prefilter (e - last)`.
#[inline(always)]
fn filter<T: Real>(prefilter: T, last: T, e: T) -> T {
    if prefilter == T::one() {
        e
    } else {
        low_pass(last, prefilter, e)
    }
}

/// `last + gain (e - last)`, out of line: the step without a prefilter then
/// pays a compare and a branch, not the arithmetic of a selected-away value.
#[inline(never)]
fn low_pass<T: Real>(last: T, gain: T, e: T) -> T {
    last + gain * (e - last)
}
