//! Closed-loop invariant over random plants of the paper's class (eq. (5) (SFS)):
//!
//! `x_i' = g_i(x_1..x_i, t) x_{i+1} + f_i(x_1..x_i, t)`,
//! `x_n' = g_n(x, t) u + f_n(x, t)`, `y = x_1`,
//!
//! with smooth bounded gains `g_i = g0_i + 0.1 sin(w t + x_i)` (g0_i in
//! [0.5, 3], so `prod g_i >= 0.4^n > 0`), smooth bounded disturbances plus a
//! damping term that keeps the plant input-to-state stable under any bounded
//! input (`f_i = d_i sin(w_i t + phi_i) + 0.2 sin(x_1) - c_i x_i`), random
//! initial states, a random reference `y_d = A sin(w t)` and random (sometimes
//! tight) input limits. The controller is one of the paper's designs at
//! 1 kHz with the flexible boundary on (`rho_e = 0.01`); the plant is
//! integrated by RK4 with 5 substeps per sample, for 4 s.
//!
//! Invariant (eq. (88) (|xi|), Theorems 2-3): at every sample `|xi~| < 1`, no clamp
//! ever happens, and the output and the plant state stay finite. Settling is
//! not claimed: with tight limits the accuracy may be out of reach.
#![allow(clippy::unwrap_used, clippy::indexing_slicing)]

mod common;

use common::*;
use famcc_core::{Controller, Real};
use proptest::prelude::*;

const DT: f64 = 1e-3;
const SUB: usize = 5;
const T_END: f64 = 4.0;

#[derive(Clone, Debug)]
struct Stage {
    g0: f64,
    wg: f64,
    d: f64,
    w: f64,
    phi: f64,
    c: f64,
}

#[derive(Clone, Debug)]
struct RandomPlant<const N: usize> {
    stages: [Stage; N],
    x0: [f64; N],
}

impl<const N: usize> TimePlant<N> for RandomPlant<N> {
    fn initial_state(&self) -> [f64; N] {
        self.x0
    }
    fn rate(&self, t: f64, x: &[f64; N], u: f64) -> [f64; N] {
        let mut dx = [0.0; N];
        for i in 0..N {
            let s = &self.stages[i];
            let g = s.g0 + 0.1 * (s.wg * t + x[i]).sin();
            let f = s.d * (s.w * t + s.phi).sin() + 0.2 * x[0].sin() - s.c * x[i];
            let next = if i + 1 < N { x[i + 1] } else { u };
            dx[i] = g * next + f;
        }
        dx
    }
}

#[derive(Clone, Debug)]
struct Case<const N: usize> {
    plant: RandomPlant<N>,
    /// Reference `A sin(w t)`.
    amp: f64,
    omega: f64,
    limits: (f64, f64),
    /// Which design: example 1 or 2 at order 2 (ignored at order 3).
    design: u8,
    variant: Variant,
    single: bool,
}

fn stage(max_d: f64) -> impl Strategy<Value = Stage> {
    (
        0.5..3.0f64,
        0.1..3.0f64,
        0.0..max_d,
        0.2..3.0f64,
        0.0..6.3f64,
        0.5..2.0f64,
    )
        .prop_map(|(g0, wg, d, w, phi, c)| Stage { g0, wg, d, w, phi, c })
}

fn limits() -> impl Strategy<Value = (f64, f64)> {
    prop_oneof![
        Just((-100.0, 100.0)),
        (-100.0..-10.0f64, 10.0..100.0f64),
        // Tight: the disturbance may need more than the actuator gives.
        (-5.0..-1.0f64, 1.0..5.0f64),
    ]
}

fn case<const N: usize>() -> impl Strategy<Value = Case<N>> {
    let stages = prop::collection::vec(stage(1.0), N - 1)
        .prop_flat_map(|inner| (Just(inner), stage(5.0)))
        .prop_map(|(mut inner, last)| {
            inner.push(last);
            let arr: [Stage; N] = inner.try_into().unwrap();
            arr
        });
    (
        stages,
        prop::collection::vec(-2.0..2.0f64, N),
        0.0..1.5f64,
        0.2..2.0f64,
        limits(),
        1u8..3,
        prop_oneof![Just(Variant::Code), Just(Variant::Paper)],
        prop::bool::weighted(0.25),
    )
        .prop_map(|(stages, x0, amp, omega, limits, design, variant, single)| Case {
            plant: RandomPlant {
                stages,
                x0: x0.try_into().unwrap(),
            },
            amp,
            omega,
            limits,
            design,
            variant,
            single,
        })
}

