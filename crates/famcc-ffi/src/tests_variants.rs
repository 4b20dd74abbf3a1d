//! Every configuration variant, C ABI and core side by side, bit for bit.
//!
//! The C configurations below are written with the `FamccXxx::Yyy as u32`
//! constants of the header and the core's with its own enumerations: nothing
//! goes through `convert`'s tables, so a wrong entry there (say
//! `FAMCC_GAMMA_RATIONAL` mapped to Log) fails here.
#![allow(clippy::unwrap_used, clippy::indexing_slicing, clippy::float_cmp)]

extern crate std;

use super::*;
use core::mem::MaybeUninit;
use famcc_core::{Config, Constraint, Controller, Feedback, Real};
use famcc_core::{Discretization, Gamma, HighGain, Latch, Skew, Transition};

/// A law of the table, in both worlds.
#[derive(Clone, Copy, Debug)]
enum Law {
    Linear(f64),
    Finite(f64, f64),
    Fixed(f64, f64, f64, f64),
    Variable(f64, f64, f64, f64),
    Moulay(f64, f64, f64),
}

#[derive(Clone, Copy, Debug)]
enum SkewSpec {
    None,
    Smooth(f64, f64, FamccTransition),
    Nsmd(f64, f64, f64, FamccTransition),
}

#[derive(Clone, Copy, Debug)]
enum Flex {
    Off,
    On(f64),
    Auto,
}

#[derive(Clone, Copy, Debug)]
struct Case {
    stages: [(Law, SkewSpec); 2],
    constraint: (FamccConstraintKind, f64, f64),
    gamma: FamccGamma,
    flex: Flex,
    transition: FamccTransition,
    latch: FamccLatch,
    discretization: FamccDiscretization,
    limits: Option<[f64; 3]>,
    init: Option<[f64; 3]>,
    k_u: f64,
}

fn core_transition(t: FamccTransition) -> Transition {
    match t {
        FamccTransition::Exponential => Transition::Exponential,
        FamccTransition::Cubic => Transition::Cubic,
        FamccTransition::Quintic => Transition::Quintic,
        FamccTransition::Sine => Transition::Sine,
    }
}

fn core_law<T: Real>(l: Law) -> Feedback<T> {
    let f = T::from_f64;
    match l {
        Law::Linear(k) => Feedback::Linear { k: f(k) },
        Law::Finite(k, p) => Feedback::FiniteTime { k: f(k), p: f(p) },
        Law::Fixed(alpha, p, beta, q) => Feedback::FixedTime {
            alpha: f(alpha),
            p: f(p),
            beta: f(beta),
            q: f(q),
        },
        Law::Variable(k, r_b, r_1, r_t) => Feedback::VariableExponent {
            k: f(k),
            r_b: f(r_b),
            r_1: f(r_1),
            r_t: f(r_t),
        },
        Law::Moulay(beta, lambda, mu) => Feedback::MoulayDiscontinuous {
            beta: f(beta),
            lambda: f(lambda),
            mu: f(mu),
        },
    }
}

fn core_skew<T: Real>(s: SkewSpec) -> Option<Skew<T>> {
    let f = T::from_f64;
    let (mut sk, t) = match s {
        SkewSpec::None => return None,
        SkewSpec::Smooth(eps_s, eps_z, t) => (Skew::smooth(f(eps_s), f(eps_z)), t),
        SkewSpec::Nsmd(eps_s, eps_z, k_pp, t) => (Skew::nonsingular(f(eps_s), f(eps_z), f(k_pp)), t),
    };
    sk.transition = core_transition(t);
    Some(sk)
}

fn first<T: Real, const N: usize>(x: [f64; 3]) -> [T; N] {
    let mut a = [T::zero(); N];
    a.iter_mut().zip(x).for_each(|(d, s)| *d = T::from_f64(s));
    a
}

/// The paper's differentiator coefficients, written out.
const A2: [f64; 3] = [4.0, 4.0, 0.0];
const A3: [f64; 3] = [4.0, 6.0, 4.0];

