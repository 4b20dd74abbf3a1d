//! Property tests of the building blocks: the paper's Definitions 1-3
//! (transitions), the envelope (eq. (4) (rho)), the feedback laws (odd, decreasing,
//! zero at zero), jet arithmetic (against finite differences and closed forms),
//! NSMD smoothness at 0 (docs/design.md §4.2), the linear manifold against eq. (60) (LFAM),
//! the Gamma maps, and the settling-time bounds of Corollaries 1-3.

use famcc_core::envelope::{rho, Envelope, Latch};
use famcc_core::transition::{self, Transition};
use famcc_core::{bounds, manifold, Feedback, Gamma, Jet, Skew, SkewedLaw};
use proptest::prelude::*;
use proptest::test_runner::Config;

const ALL_S: [Transition; 4] = [
    Transition::Exponential,
    Transition::Cubic,
    Transition::Quintic,
    Transition::Sine,
];

/// Every finite f64: normal, subnormal, zero, either sign.
fn finite_f64() -> impl Strategy<Value = f64> {
    use proptest::num::f64 as pf;
    pf::POSITIVE | pf::NEGATIVE | pf::NORMAL | pf::SUBNORMAL | pf::ZERO
}

/// Hand-picked finite inputs around every place where the formulas change.
fn edge_values() -> Vec<f64> {
    let e = f64::EPSILON;
    let mut v = vec![
        0.0,
        -0.0,
        5e-324,
        -5e-324,
        f64::MIN_POSITIVE,
        -f64::MIN_POSITIVE,
        1e-300,
        1e-200,
        1e-20,
        1e-9,
        1.0 / 1417.0,
        1.0 / 709.0,
        1.0 / 708.0,
        0.5 - e,
        0.5,
        0.5 + e,
        1.0 - e / 2.0,
        1.0 - e,
        1.0,
        1.0 + e,
        2.0,
        1e154,
        1.3e154,
        1e200,
        1e308,
        f64::MAX,
    ];
    let neg: Vec<f64> = v.iter().map(|x| -x).collect();
    v.extend(neg);
    v
}

/// A log-uniform magnitude in [10^lo, 10^hi] with either sign.
fn signed_log(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    (lo..hi, any::<bool>()).prop_map(|(e, neg)| {
        let m = 10f64.powf(e);
        if neg {
            -m
        } else {
            m
        }
    })
}

// ===========================================================================
// Definitions 1-3: T, S, U
// ===========================================================================

proptest! {
    #![proptest_config(Config::with_cases(512))]

    /// Definition 1: T = 0 for z <= 0, values in [0, 1] on (-inf, 1].
    #[test]
    fn t_single_zero_left_and_bounded(z in finite_f64()) {
        let t = transition::single_ended(z);
        prop_assert!(t.is_finite());
        if z <= 0.0 {
            prop_assert_eq!(t, 0.0);
        }
        if z <= 1.0 {
            prop_assert!((0.0..=1.0).contains(&t), "T({z}) = {t}");
        }
    }

    /// Definition 1: T nondecreasing.
    #[test]
    fn t_single_nondecreasing(a in -2.0..3.0f64, b in -2.0..3.0f64) {
        let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
        prop_assert!(transition::single_ended(lo) <= transition::single_ended(hi));
    }

    /// Definition 2 for every S variant: 0 for z <= 0, 1 for z >= 1, values in [0, 1].
    #[test]
    fn s_flat_outside_and_bounded(z in finite_f64()) {
        for tr in ALL_S {
            let s = tr.double_ended(z);
            prop_assert!(s.is_finite());
            prop_assert!((0.0..=1.0).contains(&s), "{tr:?} S({z}) = {s}");
            if z <= 0.0 {
                prop_assert_eq!(s, 0.0);
            }
            if z >= 1.0 {
                prop_assert_eq!(s, 1.0);
            }
        }
    }

    /// Definition 2: S nondecreasing (on a wide range and inside (0, 1)).
    #[test]
    fn s_nondecreasing(a in -0.5..1.5f64, b in -0.5..1.5f64) {
        let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
        for tr in ALL_S {
            prop_assert!(tr.double_ended(lo) <= tr.double_ended(hi), "{tr:?} at {lo}, {hi}");
        }
    }

    /// The exponential S is symmetric: S(z) + S(1 - z) = 1 (also true of the
    /// polynomial and sine variants).
    #[test]
    fn s_point_symmetry(z in -0.5..1.5f64) {
        for tr in ALL_S {
            let sum = tr.double_ended(z) + tr.double_ended(1.0 - z);
            prop_assert!((sum - 1.0).abs() <= 4.0 * f64::EPSILON, "{tr:?} z = {z}: {sum}");
        }
    }

    /// Definition 3: U(0) = 0, U = 1 for |z| >= 1, U even, values in [0, 1].
    #[test]
    fn u_even_and_flat_outside(z in finite_f64()) {
        for tr in ALL_S {
            let u = tr.interval(z);
            prop_assert!((0.0..=1.0).contains(&u));
            prop_assert_eq!(u, tr.interval(-z));
            if z.abs() >= 1.0 {
                prop_assert_eq!(u, 1.0);
            }
        }
    }

    /// Definition 3: U nonincreasing for z <= 0 and nondecreasing for z >= 0.
    #[test]
    fn u_monotone_each_side(a in 0.0..1.5f64, b in 0.0..1.5f64) {
        let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
        for tr in ALL_S {
            prop_assert!(tr.interval(lo) <= tr.interval(hi));
            prop_assert!(tr.interval(-hi) >= tr.interval(-lo));
        }
    }

    /// Every transition and its jet is finite for every finite input
    /// (derivatives of the argument of moderate size).
    #[test]
    fn transitions_finite_everywhere(z in finite_f64(), d in prop::array::uniform4(-10.0..10.0f64)) {
        let j = Jet::<f64, 5>::from_derivatives([z, d[0], d[1], d[2], d[3]]);
        prop_assert!(transition::single_ended(z).is_finite());
        prop_assert!(transition::single_ended_jet(j).is_finite(), "T jet at {z}");
        for tr in ALL_S {
            prop_assert!(tr.double_ended(z).is_finite() && tr.interval(z).is_finite());
            prop_assert!(tr.double_ended_jet(j).is_finite(), "{tr:?} S jet at {z}: {:?}", tr.double_ended_jet(j));
            prop_assert!(tr.interval_jet(j).is_finite(), "{tr:?} U jet at {z}");
        }
    }
}

