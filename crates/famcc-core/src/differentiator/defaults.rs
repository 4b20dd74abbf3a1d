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
}