fn core_config<T: Real, const N: usize>(v: &Case) -> Result<Config<T, N>, famcc_core::ConfigError> {
    let f = T::from_f64;
    let laws: std::vec::Vec<_> = v.stages[..N - 1]
        .iter()
        .map(|(l, s)| (core_law::<T>(*l), core_skew::<T>(*s)))
        .collect();
    let (kind, ex, ey) = v.constraint;
    let constraint = match kind {
        FamccConstraintKind::Longitudinal => Constraint::Longitudinal { eps: f(ey) },
        FamccConstraintKind::Lateral => Constraint::Lateral { eps: f(ex) },
        FamccConstraintKind::Oblique => Constraint::Oblique {
            eps_x: f(ex),
            eps_y: f(ey),
        },
    };
    let disc = match v.discretization {
        FamccDiscretization::Exact => Discretization::Exact,
        FamccDiscretization::Euler => Discretization::Euler,
        FamccDiscretization::Tustin => Discretization::Tustin,
    };
    let a = if N == 2 { A2 } else { A3 };
    let mut b = Config::<T, N>::builder(f(1e-3), &laws, constraint, f(v.k_u))
        .gamma(match v.gamma {
            FamccGamma::Log => Gamma::Log,
            FamccGamma::Rational => Gamma::Rational,
        })
        .transition(core_transition(v.transition))
        .latch(match v.latch {
            FamccLatch::Paper => Latch::Paper,
            FamccLatch::Authors => Latch::Authors,
        })
        .differentiator(Some(HighGain::new(f(0.01), first::<T, N>(a), disc)))
        .estimate_limits(v.limits.map(first::<T, N>))
        .initial_derivatives(v.init.map(first::<T, N>));
    b = match v.flex {
        Flex::Off => b.rho_e(None),
        Flex::On(r) => b.rho_e(Some(f(r))),
        Flex::Auto => b,
    };
    b.build()
}

fn c_law<T: Real>(l: Law) -> FamccFeedback<T> {
    let f = T::from_f64;
    let (kind, params) = match l {
        Law::Linear(k) => (
            FamccFeedbackKind::Linear,
            FamccFeedbackParams {
                linear: FamccLinear { k: f(k) },
            },
        ),
        Law::Finite(k, p) => (
            FamccFeedbackKind::FiniteTime,
            FamccFeedbackParams {
                finite_time: FamccFiniteTime { k: f(k), p: f(p) },
            },
        ),
        Law::Fixed(alpha, p, beta, q) => (
            FamccFeedbackKind::FixedTime,
            FamccFeedbackParams {
                fixed_time: FamccFixedTime {
                    alpha: f(alpha),
                    p: f(p),
                    beta: f(beta),
                    q: f(q),
                },
            },
        ),
        Law::Variable(k, r_b, r_1, r_t) => (
            FamccFeedbackKind::VariableExponent,
            FamccFeedbackParams {
                variable_exponent: FamccVariableExponent {
                    k: f(k),
                    r_b: f(r_b),
                    r_1: f(r_1),
                    r_t: f(r_t),
                },
            },
        ),
        Law::Moulay(beta, lambda, mu) => (
            FamccFeedbackKind::MoulayDiscontinuous,
            FamccFeedbackParams {
                moulay: FamccMoulay {
                    beta: f(beta),
                    lambda: f(lambda),
                    mu: f(mu),
                },
            },
        ),
    };
    FamccFeedback {
        kind: kind as u32,
        params,
    }
}

fn c_skew<T: Real>(s: SkewSpec) -> FamccSkew<T> {
    let f = T::from_f64;
    match s {
        SkewSpec::None => FamccSkew {
            kind: FamccSkewKind::None as u32,
            ..FamccSkew::default()
        },
        SkewSpec::Smooth(eps_s, eps_z, t) => FamccSkew {
            kind: FamccSkewKind::Smooth as u32,
            eps_s: f(eps_s),
            eps_z: f(eps_z),
            k_pp: T::zero(),
            transition: t as u32,
        },
        SkewSpec::Nsmd(eps_s, eps_z, k_pp, t) => FamccSkew {
            kind: FamccSkewKind::Nonsingular as u32,
            eps_s: f(eps_s),
            eps_z: f(eps_z),
            k_pp: f(k_pp),
            transition: t as u32,
        },
    }
}

