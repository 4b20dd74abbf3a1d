//! The differentiator's parameters ([`HighGain`]: `mu`, `a` and the [`Discretization`]),
//! their rules (Hurwitz) and their discretization into a [`DiscreteHgd`].

use super::discretize::{self, Failure};
use super::linalg::routh_hurwitz;
use super::DiscreteHgd;
use crate::error::positive;
use crate::{ConfigError, Real};

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
    /// First-order (triangle) hold: the measurement is taken as the straight
    /// line through the samples, so the estimate at sample `k` uses `e_k`
    /// itself. `Phi` and `Gamma` as [`Discretization::Exact`], and the direct
    /// feedthrough `D = (1/dt) (integral_0^dt exp(M s) (dt - s) ds) H` of the
    /// increment `e_k - e_(k-1)`
    /// ([`DiscreteHgd::feedthrough`](super::DiscreteHgd::feedthrough)). Exact
    /// for a piecewise-linear measurement and stable for every `dt`: it
    /// removes the sample of delay that the held (ZOH) input adds, which is
    /// what a slow loop lacks (docs/tuning.md, "Sample rate").
    Foh,
}

/// The high-gain differentiator's parameters (eq. (34), HGD): time constant `mu`
/// (seconds), coefficients `a = (a1, ..., aN)` (dimensionless), the
/// discretization method, and an optional low-pass prefilter (not in the
/// paper; [`HighGain::with_prefilter`]).
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
    /// Time constant `tau` of a first-order low-pass stage on `z1` in front
    /// of eq. (34), seconds; 0 for none (the paper's differentiator).
    pub prefilter: T,
}

impl<T: Real, const N: usize> HighGain<T, N> {
    /// The parameters as given (not validated; see [`HighGain::validate`]),
    /// without a prefilter.
    pub fn new(mu: T, a: [T; N], discretization: Discretization) -> Self {
        Self {
            mu,
            a,
            discretization,
            prefilter: T::zero(),
        }
    }

    /// The same differentiator fed through a first-order low-pass stage
    /// `tau f' = z1 - f` (`tau` in seconds, 0 for none), sampled exactly:
    /// `f_k = f_(k-1) + (1 - exp(-dt/tau)) (e_k - f_(k-1))`, `f_0 = e_0`.
    ///
    /// Against measurement noise: the `k`-th estimate's noise grows like
    /// `sigma / mu^(k-1)` and enters `Zhat` with every sample (`Gamma e_k`),
    /// so the input chatters from sample to sample. The prefilter rolls the
    /// noise off by one more order above `1 / tau` at the price of a lag of
    /// about `tau`, which [`crate::design::design`] counts in its loop check.
    /// Not in the paper (docs/tuning.md, "Noise").
    ///
    /// ```
    /// use famcc_core::{Discretization, HighGain};
    /// let h = HighGain::new(0.02_f64, [4.0, 6.0, 4.0], Discretization::Exact).with_prefilter(0.01);
    /// let d = h.discretize(1e-3).unwrap();
    /// assert!((d.prefilter - (1.0 - (-0.1_f64).exp())).abs() < 1e-15);
    /// assert_eq!(h.with_prefilter(0.0).discretize(1e-3).unwrap().prefilter, 1.0);
    /// assert_eq!(h.with_prefilter(-1.0).validate().unwrap_err().parameter, "prefilter");
    /// ```
    pub fn with_prefilter(self, tau: T) -> Self {
        Self {
            prefilter: tau,
            ..self
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
        self.validate_values(order)?;
        let used = self.a.get(..order).unwrap_or(&[]);
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

    /// [`HighGain::validate_order`] without the Hurwitz test, in `T` alone:
    /// for a recursion precomputed on a host, whose stability
    /// [`crate::ConfigBuilder::build_discretized`] checks on `Phi` itself.
    pub(crate) fn validate_values(&self, order: usize) -> Result<(), ConfigError> {
        positive(self.mu, "mu")?;
        if !(self.prefilter.is_finite() && self.prefilter >= T::zero()) {
            return Err(ConfigError::new(
                "prefilter",
                "must be finite and >= 0 (seconds; 0 for none, e.g. mu / 2 against noise)",
            ));
        }
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
        Ok(())
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
        let mut d = discretize::discretize(&a, order, tau, mu, self.discretization).map_err(|f| match f {
            Failure::Singular => {
                ConfigError::new("dt", "gives a numerically singular system in the discretization")
            }
            Failure::Overflow => {
                ConfigError::new("mu", "is so small that Phi or Gamma overflows this float type")
            }
        })?;
        d.prefilter = T::from_f64(prefilter_gain(
            dt.to_f64_lossless(),
            self.prefilter.to_f64_lossless(),
        ));
        Ok(d)
    }
}

/// The prefilter's gain per period, `1 - exp(-dt / tau)` (`-expm1`, exact for
/// small `dt / tau`); exactly 1 for `tau = 0` (no prefilter) or where the
/// stage settles within one period in `f64`.
pub(crate) fn prefilter_gain(dt: f64, tau: f64) -> f64 {
    if tau > 0.0 {
        -num_traits::Float::exp_m1(-dt / tau)
    } else {
        1.0
    }
}
