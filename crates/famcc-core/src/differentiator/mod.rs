//! The high-gain differentiator (paper eq. (34), HGD), discretized once at
//! construction, and the paper's choice of its parameters
//! ([`HighGain::paper`]: `mu = 0.01`, `a = (4, 4)` at order 2 and `(4, 6, 4)`
//! at order 3 as in the paper's examples, binomial `(s + 2)^n` otherwise).
//!
//! The paper estimates the error vector `Z = (z1, z1', ..., z1^(N-1))` from the
//! measured `z1` alone with
//!
//! ```text
//! dZhat/dt = A Zhat + H (z1 - C Zhat) = (A - H C) Zhat + H z1        (eq. (34))
//! ```
//!
//! where `A` is the shift matrix (ones on the superdiagonal), `C = [1 0 ... 0]`
//! and `H = (a1/mu, a2/mu^2, ..., aN/mu^N)^T`. The small time constant `mu`
//! (seconds) sets the speed, the dimensionless `a_i` make
//! `s^N + a1 s^(N-1) + ... + aN` Hurwitz. Units: `Zhat_i` has the units of
//! `z1` per `s^(i-1)`, `H_i` is in `1/s^i`, the sample period `dt` in seconds.
//!
//! The system is linear and time-invariant, so it is turned into the
//! recursion `Zhat_{k+1} = Phi Zhat_k + Gamma e_k` once, for a fixed `dt`
//! (docs/design.md §3.3), by one of three [`Discretization`]s. The default,
//! [`Discretization::Exact`], is the zero-order-hold solution: stable for
//! every `dt`.
//!
//! ```
//! use famcc_core::{Discretization, HighGain};
//! // order 1: Phi = exp(-a1 dt / mu) = exp(-1), Gamma = 1 - Phi
//! let d = HighGain::new(0.1_f64, [1.0], Discretization::Exact).discretize(0.1).unwrap();
//! assert!((d.phi[0][0] - 0.367_879_441_171_442_3).abs() < 1e-15);
//! assert!((d.gamma[0] - 0.632_120_558_828_557_7).abs() < 1e-15);
//! // one step from 0 towards a constant measurement of 2
//! assert!((d.advance(&[0.0], 2.0)[0] - 1.264_241_117_657_115_4).abs() < 1e-14);
//! ```
//!
//! # Numerics
//!
//! Everything is computed in `f64` whatever `T` is, then rounded once to `T`,
//! so an `f32` user gets `Phi` and `Gamma` correct to `f32` rounding.
//!
//! The matrices are built in balanced coordinates `w_i = mu^(i-1) Zhat_i`,
//! where eq. (34) reads `dw/dsigma = M0 w + a z1` with `sigma = t / mu` and
//! `M0 = A - a C` (all entries `O(a_i)`, independent of `mu`). The recursion
//! for `w` over `tau = dt / mu` is computed and mapped back with
//! `Phi_ij = Phi0_ij mu^(j-i)`, `Gamma_i = Gamma0_i mu^(1-i)`. This diagonal
//! similarity is exact in theory and keeps the non-normality `mu^(1-N)` of
//! `A - H C` out of the matrix exponential, so small entries of `Phi` are
//! accurate relative to their own size, not only to the largest entry.

mod expm;
mod linalg;

use crate::error::positive;
use crate::{ConfigError, Real};
use expm::expm_zoh;
use linalg::{identity, lu_solve, routh_hurwitz, Mat};

/// The paper's differentiator time constant `mu = 0.01` s (all three of its
/// examples).
pub const PAPER_MU: f64 = 0.01;

/// True when output feedback at `order` needs a differentiator: at order 1
/// the measured error is the whole error vector `Z = (e)` (docs/design.md
/// §3.5), so `step(e)` works without one.
pub const fn needed_at(order: usize) -> bool {
    order > 1
}