/// The C configuration of a variant, every field set explicitly.
fn c_variant<T: Real>(v: &Case, order: usize) -> FamccConfig<T> {
    let f = T::from_f64;
    let pad = |x: [f64; 3]| {
        let mut a = [T::zero(); FAMCC_MAX_ORDER];
        for (d, s) in a.iter_mut().zip(x) {
            *d = f(s);
        }
        a
    };
    let (kind, ex, ey) = v.constraint;
    let (flexible, rho_e) = match v.flex {
        Flex::Off => (FamccFlexible::Off, T::zero()),
        Flex::On(r) => (FamccFlexible::On, f(r)),
        Flex::Auto => (FamccFlexible::Auto, T::zero()),
    };
    let stage = |i: usize| FamccStage {
        feedback: c_law::<T>(v.stages[i].0),
        skew: c_skew::<T>(v.stages[i].1),
    };
    FamccConfig {
        dt: f(1e-3),
        settle_time: f(1.0),
        k0: f(2.0),
        k_u: f(v.k_u),
        constraint: FamccConstraint {
            kind: kind as u32,
            eps_x: f(ex),
            eps_y: f(ey),
        },
        gamma: v.gamma as u32,
        flexible: flexible as u32,
        rho_e,
        transition: v.transition as u32,
        latch: v.latch as u32,
        stages: core::array::from_fn(|i| if i < 2 { stage(i) } else { stage(0) }),
        differentiator: FamccDifferentiator {
            enabled: 1,
            mu: f(0.01),
            a: pad(if order == 2 { A2 } else { A3 }),
            discretization: v.discretization as u32,
        },
        has_initial_derivatives: u32::from(v.init.is_some()),
        initial_derivatives: pad(v.init.unwrap_or([0.0; 3])),
        has_estimate_limits: u32::from(v.limits.is_some()),
        estimate_limits: pad(v.limits.unwrap_or([0.0; 3])),
        // the options beyond the paper are off (tests_options.rs covers them)
        integral: 0,
        has_output_limits: 0,
        output_limits: [T::zero(); 2],
        has_rate_limit: 0,
        rate_limit: T::zero(),
        has_initial_output: 0,
        initial_output: T::zero(),
    }
}

const BASE: Case = Case {
    stages: [
        (
            Law::Fixed(1.0, 0.5, 0.5, 2.0),
            SkewSpec::Nsmd(0.1, 0.1, 0.1, FamccTransition::Exponential),
        ),
        (Law::Finite(1.0, 0.5), SkewSpec::None),
    ],
    constraint: (FamccConstraintKind::Longitudinal, 0.1, 0.2),
    gamma: FamccGamma::Log,
    flex: Flex::Auto,
    transition: FamccTransition::Exponential,
    latch: FamccLatch::Paper,
    discretization: FamccDiscretization::Exact,
    limits: None,
    init: None,
    k_u: 5.0,
};

