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

use crate::common;

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

#[derive(Debug, Default, Clone, Copy, PartialEq)]
struct Summary {
    max_abs_xi: f64,
    max_abs_xi_nominal: f64,
    clamps: u64,
    saturated: usize,
    expanded: usize,
    /// max |z1| over the last second of the run.
    final_abs_z1: f64,
    /// First time after which |z1| < [`EPS`] to the end (None: not settled).
    settling_time: Option<f64>,
    /// First time with |z1| < [`EPS`] (None: never).
    first_entry: Option<f64>,
    u_min: f64,
    u_max: f64,
}

/// The accuracy the settling metrics are measured at (every design's eps_z).
const EPS: f64 = 0.1;

/// Runs one loop and checks the invariant at every sample.
fn run_case<T: Real, const N: usize>(
    c: &Case<N>,
    mut ctrl: Controller<T, N>,
) -> Result<Summary, TestCaseError> {
    let steps = (T_END / DT).round() as usize;
    let mut x = c.plant.initial_state();
    let mut s = Summary {
        u_min: f64::INFINITY,
        u_max: f64::NEG_INFINITY,
        ..Summary::default()
    };
    let mut last_outside: Option<usize> = None;
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
        s.max_abs_xi_nominal = s.max_abs_xi_nominal.max(d.xi_nominal.to_f64_lossless().abs());
        s.expanded += usize::from(d.expanded);
        let u = v.clamp(c.limits.0, c.limits.1);
        s.saturated += usize::from(u != v);
        s.u_min = s.u_min.min(u);
        s.u_max = s.u_max.max(u);
        if e.abs() >= EPS {
            last_outside = Some(k);
        } else if s.first_entry.is_none() {
            s.first_entry = Some(t);
        }
        if t >= T_END - 1.0 - 1e-12 {
            s.final_abs_z1 = s.final_abs_z1.max(e.abs());
        }
        let h = DT / SUB as f64;
        for j in 0..SUB {
            x = rk4(&c.plant, t + j as f64 * h, &x, u, h);
        }
        prop_assert!(
            x.iter().all(|xi| xi.is_finite()),
            "plant state non-finite at t = {}",
            t
        );
    }
    s.settling_time = match last_outside {
        None => Some(0.0),
        Some(k) if k < steps => Some((k + 1) as f64 * DT),
        Some(_) => None,
    };
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

// ---------------------------------------------------------------------------
// A fixed, seeded suite of random plants with committed outcomes
// ---------------------------------------------------------------------------

/// `(relative, absolute)` tolerances of the committed outcomes below, the same
/// as `closed_loop_outcomes.rs`: settling within 5 % (or two samples), max
/// |nominal xi| within 2 %, the input range within 5 %, the final error within
/// 10 % (or 2e-3), the saturated fraction within one percentage point.
const TOL: [(&str, f64, f64); 7] = [
    ("settling_time", 0.05, 2e-3),
    ("first_entry", 0.05, 2e-3),
    ("max_abs_xi_nominal", 0.02, 1e-3),
    ("u_min", 0.05, 0.05),
    ("u_max", 0.05, 0.05),
    ("final_abs_z1", 0.10, 2e-3),
    ("saturated_fraction", 0.0, 0.01),
];

/// The metrics of a summary in the order of [`TOL`].
fn metrics(s: &Summary) -> [Option<f64>; 7] {
    let steps = (T_END / DT).round() + 1.0;
    [
        s.settling_time,
        s.first_entry,
        Some(s.max_abs_xi_nominal),
        Some(s.u_min),
        Some(s.u_max),
        Some(s.final_abs_z1),
        Some(s.saturated as f64 / steps),
    ]
}

/// The suite: the strategies above sampled with a fixed ChaCha seed (the
/// proptest version is pinned by Cargo.lock), so the cases are the same on
/// every run and machine.
fn fixed_cases<const N: usize>(seed: u8, n: usize) -> Vec<Case<N>> {
    use proptest::strategy::ValueTree;
    use proptest::test_runner::{RngAlgorithm, TestRng, TestRunner};
    let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &[seed; 32]);
    let mut runner = TestRunner::new_with_rng(ProptestConfig::default(), rng);
    (0..n)
        .map(|_| case::<N>().new_tree(&mut runner).unwrap().current())
        .collect()
}