#[test]
fn t_single_at_one_is_one() {
    assert_eq!(transition::single_ended(1.0_f64), 1.0);
    assert_eq!(transition::single_ended(1.0_f32), 1.0);
    assert_eq!(
        transition::single_ended_jet(Jet::<f64, 3>::from_derivatives([1.0, 1.0, 0.0])).value(),
        1.0
    );
}

#[test]
fn transitions_finite_at_edge_values() {
    for &z in &edge_values() {
        for &d in &[0.0, 1.0, -7.5] {
            let j = Jet::<f64, 6>::from_derivatives([z, d, -d, d, 0.5 * d, -2.0 * d]);
            assert!(transition::single_ended(z).is_finite(), "T({z})");
            assert!(transition::single_ended_jet(j).is_finite(), "T jet at {z}");
            for tr in ALL_S {
                let (s, u) = (tr.double_ended(z), tr.interval(z));
                assert!(
                    (0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&u),
                    "{tr:?} at {z}"
                );
                assert!(
                    tr.double_ended_jet(j).is_finite(),
                    "{tr:?} S jet at {z}: {:?}",
                    tr.double_ended_jet(j)
                );
                assert!(tr.interval_jet(j).is_finite(), "{tr:?} U jet at {z}");
            }
        }
    }
    for tr in ALL_S {
        assert_eq!(tr.interval(0.0_f64), 0.0);
        assert!(
            (tr.double_ended(0.5_f64) - 0.5).abs() <= f64::EPSILON,
            "{tr:?}: S(1/2) = 1/2"
        );
    }
}

/// `d^k/dz^k S(z)` at `z` through a jet with `z' = 1`.
fn s_derivs(tr: Transition, z: f64) -> [f64; 5] {
    tr.double_ended_jet(Jet::<f64, 5>::from_derivatives([z, 1.0, 0.0, 0.0, 0.0]))
        .derivatives()
}

proptest! {
    #![proptest_config(Config::with_cases(256))]

    /// Smoothness at the ends (Definition 2): the derivatives that the class
    /// promises continuous tend to 0 as z -> 0+ and z -> 1- (and are exactly 0
    /// outside): exponential C-infinity (checked: 1st-4th), quintic C2, cubic
    /// and sine C1. The bounds are the exact leading terms.
    #[test]
    fn s_derivatives_vanish_at_the_ends(e in -12.0..-2.0f64) {
        let d = 10f64.powf(e);
        for (z, m) in [(d, d), (1.0 - d, 1.0 - (1.0 - d))] {
            let exp = s_derivs(Transition::Exponential, z);
            for (k, v) in exp.iter().enumerate().skip(1) {
                // S^(k) ~ exp(-1/m) m^-2k: below 1e-20 for m <= 1e-2.
                prop_assert!(v.abs() < 1e-20, "exponential S^({k})({z}) = {v}");
            }
            let cubic = s_derivs(Transition::Cubic, z);
            prop_assert!(cubic[1].abs() <= 6.0 * m * (1.0 + 1e-9), "cubic S'({z}) = {}", cubic[1]);
            let quintic = s_derivs(Transition::Quintic, z);
            prop_assert!(quintic[1].abs() <= 30.0 * m * m * (1.0 + 1e-9), "quintic S'({z})");
            prop_assert!(quintic[2].abs() <= 60.0 * m * (1.0 + 1e-9), "quintic S''({z}) = {}", quintic[2]);
            let sine = s_derivs(Transition::Sine, z);
            let bound = 0.5 * std::f64::consts::PI * std::f64::consts::PI * m;
            prop_assert!(sine[1].abs() <= bound * (1.0 + 1e-9), "sine S'({z}) = {}", sine[1]);
        }
    }

    /// The single-ended T is C-infinity at 0: its derivatives tend to 0 from the right.
    #[test]
    fn t_derivatives_vanish_at_zero(e in -12.0..-2.0f64) {
        let z = 10f64.powf(e);
        let t = transition::single_ended_jet(Jet::<f64, 5>::from_derivatives([z, 1.0, 0.0, 0.0, 0.0]));
        for (k, v) in t.derivatives().iter().enumerate() {
            prop_assert!(v.abs() < 1e-20, "T^({k})({z}) = {v}");
        }
    }
}

#[test]
fn s_derivatives_are_zero_outside_and_match_at_interior() {
    for tr in ALL_S {
        for z in [-1.0, 0.0, 1.0, 2.0] {
            assert!(s_derivs(tr, z).iter().skip(1).all(|v| *v == 0.0), "{tr:?} at {z}");
        }
    }
    // The classes are sharp: the first derivative that the class does not
    // promise continuous is NOT 0 at the ends (cubic/sine S'' and quintic S''').
    let near0 = 1e-9;
    assert!((s_derivs(Transition::Cubic, near0)[2] - 6.0).abs() < 1e-6);
    assert!((s_derivs(Transition::Sine, near0)[2] - std::f64::consts::PI.powi(2) / 2.0).abs() < 1e-6);
    assert!((s_derivs(Transition::Quintic, near0)[3] - 60.0).abs() < 1e-6);
    // Interior values against closed forms: cubic S'(z) = 6 z (1-z), S'' = 6 - 12 z.
    let c = s_derivs(Transition::Cubic, 0.3);
    assert!((c[1] - 1.26).abs() < 1e-14 && (c[2] - 2.4).abs() < 1e-14 && (c[3] + 12.0).abs() < 1e-13);
    let c = s_derivs(Transition::Cubic, 0.7);
    assert!((c[1] - 1.26).abs() < 1e-14 && (c[2] + 2.4).abs() < 1e-14 && (c[3] + 12.0).abs() < 1e-13);
    // Exponential: S'(1/2) = 2.
    assert!((s_derivs(Transition::Exponential, 0.5)[1] - 2.0).abs() < 1e-14);
}

