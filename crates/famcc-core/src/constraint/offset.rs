//! The state's offset from the zero manifold along a gradient line (paper
//! Step C2, eqs. (26)-(28): gradient, xyc, xi).
//!
//! The state is seen on the phase plane `(s_{n-1}, ds_{n-1})`, where the zero
//! manifold is the curve `y = h_m(n-1)(x)` (eq. (23), S0P). Each constraint
//! type measures the state's offset from that curve along its own gradient
//! line (eq. (26)):
//!
//! - LoMC (vertical line `x = s_{n-1}`): offset `s = ds - h(s_{n-1})`;
//! - LaMC (horizontal line `y = ds`): offset `s_{n-1} - h_v(ds)` with
//!   `h_v = h^{-1}`;
//! - OMC (slope `y_U / x_U`): offset `s_{n-1} - x_c` with `x_c` solving
//!   eq. (27) (xyc) `x_U (h(x_c) - ds) = y_U (x_c - s_{n-1})`.
//!
//! `h_v` and `x_c` come from [`decreasing_root`], a bracketing search that
//! always terminates: the function is strictly decreasing, so the root is
//! unique. Closed forms are used where they exist (linear and finite-time
//! laws without skew).

use super::{decreasing_root, Constraint};
use crate::{Feedback, Real, SkewedLaw};

/// The state's offset from the zero manifold along the gradient line.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Offset<T> {
    /// Signed offset in the constraint's own unit: `s` (LoMC), or the
    /// horizontal offset `s_{n-1} - x_c` (LaMC, OMC). `xi = sigma / width`.
    pub sigma: T,
    /// `x_c`, the abscissa of the intersection with the zero manifold.
    pub x_c: T,
    /// `y_c = h(x_c)`.
    pub y_c: T,
}

/// `h_v(y) = h^{-1}(y)`: the inverse of the last stage's law (paper Step B1),
/// closed form for unskewed linear and finite-time laws, otherwise by
/// [`decreasing_root`].
///
/// ```
/// use famcc_core::constraint::inverse;
/// use famcc_core::{Feedback, Skew, SkewedLaw};
/// let h = SkewedLaw::new(Feedback::FixedTime { alpha: 1.0_f64, p: 0.5, beta: 0.5, q: 2.0 },
///                        Some(Skew::nonsingular(0.2, 0.1, 0.1))).unwrap();
/// let x = inverse(&h, h.eval(0.7));
/// assert!((x - 0.7).abs() < 1e-14);
/// ```
#[inline(always)]
pub fn inverse<T: Real>(law: &SkewedLaw<T>, y: T) -> T {
    if law.skew().is_none() {
        if let Some(x) = law.feedback().inverse_closed_form(y) {
            return x;
        }
    }
    // Without the skew and the laws beyond the finite-time one, every law
    // has a closed form (src/compiled.rs): no search is compiled.
    if cfg!(any(
        feature = "skew",
        feature = "fixed-time",
        feature = "variable-exponent"
    )) {
        decreasing_root(|x| law.eval(x) - y, initial_guess(law.feedback(), y))
    } else {
        T::nan()
    }
}

/// A starting point for the inverse: the closed-form inverse of the
/// underlying law, or 0.
#[inline]
fn initial_guess<T: Real>(h: &Feedback<T>, y: T) -> T {
    h.inverse_closed_form(y)
        .filter(|x| x.is_finite())
        .unwrap_or_else(T::zero)
}

/// The horizontal (LaMC) offset `s_{n-1} - h_v(ds_{n-1})`.
#[cfg_attr(not(any(feature = "lateral", feature = "oblique")), allow(dead_code))]
#[inline]
pub(super) fn lateral<T: Real>(law: &SkewedLaw<T>, s_prev: T, ds_prev: T) -> Offset<T> {
    let x_c = inverse(law, ds_prev);
    Offset {
        sigma: s_prev - x_c,
        x_c,
        y_c: ds_prev,
    }
}

impl<T: Real> Constraint<T> {
    /// The offset of the state `(s_prev, ds_prev)` from the zero manifold of
    /// the last stage's law `law`, along this constraint's gradient line
    /// (eq. (26)). `x_u`, `y_u` are the current nominal half-widths (only
    /// their ratio matters, and only for OMC); the final widths the variant
    /// carries play no part. For LoMC `sigma` equals the manifold value `s`.
    ///
    /// ```
    /// use famcc_core::{Constraint, Feedback, SkewedLaw};
    /// let h = SkewedLaw::new(Feedback::FiniteTime { k: 1.0_f64, p: 0.5 }, None).unwrap();
    /// // LaMC at (z1, z2) = (0.5, -1): s_fn = z1 + sign(z2)|z2|^2 = -0.5 (eq. (39), nfn).
    /// let o = Constraint::Lateral { eps: 0.1 }.offset(&h, 0.5, -1.0, 1.0, 0.0);
    /// assert!((o.sigma + 0.5).abs() < 1e-15);
    /// ```
    #[inline]
    pub fn offset(&self, law: &SkewedLaw<T>, s_prev: T, ds_prev: T, x_u: T, y_u: T) -> Offset<T> {
        match self {
            Constraint::Longitudinal { .. } => {
                let y_c = law.eval(s_prev);
                Offset {
                    sigma: ds_prev - y_c,
                    x_c: s_prev,
                    y_c,
                }
            }
            Constraint::Lateral { .. } => lateral(law, s_prev, ds_prev),
            #[cfg(feature = "oblique")]
            Constraint::Oblique { .. } => {
                let m = y_u / x_u;
                // eq. (27): x_U (h(x) - ds) = y_U (x - s_{n-1}); strictly decreasing in x.
                let x_c = decreasing_root(|x| law.eval(x) - ds_prev - m * (x - s_prev), s_prev);
                Offset {
                    sigma: s_prev - x_c,
                    x_c,
                    y_c: law.eval(x_c),
                }
            }
            // Compiled out (src/compiled.rs): no configuration holds it.
            #[cfg(not(feature = "oblique"))]
            Constraint::Oblique { .. } => {
                let _ = (x_u, y_u);
                Offset {
                    sigma: T::nan(),
                    x_c: T::nan(),
                    y_c: T::nan(),
                }
            }
        }
    }
}
