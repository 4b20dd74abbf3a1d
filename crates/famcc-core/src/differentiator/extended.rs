//! The extended high-gain differentiator (beyond the paper; docs/observer.md):
//! the paper's differentiator (eq. (34)) of order `n` with one more state that
//! estimates the lumped term of the error dynamics, as an extended-state
//! observer does.
//!
//! Written as `z1^(n) = L + b0 u` with a nominal input gain `b0` and the
//! lumped term `L = F(x, t) + (G - b0) u - y_d^(n)` (everything the nominal
//! model does not know), the observer of `(z1, ..., zn, L)` from the measured
//! error `e = z1` and the applied input `u` is, with `eta = e - zhat_1`,
//!
//! ```text
//! zhat_i'     = zhat_(i+1) + (a_i / mu^i) eta               (i < n)
//! zhat_n'     = zhat_(n+1) + b0 u + (a_n / mu^n) eta
//! zhat_(n+1)' = (a_(n+1) / mu^(n+1)) eta                    (zhat_(n+1) = Lhat)
//! ```
//!
//! so its error obeys `s^(n+1) + a_1 s^n + ... + a_(n+1)` scaled by `1/mu`,
//! which must be Hurwitz. The input `u` is held over each sample period by
//! the actuator, so the zero-order hold is exact for it. The recursion
//!
//! ```text
//! (Zhat, Lhat)_(k+1) = Phi (Zhat, Lhat)_k + Gamma_e e_k + Gamma_u u_k
//! ```
//!
//! (the measurement held, [`Discretization::Exact`]) or, with the first-order
//! hold ([`Discretization::Foh`]: the measurement is the straight line through
//! the samples), `V_(k+1)` of the same recursion and the estimate
//! `V_(k+1) + D (e_(k+1) - e_k)` with the ramp's feedthrough `D`, as the plain
//! differentiator's first-order hold. Either
//! is computed once, in `f64`, in the balanced coordinates `w_i = mu^(i-1)
//! xhat_i` of the plain differentiator (where every entry is `O(a_i)`), and
//! rounded once to `T`. The extended state sits beside the order-`N` arrays
//! (stable Rust has no `[T; N + 1]`): `Phi`'s block on `Zhat`, the column of
//! `Lhat` into `Zhat`, the row of `Zhat` into `Lhat` and its corner.
//!
//! ```
//! use famcc_core::ExtendedHighGain;
//! // order 1: zhat' = Lhat + b0 u + (a1/mu) eta, Lhat' = (a2/mu^2) eta
//! let obs = ExtendedHighGain::<f64, 1>::new(0.05, [2.0], 1.0, 2.0);
//! let d = obs.discretize(1e-3).unwrap();
//! // a plant y' = 3 + 2 u (L = 3, b0 = 2) with u = 0.5 held: y' = 4, y = 4 t
//! let (mut z, mut l) = ([0.0], 0.0);
//! for k in 0..2000 {
//!     (z, l) = d.advance(&z, l, 4.0 * k as f64 * 1e-3, 0.5);
//! }
//! assert!((l - 3.0).abs() < 1e-2);
//! ```

use super::discretize::{balanced_matrix, ramp_response};
use super::expm::expm_zoh;
use super::linalg::{routh_hurwitz, Mat};
use crate::config::MAX_ORDER;
use crate::error::{positive, scale};
use crate::{ConfigError, Discretization, Real};

/// The size of the `f64` arrays the extended system is computed in: the
/// largest order plus the extended state (zero-padded: the padded block is
/// decoupled, its exponential the identity, and never read).
const EXT: usize = MAX_ORDER + 1;

/// The extended differentiator's parameters: time constant `mu` (seconds),
/// the coefficients `a_1..a_N` and `a_(N+1)` of
/// `s^(N+1) + a_1 s^N + ... + a_(N+1)` (dimensionless) and the nominal input
/// gain `b0` (output units per input unit per `s^N`; either sign).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExtendedHighGain<T, const N: usize> {
    /// The time constant `mu`, seconds.
    pub mu: T,
    /// `a_1, ..., a_N`.
    pub a: [T; N],
    /// `a_(N+1)`, the extended state's coefficient.
    pub a_ext: T,
    /// The nominal input gain `b0` (nonzero; its sign is the control direction).
    pub b0: T,
    /// How the measurement is sampled: [`Discretization::Exact`] (held) or
    /// [`Discretization::Foh`] (the straight line through the samples); the
    /// input is always held, as the actuator holds it.
    pub discretization: Discretization,
}