// ===========================================================================
// Envelope (eq. (4) (rho))
// ===========================================================================

proptest! {
    #![proptest_config(Config::with_cases(512))]

    /// rho(0) = rho0, rho = eps for t >= T, nonincreasing, within [eps, rho0].
    #[test]
    fn envelope_shape(
        eps in 1e-3..1.0f64,
        extra in 1e-3..100.0f64,
        settle in 1e-2..20.0f64,
        f1 in -0.5..2.0f64,
        f2 in -0.5..2.0f64,
    ) {
        let rho0 = eps + extra;
        let slack = 4.0 * f64::EPSILON * rho0;
        prop_assert!((rho(rho0, eps, settle, 0.0) - rho0).abs() <= slack);
        let env = Envelope { rho0, eps, settle_time: settle };
        prop_assert_eq!(env.at(settle), eps);
        prop_assert_eq!(env.at(settle * (1.0 + f1.abs()) + 1.0), eps);
        let (ta, tb) = (settle * f1.min(f2), settle * f1.max(f2));
        let (ra, rb) = (env.at(ta), env.at(tb));
        prop_assert!(ra + slack >= rb, "rho({ta}) = {ra} < rho({tb}) = {rb}");
        for r in [ra, rb] {
            if ta >= 0.0 {
                prop_assert!(r >= eps && r <= rho0 + slack, "rho out of [eps, rho0]: {r}");
            }
        }
    }

    /// The initial-width latches: paper k0 max(|s0|, eps), authors max(k0 |s0|, eps).
    #[test]
    fn latch_rules(s0 in -10.0..10.0f64, k0 in 1.01..5.0f64, eps in 1e-3..1.0f64) {
        prop_assert_eq!(Latch::Paper.rho0(s0, k0, eps), k0 * s0.abs().max(eps));
        prop_assert_eq!(Latch::Authors.rho0(s0, k0, eps), (k0 * s0.abs()).max(eps));
        prop_assert!(Latch::Paper.rho0(s0, k0, eps) > eps);
    }
}

// ===========================================================================
// Feedback laws
// ===========================================================================

/// Valid parameters for every continuous law (Linear, FiniteTime, FixedTime,
/// VariableExponent).
fn continuous_law() -> impl Strategy<Value = Feedback<f64>> {
    prop_oneof![
        (0.05..10.0f64).prop_map(|k| Feedback::Linear { k }),
        (0.05..10.0f64, 0.05..0.95f64).prop_map(|(k, p)| Feedback::FiniteTime { k, p }),
        (0.05..10.0f64, 0.05..0.95f64, 0.05..10.0f64, 1.05..4.0f64)
            .prop_map(|(alpha, p, beta, q)| Feedback::FixedTime { alpha, p, beta, q }),
        variable_exponent_law(),
    ]
}

/// Random variable-exponent laws that pass validation. Validation rejects
/// the parameter sets (valid by the inequalities 0 < r_b < 1 < r_1 < r_t alone)
/// whose law is not strictly decreasing near 0 (paper Step B1, property 1):
/// see `variable_exponent_validation_is_monotonicity`.
fn variable_exponent_law() -> impl Strategy<Value = Feedback<f64>> {
    (0.05..10.0f64, 0.05..0.95f64, 1.05..3.0f64, 0.05..2.0f64)
        .prop_map(|(k, r_b, r_1, gap)| Feedback::VariableExponent {
            k,
            r_b,
            r_1,
            r_t: r_1 + gap,
        })
        .prop_filter("validated", |l| l.validate().is_ok())
}

/// Laws whose derivatives are singular at 0 (the ones NSMD exists for).
fn power_law() -> impl Strategy<Value = Feedback<f64>> {
    continuous_law().prop_filter("power laws only", |l| !matches!(l, Feedback::Linear { .. }))
}

proptest! {
    #![proptest_config(Config::with_cases(512))]

    /// Every continuous law is odd, zero at zero, strictly decreasing, and has
    /// a negative slope.
    #[test]
    fn laws_odd_zero_decreasing(law in continuous_law(), a in -100.0..100.0f64, b in -100.0..100.0f64) {
        prop_assert!(law.validate().is_ok());
        prop_assert_eq!(law.eval(0.0), 0.0);
        prop_assert_eq!(law.eval(-a), -law.eval(a), "odd at {}", a);
        prop_assert_eq!(law.slope(-a), law.slope(a), "slope even at {}", a);
        let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
        if hi - lo > 1e-6 * (1.0 + lo.abs().max(hi.abs())) {
            prop_assert!(law.eval(lo) > law.eval(hi), "{law:?}: h({lo}) <= h({hi})");
        }
        if a != 0.0 {
            prop_assert!(law.eval(a) * a < 0.0, "negative feedback");
            prop_assert!(law.slope(a) < 0.0, "{law:?}: slope({a}) = {}", law.slope(a));
        }
    }

    /// The slope is the derivative of the law (central differences).
    #[test]
    fn law_slope_is_derivative(law in continuous_law(), a in signed_log(-1.0, 1.5)) {
        let h = 1e-6 * a.abs();
        let fd = (law.eval(a + h) - law.eval(a - h)) / (2.0 * h);
        let s = law.slope(a);
        prop_assert!((s - fd).abs() <= 1e-5 * s.abs(), "{law:?} at {a}: slope {s}, fd {fd}");
    }

    /// The closed-form inverses invert the law.
    #[test]
    fn law_closed_form_inverse(k in 0.1..10.0f64, p in 0.1..0.9f64, a in -50.0..50.0f64) {
        for law in [Feedback::Linear { k }, Feedback::FiniteTime { k, p }] {
            let inv = law.inverse_closed_form(law.eval(a));
            prop_assert!(inv.is_some());
            let x = inv.unwrap_or(f64::NAN);
            prop_assert!((x - a).abs() <= 1e-9 * (1.0 + a.abs()), "{law:?}: {x} != {a}");
        }
    }

    /// The discontinuous Moulay law: odd, zero at 0, and jumps to -+beta next to 0.
    #[test]
    fn moulay_odd_and_jumps(beta in 0.1..5.0f64, lambda in 0.1..5.0f64, mu in 0.0..1.0f64, a in -20.0..20.0f64) {
        let law = Feedback::MoulayDiscontinuous { beta, lambda, mu };
        prop_assert!(law.validate().is_ok());
        prop_assert_eq!(law.eval(0.0), 0.0);
        prop_assert_eq!(law.eval(-a), -law.eval(a));
        prop_assert!((law.eval(1e-12) + beta).abs() < 1e-9 * beta);
        prop_assert!((law.eval(-1e-12) - beta).abs() < 1e-9 * beta);
    }
}