/// Writes the paper's coefficients for order `a.len()` into `a`: `(4, 4)` at
/// order 2 (`(s + 2)^2`, examples 1-2), `(4, 6, 4)` at order 3 (roots `-2`,
/// `-1 +- i`, example 3), and the binomial coefficients of `(s + 2)^n`
/// (`a_i = C(n, i) 2^i`) at every other order.
///
/// ```
/// use famcc_core::differentiator::paper_coefficients;
/// let mut a = [0.0_f64; 4];
/// paper_coefficients(&mut a);
/// assert_eq!(a, [8.0, 24.0, 32.0, 16.0]);
/// let mut b = [0.0_f32; 3];
/// paper_coefficients(&mut b);
/// assert_eq!(b, [4.0, 6.0, 4.0]);
/// ```
pub fn paper_coefficients<T: Real>(a: &mut [T]) {
    if let [a1, a2, a3] = a {
        (*a1, *a2, *a3) = (T::from_f64(4.0), T::from_f64(6.0), T::from_f64(4.0));
        return;
    }
    let n = a.len();
    let mut binomial = 1.0_f64;
    let mut power = 1.0_f64;
    for (i, ai) in a.iter_mut().enumerate() {
        // C(n, i+1) 2^(i+1) from C(n, i) 2^i; exact in f64 for every order famcc builds.
        binomial = binomial * (n - i) as f64 / (i + 1) as f64;
        power *= 2.0;
        *ai = T::from_f64(binomial * power);
    }
}

/// How eq. (34) (HGD) is turned into a sampled recursion
/// `Zhat_{k+1} = Phi Zhat_k + Gamma e_k` (with `M = A - H C`, `dt` in seconds).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Discretization {
    /// Zero-order hold on `z1` (the sample `e_k` is held over the period):
    /// `Phi = exp(M dt)`, `Gamma = (integral_0^dt exp(M s) ds) H`. Exact for a
    /// held input and stable for every `dt` (the eigenvalues of `Phi` are
    /// `exp(lambda dt)` with `Re lambda < 0`).
    #[default]
    Exact,
    /// Forward Euler: `Phi = I + M dt`, `Gamma = H dt`. For comparison only:
    /// it is unstable once `dt` exceeds roughly `mu` times a constant that
    /// depends on `a` (e.g. `dt > mu` for order 2 with `a = (4, 4)`). Such a
    /// `dt` is accepted, not rejected; the caller asked for Euler.
    Euler,
    /// Tustin (bilinear, trapezoidal rule) with the input held over the
    /// period: `Phi = (I - M dt/2)^-1 (I + M dt/2)`,
    /// `Gamma = (I - M dt/2)^-1 H dt`. Stable for every `dt`, but it maps very
    /// fast modes to eigenvalues near `-1` (ringing) when `dt >> mu`.
    Tustin,
}

/// The high-gain differentiator's parameters (eq. (34), HGD): time constant `mu`
/// (seconds), coefficients `a = (a1, ..., aN)` (dimensionless) and the
/// discretization method.
///
/// ```
/// use famcc_core::{Discretization, HighGain};
/// // the paper's order-2 choice: s^2 + 4 s + 4 = (s + 2)^2
/// let hg = HighGain::new(0.01_f64, [4.0, 4.0], Discretization::Exact);
/// assert!(hg.validate().is_ok());
/// let bad = HighGain::new(0.01_f64, [1.0, 1.0, 10.0], Discretization::Exact);
/// assert_eq!(bad.validate().unwrap_err().parameter, "a");
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HighGain<T, const N: usize> {
    /// The small positive time constant `mu`, seconds.
    pub mu: T,
    /// The coefficients `a1, ..., aN` of the Hurwitz polynomial
    /// `s^N + a1 s^(N-1) + ... + aN` (dimensionless).
    pub a: [T; N],
    /// How eq. (34) is sampled.
    pub discretization: Discretization,
}

/// The sampled differentiator `Zhat_{k+1} = Phi Zhat_k + Gamma e_k` of
/// eq. (34) for one sample period.
///
/// `phi` is row-major (`phi[row][col]`), `gamma[i]` multiplies the held sample
/// `e_k` of `z1`. Build it with [`HighGain::discretize`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DiscreteHgd<T, const N: usize> {
    /// State transition over one period, row-major.
    pub phi: [[T; N]; N],
    /// Input vector over one period.
    pub gamma: [T; N],
}

impl<T: Real, const N: usize> HighGain<T, N> {
    /// The paper's differentiator for order `N`: [`PAPER_MU`], the
    /// coefficients of [`paper_coefficients`], the exact discretization.
    ///
    /// ```
    /// use famcc_core::HighGain;
    /// let h = HighGain::<f64, 2>::paper();
    /// assert_eq!((h.mu, h.a), (0.01, [4.0, 4.0]));
    /// ```
    pub fn paper() -> Self {
        let mut a = [T::zero(); N];
        paper_coefficients(&mut a);
        Self::new(T::from_f64(PAPER_MU), a, Discretization::default())
    }

    /// The parameters as given (not validated; see [`HighGain::validate`]).
    pub fn new(mu: T, a: [T; N], discretization: Discretization) -> Self {
        Self {
            mu,
            a,
            discretization,
        }
    }

