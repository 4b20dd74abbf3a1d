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

mod discretize;
mod expm;
mod linalg;

use crate::error::positive;
use crate::{ConfigError, Real};
use discretize::Failure;
use linalg::routh_hurwitz;
pub use linalg::spectral_radius;

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

/// The discretization of famcc's default differentiator ("auto") at order
/// `order`: [`Discretization::Exact`] up to order 3 (the paper's), and
/// [`Discretization::Tustin`] from order 4 on, where the zero-order hold
/// aliases (docs/design.md §7.2: on a clean `sin t` with `mu = 0.01`, order 4
/// estimates `z4 = 55.4` where the truth is 0.42; Tustin gives 0.397).
///
/// ```
/// use famcc_core::differentiator::auto_discretization;
/// use famcc_core::Discretization;
/// assert_eq!(auto_discretization(3), Discretization::Exact);
/// assert_eq!(auto_discretization(4), Discretization::Tustin);
/// ```
pub const fn auto_discretization(order: usize) -> Discretization {
    if order <= 3 {
        Discretization::Exact
    } else {
        Discretization::Tustin
    }
}

/// The ratio `dt / mu` up to which [`auto_discretization_at`] keeps the exact
/// zero-order hold (at order <= 3): the lint's "dt too coarse for mu" bound
/// (docs/design.md §3.8). Beyond it the held sample is a poor model of the
/// measurement and Tustin, which maps the poles `-a/mu` to
/// `(1 - a dt / 2 mu) / (1 + a dt / 2 mu)`, closes the paper's loops where
/// the exact hold does not (measured at 200 Hz, docs/tuning.md).
pub const EXACT_DT_PER_MU: f64 = 0.2;

/// The delay the sampled law adds to the continuous one, in sample periods:
/// one period because the output at sample `k` uses the estimate built from
/// the samples up to `k - 1` (docs/design.md §3.2), and half a period of
/// zero-order hold.
pub const SAMPLE_DELAY: f64 = 1.5;

/// The discretization famcc picks for a differentiator of order `order` and
/// time constant `mu` (s) sampled every `dt` (s): from order 4 on
/// [`Discretization::Tustin`] (the exact hold aliases there, §7.2 of
/// docs/design.md); up to order 3 [`Discretization::Exact`] while `dt <=
/// EXACT_DT_PER_MU * mu`, Tustin for `EXACT_DT_PER_MU * mu < dt <= mu`,
/// and the exact hold again beyond (`dt > mu`, where Tustin's poles
/// `(1 - dt/mu) / (1 + dt/mu)` turn negative and ring; measured on the
/// paper's example 1 at 50 Hz: exact settles, Tustin never does).
/// `famcc_core::design` and [`HighGain::auto_at`] both use it.
///
/// ```
/// use famcc_core::differentiator::auto_discretization_at;
/// use famcc_core::Discretization;
/// assert_eq!(auto_discretization_at(3, 1e-3, 0.01), Discretization::Exact);
/// assert_eq!(auto_discretization_at(3, 5e-3, 0.01), Discretization::Tustin);
/// assert_eq!(auto_discretization_at(3, 2e-2, 0.01), Discretization::Exact);
/// assert_eq!(auto_discretization_at(4, 1e-3, 0.01), Discretization::Tustin);
/// ```
pub fn auto_discretization_at(order: usize, dt: f64, mu: f64) -> Discretization {
    if order <= 3 && (dt <= EXACT_DT_PER_MU * mu || dt > mu) {
        Discretization::Exact
    } else {
        Discretization::Tustin
    }
}

