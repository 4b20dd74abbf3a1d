//! Manifold constraint variables (paper Step C2, eqs. gradient, xyc, xi).
//!
//! The state is seen on the phase plane `(s_{n-1}, ds_{n-1})`, where the zero
//! manifold is the curve `y = h_m(n-1)(x)`. Each constraint type measures the
//! state's offset from that curve along its own gradient line:
//!
//! - LoMC (longitudinal, vertical line `x = s_{n-1}`): offset `s = ds - h(s_{n-1})`,
//!   `xi = s / y_U`;
//! - LaMC (lateral, horizontal line `y = ds`): offset `s_{n-1} - h_v(ds)` with
//!   `h_v = h^{-1}`, `xi = (s_{n-1} - h_v(ds)) / x_U`;
//! - OMC (oblique, slope `y_U / x_U`): offset `s_{n-1} - x_c` with `x_c` solving
//!   eq. (xyc) `x_U (h(x_c) - ds) = y_U (x_c - s_{n-1})`, `xi = (s_{n-1} - x_c) / x_U`.
//!
//! With symmetric bounds (`x_L = -x_U`, `y_L = -y_U`) eq. (xi) reduces to these
//! ratios, and `|xi| = d_sc / d_U` where `d_sc` is the distance from the state
//! to `(x_c, y_c)` and `d_U = sqrt(x_U^2 + y_U^2)` (the quantities of the
//! flexible boundary, eq. WxyUxyL).
//!
//! `h_v` and `x_c` come from [`decreasing_root`], a bracketing search that
//! always terminates: the function is strictly decreasing, so the root is
//! unique. Closed forms are used where they exist (linear and finite-time
//! laws without skew).
//!
//! ```
//! use famcc_core::constraint::{offset, ConstraintKind};
//! use famcc_core::{Feedback, SkewedLaw};
//! let h = SkewedLaw::new(Feedback::FiniteTime { k: 1.0_f64, p: 0.5 }, None).unwrap();
//! // LaMC at (z1, z2) = (0.5, -1): s_fn = z1 + sign(z2)|z2|^2 = -0.5 (eq. nfn).
//! let o = offset(ConstraintKind::Lateral, &h, 0.5, -1.0, 1.0, 0.0);
//! assert!((o.sigma + 0.5).abs() < 1e-15);
//! ```

use crate::{Feedback, Real, SkewedLaw};

/// The three manifold constraint types (paper Step C1).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum ConstraintKind {
    /// LoMC: the boundaries are the zero manifold shifted vertically by `±y_U`.
    #[default]
    Longitudinal,
    /// LaMC: shifted horizontally by `±x_U`.
    Lateral,
    /// OMC: shifted obliquely by `(±x_U, ±y_U)`.
    Oblique,
}

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

/// Iteration budget of [`decreasing_root`]'s refinement phase.
pub const ROOT_ITERATIONS: usize = 96;
/// Iteration budget of [`decreasing_root`]'s bracketing phase (enough to
/// double a step from 1 past the largest finite `f64`).
pub const BRACKET_ITERATIONS: usize = 1100;