/// `(min, argmin)` over a dense log grid of
/// `phi(u) = r_b (1 + b u)^2 + a u (1 + b u + ln u)`, `u = s^2` in (0, 1):
/// `phi(s^2) > 0` iff `|s|^{r(s)}` increases at `s` (so the law decreases).
fn phi_min_on_grid(r_b: f64, r_1: f64, r_t: f64) -> (f64, f64) {
    let b = (r_1 - r_b) / (r_t - r_1);
    let a = (r_t - r_b) * b;
    (0..4000)
        .map(|i| (-40.0 * i as f64 / 4000.0).exp())
        .map(|u| (r_b * (1.0 + b * u).powi(2) + a * u * (1.0 + b * u + u.ln()), u))
        .fold((f64::INFINITY, 1.0), |acc, v| if v.0 < acc.0 { v } else { acc })
}

proptest! {
    #![proptest_config(Config::with_cases(512))]

    /// VariableExponent validation accepts exactly the parameter sets whose
    /// law is strictly decreasing (away from the boundary of that set).
    #[test]
    fn variable_exponent_validation_is_monotonicity(
        k in 0.05..10.0f64,
        r_b in 0.01..0.99f64,
        r_1 in 1.01..4.0f64,
        gap in 0.01..4.0f64,
    ) {
        let law = Feedback::VariableExponent { k, r_b, r_1, r_t: r_1 + gap };
        let (m, u) = phi_min_on_grid(r_b, r_1, r_1 + gap);
        if m > 1e-3 {
            prop_assert!(law.validate().is_ok(), "{law:?} rejected, phi min {m}");
        } else if m < -1e-3 {
            let e = law.validate();
            prop_assert!(e.is_err(), "{law:?} accepted, phi min {m}");
            prop_assert_eq!(e.err().map(|e| e.parameter), Some("r_b"));
            // And it really is not decreasing there.
            let s = u.sqrt();
            prop_assert!(law.slope(s) > 0.0, "{law:?}: slope({s}) = {}", law.slope(s));
        }
    }
}

#[test]
fn variable_exponent_paper_example_is_valid() {
    // Example 2 (k = 1.5, r_b = 0.5, r_1 = 2, r_t = 3) and the authors' unit-gain law.
    for k in [1.0, 1.5] {
        let law = Feedback::VariableExponent {
            k,
            r_b: 0.5,
            r_1: 2.0,
            r_t: 3.0,
        };
        assert!(law.validate().is_ok());
        assert!(phi_min_on_grid(0.5, 2.0, 3.0).0 > 0.1);
    }
    // A steep exponent ramp from a tiny r_b is not a negative feedback law.
    let bad = Feedback::VariableExponent {
        k: 0.05,
        r_b: 0.05,
        r_1: 1.05,
        r_t: 1.1,
    };
    assert!(bad.validate().is_err());
    assert!(bad.slope(0.143) > 0.0);
}

#[test]
fn laws_defined_at_extreme_arguments() {
    let laws = [
        Feedback::Linear { k: 2.0 },
        Feedback::FiniteTime { k: 1.0, p: 0.5 },
        Feedback::FixedTime {
            alpha: 2.0,
            p: 0.5,
            beta: 1.0,
            q: 2.0,
        },
        Feedback::VariableExponent {
            k: 1.5,
            r_b: 0.5,
            r_1: 2.0,
            r_t: 3.0,
        },
        Feedback::MoulayDiscontinuous {
            beta: 1.0,
            lambda: 2.0,
            mu: 0.1,
        },
    ];
    for law in laws {
        for &x in &edge_values() {
            let (h, s) = (law.eval(x), law.slope(x));
            // Values and slopes may overflow to an infinity, never to NaN.
            assert!(!h.is_nan() && !s.is_nan(), "{law:?} at {x}: h = {h}, slope = {s}");
            if x != 0.0 {
                assert!(h * x.signum() <= 0.0, "{law:?} at {x}: h = {h}");
            }
        }
    }
    // x^2 must not overflow inside the variable exponent (was NaN).
    let ve = laws[3];
    assert_eq!(ve.eval(1e200), f64::NEG_INFINITY);
    assert_eq!(ve.eval(-1e200), f64::INFINITY);
    assert_eq!(ve.slope(1e200), f64::NEG_INFINITY);
    // x^2 at 1e200 overflows but the fixed-time slope -(1/sqrt x + 2x) does not.
    let ft = laws[2];
    assert!((ft.slope(1e200) + 2e200).abs() <= 1e-12 * 2e200);
}

// ===========================================================================
// Jets
// ===========================================================================

/// x(t) = a + b t + c t^2 + d sin t.
#[derive(Clone, Copy, Debug)]
struct Signal {
    a: f64,
    b: f64,
    c: f64,
    d: f64,
}

