//! The paper's differentiator and famcc's default ("auto"): [`PAPER_MU`], the
//! coefficients, the discretization per order and the [`HighGain`] built from them.

use super::{Discretization, HighGain};
use crate::Real;

/// The paper's differentiator time constant `mu = 0.01` s (all three of its
/// examples).
pub const PAPER_MU: f64 = 0.01;

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

/// The largest `dt / mu` at which the exact zero-order hold is used without
/// a lint (docs/design.md §3.8): beyond it the held sample is a poor model
/// of the measurement.
pub const EXACT_DT_PER_MU: f64 = 0.2;

/// The paper's `mu / dt` (`mu = 0.01` at 1 kHz): [`auto_discretization_at`]
/// keeps the paper's exact zero-order hold while `mu >= PAPER_MU_PER_DT dt`,
/// and takes the first-order hold ([`Discretization::Foh`]) at coarser
/// sampling, where a held input costs the loop more delay than the paper's
/// loop was designed with (measured at 500, 200 and 100 Hz, docs/tuning.md).
pub const PAPER_MU_PER_DT: f64 = 10.0;

/// The delay the sampled law adds to the continuous one, in sample periods,
/// with a held input (exact ZOH, Tustin, Euler): one period because the
/// output at sample `k` uses the estimate built from the samples up to
/// `k - 1` (docs/design.md §3.2), and half a period of zero-order hold.
pub const SAMPLE_DELAY: f64 = 1.5;

/// [`SAMPLE_DELAY`] with the first-order hold ([`Discretization::Foh`]):
/// its estimate at sample `k` uses `e_k`, so only the output's half period
/// of hold is left.
pub const FOH_SAMPLE_DELAY: f64 = 0.5;

/// The smallest `mu / dt` that [`auto_mu`] gives the first-order hold: its
/// poles `-2/mu` then sit at `exp(-4)` per period, a differentiator that
/// forgets within a period (faster would only pass the noise on).
pub const FOH_MIN_MU_PER_DT: f64 = 0.5;

/// The discretization famcc picks for a differentiator of order `order` and
/// time constant `mu` (s) sampled every `dt` (s): from order 4 on
/// [`Discretization::Tustin`] (the exact hold aliases there, §7.2 of
/// docs/design.md); up to order 3 [`Discretization::Exact`] while `mu >=
/// PAPER_MU_PER_DT dt` (the paper's, and its ratio), and the first-order
/// hold [`Discretization::Foh`] at coarser sampling: its estimate uses the
/// current sample, which removes the period of delay a held input costs,
/// and its poles are `exp(-a dt / mu)`, stable and never ringing, however
/// coarse `dt` is. `famcc_core::design` and [`HighGain::auto_at`] both use it.
///
/// ```
/// use famcc_core::differentiator::auto_discretization_at;
/// use famcc_core::Discretization;
/// assert_eq!(auto_discretization_at(3, 1e-3, 0.01), Discretization::Exact);
/// assert_eq!(auto_discretization_at(3, 2e-3, 0.01), Discretization::Foh);
/// assert_eq!(auto_discretization_at(2, 2e-2, 0.01), Discretization::Foh);
/// assert_eq!(auto_discretization_at(4, 1e-3, 0.01), Discretization::Tustin);
/// ```
pub fn auto_discretization_at(order: usize, dt: f64, mu: f64) -> Discretization {
    if order > 3 {
        Discretization::Tustin
    } else if mu >= PAPER_MU_PER_DT * dt {
        Discretization::Exact
    } else {
        Discretization::Foh
    }
}

/// The time constant of famcc's default differentiator at order `order`
/// sampled every `dt` (s), for a loop designed around the paper's
/// [`PAPER_MU`] at `dt_ref = PAPER_MU / 10` (1 kHz).
///
/// The loop's gains fix its crossover, so what the differentiator may cost
/// is a delay: about `order mu / 2` (`order` poles at `-2/mu`) plus the
/// sampling's, [`SAMPLE_DELAY`] `dt` with a held input. A slower sample rate
/// keeps the total at its 1 kHz value by a faster differentiator:
///
/// - up to order 3, the paper's [`PAPER_MU`] with its exact hold at
///   `dt <= dt_ref`; beyond, with the first-order hold's [`FOH_SAMPLE_DELAY`],
///   `mu = PAPER_MU - (2 / order) (FOH_SAMPLE_DELAY dt - SAMPLE_DELAY dt_ref)`,
///   never slower than [`PAPER_MU`] and never below
///   [`FOH_MIN_MU_PER_DT`] `dt`;
/// - from order 4 on (Tustin), `mu = PAPER_MU - (2 SAMPLE_DELAY / order)
///   (dt - dt_ref)`, never slower than [`PAPER_MU`] and never below
///   `min(dt, PAPER_MU)` (below `dt` Tustin maps the poles to negative
///   reals: ringing).
///
/// Measurement noise asks for the opposite (a slower `mu`): that trade is
/// `famcc_core::design`'s, which sets the loop from `mu`.
///
/// ```
/// use famcc_core::differentiator::{auto_mu, PAPER_MU};
/// assert_eq!(auto_mu(3, 1e-3), PAPER_MU);
/// assert_eq!(auto_mu(2, 1e-4), PAPER_MU);
/// assert_eq!(auto_mu(3, 2e-3), PAPER_MU); // 500 Hz: the paper's mu, first-order hold
/// assert!((auto_mu(2, 5e-3) - 0.009).abs() < 1e-12); // 200 Hz, first-order hold
/// assert!((auto_mu(3, 1e-2) - 0.01 + 0.007 / 3.0).abs() < 1e-12);
/// assert_eq!(auto_mu(2, 2e-2), 0.01); // 50 Hz: held at dt / 2
/// assert!((auto_mu(4, 5e-3) - 0.007).abs() < 1e-12); // Tustin
/// ```
pub fn auto_mu(order: usize, dt: f64) -> f64 {
    let dt_ref = 0.1 * PAPER_MU;
    let n = order.max(1) as f64;
    if order <= 3 {
        if PAPER_MU >= PAPER_MU_PER_DT * dt {
            return PAPER_MU;
        }
        let mu = PAPER_MU - 2.0 / n * (FOH_SAMPLE_DELAY * dt - SAMPLE_DELAY * dt_ref);
        let floor = FOH_MIN_MU_PER_DT * dt;
        return if mu > PAPER_MU {
            PAPER_MU
        } else if mu > floor {
            mu
        } else {
            floor
        };
    }
    let late = if dt > dt_ref { dt - dt_ref } else { 0.0 };
    if late == 0.0 {
        return PAPER_MU;
    }
    let mu = PAPER_MU - 2.0 * SAMPLE_DELAY / n * late;
    let floor = if dt < PAPER_MU { dt } else { PAPER_MU };
    if mu > floor {
        mu
    } else {
        floor
    }
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
    /// assert!((h.mu - 0.01 + 0.002 / 3.0).abs() < 1e-12);
    /// assert_eq!((h.a, h.discretization), ([4.0, 6.0, 4.0], Discretization::Foh));
    /// ```
    pub fn auto_at(order: usize, dt: f64) -> Self {
        let mut h = Self::auto_for(order);
        let mu = auto_mu(order, dt);
        h.mu = T::from_f64(mu);
        h.discretization = auto_discretization_at(order, dt, mu);
        h
    }
}