impl<T: Real, const N: usize> ExtendedHighGain<T, N> {
    /// The parameters as given (checked by [`ExtendedHighGain::validate`]),
    /// the measurement held ([`Discretization::Exact`]).
    pub fn new(mu: T, a: [T; N], a_ext: T, b0: T) -> Self {
        Self {
            mu,
            a,
            a_ext,
            b0,
            discretization: Discretization::Exact,
        }
    }

    /// The same observer with the measurement sampled by `discretization`
    /// (`Exact` or `Foh`).
    pub fn with_discretization(self, discretization: Discretization) -> Self {
        Self {
            discretization,
            ..self
        }
    }

    /// The default coefficients for `mu`: every pole of the error dynamics at
    /// `-2 / mu`, `(s + 2)^(N+1)` (the plain differentiator's `(s + 2)^N`
    /// with one more factor), so `a_i = C(N+1, i) 2^i`.
    ///
    /// ```
    /// use famcc_core::ExtendedHighGain;
    /// let obs = ExtendedHighGain::<f64, 2>::binomial(0.01, 1.0);
    /// assert_eq!((obs.a, obs.a_ext), ([6.0, 12.0], 8.0)); // (s + 2)^3
    /// ```
    pub fn binomial(mu: T, b0: T) -> Self {
        let mut a = [T::zero(); N];
        let mut c = 1.0_f64; // C(N+1, i) 2^i, built up from i = 0
        for (i, ai) in a.iter_mut().enumerate() {
            c = c * ((N + 1 - i) as f64) / ((i + 1) as f64) * 2.0;
            *ai = T::from_f64(c);
        }
        let a_ext = T::from_f64(num_traits::Float::powi(2.0_f64, (N + 1) as i32));
        Self::new(mu, a, a_ext, b0)
    }

    /// Checks the parameters: order `1 <= N <= MAX_ORDER`, `mu` finite and
    /// `> 0`, every coefficient finite and `> 0` with the polynomial Hurwitz
    /// (Routh-Hurwitz), `b0` finite and nonzero. The error names the
    /// parameter.
    ///
    /// ```
    /// use famcc_core::ExtendedHighGain;
    /// let bad = ExtendedHighGain::<f64, 2>::new(0.01, [1.0, 1.0], 10.0, 1.0);
    /// assert_eq!(bad.validate().unwrap_err().parameter, "observer_a"); // s^3 + s^2 + s + 10
    /// let zero = ExtendedHighGain::<f64, 2>::binomial(0.01, 0.0);
    /// assert_eq!(zero.validate().unwrap_err().parameter, "b0");
    /// ```
    pub fn validate(&self) -> Result<(), ConfigError> {
        if N == 0 || N > MAX_ORDER {
            return Err(ConfigError::new(
                "order",
                "must be between 1 and 8 for the extended observer",
            ));
        }
        positive(self.mu, "observer_mu")?;
        let mut coeffs = [0.0_f64; EXT];
        for (c, a) in coeffs
            .iter_mut()
            .zip(self.a.iter().chain(core::iter::once(&self.a_ext)))
        {
            if !(a.is_finite() && *a > T::zero()) {
                return Err(ConfigError::new("observer_a", "must all be finite and > 0"));
            }
            *c = a.to_f64_lossless();
        }
        if !routh_hurwitz::<EXT>(coeffs.get(..N + 1).unwrap_or(&[])) {
            return Err(ConfigError::new(
                "observer_a",
                "must make s^(n+1) + a1 s^n + ... + a(n+1) Hurwitz (e.g. the binomial (s + 2)^(n+1))",
            ));
        }
        if !(self.b0.is_finite() && self.b0 != T::zero()) {
            return Err(ConfigError::new(
                "b0",
                "must be finite and nonzero (the nominal input gain; negative for a negative control direction)",
            ));
        }
        scale(self.b0.abs(), "b0")?;
        match self.discretization {
            Discretization::Exact | Discretization::Foh => {}
            Discretization::Euler | Discretization::Tustin => {
                return Err(ConfigError::new(
                    "observer_discretization",
                    "must be exact (the measurement held) or foh (the straight line through the samples)",
                ))
            }
        }
        crate::compiled::discretization(self.discretization)
    }

