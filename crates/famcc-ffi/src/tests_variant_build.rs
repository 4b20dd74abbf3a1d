//! Each case of `tests_variant_cases.rs` built in both worlds: the core's
//! `Config` with its own enumerations, and the C `FamccConfig` written with
//! the header's `FamccXxx::Yyy as u32` constants (nothing goes through
//! `convert`'s tables).
#![allow(clippy::unwrap_used, clippy::indexing_slicing, clippy::float_cmp)]

extern crate std;

use super::tests_variant_cases::*;
use crate::types::*;
use famcc_core::{Config, Constraint, Feedback, Real};
use famcc_core::{Discretization, Gamma, HighGain, Latch, Skew, Transition};

pub(crate) fn core_transition(t: FamccTransition) -> Transition {
    match t {
        FamccTransition::Exponential => Transition::Exponential,
        FamccTransition::Cubic => Transition::Cubic,
        FamccTransition::Quintic => Transition::Quintic,
        FamccTransition::Sine => Transition::Sine,
    }
}

pub(crate) fn core_law<T: Real>(l: Law) -> Feedback<T> {
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

pub(crate) fn core_skew<T: Real>(s: SkewSpec) -> Option<Skew<T>> {
    let f = T::from_f64;
    let (mut sk, t) = match s {
        SkewSpec::None => return None,
        SkewSpec::Smooth(eps_s, eps_z, t) => (Skew::smooth(f(eps_s), f(eps_z)), t),
        SkewSpec::Nsmd(eps_s, eps_z, k_pp, t) => (Skew::nonsingular(f(eps_s), f(eps_z), f(k_pp)), t),
    };
    sk.transition = core_transition(t);
    Some(sk)
}

pub(crate) fn first<T: Real, const N: usize>(x: [f64; 3]) -> [T; N] {
    let mut a = [T::zero(); N];
    a.iter_mut().zip(x).for_each(|(d, s)| *d = T::from_f64(s));
    a
}

/// The paper's differentiator coefficients, written out.
pub(crate) const A2: [f64; 3] = [4.0, 4.0, 0.0];
pub(crate) const A3: [f64; 3] = [4.0, 6.0, 4.0];

pub(crate) fn core_config<T: Real, const N: usize>(
    v: &Case,
) -> Result<Config<T, N>, famcc_core::ConfigError> {
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
        FamccDiscretization::Foh => Discretization::Foh,
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
        .differentiator(Some(
            HighGain::new(f(0.01), first::<T, N>(a), disc).with_prefilter(f(v.prefilter)),
        ))
        .estimate_limits(v.limits.map(first::<T, N>))
        .initial_derivatives(v.init.map(first::<T, N>));
    b = match v.flex {
        Flex::Off => b.rho_e(None),
        Flex::On(r) => b.rho_e(Some(f(r))),
        Flex::Auto => b,
    };
    b.build()
}

pub(crate) fn c_law<T: Real>(l: Law) -> FamccFeedback<T> {
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

pub(crate) fn c_skew<T: Real>(s: SkewSpec) -> FamccSkew<T> {
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
pub(crate) fn c_variant<T: Real>(v: &Case, order: usize) -> FamccConfig<T> {
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
            prefilter: f(v.prefilter),
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
        observer: FamccObserver::default(),
        direction: FamccDirection::Positive as u32,
    }
}