/// The root of a strictly decreasing function `f`, searched from `x0`.
///
/// Phase 1 brackets the root by doubling steps from `x0` (at most
/// [`BRACKET_ITERATIONS`]); phase 2 refines with the Illinois variant of
/// regula falsi, which falls back to bisection when it stalls (at most
/// [`ROOT_ITERATIONS`]). It stops when the bracket is within 4 ulps of the
/// root or `f` is exactly zero, so the result is within a few ulps of the
/// true root (absolute `4 * epsilon` for roots below 1 in magnitude). If no
/// sign change exists in the representable range the nearest end is
/// returned: the search always terminates and never returns NaN for finite
/// `f` values.
///
/// ```
/// use famcc_core::constraint::decreasing_root;
/// let r = decreasing_root(|x: f64| 2.0 - x * x * x, 0.0);
/// assert!((r - 2.0_f64.cbrt()).abs() < 1e-15);
/// ```
pub fn decreasing_root<T: Real>(f: impl Fn(T) -> T, x0: T) -> T {
    let f0 = f(x0);
    if f0 == T::zero() || !f0.is_finite() {
        return x0;
    }
    // f decreasing: f(x0) > 0 means the root lies right of x0.
    let dir = if f0 > T::zero() { T::one() } else { -T::one() };
    let mut step = x0.abs().max(T::one());
    let (mut a, mut fa) = (x0, f0);
    let (mut b, mut fb) = (x0, f0);
    let mut bracketed = false;
    for _ in 0..BRACKET_ITERATIONS {
        let x = x0 + dir * step;
        let fx = f(x);
        if !x.is_finite() || !fx.is_finite() {
            break;
        }
        if fx == T::zero() {
            return x;
        }
        if (fx > T::zero()) != (f0 > T::zero()) {
            b = x;
            fb = fx;
            bracketed = true;
            break;
        }
        a = x;
        fa = fx;
        step = step * T::c(2.0);
    }
    if !bracketed {
        return a;
    }
    let four_eps = T::c(4.0) * T::epsilon();
    let mut side = 0i8;
    for _ in 0..ROOT_ITERATIONS {
        let width = (b - a).abs();
        let scale = a.abs().max(b.abs()).max(T::one());
        if width <= four_eps * scale {
            break;
        }
        let mut x = (a * fb - b * fa) / (fb - fa);
        let lo = a.min(b);
        let hi = a.max(b);
        if !(x > lo && x < hi) {
            x = a + (b - a) * T::c(0.5);
        }
        let fx = f(x);
        if fx == T::zero() || !fx.is_finite() {
            return x;
        }
        if (fx > T::zero()) == (fa > T::zero()) {
            a = x;
            fa = fx;
            if side == -1 {
                fb = fb * T::c(0.5);
            }
            side = -1;
        } else {
            b = x;
            fb = fx;
            if side == 1 {
                fa = fa * T::c(0.5);
            }
            side = 1;
        }
    }
    if fa.abs() < fb.abs() {
        a
    } else {
        b
    }
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
#[inline]
pub fn inverse<T: Real>(law: &SkewedLaw<T>, y: T) -> T {
    if law.skew().is_none() {
        if let Some(x) = law.feedback().inverse_closed_form(y) {
            return x;
        }
    }
    decreasing_root(|x| law.eval(x) - y, initial_guess(law.feedback(), y))
}

/// A starting point for the inverse: the closed-form inverse of the
/// underlying law, or 0.
#[inline]
fn initial_guess<T: Real>(h: &Feedback<T>, y: T) -> T {
    h.inverse_closed_form(y)
        .filter(|x| x.is_finite())
        .unwrap_or_else(T::zero)
}

/// The offset of the state `(s_prev, ds_prev)` from the zero manifold of the
/// last stage's law `law`, along the gradient line of `kind` (eq. gradient).
/// `x_u`, `y_u` are the current nominal half-widths (only their ratio matters,
/// and only for OMC). For LoMC `sigma` equals the manifold value `s`.
#[inline]
pub fn offset<T: Real>(
    kind: ConstraintKind,
    law: &SkewedLaw<T>,
    s_prev: T,
    ds_prev: T,
    x_u: T,
    y_u: T,
) -> Offset<T> {
    match kind {
        ConstraintKind::Longitudinal => {
            let y_c = law.eval(s_prev);
            Offset {
                sigma: ds_prev - y_c,
                x_c: s_prev,
                y_c,
            }
        }
        ConstraintKind::Lateral => {
            let x_c = inverse(law, ds_prev);
            Offset {
                sigma: s_prev - x_c,
                x_c,
                y_c: ds_prev,
            }
        }
        ConstraintKind::Oblique => {
            let m = y_u / x_u;
            // eq. (xyc): x_U (h(x) - ds) = y_U (x - s_{n-1}); strictly decreasing in x.
            let x_c = decreasing_root(|x| law.eval(x) - ds_prev - m * (x - s_prev), s_prev);
            Offset {
                sigma: s_prev - x_c,
                x_c,
                y_c: law.eval(x_c),
            }
        }
    }
}