#[derive(Debug, Default)]
struct Summary {
    max_abs_xi: f64,
    clamps: u64,
    saturated: usize,
    expanded: usize,
    final_abs_z1: f64,
}

/// Runs one loop and checks the invariant at every sample.
fn run_case<T: Real, const N: usize>(
    c: &Case<N>,
    mut ctrl: Controller<T, N>,
) -> Result<Summary, TestCaseError> {
    let steps = (T_END / DT).round() as usize;
    let mut x = c.plant.initial_state();
    let mut s = Summary::default();
    for k in 0..=steps {
        let t = k as f64 * DT;
        let e = x[0] - c.amp * (c.omega * t).sin();
        let v = ctrl.step(T::from_f64(e));
        prop_assert!(v.is_ok(), "step failed at t = {}: {:?}", t, v);
        let v = v.unwrap().to_f64_lossless();
        let d = ctrl.diagnostics();
        let xi = d.xi.to_f64_lossless();
        prop_assert!(v.is_finite(), "non-finite output at t = {}", t);
        prop_assert!(xi.abs() < 1.0, "|xi~| = {} at t = {}", xi, t);
        prop_assert_eq!(d.clamp_count, 0, "clamped at t = {}", t);
        s.max_abs_xi = s.max_abs_xi.max(xi.abs());
        s.expanded += usize::from(d.expanded);
        let u = v.clamp(c.limits.0, c.limits.1);
        s.saturated += usize::from(u != v);
        let h = DT / SUB as f64;
        for j in 0..SUB {
            x = rk4(&c.plant, t + j as f64 * h, &x, u, h);
        }
        prop_assert!(
            x.iter().all(|xi| xi.is_finite()),
            "plant state non-finite at t = {}",
            t
        );
        s.final_abs_z1 = e.abs();
    }
    s.clamps = ctrl.diagnostics().clamp_count;
    Ok(s)
}

fn order2(c: &Case<2>) -> Result<Summary, TestCaseError> {
    match (c.design, c.single) {
        (1, false) => run_case(c, example1::<f64>(c.variant, DT)),
        (1, true) => run_case(c, example1::<f32>(c.variant, DT)),
        (_, false) => run_case(c, example2::<f64>(c.variant, DT)),
        (_, true) => run_case(c, example2::<f32>(c.variant, DT)),
    }
}

fn order3(c: &Case<3>) -> Result<Summary, TestCaseError> {
    if c.single {
        run_case(c, example3::<f32>(c.variant, DT))
    } else {
        run_case(c, example3::<f64>(c.variant, DT))
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 32, ..ProptestConfig::default() })]

    #[test]
    fn order2_random_plants_keep_xi_inside(c in case::<2>()) {
        let s = order2(&c)?;
        prop_assert!(s.max_abs_xi < 1.0);
    }

    #[test]
    fn order3_random_plants_keep_xi_inside(c in case::<3>()) {
        let s = order3(&c)?;
        prop_assert!(s.max_abs_xi < 1.0);
    }
}

/// The generator really produces hard cases: a plant with the largest
/// disturbance and tight limits saturates and expands the boundary, and the
/// invariant still holds.
#[test]
fn tight_limits_saturate_and_expand_but_keep_the_invariant() {
    let hard = |g0: f64| Stage {
        g0,
        wg: 1.0,
        d: 4.5,
        w: 1.3,
        phi: 0.5,
        c: 0.5,
    };
    let easy = Stage {
        g0: 1.0,
        wg: 2.0,
        d: 0.8,
        w: 2.0,
        phi: 1.0,
        c: 1.0,
    };
    let c2 = Case {
        plant: RandomPlant {
            stages: [easy.clone(), hard(0.6)],
            x0: [1.8, -1.5],
        },
        amp: 1.2,
        omega: 1.5,
        limits: (-1.5, 1.5),
        design: 2,
        variant: Variant::Code,
        single: false,
    };
    let s = order2(&c2).unwrap();
    println!("order 2, tight limits: {s:?}");
    assert!(s.saturated > 100 && s.expanded > 10, "{s:?}");
    let c3 = Case {
        plant: RandomPlant {
            stages: [easy.clone(), easy, hard(0.6)],
            x0: [1.8, -1.5, 2.0],
        },
        amp: 1.2,
        omega: 1.5,
        limits: (-2.0, 2.0),
        design: 0,
        variant: Variant::Code,
        single: false,
    };
    let s = order3(&c3).unwrap();
    println!("order 3, tight limits: {s:?}");
    assert!(s.saturated > 100 && s.expanded > 10, "{s:?}");
}