/// One factor at a time from [`BASE`], and a few combinations. The first
/// stage law varies at order 2 (its last stage) only where it is singular.
fn variants() -> std::vec::Vec<(usize, Case)> {
    use FamccTransition as Tr;
    let mut out = std::vec::Vec::new();
    let nsmd = SkewSpec::Nsmd(0.1, 0.1, 0.2, Tr::Exponential);
    let laws2 = [
        (Law::Linear(2.0), SkewSpec::None),
        (Law::Finite(1.0, 0.5), SkewSpec::None),
        (Law::Finite(1.5, 0.7), SkewSpec::Smooth(0.15, 0.1, Tr::Cubic)),
        (Law::Fixed(1.0, 0.5, 0.5, 2.0), nsmd),
        (
            Law::Variable(1.5, 0.5, 2.0, 3.0),
            SkewSpec::Smooth(0.225, 0.1, Tr::Exponential),
        ),
        (Law::Moulay(1.0, 2.0, 0.1), SkewSpec::None),
        (Law::Linear(1.0), SkewSpec::Nsmd(0.2, 0.1, 0.5, Tr::Quintic)),
        (Law::Finite(1.0, 0.5), SkewSpec::Nsmd(0.2, 0.1, 0.1, Tr::Sine)),
    ];
    let laws3_first = [
        (Law::Linear(2.0), SkewSpec::None),
        (
            Law::Fixed(1.0, 0.5, 0.5, 2.0),
            SkewSpec::Nsmd(0.1, 0.1, 0.1, Tr::Cubic),
        ),
        (
            Law::Variable(1.5, 0.5, 2.0, 3.0),
            SkewSpec::Nsmd(0.2, 0.1, 0.3, Tr::Sine),
        ),
        (Law::Finite(1.0, 0.6), SkewSpec::Nsmd(0.2, 0.1, 0.3, Tr::Quintic)),
    ];
    let constraints = [
        (FamccConstraintKind::Longitudinal, 0.1, 0.2),
        (FamccConstraintKind::Lateral, 0.1, 0.2),
        (FamccConstraintKind::Oblique, 0.1, 0.2),
    ];
    for order in [2, 3] {
        for c in constraints {
            for gamma in [FamccGamma::Log, FamccGamma::Rational] {
                for flex in [Flex::Off, Flex::On(0.005), Flex::Auto] {
                    out.push((
                        order,
                        Case {
                            constraint: c,
                            gamma,
                            flex,
                            ..BASE
                        },
                    ));
                }
            }
            for discretization in [FamccDiscretization::Euler, FamccDiscretization::Tustin] {
                out.push((
                    order,
                    Case {
                        constraint: c,
                        discretization,
                        ..BASE
                    },
                ));
            }
            for latch in [FamccLatch::Paper, FamccLatch::Authors] {
                for transition in [Tr::Cubic, Tr::Quintic, Tr::Sine] {
                    out.push((
                        order,
                        Case {
                            constraint: c,
                            latch,
                            transition,
                            ..BASE
                        },
                    ));
                }
            }
            out.push((
                order,
                Case {
                    constraint: c,
                    limits: Some([5.0, 3.0, 50.0]),
                    init: Some([0.0, 0.5, -2.0]),
                    ..BASE
                },
            ));
            out.push((
                order,
                Case {
                    constraint: c,
                    gamma: FamccGamma::Rational,
                    flex: Flex::Off,
                    discretization: FamccDiscretization::Tustin,
                    latch: FamccLatch::Authors,
                    limits: Some([f64::INFINITY, 2.0, 10.0]),
                    init: Some([0.0, -0.3, 1.0]),
                    ..BASE
                },
            ));
        }
    }
    for l in laws2 {
        for c in constraints {
            let mut v = Case {
                constraint: c,
                ..BASE
            };
            v.stages[0] = l;
            out.push((2, v));
        }
    }
    for l in laws3_first {
        for last in laws2 {
            let mut v = BASE;
            v.stages = [l, last];
            out.push((3, v));
        }
    }
    out
}

/// A signal that saturates, expands and clamps somewhere across the table:
/// a decaying oscillation, a pulse and a slow ramp.
fn wild_signal<T: Real>(n: usize) -> std::vec::Vec<T> {
    (0..n)
        .map(|k| {
            let t = k as f64 * 1e-3;
            let pulse = if (300..360).contains(&k) { 1.5 } else { 0.0 };
            T::from_f64(0.9 * (-t).exp() * (6.0 * t).cos() - 0.3 + pulse + 0.2 * t)
        })
        .collect()
}