    /// The recursion for the sample period `dt` (seconds), zero-order hold on
    /// `e` and `u`. Errors: the parameters' ([`ExtendedHighGain::validate`]),
    /// `"dt"` when not finite and `> 0`, `"observer_mu"` when `mu` is so small
    /// against `dt` that the recursion does not fit `T`.
    pub fn discretize(&self, dt: T) -> Result<DiscreteExtended<T, N>, ConfigError> {
        self.validate()?;
        positive(dt, "dt")?;
        let mu = self.mu.to_f64_lossless();
        let tau = dt.to_f64_lossless() / mu;
        let m = N + 1;
        let mut a = [0.0_f64; EXT];
        for (c, x) in a
            .iter_mut()
            .zip(self.a.iter().chain(core::iter::once(&self.a_ext)))
        {
            *c = x.to_f64_lossless();
        }
        // M0 = A - a C on the leading (N+1) x (N+1) block.
        let m0: Mat<EXT> = balanced_matrix(&a, m);
        let singular = || {
            ConfigError::new(
                "observer_mu",
                "gives a singular discretization: raise mu or lower dt",
            )
        };
        let (phi0, ge0) = expm_zoh(&m0, &a, tau).ok_or_else(singular)?;
        // u enters row N-1 (0-based) as mu^N b0 u in balanced coordinates.
        let mut unit = [0.0_f64; EXT];
        if let Some(x) = unit.get_mut(N - 1) {
            *x = 1.0;
        }
        let (_, gu0) = expm_zoh(&m0, &unit, tau).ok_or_else(singular)?;
        let fe0 = match self.discretization {
            Discretization::Foh => ramp_response(&m0, &a, &ge0, tau, m).ok_or_else(singular)?,
            _ => [0.0; EXT],
        };
        let b0 = self.b0.to_f64_lossless();
        unbalance(&phi0, [&ge0, &fe0, &gu0], mu, b0).ok_or(ConfigError::new(
            "observer_mu",
            "is so small against dt that the observer's recursion does not fit the float type: raise mu",
        ))
    }
}

/// The sampled extended differentiator (see the module docs): the blocks of
/// `Phi`, `Gamma_e` and `Gamma_u` on `(Zhat, Lhat)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DiscreteExtended<T, const N: usize> {
    /// `Zhat <- Zhat`.
    pub phi: [[T; N]; N],
    /// `Zhat <- Lhat`.
    pub phi_zl: [T; N],
    /// `Lhat <- Zhat`.
    pub phi_lz: [T; N],
    /// `Lhat <- Lhat`.
    pub phi_ll: T,
    /// `Zhat <- e`.
    pub gamma_e: [T; N],
    /// `Lhat <- e`.
    pub gamma_e_l: T,
    /// `Zhat <- u` (with `b0`).
    pub gamma_u: [T; N],
    /// `Lhat <- u` (with `b0`).
    pub gamma_u_l: T,
    /// `Zhat <-` the measurement's increment `e_(k+1) - e_k` (the first-order
    /// hold's feedthrough; zero when the measurement is held).
    pub feed_e: [T; N],
    /// `Lhat <-` the increment.
    pub feed_e_l: T,
}

impl<T: Real, const N: usize> DiscreteExtended<T, N> {
    /// One sample: `(Zhat, Lhat)_(k+1)` from `(Zhat, Lhat)_k`, the sample
    /// `e_k` and the input `u_k` held until the next sample; with the
    /// first-order hold, the part `V_(k+1)` that does not depend on the next
    /// sample ([`DiscreteExtended::current`] adds it).
    #[inline]
    pub fn advance(&self, z: &[T; N], l: T, e: T, u: T) -> ([T; N], T) {
        let mut out = [T::zero(); N];
        for ((((o, row), pl), ge), gu) in out
            .iter_mut()
            .zip(self.phi.iter())
            .zip(self.phi_zl.iter())
            .zip(self.gamma_e.iter())
            .zip(self.gamma_u.iter())
        {
            let mut acc = *pl * l + *ge * e + *gu * u;
            for (p, x) in row.iter().zip(z.iter()) {
                acc = acc + *p * *x;
            }
            *o = acc;
        }
        let mut l_next = self.phi_ll * l + self.gamma_e_l * e + self.gamma_u_l * u;
        for (p, x) in self.phi_lz.iter().zip(z.iter()) {
            l_next = l_next + *p * *x;
        }
        (out, l_next)
    }