impl Signal {
    fn at(&self, t: f64) -> f64 {
        self.a + self.b * t + self.c * t * t + self.d * t.sin()
    }
    fn jet(&self, t: f64) -> Jet<f64, 5> {
        let (s, co) = t.sin_cos();
        Jet::from_derivatives([
            self.at(t),
            self.b + 2.0 * self.c * t + self.d * co,
            2.0 * self.c - self.d * s,
            -self.d * co,
            self.d * s,
        ])
    }
}

/// Finite differences of `f` at `t`: derivatives 1, 2 (O(h^4) stencils) and 3
/// (O(h^4) seven-point stencil).
fn finite_differences(f: impl Fn(f64) -> f64, t: f64) -> [f64; 3] {
    let h = 1e-3;
    let d1 = (f(t - 2.0 * h) - 8.0 * f(t - h) + 8.0 * f(t + h) - f(t + 2.0 * h)) / (12.0 * h);
    let d2 =
        (-f(t + 2.0 * h) + 16.0 * f(t + h) - 30.0 * f(t) + 16.0 * f(t - h) - f(t - 2.0 * h)) / (12.0 * h * h);
    let h3 = 5e-3;
    let d3 = (-f(t + 3.0 * h3) + 8.0 * f(t + 2.0 * h3) - 13.0 * f(t + h3) + 13.0 * f(t - h3)
        - 8.0 * f(t - 2.0 * h3)
        + f(t - 3.0 * h3))
        / (8.0 * h3 * h3 * h3);
    [d1, d2, d3]
}

fn assert_matches_fd(
    name: &str,
    jet: Jet<f64, 5>,
    f: impl Fn(f64) -> f64,
    t: f64,
) -> Result<(), TestCaseError> {
    let fd = finite_differences(&f, t);
    let scale = 1.0 + jet.value().abs();
    let tol = [1e-8, 1e-6, 1e-5];
    for k in 0..3 {
        let got = jet.derivative(k + 1);
        let err = (got - fd[k]).abs();
        prop_assert!(
            err <= tol[k] * (scale + fd[k].abs()),
            "{name}: derivative {} is {got}, finite differences give {} (t = {t})",
            k + 1,
            fd[k]
        );
    }
    prop_assert_eq!(jet.value(), jet.derivative(0));
    Ok(())
}

/// Positive smooth signals (x >= 0.6 near t0), so ln and powers are smooth.
fn positive_signal() -> impl Strategy<Value = Signal> {
    (1.5..3.0f64, -0.3..0.3f64, -0.3..0.3f64, -0.3..0.3f64).prop_map(|(a, b, c, d)| Signal { a, b, c, d })
}

/// Signals of either sign, bounded away from 0 near t0.
fn signed_signal() -> impl Strategy<Value = Signal> {
    (positive_signal(), any::<bool>()).prop_map(|(s, neg)| {
        if neg {
            Signal {
                a: -s.a,
                b: -s.b,
                c: -s.c,
                d: -s.d,
            }
        } else {
            s
        }
    })
}