    /// Checks the parameters of eq. (34): `mu` (seconds) finite and `> 0`,
    /// order `N >= 1`, every `a_i` finite and `> 0`, and
    /// `s^N + a1 s^(N-1) + ... + aN` Hurwitz (Routh-Hurwitz test, computed in
    /// `f64`; a first-column entry that cancels to within rounding counts as
    /// a root on the imaginary axis, i.e. not Hurwitz).
    ///
    /// ```
    /// use famcc_core::{Discretization, HighGain};
    /// // s^3 + 4 s^2 + 6 s + 4 = (s + 2)(s^2 + 2 s + 2): Hurwitz
    /// assert!(HighGain::new(0.01_f64, [4.0, 6.0, 4.0], Discretization::Exact).validate().is_ok());
    /// // s^2 + s - 1 has a root at 0.618...
    /// assert!(HighGain::new(0.01_f64, [1.0, -1.0], Discretization::Exact).validate().is_err());
    /// ```
    pub fn validate(&self) -> Result<(), ConfigError> {
        positive(self.mu, "mu")?;
        if N == 0 {
            return Err(ConfigError::new(
                "a",
                "must have at least one coefficient (order N >= 1)",
            ));
        }
        if !self.a.iter().all(|&ai| ai.is_finite() && ai > T::zero()) {
            return Err(ConfigError::new("a", "must all be finite and > 0"));
        }
        let mut a = [0.0_f64; N];
        for (d, s) in a.iter_mut().zip(self.a.iter()) {
            *d = s.to_f64_lossless();
        }
        if routh_hurwitz(&a) {
            Ok(())
        } else {
            Err(ConfigError::new(
                "a",
                "must make s^N + a1 s^(N-1) + ... + aN Hurwitz; this polynomial is not Hurwitz",
            ))
        }
    }

    /// Validates, checks the sample period `dt` (seconds; finite and `> 0`,
    /// errors name `"dt"`) and discretizes eq. (34) with
    /// [`HighGain::discretization`].
    ///
    /// [`Discretization::Exact`] computes the exponential of the augmented
    /// matrix `[[M0 tau, a tau], [0, 0]]` (balanced coordinates, see the
    /// module docs; `tau = dt / mu`) by scaling and squaring with the
    /// degree-13 diagonal Pade approximant of Higham (2005): the matrix is
    /// divided by the smallest `2^s` (`s >= 0`) that brings its 1-norm to at
    /// most `theta_13 = 5.371920351148152`, the Pade system is solved by LU
    /// with partial pivoting, and the result is squared `s` times.
    ///
    /// Errors: `"mu"` when `mu` is so small that `Phi` or `Gamma` overflows
    /// `T` (entries scale like `mu^(1-N)`); `"dt"` when `dt / mu` overflows.
    ///
    /// ```
    /// use famcc_core::{Discretization, HighGain};
    /// let hg = HighGain::new(0.01_f64, [4.0, 4.0], Discretization::Exact);
    /// let d = hg.discretize(1e-3).unwrap();
    /// // DC gain: a constant measurement 1.5 is a fixed point at (1.5, 0)
    /// let z = d.advance(&[1.5, 0.0], 1.5);
    /// assert!((z[0] - 1.5).abs() < 1e-12 && z[1].abs() < 1e-9);
    /// // dt = 1 s with mu = 0.01: everything decays within one period
    /// let slow = hg.discretize(1.0).unwrap();
    /// assert!(slow.phi.iter().flatten().all(|p| p.abs() < 1e-60));
    /// assert!(hg.discretize(0.0).is_err());
    /// ```
    pub fn discretize(&self, dt: T) -> Result<DiscreteHgd<T, N>, ConfigError> {
        self.validate()?;
        positive(dt, "dt")?;
        let mu = self.mu.to_f64_lossless();
        let tau = dt.to_f64_lossless() / mu;
        if !tau.is_finite() {
            return Err(ConfigError::new(
                "dt",
                "is too large for this mu (dt / mu overflows)",
            ));
        }
        let mut a = [0.0_f64; N];
        for (d, s) in a.iter_mut().zip(self.a.iter()) {
            *d = s.to_f64_lossless();
        }
        let m0 = balanced_matrix(&a);
        let singular = ConfigError::new("dt", "gives a numerically singular system in the discretization");
        let (phi0, gamma0) = match self.discretization {
            Discretization::Exact => expm_zoh(&m0, &a, tau).ok_or(singular)?,
            Discretization::Euler => {
                let mut phi0 = identity::<N>();
                for (prow, mrow) in phi0.iter_mut().zip(m0.iter()) {
                    for (p, m) in prow.iter_mut().zip(mrow.iter()) {
                        *p += tau * m;
                    }
                }
                let mut g = a;
                for gi in g.iter_mut() {
                    *gi *= tau;
                }
                (phi0, g)
            }
            Discretization::Tustin => {
                let mut lhs = identity::<N>();
                let mut rhs = identity::<N>();
                for ((lrow, rrow), mrow) in lhs.iter_mut().zip(rhs.iter_mut()).zip(m0.iter()) {
                    for ((l, r), m) in lrow.iter_mut().zip(rrow.iter_mut()).zip(mrow.iter()) {
                        *l -= 0.5 * tau * m;
                        *r += 0.5 * tau * m;
                    }
                }
                let mut g = a;
                for gi in g.iter_mut() {
                    *gi *= tau;
                }
                lu_solve(lhs, rhs, g).ok_or(singular)?
            }
        };
        unbalance(&phi0, &gamma0, mu).ok_or(ConfigError::new(
            "mu",
            "is so small that Phi or Gamma overflows this float type",
        ))
    }
}