/// Every diagnostics field, bit for bit.
fn same_diagnostics<T: Real + core::fmt::Debug, const N: usize>(
    c: &FamccDiagnostics<T>,
    r: &famcc_core::Diagnostics<T, N>,
    what: &str,
) {
    let want = convert::diag_to_c(r);
    let bits = |d: &FamccDiagnostics<T>| std::format!("{d:?}");
    // Debug text of the floats is exact (shortest round trip) and NaN-free here.
    assert_eq!(bits(c), bits(&want), "{what}");
    assert_eq!(
        c.v.to_f64_lossless().to_bits(),
        r.v.to_f64_lossless().to_bits(),
        "{what}"
    );
    assert_eq!(
        c.xi.to_f64_lossless().to_bits(),
        r.xi.to_f64_lossless().to_bits(),
        "{what}"
    );
    assert_eq!(c.clamp_count, r.clamp_count, "{what}");
    assert_eq!(c.expanded != 0, r.expanded, "{what}");
    assert_eq!(c.has_saturation_gap != 0, r.saturation_gap.is_some(), "{what}");
}

macro_rules! variants_match {
    ($name:ident, $t:ty, $n:literal, $storage:ty, $init:ident, $step:ident, $applied:ident, $diag:ident, $reset:ident) => {
        #[test]
        fn $name() {
            let input = wild_signal::<$t>(700);
            let mut stats = [0usize; 3]; // expanded, clamped, rational
            let mut rejected = 0usize;
            for (i, (order, v)) in variants().into_iter().enumerate() {
                if order != $n {
                    continue;
                }
                let what = std::format!("variant {i}: {v:?}");
                let cfg = c_variant::<$t>(&v, $n);
                let mut storage = MaybeUninit::<$storage>::zeroed();
                let p = storage.as_mut_ptr();
                let mut err = MaybeUninit::<FamccError>::zeroed();
                let status = unsafe { $init(p, &cfg, err.as_mut_ptr()) };
                // The C ABI accepts exactly what the core's builder accepts
                // (e.g. the validation probe rejects some f32 variants).
                let core_cfg = match core_config::<$t, $n>(&v) {
                    Ok(c) => c,
                    Err(e) => {
                        assert_eq!(status, FamccStatus::InvalidConfig, "{what}: {e:?}");
                        let got = unsafe { err.assume_init() };
                        let name: std::vec::Vec<u8> = got.parameter[..e.parameter.len()]
                            .iter()
                            .map(|&c| c as u8)
                            .collect();
                        assert_eq!(name, e.parameter.as_bytes(), "{what}");
                        rejected += 1;
                        continue;
                    }
                };
                assert_eq!(status, FamccStatus::Ok, "{what}: {:?}", unsafe {
                    err.assume_init()
                });
                // The C ABI builds exactly this configuration.
                assert_eq!(
                    convert::to_config::<$t, $n>(&cfg).unwrap(),
                    core_cfg,
                    "{what}"
                );
                let mut ctrl = Controller::new(core_cfg);
                for pass in 0..2 {
                    for (k, &e) in input.iter().enumerate() {
                        let mut out: $t = 0.0;
                        let (status, want) = if k % 7 == 3 {
                            let a = (0.8 * (k as f64)).sin() as $t;
                            (
                                unsafe { $applied(p, e, a, &mut out) },
                                ctrl.step_applied(e, Some(a)),
                            )
                        } else {
                            (unsafe { $step(p, e, &mut out) }, ctrl.step(e))
                        };
                        match want {
                            Ok(w) => {
                                assert_eq!(status, FamccStatus::Ok, "{what} step {k}");
                                assert_eq!(out.to_bits(), w.to_bits(), "{what} step {k}");
                            }
                            Err(e) => assert_eq!(status, convert::status_of(e), "{what} step {k}"),
                        }
                        let mut d = MaybeUninit::<FamccDiagnostics<$t>>::zeroed();
                        assert_eq!(unsafe { $diag(p, d.as_mut_ptr()) }, FamccStatus::Ok);
                        let r = ctrl.diagnostics();
                        same_diagnostics(
                            &unsafe { d.assume_init() },
                            &r,
                            &std::format!("{what} step {k}"),
                        );
                        if pass == 0 {
                            stats[0] += usize::from(r.expanded);
                        }
                    }
                    if pass == 0 {
                        stats[1] += ctrl.diagnostics().clamp_count as usize;
                        stats[2] += usize::from(v.gamma == FamccGamma::Rational);
                        assert_eq!(unsafe { $reset(p) }, FamccStatus::Ok);
                        ctrl.reset();
                    }
                }
            }
            // Most of the table runs; the flexible boundary, the clamp and
            // both maps are exercised.
            let total = variants().iter().filter(|(o, _)| *o == $n).count();
            assert!(
                rejected * 10 <= total,
                "{rejected} of {total} variants rejected"
            );
            assert!(
                stats.iter().all(|s| *s > 0),
                "expanded, clamped, rational: {stats:?}"
            );
        }
    };
}