/// The time constant of famcc's default differentiator at order `order`
/// sampled every `dt` (s), for a loop designed around the paper's
/// [`PAPER_MU`] at `dt_ref = PAPER_MU / 10` (1 kHz).
///
/// The loop's gains fix its crossover, so what the differentiator may cost
/// is a delay: about `order mu / 2` (`order` poles at `-2/mu`) plus
/// [`SAMPLE_DELAY`] `dt` from the sampling. A slower sample rate keeps that
/// total by a faster differentiator,
/// `mu = PAPER_MU - (2 SAMPLE_DELAY / order) (dt - dt_ref)`, never slower
/// than [`PAPER_MU`] (so `mu = PAPER_MU` for `dt <= dt_ref`) and never
/// below `min(dt, PAPER_MU)` (below `dt` Tustin maps the poles to negative
/// reals: ringing; at `dt > PAPER_MU` the paper's `mu` with the exact hold).
/// Measurement noise asks for the opposite (a slower `mu`): that trade is
/// `famcc_core::design`'s, which sets the loop from `mu`.
///
/// ```
/// use famcc_core::differentiator::{auto_mu, PAPER_MU};
/// assert_eq!(auto_mu(3, 1e-3), PAPER_MU);
/// assert_eq!(auto_mu(2, 1e-4), PAPER_MU);
/// assert!((auto_mu(3, 5e-3) - 0.006).abs() < 1e-12);
/// assert!((auto_mu(2, 5e-3) - 0.005).abs() < 1e-12); // 0.004, raised to dt
/// assert_eq!(auto_mu(2, 2e-2), PAPER_MU); // 50 Hz: the paper's (exact hold)
/// ```
pub fn auto_mu(order: usize, dt: f64) -> f64 {
    let dt_ref = 0.1 * PAPER_MU;
    let order = order.max(1) as f64;
    let late = if dt > dt_ref { dt - dt_ref } else { 0.0 };
    if late == 0.0 {
        return PAPER_MU;
    }
    let mu = PAPER_MU - 2.0 * SAMPLE_DELAY / order * late;
    let floor = if dt < PAPER_MU { dt } else { PAPER_MU };
    if mu > floor {
        mu
    } else {
        floor
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

    /// famcc's default differentiator for order `N` (`differentiator="auto"`
    /// in every binding): [`HighGain::auto_for`]`(N)`.
    ///
    /// ```
    /// use famcc_core::{Discretization, HighGain};
    /// assert_eq!(HighGain::<f64, 3>::auto(), HighGain::paper());
    /// let h = HighGain::<f64, 5>::auto();
    /// assert_eq!((h.mu, h.a[0], h.discretization), (0.01, 10.0, Discretization::Tustin));
    /// ```
    pub fn auto() -> Self {
        Self::auto_for(N)
    }

    /// famcc's default differentiator of run-time order `order <= N` (the
    /// leading `order` coefficients; the rest are zero): up to order 3 the
    /// paper's ([`HighGain::paper`]: `mu = 0.01`, `(4, 4)`, `(4, 6, 4)`,
    /// exact), from order 4 on `mu = 0.01`, the binomial `(s + 2)^n` and
    /// [`Discretization::Tustin`] ([`auto_discretization`]). With integral
    /// action a controller of law order `N` runs the differentiator of order
    /// `N - 1` on the error.
    ///
    /// ```
    /// use famcc_core::{Discretization, HighGain};
    /// let h = HighGain::<f64, 3>::auto_for(2);
    /// assert_eq!((h.a, h.discretization), ([4.0, 4.0, 0.0], Discretization::Exact));
    /// ```
    pub fn auto_for(order: usize) -> Self {
        let mut a = [T::zero(); N];
        if let Some(head) = a.get_mut(..order) {
            paper_coefficients(head);
        }
        Self::new(T::from_f64(PAPER_MU), a, auto_discretization(order))
    }

    /// famcc's default differentiator of run-time order `order <= N` for the
    /// sample period `dt` (s): the coefficients of [`HighGain::auto_for`],
    /// `mu = `[`auto_mu`]`(order, dt)` and
    /// [`auto_discretization_at`]`(order, dt, mu)`. At `dt <= 1 ms` it is
    /// [`HighGain::auto_for`] (the paper's differentiator up to order 3).
    ///
    /// ```
    /// use famcc_core::{Discretization, HighGain};
    /// assert_eq!(HighGain::<f64, 3>::auto_at(3, 1e-3), HighGain::paper());
    /// let h = HighGain::<f64, 3>::auto_at(3, 5e-3); // 200 Hz
    /// assert!((h.mu - 0.006).abs() < 1e-12);
    /// assert_eq!((h.a, h.discretization), ([4.0, 6.0, 4.0], Discretization::Tustin));
    /// ```
    pub fn auto_at(order: usize, dt: f64) -> Self {
        let mut h = Self::auto_for(order);
        let mu = auto_mu(order, dt);
        h.mu = T::from_f64(mu);
        h.discretization = auto_discretization_at(order, dt, mu);
        h
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
        self.validate_order(N)
    }

    /// [`HighGain::validate`] for the differentiator of run-time order
    /// `order` (`1 <= order <= N`): only the leading `order` coefficients
    /// are used and checked.
    ///
    /// ```
    /// use famcc_core::{Discretization, HighGain};
    /// let h = HighGain::new(0.01_f64, [4.0, 4.0, 0.0], Discretization::Exact);
    /// assert!(h.validate_order(2).is_ok());
    /// assert_eq!(h.validate().unwrap_err().parameter, "a");
    /// assert!(h.validate_order(4).is_err());
    /// ```
    pub fn validate_order(&self, order: usize) -> Result<(), ConfigError> {
        positive(self.mu, "mu")?;
        if order == 0 || order > N {
            return Err(ConfigError::new(
                "a",
                "must have at least one coefficient (order N >= 1) and at most N",
            ));
        }
        let used = self.a.get(..order).unwrap_or(&[]);
        if !used.iter().all(|&ai| ai.is_finite() && ai > T::zero()) {
            return Err(ConfigError::new("a", "must all be finite and > 0"));
        }
        let mut a = [0.0_f64; N];
        for (d, s) in a.iter_mut().zip(used.iter()) {
            *d = s.to_f64_lossless();
        }
        if routh_hurwitz::<N>(a.get(..order).unwrap_or(&[])) {
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
        self.discretize_order(dt, N)
    }

    /// [`HighGain::discretize`] for the differentiator of run-time order
    /// `order <= N` ([`HighGain::validate_order`]), embedded in the last
    /// `order` slots of the `N`-sized recursion: the leading `N - order`
    /// rows and columns of `Phi` and entries of `Gamma` are exactly zero, so
    /// [`DiscreteHgd::advance`] leaves those slots at 0 (with integral action
    /// slot 0 holds the integral of the error, which the controller keeps).
    /// One computation serves every order: `order = N` is `discretize`.
    ///
    /// ```
    /// use famcc_core::{Discretization, HighGain};
    /// let h = HighGain::new(0.01_f64, [4.0, 4.0, 0.0], Discretization::Exact);
    /// let d3 = h.discretize_order(1e-3, 2).unwrap();
    /// let d2 = HighGain::new(0.01_f64, [4.0, 4.0], Discretization::Exact).discretize(1e-3).unwrap();
    /// assert_eq!((d3.phi[0], d3.gamma[0]), ([0.0; 3], 0.0));
    /// assert_eq!([d3.phi[1][1], d3.phi[1][2], d3.phi[2][1], d3.phi[2][2]],
    ///            [d2.phi[0][0], d2.phi[0][1], d2.phi[1][0], d2.phi[1][1]]);
    /// assert_eq!(d3.advance(&[7.0, 1.0, 0.0], 1.0)[0], 0.0);
    /// ```
    pub fn discretize_order(&self, dt: T, order: usize) -> Result<DiscreteHgd<T, N>, ConfigError> {
        self.validate_order(order)?;
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
        discretize::discretize(&a, order, tau, mu, self.discretization).map_err(|f| match f {
            Failure::Singular => {
                ConfigError::new("dt", "gives a numerically singular system in the discretization")
            }
            Failure::Overflow => {
                ConfigError::new("mu", "is so small that Phi or Gamma overflows this float type")
            }
        })
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
}
