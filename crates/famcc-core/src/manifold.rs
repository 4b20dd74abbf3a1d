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

/// The first `B` Taylor coefficients of a jet (`B <= A`; extra ones are zero).
#[inline(always)]
fn truncate<T: Real, const A: usize, const B: usize>(j: &Jet<T, A>) -> Jet<T, B> {
    let mut c = [T::zero(); B];
    for (dst, src) in c.iter_mut().zip(j.taylor().iter()) {
        *dst = *src;
    }
    Jet::from_taylor(c)
}

/// One stage `s_{i+1} = d/dt s_i - h(s_i)` on jets that shrink by one
/// coefficient (`K1 = K - 1`): `d/dt` loses the last one, and `h` is
/// evaluated on the `K1` coefficients the next stage needs. Every jet
/// operation is causal (a coefficient depends only on those below it), so
/// the result is bit-identical to the untruncated stage's first `K1`
/// coefficients, at about half the jet work along a chain.
#[inline(always)]
fn shrinking_stage<T: Real, const K: usize, const K1: usize>(
    s: &Jet<T, K>,
    law: &SkewedLaw<T>,
) -> Jet<T, K1> {
    truncate::<T, K, K1>(&s.shift()) - law.eval_jet(truncate::<T, K, K1>(s))
}

/// Stages `s_1..s_{n-1}` with shrinking jets for the orders listed (the
/// first size is the order), writing their values into `$out.stages`;
/// returns `(s_{n-1}, d/dt s_{n-1})`. The caller guarantees `N - 1` laws.
macro_rules! shrinking_chain {
    ($z:ident, $laws:ident, $out:ident, $n:literal; $($k:literal => $k1:literal),*) => {{
        let mut d = [T::zero(); $n];
        for (dst, src) in d.iter_mut().zip($z.iter()) {
            *dst = *src;
        }
        let jet = Jet::<T, $n>::from_derivatives(d);
        let mut laws = $laws.iter();
        let mut slots = $out.stages.iter_mut();
        if let Some(slot) = slots.next() {
            *slot = jet.value();
        }
        $(
            let jet: Jet<T, $k1> = match laws.next() {
                Some(law) => shrinking_stage::<T, $k, $k1>(&jet, law),
                None => Jet::constant(T::zero()),
            };
            if let Some(slot) = slots.next() {
                *slot = jet.value();
            }
        )*
        (jet.value(), jet.derivative(1))
    }};
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
    // Orders 4-8 (docs/design.md §4.1): the jets shrink along the chain.
    // Order 3 keeps the loop below, whose one jet stage gains little and
    // whose firmware build stays smaller without a second jet size.
    if (4..=8).contains(&N) && laws.len() >= N.saturating_sub(1) {
        let (v, dv) = match N {
            4 => shrinking_chain!(z, laws, out, 4; 4 => 3, 3 => 2),
            5 => shrinking_chain!(z, laws, out, 5; 5 => 4, 4 => 3, 3 => 2),
            6 => shrinking_chain!(z, laws, out, 6; 6 => 5, 5 => 4, 4 => 3, 3 => 2),
            7 => shrinking_chain!(z, laws, out, 7; 7 => 6, 6 => 5, 5 => 4, 4 => 3, 3 => 2),
            _ => shrinking_chain!(z, laws, out, 8; 8 => 7, 7 => 6, 6 => 5, 5 => 4, 4 => 3, 3 => 2),
        };
        out.s_prev = v;
        out.ds_prev = dv;
        if with_last {
            // The last stage needs only the value of h_m(n-1).
            if let (Some(law), Some(slot)) = (laws.get(N.saturating_sub(2)), out.stages.last_mut()) {
                *slot = dv - law.eval(v);
            }
        }
        return out;
    }
    full_stages(z, laws, with_last)
}

/// The stages with jets of `N` coefficients throughout (orders 1-3 and
/// above 8, and the reference of the shrinking chain's test).
#[inline(always)]
fn full_stages<T: Real, const N: usize>(
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

#[cfg(test)]
mod tests {
    // The laws below need these features (src/compiled.rs).
    #[cfg(all(feature = "fixed-time", feature = "skew"))]
    mod shrinking {
        use super::super::{evaluate, evaluate_prev, full_stages, Manifold};
        use crate::{Feedback, Skew, SkewedLaw};

        fn bits<const N: usize>(m: &Manifold<f64, N>) -> ([u64; N], u64, u64) {
            (
                m.stages.map(f64::to_bits),
                m.s_prev.to_bits(),
                m.ds_prev.to_bits(),
            )
        }

        /// The shrinking chain of orders 4-8 is bit-identical to jets of `N`
        /// coefficients throughout, for NSMD finite-time, fixed-time and linear
        /// stages, over errors from 1e-6 to 1e3 and derivatives of both signs.
        fn check<const N: usize>() {
            let nsmd = Some(Skew::nonsingular(0.1, 0.1, 0.1));
            let laws = [
                SkewedLaw::new(Feedback::FiniteTime { k: 1.5, p: 0.6 }, nsmd).unwrap(),
                SkewedLaw::new(
                    Feedback::FixedTime {
                        alpha: 2.0,
                        p: 0.5,
                        beta: 1.0,
                        q: 1.5,
                    },
                    nsmd,
                )
                .unwrap(),
                SkewedLaw::new(Feedback::Linear { k: 3.0 }, None).unwrap(),
            ];
            let laws: [SkewedLaw<f64>; 7] = core::array::from_fn(|i| laws[i % 3]);
            let mut x = 0.123_f64;
            for _ in 0..500 {
                let z: [f64; N] = core::array::from_fn(|k| {
                    x = (x * 997.0 + 0.371).fract();
                    let mag = 10f64.powf(9.0 * x - 6.0 + k as f64);
                    if (x * 1e4) as u64 % 2 == 0 {
                        mag
                    } else {
                        -mag
                    }
                });
                assert_eq!(
                    bits(&evaluate(&z, &laws)),
                    bits(&full_stages(&z, &laws, true)),
                    "{z:?}"
                );
                assert_eq!(
                    bits(&evaluate_prev(&z, &laws)),
                    bits(&full_stages(&z, &laws, false)),
                    "{z:?}"
                );
            }
        }

        #[test]
        fn the_shrinking_chain_is_bit_identical_to_full_jets() {
            check::<4>();
            check::<5>();
            check::<6>();
            check::<7>();
            check::<8>();
        }
    }
}
