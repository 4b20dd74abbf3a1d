//! The iterative fully actuated manifold (paper eq. (11) (IS) / ISFM).
//!
//! `s_1 = z1`, `s_{i+1} = d/dt s_i - h_mi(s_i)` for `i = 1..n-1`, `s = s_n`.
//! The error vector `Z = (z1, ..., zn)` is the derivative list of `z1`, so
//! `s_1` is a [`Jet`] and each stage is a shift and a subtraction: any order
//! `N`, no hand-derived formulas (docs/design.md §4.1).
//!
//! ```
//! use famcc_core::{manifold, Feedback, SkewedLaw};
//! // Linear law, order 3: s = (d/dt + 2)(d/dt + 3) z1 = z3 + 5 z2 + 6 z1 (eq. (60) (LFAM)).
//! let stages = [
//!     SkewedLaw::new(Feedback::Linear { k: 2.0_f64 }, None).unwrap(),
//!     SkewedLaw::new(Feedback::Linear { k: 3.0 }, None).unwrap(),
//! ];
//! let m = manifold::evaluate(&[1.0, 1.0, 1.0], &stages);
//! assert_eq!(m.s(), 12.0);
//! ```

use crate::{Jet, Real, SkewedLaw};

/// The manifold values for one error vector.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Manifold<T, const N: usize> {
    /// `s_1, ..., s_n` (eq. (11) (IS)).
    pub stages: [T; N],
    /// `s_{n-1}` (equals `z1` at order 2; 0 at order 1).
    pub s_prev: T,
    /// `d/dt s_{n-1}` (equals `z2` at order 2; 0 at order 1).
    pub ds_prev: T,
}

impl<T: Real, const N: usize> Manifold<T, N> {
    /// The manifold value `s = s_n`.
    #[inline(always)]
    pub fn s(&self) -> T {
        self.stages.last().copied().unwrap_or_else(T::zero)
    }
}

/// Evaluates `s_1..s_n` for the error vector `z = (z1, ..., zn)` and the
/// stage laws `h_m1..h_m(n-1)` (`laws.len()` must be `N - 1`; missing laws are
/// treated as stopping the iteration, extra ones are ignored).
#[inline]
pub fn evaluate<T: Real, const N: usize>(z: &[T; N], laws: &[SkewedLaw<T>]) -> Manifold<T, N> {
    evaluate_stages(z, laws, true)
}

/// Like [`evaluate`] but stops at `s_{n-1}`: `s_prev` and `ds_prev` are set,
/// `stages` holds `s_1..s_{n-1}` and the last entry (`s`) is left at 0. The
/// lateral and oblique constraints need no more.
#[inline]
pub fn evaluate_prev<T: Real, const N: usize>(z: &[T; N], laws: &[SkewedLaw<T>]) -> Manifold<T, N> {
    evaluate_stages(z, laws, false)
}

#[inline(always)]
fn evaluate_stages<T: Real, const N: usize>(
    z: &[T; N],
    laws: &[SkewedLaw<T>],
    with_last: bool,
) -> Manifold<T, N> {
    let mut out = Manifold {
        stages: [T::zero(); N],
        s_prev: T::zero(),
        ds_prev: T::zero(),
    };
    let mut jet = Jet::<T, N>::from_derivatives(*z);
    if let Some(first) = out.stages.first_mut() {
        *first = jet.value();
    }
    let n_laws = N.saturating_sub(1).min(laws.len());
    for (i, law) in laws.iter().take(n_laws).enumerate() {
        let (s_next, last) = if i + 1 == n_laws {
            // Last stage: only the value of h_m(n-1) is needed.
            let v = jet.value();
            let dv = jet.derivative(1);
            out.s_prev = v;
            out.ds_prev = dv;
            if !with_last {
                break;
            }
            (Jet::constant(dv - law.eval(v)), true)
        } else {
            (jet.shift() - law.eval_jet(jet), false)
        };
        jet = s_next;
        if let Some(slot) = out.stages.get_mut(i + 1) {
            *slot = jet.value();
        }
        if last {
            break;
        }
    }
    out
}