proptest! {
    #![proptest_config(Config::with_cases(256))]

    /// exp, ln, powf, signed_pow, products, quotients, sin_cos, recip:
    /// jet derivatives equal finite differences of the scalar function along t.
    #[test]
    fn jet_ops_match_finite_differences(
        x in positive_signal(),
        y in signed_signal(),
        t in -1.0..1.0f64,
        p in -2.5..3.5f64,
        q in 0.2..3.0f64,
    ) {
        let (xj, yj) = (x.jet(t), y.jet(t));
        assert_matches_fd("exp", xj.exp(), |s| x.at(s).exp(), t)?;
        assert_matches_fd("ln", xj.ln(), |s| x.at(s).ln(), t)?;
        assert_matches_fd("powf", xj.powf(p), |s| x.at(s).powf(p), t)?;
        assert_matches_fd("signed_pow", yj.signed_pow(q), |s| {
            let v = y.at(s);
            v.abs().powf(q) * v.signum()
        }, t)?;
        assert_matches_fd("mul", xj * yj, |s| x.at(s) * y.at(s), t)?;
        assert_matches_fd("div", yj / xj, |s| y.at(s) / x.at(s), t)?;
        assert_matches_fd("recip", yj.recip(), |s| 1.0 / y.at(s), t)?;
        let (sj, cj) = yj.sin_cos();
        assert_matches_fd("sin", sj, |s| y.at(s).sin(), t)?;
        assert_matches_fd("cos", cj, |s| y.at(s).cos(), t)?;
        assert_matches_fd("abs", yj.abs(), |s| y.at(s).abs(), t)?;
        assert_matches_fd("shift", xj.shift(), |s| x.b + 2.0 * x.c * s + x.d * s.cos(), t)?;
        assert_matches_fd("compound", (xj * yj).exp().scale(0.1) + (yj / xj).powf(2.0),
            |s| 0.1 * (x.at(s) * y.at(s)).exp() + (y.at(s) / x.at(s)).powi(2), t)?;
        let vexp = |z: Jet<f64, 5>| (z * z * 0.5 + 1.0).recip() + 0.3;
        assert_matches_fd("signed_pow_jet", yj.signed_pow_jet(&vexp(yj)), |s| {
            let v = y.at(s);
            v.abs().powf(1.0 / (0.5 * v * v + 1.0) + 0.3) * v.signum()
        }, t)?;
    }

    /// Closed forms: exp of a linear signal, products of polynomials (Cauchy
    /// product of the coefficients), quotients and inverse functions.
    #[test]
    fn jet_closed_forms(
        a in -3.0..3.0f64,
        b in -3.0..3.0f64,
        pc in prop::array::uniform3(-5.0..5.0f64),
        qc in prop::array::uniform3(-5.0..5.0f64),
        x0 in 0.2..5.0f64,
        r in 0.1..3.0f64,
    ) {
        // exp(a + b t): k-th derivative b^k e^a.
        let e = Jet::<f64, 6>::from_derivatives([a, b, 0.0, 0.0, 0.0, 0.0]).exp();
        for k in 0..6 {
            let want = b.powi(k as i32) * a.exp();
            prop_assert!((e.derivative(k) - want).abs() <= 1e-12 * (1.0 + want.abs()), "exp: d{k}");
        }
        // (p0 + p1 t + p2 t^2)(q0 + q1 t + q2 t^2): degree 4 fits in 6 coefficients.
        let p = Jet::<f64, 6>::from_taylor([pc[0], pc[1], pc[2], 0.0, 0.0, 0.0]);
        let q = Jet::<f64, 6>::from_taylor([qc[0], qc[1], qc[2], 0.0, 0.0, 0.0]);
        let mut want = [0.0; 6];
        for i in 0..3 {
            for j in 0..3 {
                want[i + j] += pc[i] * qc[j];
            }
        }
        let got = (p * q).taylor();
        for k in 0..6 {
            prop_assert!((got[k] - want[k]).abs() <= 1e-12 * (1.0 + want[k].abs()), "product c{k}");
        }
        // (p q)/q = p where q(0) != 0.
        if qc[0].abs() > 0.5 {
            let back = ((p * q) / q).taylor();
            for k in 0..6 {
                let w = if k < 3 { pc[k] } else { 0.0 };
                prop_assert!((back[k] - w).abs() <= 1e-9 * (1.0 + pc.iter().map(|v| v.abs()).sum::<f64>()), "quotient c{k}");
            }
        }
        // ln(exp x) = x, (x^r)^(1/r) = x, signed_pow of -x is -x^r.
        let x = Jet::<f64, 6>::from_derivatives([x0, b, a, 0.5, -0.25, 1.0]);
        let round = |j: Jet<f64, 6>, name: &str| -> Result<(), TestCaseError> {
            for (k, (u, v)) in j.taylor().iter().zip(x.taylor().iter()).enumerate() {
                prop_assert!((u - v).abs() <= 1e-9 * (1.0 + v.abs()) * (1.0 + 1.0 / x0).powi(k as i32), "{name}: c{k}: {u} vs {v}");
            }
            Ok(())
        };
        round(x.exp().ln(), "ln(exp x)")?;
        round(x.powf(r).powf(1.0 / r), "(x^r)^(1/r)")?;
        round(-((-x).signed_pow(r).signed_pow(1.0 / r)), "signed_pow of -x")?;
        round(x.recip().recip(), "1/(1/x)")?;
    }

    /// The powers stay accurate where the value itself overflows/underflows.
    #[test]
    fn jet_powers_at_extreme_scales(e in 160.0..300.0f64, d in -10.0..10.0f64) {
        let x0 = 10f64.powf(e);
        let j = Jet::<f64, 3>::from_derivatives([x0, d, 0.0]).powf(2.0);
        prop_assert_eq!(j.value(), f64::INFINITY);
        let want = 2.0 * x0 * d;
        // Rescaled through exp(p ln x0 + ln|r_k|): the ~700-sized logs cost
        // up to ~1e-13 relative, hence 1e-11. Higher derivatives are only
        // promised finite at this scale.
        prop_assert!((j.derivative(1) - want).abs() <= 1e-11 * want.abs(), "{} vs {want}", j.derivative(1));
        prop_assert!(!j.derivative(2).is_nan());
        // Underflowing value, normal derivative: (1/x0)^2 at x0 = 10^e.
        let small = 1.0 / x0;
        let k = Jet::<f64, 2>::from_derivatives([small, d]).powf(2.0);
        let want = 2.0 * small * d;
        prop_assert!((k.derivative(1) - want).abs() <= 1e-11 * want.abs());
    }
}

#[test]
fn signed_pow_at_zero_is_smooth_or_infinite_by_order() {
    let s = Jet::<f64, 4>::from_derivatives([0.0, 2.0, 1.0, -1.0]);
    // p = 2.5: derivatives 1 and 2 vanish (p > k), derivative 3 is infinite.
    let y = s.signed_pow(2.5);
    assert_eq!(y.value(), 0.0);
    assert_eq!(y.derivative(1), 0.0);
    assert_eq!(y.derivative(2), 0.0);
    assert_eq!(y.derivative(3), f64::INFINITY);
    // p = 0.5 and a falling signal: -inf from the first derivative on.
    let y = (-s).signed_pow(0.5);
    assert_eq!(y.derivative(1), f64::NEG_INFINITY);
    // A signal at rest at 0 stays at 0.
    assert!(Jet::<f64, 4>::constant(0.0).signed_pow(0.5).is_zero());
}

// ===========================================================================
// NSMD is smooth at 0 (docs/design.md §4.2)
// ===========================================================================

fn nsmd_jet_finite<const K: usize>(law: &SkewedLaw<f64>, s: f64, d: &[f64; 5]) -> Result<(), TestCaseError> {
    let mut v = [0.0; K];
    v[0] = s;
    v[1..].copy_from_slice(&d[..K - 1]);
    let j = law.eval_jet(Jet::<f64, K>::from_derivatives(v));
    prop_assert!(
        j.is_finite(),
        "K = {K}, s = {s}, d = {d:?}: {:?}",
        j.derivatives()
    );
    prop_assert!((j.value() - law.eval(s)).abs() <= 1e-12 * (1.0 + j.value().abs()));
    Ok(())
}

fn nsmd_law() -> impl Strategy<Value = SkewedLaw<f64>> {
    (power_law(), 0.01..1.0f64, 0.001..0.5f64, 0.05..3.0f64).prop_map(|(law, eps_s, eps_z, k_pp)| {
        SkewedLaw::new(law, Some(Skew::nonsingular(eps_s, eps_z, k_pp))).unwrap_or_else(|e| panic!("{e}"))
    })
}

