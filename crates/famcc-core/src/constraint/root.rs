//! The root search of the constraint geometry: `h_v = h^{-1}` (LaMC,
//! eq. (28)) and the intersection `x_c` of eq. (27) (OMC) are roots of
//! strictly decreasing functions, so a bracketing search always finds the
//! unique root and always terminates. [`bracketed_root`] refines a root
//! already bracketed (the controller's bumpless start).

use crate::Real;

/// Iteration budget of [`decreasing_root`]'s refinement phase.
pub const ROOT_ITERATIONS: usize = 96;
/// Iteration budget of [`decreasing_root`]'s bracketing phase: 16 doublings
/// of the step, then squarings (from `2^16` past the largest finite `f64` in
/// 7), so every root in range is bracketed within 23 evaluations.
pub const BRACKET_ITERATIONS: usize = 24;
/// Doublings before the bracketing step is squared instead.
const DOUBLINGS: usize = 16;

/// The root of a strictly decreasing function `f`, searched from `x0`.
///
/// Phase 1 brackets the root by doubling steps from `x0`, squaring them
/// after 16 doublings (at most [`BRACKET_ITERATIONS`]); phase 2 refines, a
/// bracket wider than a factor 4 on one side of 0 first by geometric
/// bisection, then with the Illinois variant of regula falsi, which falls
/// back to bisection when it stalls (at most [`ROOT_ITERATIONS`] in all).
/// So a search costs at most `1 + BRACKET_ITERATIONS + ROOT_ITERATIONS`
/// evaluations of `f`, whatever the state (docs/design.md §3.12). It stops when the bracket is within 4 ulps of the
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
    for i in 0..BRACKET_ITERATIONS {
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
        step = if i + 1 < DOUBLINGS {
            step * T::from_f64(2.0)
        } else {
            step * step.max(T::from_f64(2.0))
        };
    }
    if !bracketed {
        return a;
    }
    refine(&f, a, fa, b, fb)
}

/// The root of a continuous `f` between `lo` and `hi` when `f(lo)` and
/// `f(hi)` are finite and differ in sign (either may be the larger); `None`
/// otherwise (no sign change: the caller chooses what is nearest). Refined
/// as [`decreasing_root`]'s phase 2 (Illinois regula falsi with a bisection
/// fallback, at most [`ROOT_ITERATIONS`] steps), so it always terminates.
///
/// ```
/// use famcc_core::constraint::bracketed_root;
/// let r = bracketed_root(|x: f64| x * x - 2.0, 0.0, 4.0).unwrap();
/// assert!((r - 2.0_f64.sqrt()).abs() < 1e-15);
/// assert_eq!(bracketed_root(|x: f64| x * x + 1.0, -1.0, 1.0), None);
/// ```
pub fn bracketed_root<T: Real>(f: impl Fn(T) -> T, lo: T, hi: T) -> Option<T> {
    let (fa, fb) = (f(lo), f(hi));
    if !(fa.is_finite() && fb.is_finite()) {
        return None;
    }
    if fa == T::zero() {
        return Some(lo);
    }
    if fb == T::zero() {
        return Some(hi);
    }
    if (fa > T::zero()) == (fb > T::zero()) {
        return None;
    }
    Some(refine(&f, lo, fa, hi, fb))
}

/// Phase 2 of the root searches: `f(a)` and `f(b)` differ in sign.
fn refine<T: Real>(f: &impl Fn(T) -> T, mut a: T, mut fa: T, mut b: T, mut fb: T) -> T {
    let four_eps = T::from_f64(4.0) * T::epsilon();
    let four = T::from_f64(4.0);
    let mut side = 0i8;
    for _ in 0..ROOT_ITERATIONS {
        let width = (b - a).abs();
        let scale = a.abs().max(b.abs()).max(T::one());
        if width <= four_eps * scale {
            break;
        }
        let (near, far) = (a.abs().min(b.abs()), a.abs().max(b.abs()));
        // A bracket over many binades on one side of 0 (only after the
        // squaring steps of phase 1): halve it in the exponent first.
        let geometric = (a > T::zero()) == (b > T::zero()) && near > T::zero() && far > four * near;
        let mut x = if geometric {
            near.root() * far.root() * a.signum()
        } else {
            (a * fb - b * fa) / (fb - fa)
        };
        let lo = a.min(b);
        let hi = a.max(b);
        if !(x > lo && x < hi) {
            x = a + (b - a) * T::from_f64(0.5);
        }
        let fx = f(x);
        if fx == T::zero() {
            return x;
        }
        if !fx.is_finite() {
            // Never a point where f is not finite: the better end instead.
            break;
        }
        if (fx > T::zero()) == (fa > T::zero()) {
            a = x;
            fa = fx;
            if side == -1 {
                fb = fb * T::from_f64(0.5);
            }
            side = -1;
        } else {
            b = x;
            fb = fx;
            if side == 1 {
                fa = fa * T::from_f64(0.5);
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