variants_match!(
    every_variant_o2_f32_matches_core,
    f32,
    2,
    FamccO2F32,
    famcc_o2_f32_init,
    famcc_o2_f32_step,
    famcc_o2_f32_step_applied,
    famcc_o2_f32_diagnostics,
    famcc_o2_f32_reset
);
variants_match!(
    every_variant_o2_f64_matches_core,
    f64,
    2,
    FamccO2F64,
    famcc_o2_f64_init,
    famcc_o2_f64_step,
    famcc_o2_f64_step_applied,
    famcc_o2_f64_diagnostics,
    famcc_o2_f64_reset
);
variants_match!(
    every_variant_o3_f32_matches_core,
    f32,
    3,
    FamccO3F32,
    famcc_o3_f32_init,
    famcc_o3_f32_step,
    famcc_o3_f32_step_applied,
    famcc_o3_f32_diagnostics,
    famcc_o3_f32_reset
);
variants_match!(
    every_variant_o3_f64_matches_core,
    f64,
    3,
    FamccO3F64,
    famcc_o3_f64_init,
    famcc_o3_f64_step,
    famcc_o3_f64_step_applied,
    famcc_o3_f64_diagnostics,
    famcc_o3_f64_reset
);

/// The table covers every enumeration value of the header.
#[test]
fn the_variant_table_covers_every_enumeration_value() {
    let vs = variants();
    let has = |f: &dyn Fn(&Case) -> bool| vs.iter().any(|(_, v)| f(v));
    for g in [FamccGamma::Log, FamccGamma::Rational] {
        assert!(has(&|v| v.gamma == g));
    }
    for d in [
        FamccDiscretization::Exact,
        FamccDiscretization::Euler,
        FamccDiscretization::Tustin,
    ] {
        assert!(has(&|v| v.discretization == d));
    }
    for c in [
        FamccConstraintKind::Longitudinal,
        FamccConstraintKind::Lateral,
        FamccConstraintKind::Oblique,
    ] {
        assert!(has(&|v| v.constraint.0 == c));
    }
    for l in [FamccLatch::Paper, FamccLatch::Authors] {
        assert!(has(&|v| v.latch == l));
    }
    for t in [
        FamccTransition::Exponential,
        FamccTransition::Cubic,
        FamccTransition::Quintic,
        FamccTransition::Sine,
    ] {
        assert!(has(&|v| v.transition == t));
        assert!(has(&|v| v.stages.iter().any(
            |s| matches!(s.1, SkewSpec::Nsmd(_, _, _, x) | SkewSpec::Smooth(_, _, x) if x == t)
        )));
    }
    assert!(has(&|v| matches!(v.flex, Flex::Off)) && has(&|v| matches!(v.flex, Flex::On(_))));
    assert!(has(&|v| v.limits.is_some()) && has(&|v| v.init.is_some()));
    for k in 0..5 {
        assert!(
            has(&|v| v.stages.iter().any(|s| c_law::<f64>(s.0).kind == k)),
            "law kind {k}"
        );
    }
}