proptest! {
    #![proptest_config(Config::with_cases(384))]

    /// NSMD h_m and all its jet derivatives (orders up to 5, K up to 6) are
    /// finite at s = 0 and near it, for the finite-time, fixed-time and
    /// variable-exponent laws.
    #[test]
    fn nsmd_finite_near_zero(
        law in nsmd_law(),
        s in prop_oneof![Just(0.0), Just(-0.0), signed_log(-300.0, -1.0)],
        d in prop::array::uniform5(-20.0..20.0f64),
    ) {
        prop_assert!(!law.is_singular_at_zero());
        nsmd_jet_finite::<2>(&law, s, &d)?;
        nsmd_jet_finite::<3>(&law, s, &d)?;
        nsmd_jet_finite::<4>(&law, s, &d)?;
        nsmd_jet_finite::<5>(&law, s, &d)?;
        nsmd_jet_finite::<6>(&law, s, &d)?;
    }

    /// At s = 0 the NSMD is the line -k_p s: its rate is exactly -k_p s'.
    #[test]
    fn nsmd_is_linear_at_zero(law in nsmd_law(), d in prop::array::uniform3(-20.0..20.0f64)) {
        let j = law.eval_jet(Jet::<f64, 4>::from_derivatives([0.0, d[0], d[1], d[2]]));
        for k in 1..4 {
            let want = -law.k_p() * d[k - 1];
            prop_assert!((j.derivative(k) - want).abs() <= 1e-12 * (1.0 + want.abs()));
        }
        prop_assert!(law.k_p() > 0.0);
    }

    /// Outside +-eps_z both skews equal h_p -+ eps_s; they are odd everywhere.
    #[test]
    fn skews_offset_outside_and_odd(
        law in power_law(),
        eps_s in 0.01..1.0f64,
        eps_z in 0.001..0.5f64,
        k_pp in 0.05..3.0f64,
        f in 1.0..50.0f64,
        a in -2.0..2.0f64,
    ) {
        let sk = [Skew::smooth(eps_s, eps_z), Skew::nonsingular(eps_s, eps_z, k_pp)];
        for skew in sk {
            let h = SkewedLaw::new(law, Some(skew)).unwrap_or_else(|e| panic!("{e}"));
            let s = eps_z * f;
            prop_assert!((h.eval(s) - (law.eval(s) - eps_s)).abs() <= 1e-12 * (1.0 + law.eval(s).abs()));
            prop_assert!((h.eval(-s) - (law.eval(-s) + eps_s)).abs() <= 1e-12 * (1.0 + law.eval(s).abs()));
            prop_assert!((h.eval(-a) + h.eval(a)).abs() <= 1e-12 * (1.0 + h.eval(a).abs()), "odd at {a}");
        }
    }
}

// ===========================================================================
// Linear manifold = eq. (60) (LFAM)
// ===========================================================================

/// Coefficients of prod_i (lambda + b_i), lowest power first.
fn poly_from_roots(b: &[f64]) -> Vec<f64> {
    let mut c = vec![1.0];
    for &bi in b {
        let mut next = vec![0.0; c.len() + 1];
        for (k, ck) in c.iter().enumerate() {
            next[k] += bi * ck;
            next[k + 1] += ck;
        }
        c = next;
    }
    c
}

fn check_lfam<const N: usize>(b: &[f64], z: &[f64]) -> Result<(), TestCaseError> {
    let laws: Vec<SkewedLaw<f64>> = b
        .iter()
        .take(N - 1)
        .map(|&k| SkewedLaw::new(Feedback::Linear { k }, None).unwrap_or_else(|e| panic!("{e}")))
        .collect();
    let mut zz = [0.0; N];
    zz.copy_from_slice(&z[..N]);
    let m = manifold::evaluate(&zz, &laws);
    // Every stage i: s_i = prod_{j < i} (d/dt + b_j) z1 = sum_k c_k z_{k+1}.
    for i in 0..N {
        let c = poly_from_roots(&b[..i]);
        let want: f64 = c.iter().zip(zz.iter()).map(|(ck, zk)| ck * zk).sum();
        let size: f64 = c.iter().zip(zz.iter()).map(|(ck, zk)| (ck * zk).abs()).sum();
        prop_assert!(
            (m.stages[i] - want).abs() <= 1e-12 * (1.0 + size),
            "N = {N}, s_{}: {} vs {want}",
            i + 1,
            m.stages[i]
        );
    }
    prop_assert_eq!(m.s(), m.stages[N - 1]);
    // s_prev = s_{n-1}, ds_prev = its time derivative = sum_k c_k z_{k+2}.
    let c = poly_from_roots(&b[..N - 2]);
    let want: f64 = c.iter().zip(zz.iter().skip(1)).map(|(ck, zk)| ck * zk).sum();
    let size: f64 = c
        .iter()
        .zip(zz.iter().skip(1))
        .map(|(ck, zk)| (ck * zk).abs())
        .sum();
    prop_assert!((m.s_prev - m.stages[N - 2]).abs() <= 1e-12 * (1.0 + m.s_prev.abs()));
    prop_assert!((m.ds_prev - want).abs() <= 1e-12 * (1.0 + size));
    Ok(())
}

proptest! {
    #![proptest_config(Config::with_cases(256))]

    /// With linear laws the iterative manifold is the polynomial of eq. (60) (LFAM):
    /// s = prod_i (d/dt + b_i) z1, for orders 2..6.
    #[test]
    fn linear_manifold_is_lfam(b in prop::array::uniform5(0.05..5.0f64), z in prop::array::uniform6(-10.0..10.0f64)) {
        check_lfam::<2>(&b, &z)?;
        check_lfam::<3>(&b, &z)?;
        check_lfam::<4>(&b, &z)?;
        check_lfam::<5>(&b, &z)?;
        check_lfam::<6>(&b, &z)?;
    }

    /// The nonlinear manifold is finite with NSMD stages at and near Z = 0.
    #[test]
    fn nsmd_manifold_finite(
        l1 in nsmd_law(), l2 in nsmd_law(), l3 in nsmd_law(),
        z1 in prop_oneof![Just(0.0), signed_log(-300.0, 0.5)],
        z in prop::array::uniform3(-10.0..10.0f64),
    ) {
        let m = manifold::evaluate(&[z1, z[0], z[1], z[2]], &[l1, l2, l3]);
        prop_assert!(m.stages.iter().all(|v| v.is_finite()), "{:?}", m);
        prop_assert!(m.s_prev.is_finite() && m.ds_prev.is_finite());
        prop_assert_eq!(m.stages[0], z1);
        // Stage 2 = z2 - h_m1(z1).
        prop_assert!((m.stages[1] - (z[0] - l1.eval(z1))).abs() <= 1e-12 * (1.0 + m.stages[1].abs()));
    }
}

