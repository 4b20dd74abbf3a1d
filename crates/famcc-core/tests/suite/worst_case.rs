//! The root search's budget (docs/design.md §3.12): whatever the state, one
//! search evaluates its function at most `1 + BRACKET_ITERATIONS +
//! ROOT_ITERATIONS` times and returns a finite value, so a step's worst case
//! is bounded (the firmware check measures it in instructions).
#![allow(clippy::unwrap_used, clippy::indexing_slicing)]

use core::cell::Cell;
use famcc_core::constraint::{decreasing_root, BRACKET_ITERATIONS, ROOT_ITERATIONS};
use famcc_core::{Feedback, Real, Skew, SkewedLaw};

fn laws<T: Real>() -> Vec<SkewedLaw<T>> {
    let f = T::from_f64;
    let feedback = [
        Feedback::Linear { k: f(1.0) },
        Feedback::FiniteTime { k: f(1.0), p: f(0.3) },
        Feedback::FixedTime {
            alpha: f(1.0),
            p: f(0.5),
            beta: f(0.5),
            q: f(2.0),
        },
        Feedback::VariableExponent {
            k: f(1.5),
            r_b: f(0.5),
            r_1: f(2.0),
            r_t: f(3.0),
        },
        Feedback::MoulayDiscontinuous {
            beta: f(1.0),
            lambda: f(1.0),
            mu: f(0.5),
        },
    ];
    let skews = [
        None,
        Some(Skew::smooth(f(0.15), f(0.1))),
        Some(Skew::nonsingular(f(0.2), f(0.1), f(0.1))),
    ];
    feedback
        .iter()
        .flat_map(|h| skews.iter().filter_map(move |k| SkewedLaw::new(*h, *k).ok()))
        .collect()
}

fn worst<T: Real>() -> usize {
    let budget = 1 + BRACKET_ITERATIONS + ROOT_ITERATIONS;
    let mut worst = 0;
    let ys = [
        0.0,
        1e-30,
        1e-3,
        1.0,
        1e3,
        1e10,
        1e19,
        1e38,
        1e150,
        1e300,
        f64::MAX,
    ];
    for law in laws::<T>() {
        for &y in &ys {
            for (y, x0) in [(y, 0.0), (-y, 0.0), (y, 1e30), (-y, -1e30), (y, -1e10)] {
                let (y, x0) = (T::from_f64(y), T::from_f64(x0));
                if !(y.is_finite() && x0.is_finite()) {
                    continue;
                }
                let n = Cell::new(0usize);
                let x = decreasing_root(
                    |x| {
                        n.set(n.get() + 1);
                        law.eval(x) - y
                    },
                    x0,
                );
                assert!(n.get() <= budget, "{law:?} y = {y:?}: {} evaluations", n.get());
                assert!(!x.is_nan(), "{law:?} y = {y:?}");
                worst = worst.max(n.get());
            }
        }
    }
    worst
}

#[test]
fn every_root_search_stays_within_its_budget() {
    let (w32, w64) = (worst::<f32>(), worst::<f64>());
    println!("most evaluations of one root search: f32 {w32}, f64 {w64}");
    // 16 doublings and 7 squarings bracket any root in range; the refinement
    // then converges in far fewer than its 96 iterations.
    assert!(w32 <= 64 && w64 <= 64, "f32 {w32}, f64 {w64}");
}