/// Measured (x86_64): `[settling_time, first_entry, max_abs_xi_nominal,
/// u_min, u_max, final_abs_z1, saturated_fraction]` of each suite case.
#[rustfmt::skip]
const SUITE2: &[[Option<f64>; 7]] = &[
    [Some(1.659), Some(1.659), Some(3.535131508592612), Some(-1.9045096503782866), Some(36.67450103210117), Some(0.017255904530282695), Some(0.0)],
    [Some(0.924), Some(0.924), Some(0.5004584482238134), Some(-3.3742982340409036), Some(5.499175955878117), Some(0.0013297104047499397), Some(0.0)],
    [Some(0.903), Some(0.0), Some(1.687488079071045), Some(-7.422842979431152), Some(12.109792709350586), Some(0.005163697710521227), Some(0.0)],
    [Some(2.164), Some(2.164), Some(6.68297815322876), Some(-2.052070140838623), Some(1.9049272409401663), Some(0.020206989193239266), Some(0.34866283429142714)],
    [Some(0.6920000000000001), Some(0.6920000000000001), Some(0.5004617802498948), Some(-1.2343798931301824), Some(2.1996881640708645), Some(0.0002844226254445914), Some(0.0)],
    [Some(0.449), Some(0.449), Some(2.8664054818695672), Some(-8.914114954337036), Some(8.931636101750929), Some(0.00372424093014323), Some(0.0)],
    [Some(1.875), Some(1.875), Some(1.2505323601577165), Some(-7.416820961686788), Some(10.325299248299864), Some(0.006673302119402015), Some(0.0)],
    [Some(1.495), Some(1.495), Some(7.198299884796143), Some(-19.777774810791016), Some(24.882505416870117), Some(0.006955949310044118), Some(0.0)],
];
#[rustfmt::skip]
const SUITE3: &[[Option<f64>; 7]] = &[
    [Some(0.684), Some(0.684), Some(1.4759554146931229), Some(-61.677978767365296), Some(46.836768954270944), Some(0.010603327598496054), Some(0.009997500624843789)],
    [None, Some(1.615), Some(2.0249247550964355), Some(-1.334970884570218), Some(3.5011453053049895), Some(0.5804004475918061), Some(0.9582604348912772)],
    [Some(1.211), Some(1.211), Some(5.401805877685547), Some(-56.29459424261199), Some(41.18043004342137), Some(0.020438678603442062), Some(0.30017495626093477)],
    [Some(1.289), Some(1.289), Some(6.255717376406193), Some(-100.0), Some(100.0), Some(0.01954208237207189), Some(0.6593351662084479)],
    [Some(0.715), Some(0.715), Some(9.750083923339844), Some(-34.82861116783887), Some(64.30053948549374), Some(0.048014288662266355), Some(0.7170707323169208)],
    [Some(1.349), Some(1.349), Some(4.53424924463852), Some(-49.407568350328035), Some(64.53738621651361), Some(0.0425831288908593), Some(0.6825793551612097)],
];

fn check_suite<const N: usize>(
    cases: &[Case<N>],
    committed: &[[Option<f64>; 7]],
    run: impl Fn(&Case<N>) -> Result<Summary, TestCaseError>,
) {
    let print = std::env::var_os("FAMCC_PRINT_OUTCOMES").is_some();
    if !print {
        assert_eq!(
            cases.len(),
            committed.len(),
            "suite and committed values differ in length"
        );
    }
    let mut failures = Vec::new();
    for (i, c) in cases.iter().enumerate() {
        let got = metrics(&run(c).unwrap());
        if print {
            println!("@@ROW{N} {got:?},");
            continue;
        }
        for ((g, w), (name, rel, abs)) in got.iter().zip(committed[i]).zip(TOL) {
            let ok = match (g, w) {
                (Some(g), Some(w)) => (g - w).abs() <= abs.max(rel * w.abs()),
                (None, None) => true,
                _ => false,
            };
            if !ok {
                failures.push(format!(
                    "case {i} ({c:?}): {name} measured {g:?}, committed {w:?}"
                ));
            }
        }
    }
    assert!(
        failures.is_empty(),
        "beyond the tolerances {TOL:?}:\n{}",
        failures.join("\n")
    );
}

#[test]
fn order2_fixed_suite_matches_the_committed_outcomes() {
    check_suite(&fixed_cases::<2>(2, 8), SUITE2, order2);
}

#[test]
fn order3_fixed_suite_matches_the_committed_outcomes() {
    check_suite(&fixed_cases::<3>(3, 6), SUITE3, order3);
}

/// The committed suite includes settling, saturating and f32 cases (so it
/// pins more than one regime), and its tolerance would catch a 10 % slower loop.
#[test]
fn the_fixed_suite_covers_the_regimes() {
    let c2 = fixed_cases::<2>(2, 8);
    let c3 = fixed_cases::<3>(3, 6);
    assert!(c2.iter().any(|c| c.single) || c3.iter().any(|c| c.single));
    assert!(c2.iter().any(|c| c.design == 1) && c2.iter().any(|c| c.design == 2));
    let all = SUITE2.iter().chain(SUITE3);
    assert!(all.clone().any(|m| m[6].unwrap() > 0.01), "no case saturates");
    let settled: Vec<f64> = all.clone().filter_map(|m| m[0]).filter(|t| *t > 0.1).collect();
    assert!(settled.len() >= 4, "too few settling cases: {settled:?}");
    for t in settled {
        assert!((1.1 * t - t).abs() > 2e-3_f64.max(0.05 * t));
    }
}