// ===========================================================================
// Gamma maps
// ===========================================================================

proptest! {
    #![proptest_config(Config::with_cases(512))]

    /// Gamma is odd, increasing and finite on (-1, 1).
    #[test]
    fn gamma_odd_increasing_finite(a in -1.0..1.0f64, b in -1.0..1.0f64, e in 1.0..16.0f64) {
        let edge = 1.0 - 10f64.powf(-e);
        for g in [Gamma::Log, Gamma::Rational] {
            for x in [a, b, edge, -edge, 1.0 - f64::EPSILON / 2.0, -(1.0 - f64::EPSILON / 2.0)] {
                prop_assert!(g.eval(x).is_finite(), "{g:?}({x})");
                prop_assert_eq!(g.eval(-x), -g.eval(x), "{:?} not odd at {}", g, x);
                prop_assert!(g.eval(x) * x >= 0.0);
            }
            let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
            prop_assert!(g.eval(lo) <= g.eval(hi));
            if hi - lo > 1e-9 {
                prop_assert!(g.eval(lo) < g.eval(hi), "{g:?}: not increasing on {lo}, {hi}");
            }
        }
        prop_assert_eq!(Gamma::Log.eval(0.0), 0.0);
        prop_assert_eq!(Gamma::Rational.eval(0.0), 0.0);
    }
}

#[test]
fn gamma_closed_forms() {
    for x in [-0.9_f64, -0.3, 0.1, 0.5, 0.99] {
        let (log, rat) = (((1.0 + x) / (1.0 - x)).ln(), x / (1.0 - x * x));
        assert!((Gamma::Log.eval(x) - log).abs() < 1e-14 * log.abs());
        assert!((Gamma::Rational.eval(x) - rat).abs() < 1e-14 * rat.abs());
    }
    // Slopes at 0: 2 and 1.
    assert!((Gamma::Log.eval(1e-9_f64) / 1e-9 - 2.0).abs() < 1e-9);
    assert!((Gamma::Rational.eval(1e-9_f64) / 1e-9 - 1.0).abs() < 1e-9);
}

// ===========================================================================
// Corollaries 1-3: settling-time bounds of the paper's examples
// ===========================================================================

#[test]
fn corollary1_finite_time_bound() {
    // Example 1: k_c = 1, p = 0.5, z1(0) = -1: T_fn' = 2 s, so T_fn < 1 + 2 = 3 s.
    let t = bounds::finite_time(1.0_f64, 0.5, -1.0);
    assert!((t - 2.0).abs() < 1e-15, "T_fn' = {t}");
    assert!((1.0 + t - 3.0).abs() < 1e-15);
    assert!((bounds::finite_time(1.0_f32, 0.5, -1.0) - 2.0).abs() < 1e-6);
    // Scaling: |z1(0)|^(1-p) / (k (1-p)).
    assert!((bounds::finite_time(2.0_f64, 0.75, 16.0) - 2.0 / (2.0 * 0.25)).abs() < 1e-14);
}

#[test]
fn corollary2_variable_exponent_bound() {
    // Example 2: k = 1.5, r_b = 0.5, r_1 = 2, r_t = 3: T_fxe' ~ 3.32 s, T_fxe = 4.3 s.
    let t = bounds::variable_exponent(1.5_f64, 0.5, 2.0, 3.0);
    // Closed form: b = 1.5, a = 3.75: 1/(1.5 * 1) + 1/(1.5 e^{-3.75/(2e)} 0.5).
    let want = 1.0 / 1.5 + 1.0 / (1.5 * (-3.75 / (2.0 * std::f64::consts::E)).exp() * 0.5);
    assert!((t - want).abs() < 1e-14, "{t} vs {want}");
    assert!((t - 3.32).abs() < 0.005, "T_fxe' = {t}");
    assert!((1.0 + t - 4.3).abs() < 0.05, "T_fxe = {}", 1.0 + t);
    assert!((bounds::variable_exponent(1.5_f32, 0.5, 2.0, 3.0) as f64 - want).abs() < 1e-5);
}

#[test]
fn corollary3_fixed_time_bound() {
    // Example 3: stage 1 (1, 0.5, 0.5, 2): 2 + 2 = 4 s; stage 2 (2, 0.5, 1, 2): 1 + 1 = 2 s.
    let stages = [(1.0_f64, 0.5, 0.5, 2.0), (2.0, 0.5, 1.0, 2.0)];
    assert!((bounds::fixed_time_stage(1.0_f64, 0.5, 0.5, 2.0) - 4.0).abs() < 1e-15);
    assert!((bounds::fixed_time_stage(2.0_f64, 0.5, 1.0, 2.0) - 2.0).abs() < 1e-15);
    let t = bounds::fixed_time(&stages);
    assert!((t - 6.0).abs() < 1e-15, "T_fr' = {t}");
    assert!((1.0 + t - 7.0).abs() < 1e-15);
    let t32 = bounds::fixed_time(&[(1.0_f32, 0.5, 0.5, 2.0), (2.0, 0.5, 1.0, 2.0)]);
    assert!((t32 - 6.0).abs() < 1e-6);
    assert_eq!(bounds::fixed_time::<f64>(&[]), 0.0);
}