    /// The estimate at a sample from its part `V` of [`DiscreteExtended::advance`]
    /// and the measurement's increment `de = e_(k+1) - e_k`: `V + D de` (`V`
    /// itself when the measurement is held, `D = 0`).
    ///
    /// ```
    /// use famcc_core::{Discretization, ExtendedHighGain};
    /// let obs = ExtendedHighGain::<f64, 2>::binomial(0.01, 1.0);
    /// let foh = obs.with_discretization(Discretization::Foh).discretize(1e-3).unwrap();
    /// let held = obs.discretize(1e-3).unwrap();
    /// assert_eq!((held.phi, held.gamma_e), (foh.phi, foh.gamma_e)); // the same held part
    /// assert_eq!(held.current(&[1.0, 2.0], 3.0, 0.5), ([1.0, 2.0], 3.0));
    /// assert!(foh.current(&[1.0, 2.0], 3.0, 0.5).0[1] > 2.0); // the increment moves zhat_2
    /// ```
    #[inline]
    pub fn current(&self, v: &[T; N], vl: T, de: T) -> ([T; N], T) {
        let mut out = *v;
        for (o, d) in out.iter_mut().zip(self.feed_e.iter()) {
            *o = *o + *d * de;
        }
        (out, vl + self.feed_e_l * de)
    }
}

/// Back from balanced coordinates (`x_i = w_i mu^-i`, 0-based `i <= N`):
/// `Phi_ij = Phi0_ij mu^(j-i)`, `Gamma_e_i = Gamma0_i mu^-i` (and so the
/// feedthrough `D_i = D0_i mu^-i`), `Gamma_u_i =
/// Gu0_i b0 mu^(N-i)`, rounded to `T`; `None` when an entry is not finite in
/// `T`.
fn unbalance<T: Real, const N: usize>(
    phi0: &Mat<EXT>,
    [ge0, fe0, gu0]: [&[f64; EXT]; 3],
    mu: f64,
    b0: f64,
) -> Option<DiscreteExtended<T, N>> {
    let pow = |k: i32| num_traits::Float::powi(mu, k);
    let cast = |x: f64| {
        let t = T::from_f64(x);
        t.is_finite().then_some(t)
    };
    let at = |i: usize, j: usize| -> f64 {
        let p0 = phi0.get(i).and_then(|r| r.get(j)).copied().unwrap_or(0.0);
        if p0 == 0.0 {
            0.0
        } else {
            p0 * pow(j as i32 - i as i32)
        }
    };
    let g = |v: &[f64; EXT], i: usize, scale: f64| -> f64 {
        let x = v.get(i).copied().unwrap_or(0.0);
        if x == 0.0 {
            0.0
        } else {
            x * scale * pow(-(i as i32))
        }
    };
    let n = N;
    let u_scale = b0 * pow(n as i32);
    let mut d = DiscreteExtended {
        phi: [[T::zero(); N]; N],
        phi_zl: [T::zero(); N],
        phi_lz: [T::zero(); N],
        phi_ll: cast(at(n, n))?,
        gamma_e: [T::zero(); N],
        gamma_e_l: cast(g(ge0, n, 1.0))?,
        gamma_u: [T::zero(); N],
        gamma_u_l: cast(g(gu0, n, u_scale))?,
        feed_e: [T::zero(); N],
        feed_e_l: cast(g(fe0, n, 1.0))?,
    };
    for (i, row) in d.phi.iter_mut().enumerate() {
        for (j, p) in row.iter_mut().enumerate() {
            *p = cast(at(i, j))?;
        }
    }
    for (i, (((zl, lz), (ge, gu)), fe)) in d
        .phi_zl
        .iter_mut()
        .zip(d.phi_lz.iter_mut())
        .zip(d.gamma_e.iter_mut().zip(d.gamma_u.iter_mut()))
        .zip(d.feed_e.iter_mut())
        .enumerate()
    {
        *fe = cast(g(fe0, i, 1.0))?;
        *zl = cast(at(i, n))?;
        *lz = cast(at(n, i))?;
        *ge = cast(g(ge0, i, 1.0))?;
        *gu = cast(g(gu0, i, u_scale))?;
    }
    Some(d)
}
