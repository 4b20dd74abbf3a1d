//! The controller never touches the heap (docs/design.md §9: no heap).
//!
//! A counting `#[global_allocator]` wraps `std::alloc::System`. Counting is
//! per thread (a `const`-initialised thread-local, which itself never
//! allocates), so the test harness's other threads cannot disturb the count;
//! all checks still live in one `#[test]` so nothing else runs on this thread.
#![allow(clippy::unwrap_used, clippy::indexing_slicing)]

use crate::common;

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::hint::black_box;

use common::*;
use famcc_core::{
    Config, Constraint, Controller, Discretization, Feedback, Gamma, HighGain, Latch, Real, Skew, StepError,
};

struct Counting;

thread_local! {
    static ALLOCS: Cell<usize> = const { Cell::new(0) };
}

fn bump() {
    // `try_with` so an allocation during thread teardown cannot panic.
    let _ = ALLOCS.try_with(|c| c.set(c.get() + 1));
}

// SAFETY: every method forwards to `System` unchanged; the counter is a
// thread-local `Cell` that never allocates.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        bump();
        unsafe { System.alloc(layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        bump();
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        bump();
        unsafe { System.realloc(ptr, layout, new_size) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        bump();
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

fn allocs() -> usize {
    ALLOCS.with(|c| c.get())
}

/// Runs `f` and returns how many heap operations it made on this thread.
fn count<R>(f: impl FnOnce() -> R) -> (R, usize) {
    let before = allocs();
    let r = f();
    let after = allocs();
    (r, after - before)
}

const STEPS: usize = 2000;

/// Exercises every per-step entry point of a built controller `STEPS` times
/// and returns the number of heap operations observed (must be 0).
fn exercise<T: Real, const N: usize>(ctrl: &mut Controller<T, N>) -> usize {
    let dt = ctrl.config().dt().to_f64_lossless();
    let mut acc = T::zero();
    let (_, n) = count(|| {
        for k in 0..STEPS {
            let t = k as f64 * dt;
            // A decaying error with a disturbance, plus the odd wild sample.
            let e = (-t).exp() * 1.5 + 0.05 * (7.0 * t).sin();
            let v = ctrl.step(T::from_f64(e)).unwrap();
            acc = acc + v;
            let d = ctrl.diagnostics();
            acc = acc + d.xi + d.s + d.bounds.0 + d.bounds.1;
            if k % 97 == 0 {
                // Rejected inputs take the error path: still no heap.
                assert_eq!(ctrl.step(T::nan()), Err(StepError::NonFiniteInput));
                assert_eq!(
                    ctrl.step_applied(T::from_f64(e), Some(T::infinity())),
                    Err(StepError::NonFiniteApplied)
                );
                let _ = ctrl.step_applied(T::from_f64(e), Some(v)).unwrap();
            }
            if k % 113 == 0 {
                let _ = ctrl.step_dt(T::from_f64(e), T::from_f64(dt * 1.5), None).unwrap();
                assert_eq!(
                    ctrl.step_dt(T::from_f64(e), T::zero(), None),
                    Err(StepError::InvalidDt)
                );
            }
            if k % 251 == 0 {
                let snap = ctrl.snapshot();
                let next = ctrl.step(T::from_f64(e)).unwrap();
                ctrl.restore(&snap).unwrap();
                assert_eq!(ctrl.step(T::from_f64(e)).unwrap(), next);
                let _ = black_box(ctrl.estimate());
                let _ = black_box(ctrl.time());
            }
        }
        // State feedback with a measured error vector.
        ctrl.reset();
        for k in 0..STEPS {
            let t = k as f64 * dt;
            let mut z = [T::zero(); N];
            for (i, zi) in z.iter_mut().enumerate() {
                *zi = T::from_f64((-t).exp() * if i % 2 == 0 { 1.0 } else { -1.0 });
            }
            acc = acc + ctrl.step_state(z).unwrap();
            acc = acc + ctrl.step_state_applied(z, Some(acc)).unwrap_or(T::zero());
            acc = acc + black_box(ctrl.diagnostics()).v;
        }
        ctrl.reset();
        let _ = black_box(ctrl.step(T::from_f64(0.3)));
        ctrl.reset();
    });
    black_box(acc);
    n
}

/// A generic order-`N` config touching the oblique root search, the
/// variable-exponent jets, the rational Gamma, Tustin and the authors' latch.
fn oblique<T: Real, const N: usize>(limits: bool) -> Config<T, N> {
    let stage = |i: usize| {
        if i % 2 == 0 {
            (
                Feedback::VariableExponent {
                    k: T::from_f64(1.5),
                    r_b: T::from_f64(0.5),
                    r_1: T::from_f64(2.0),
                    r_t: T::from_f64(3.0),
                },
                Some(Skew::nonsingular(
                    T::from_f64(0.2),
                    T::from_f64(0.1),
                    T::from_f64(0.5),
                )),
            )
        } else {
            (
                Feedback::FixedTime {
                    alpha: T::from_f64(1.0),
                    p: T::from_f64(0.6),
                    beta: T::from_f64(0.5),
                    q: T::from_f64(1.5),
                },
                Some(Skew::nonsingular(
                    T::from_f64(0.3),
                    T::from_f64(0.2),
                    T::from_f64(1.0),
                )),
            )
        }
    };
    let laws: [_; 3] = [stage(0), stage(1), stage(2)];
    let constraint = Constraint::Oblique {
        eps_x: T::from_f64(0.1),
        eps_y: T::from_f64(0.2),
    };
    let mut a = [T::zero(); N];
    // (s + 2)^N
    let mut binom = 1.0;
    for (i, ai) in a.iter_mut().enumerate() {
        binom = binom * (N - i) as f64 / (i + 1) as f64;
        *ai = T::from_f64(binom * 2f64.powi(i as i32 + 1));
    }
    Config::builder(T::from_f64(1e-3), &laws[..N - 1], constraint, T::from_f64(5.0))
        .differentiator(Some(HighGain::new(T::from_f64(0.01), a, Discretization::Tustin)))
        .gamma(Gamma::Rational)
        .latch(Latch::Authors)
        .estimate_limits(limits.then_some([T::from_f64(5.0); N]))
        .build()
        .unwrap()
}

fn with_limits<T: Real, const N: usize>(ctrl: &Controller<T, N>, l: [f64; N]) -> Controller<T, N> {
    let cfg = ctrl
        .config()
        .to_builder()
        .estimate_limits(Some(l.map(T::from_f64)));
    Controller::new(cfg.build().unwrap())
}

fn without_flexible<T: Real, const N: usize>(ctrl: &Controller<T, N>) -> Controller<T, N> {
    Controller::new(ctrl.config().to_builder().rho_e(None).build().unwrap())
}

#[test]
fn no_heap_allocation_anywhere_in_the_controller() {
    // The counter works: a Vec allocation is seen.
    let (v, n) = count(|| black_box(Vec::<u64>::with_capacity(8)));
    drop(v);
    assert!(n >= 1, "the counting allocator saw no allocation");

    // Construction: no heap either.
    let (_, n) = count(|| {
        black_box(example1::<f64>(Variant::Paper, 1e-3));
        black_box(example1::<f32>(Variant::Code, 1e-3));
        black_box(example2::<f64>(Variant::Code, 1e-3));
        black_box(example3::<f64>(Variant::Code, 1e-3));
        black_box(example3::<f32>(Variant::Paper, 1e-3));
        black_box(Controller::new(oblique::<f64, 4>(true)));
    });
    assert_eq!(n, 0, "construction allocated {n} times");

    let e1 = example1::<f64>(Variant::Paper, 1e-3);
    let e1f = example1::<f32>(Variant::Code, 1e-3);
    let e2 = example2::<f64>(Variant::Code, 1e-3);
    let e2f = example2::<f32>(Variant::Paper, 1e-3);
    let e3 = example3::<f64>(Variant::Code, 1e-3);
    let e3p = example3::<f64>(Variant::Paper, 1e-3);
    let e3f = example3::<f32>(Variant::Code, 1e-3);

    let mut cases2: Vec<(&str, Controller<f64, 2>)> = vec![
        ("example1 f64", e1),
        ("example1 f64 limits", with_limits(&e1, [2.0, 5.0])),
        ("example1 f64 no rho_e", without_flexible(&e1)),
        ("example2 f64", e2),
        ("example2 f64 limits", with_limits(&e2, [2.0, 5.0])),
        ("oblique f64 N=2", Controller::new(oblique(false))),
    ];
    let mut cases2f: Vec<(&str, Controller<f32, 2>)> = vec![
        ("example1 f32", e1f),
        ("example1 f32 limits", with_limits(&e1f, [2.0, 5.0])),
        ("example2 f32", e2f),
        ("example2 f32 limits", with_limits(&e2f, [2.0, 5.0])),
    ];
    let mut cases3: Vec<(&str, Controller<f64, 3>)> = vec![
        ("example3 code f64", e3),
        ("example3 code f64 limits", with_limits(&e3, [3.0, 5.0, 20.0])),
        ("example3 paper f64", e3p),
        ("example3 paper f64 limits", with_limits(&e3p, [3.0, 5.0, 20.0])),
        ("example3 f64 no rho_e", without_flexible(&e3)),
        ("oblique f64 N=3", Controller::new(oblique(true))),
    ];
    let mut cases3f: Vec<(&str, Controller<f32, 3>)> = vec![
        ("example3 code f32", e3f),
        ("example3 code f32 limits", with_limits(&e3f, [3.0, 5.0, 20.0])),
    ];
    let mut cases4: Vec<(&str, Controller<f64, 4>)> = vec![
        ("oblique f64 N=4", Controller::new(oblique(false))),
        ("oblique f64 N=4 limits", Controller::new(oblique(true))),
    ];

    let mut failures = Vec::new();
    let mut total = 0;
    for (name, c) in cases2.iter_mut() {
        let n = exercise(c);
        total += 1;
        if n != 0 {
            failures.push((*name, n));
        }
    }
    for (name, c) in cases2f.iter_mut() {
        let n = exercise(c);
        total += 1;
        if n != 0 {
            failures.push((*name, n));
        }
    }
    for (name, c) in cases3.iter_mut() {
        let n = exercise(c);
        total += 1;
        if n != 0 {
            failures.push((*name, n));
        }
    }
    for (name, c) in cases3f.iter_mut() {
        let n = exercise(c);
        total += 1;
        if n != 0 {
            failures.push((*name, n));
        }
    }
    for (name, c) in cases4.iter_mut() {
        let n = exercise(c);
        total += 1;
        if n != 0 {
            failures.push((*name, n));
        }
    }
    assert_eq!(total, 20);
    assert!(
        failures.is_empty(),
        "heap operations per controller: {failures:?}"
    );
}