impl<T: Real, const N: usize> DiscreteHgd<T, N> {
    /// One sample of eq. (34): `Zhat_{k+1} = Phi Zhat_k + Gamma e`, with `e`
    /// the sample of `z1` (held over the period). Allocation-free.
    ///
    /// ```
    /// use famcc_core::DiscreteHgd;
    /// let d = DiscreteHgd { phi: [[0.5_f64, 0.25], [0.0, 0.25]], gamma: [0.5, 2.0] };
    /// assert_eq!(d.advance(&[1.0, 2.0], 4.0), [3.0, 8.5]);
    /// ```
    #[inline]
    pub fn advance(&self, zhat: &[T; N], e: T) -> [T; N] {
        let mut out = [T::zero(); N];
        for ((o, row), g) in out.iter_mut().zip(self.phi.iter()).zip(self.gamma.iter()) {
            *o = row
                .iter()
                .zip(zhat.iter())
                .fold(*g * e, |acc, (p, z)| acc + *p * *z);
        }
        out
    }
}

// ---------------------------------------------------------------------------
// Balanced coordinates
// ---------------------------------------------------------------------------

/// `M0 = A - a C`: the matrix of eq. (34) in balanced coordinates.
fn balanced_matrix<const N: usize>(a: &[f64; N]) -> Mat<N> {
    let mut m = [[0.0; N]; N];
    for (i, (row, ai)) in m.iter_mut().zip(a.iter()).enumerate() {
        if let Some(first) = row.first_mut() {
            *first = -ai;
        }
        if let Some(sup) = row.get_mut(i + 1) {
            *sup += 1.0;
        }
    }
    m
}

/// Maps the balanced-coordinate recursion back to `Zhat`:
/// `Phi_ij = Phi0_ij mu^(j-i)`, `Gamma_i = Gamma0_i mu^(-i)` (0-based), then
/// rounds to `T`. `None` if anything is not finite in `T`.
fn unbalance<T: Real, const N: usize>(
    phi0: &Mat<N>,
    gamma0: &[f64; N],
    mu: f64,
) -> Option<DiscreteHgd<T, N>> {
    let mut phi = [[T::zero(); N]; N];
    let mut gamma = [T::zero(); N];
    let pow = |k: i64| -> f64 {
        // k is within +-(N-1); clamp keeps the cast lossless for any N.
        let k = k.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32;
        num_traits::Float::powi(mu, k)
    };
    for (i, ((prow, p0row), (g, g0))) in phi
        .iter_mut()
        .zip(phi0.iter())
        .zip(gamma.iter_mut().zip(gamma0.iter()))
        .enumerate()
    {
        let i = i as i64;
        for (j, (p, p0)) in prow.iter_mut().zip(p0row.iter()).enumerate() {
            let x = if *p0 == 0.0 { 0.0 } else { p0 * pow(j as i64 - i) };
            *p = T::from_f64(x);
            if !p.is_finite() {
                return None;
            }
        }
        let x = if *g0 == 0.0 { 0.0 } else { g0 * pow(-i) };
        *g = T::from_f64(x);
        if !g.is_finite() {
            return None;
        }
    }
    Some(DiscreteHgd { phi, gamma })
}
