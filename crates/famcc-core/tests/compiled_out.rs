//! The Cargo features (src/compiled.rs): a design whose law, skew,
//! transition or constraint type is compiled out is rejected by `build`
//! with an error that names the feature, and a design that needs none of
//! them runs. Run in both worlds by scripts/test.sh: the default build
//! (everything compiled: every design builds) and
//! `--no-default-features` (every optional variant rejected).

use famcc_core::{Config, Constraint, Controller, Discretization, Feedback, HighGain, Skew, Transition};

type Stage = (Feedback<f32>, Option<Skew<f32>>);

const FINITE: Feedback<f32> = Feedback::FiniteTime { k: 1.0, p: 0.5 };
const LONGITUDINAL: Constraint<f32> = Constraint::Longitudinal { eps: 0.1 };

fn build(
    stage: Stage,
    constraint: Constraint<f32>,
    transition: Transition,
) -> Result<Config<f32, 2>, famcc_core::ConfigError> {
    Config::<f32, 2>::builder(1e-3, &[stage], constraint, 5.0)
        .transition(transition)
        .build()
}

/// `build` succeeds exactly when `feature` is compiled, and otherwise names it.
fn check(what: &str, feature: &str, built: Result<Config<f32, 2>, famcc_core::ConfigError>, compiled: bool) {
    match built {
        Ok(_) => assert!(compiled, "{what}: built, but feature `{feature}` is off"),
        Err(e) => {
            assert!(!compiled, "{what}: rejected with feature `{feature}` on: {e}");
            let shown = e.to_string();
            assert!(
                shown.contains(&format!("Cargo feature `{feature}`")),
                "{what}: the error does not name the feature: {shown}"
            );
        }
    }
}

#[test]
fn each_optional_variant_builds_exactly_when_its_feature_is_compiled() {
    let fixed = Feedback::FixedTime {
        alpha: 1.0,
        p: 0.5,
        beta: 1.0,
        q: 1.5,
    };
    let variable = Feedback::VariableExponent {
        k: 1.0,
        r_b: 0.5,
        r_1: 1.5,
        r_t: 2.0,
    };
    let moulay = Feedback::MoulayDiscontinuous {
        beta: 1.0,
        lambda: 1.0,
        mu: 0.5,
    };
    let skew = Skew::nonsingular(0.2, 0.1, 0.1);
    let sine_skew = Skew {
        transition: Transition::Sine,
        ..skew
    };
    let exp = Transition::Exponential;
    let cases = [
        (
            "fixed-time law",
            "fixed-time",
            build((fixed, None), LONGITUDINAL, exp),
            cfg!(feature = "fixed-time"),
        ),
        (
            "variable-exponent law",
            "variable-exponent",
            build((variable, None), LONGITUDINAL, exp),
            cfg!(feature = "variable-exponent"),
        ),
        (
            "Moulay's law",
            "variable-exponent",
            build((moulay, None), LONGITUDINAL, exp),
            cfg!(feature = "variable-exponent"),
        ),
        (
            "NSMD skew",
            "skew",
            build((FINITE, Some(skew)), LONGITUDINAL, exp),
            cfg!(feature = "skew"),
        ),
        (
            "lateral constraint",
            "lateral",
            build((FINITE, None), Constraint::Lateral { eps: 0.1 }, exp),
            cfg!(feature = "lateral"),
        ),
        (
            "oblique constraint",
            "oblique",
            build(
                (FINITE, None),
                Constraint::Oblique {
                    eps_x: 0.1,
                    eps_y: 0.1,
                },
                exp,
            ),
            cfg!(feature = "oblique"),
        ),
        (
            "sine boundary transition",
            "sine",
            build((FINITE, None), LONGITUDINAL, Transition::Sine),
            cfg!(feature = "sine"),
        ),
    ];
    for (what, feature, built, compiled) in cases {
        check(what, feature, built, compiled);
    }
    let option = |b: famcc_core::ConfigBuilder<f32, 2>| b.build();
    let plain = Config::<f32, 2>::builder(1e-3, &[(FINITE, None)], LONGITUDINAL, 5.0);
    check(
        "bumpless start",
        "bumpless",
        option(plain.initial_output(Some(1.0))),
        cfg!(feature = "bumpless"),
    );
    check(
        "integral action",
        "integral",
        option(plain.integral(true)),
        cfg!(feature = "integral"),
    );
    let foh = HighGain {
        discretization: Discretization::Foh,
        ..HighGain::paper()
    };
    check(
        "first-order hold",
        "first-order-hold",
        option(plain.differentiator(Some(foh))),
        cfg!(feature = "first-order-hold"),
    );
    // A sine skew needs both features: without `skew` the skew is named first.
    if cfg!(feature = "skew") {
        let built = build((FINITE, Some(sine_skew)), LONGITUDINAL, exp);
        check("sine skew transition", "sine", built, cfg!(feature = "sine"));
    }
}

#[test]
fn a_one_off_period_steps_exactly_when_its_feature_is_compiled() {
    let built = Config::<f32, 2>::builder(1e-3, &[(FINITE, None)], LONGITUDINAL, 5.0)
        .differentiator(Some(HighGain::paper()))
        .build();
    let Ok(cfg) = built else {
        panic!("the always-compiled design was rejected: {built:?}");
    };
    let mut c = Controller::new(cfg);
    // The nominal period through step_dt is always accepted.
    assert!(c.step_dt(0.5, 1e-3, None).is_ok());
    let other = c.step_dt(0.5, 2e-3, None);
    assert_eq!(other.is_ok(), cfg!(feature = "one-off-period"), "{other:?}");
    // A state taken at another period restores exactly when one-off periods
    // are compiled (and names the feature otherwise).
    let mut snap = c.snapshot();
    snap.period = 2e-3;
    let restored = Controller::new(cfg).restore(&snap);
    assert_eq!(restored.is_ok(), cfg!(feature = "one-off-period"), "{restored:?}");
    if let Err(e) = restored {
        assert!(e.to_string().contains("Cargo feature `one-off-period`"), "{e}");
    }
}

/// A precomputed recursion with the first-order hold's feedthrough (computed
/// on a host that has it) is rejected where the hold is compiled out, not
/// run without its feedthrough.
#[test]
fn a_precomputed_first_order_hold_runs_exactly_when_its_feature_is_compiled() {
    let mut d = HighGain::<f32, 2>::paper()
        .discretize(1e-3)
        .unwrap_or_else(|e| panic!("{e}"));
    d.feedthrough = [0.5, 25.0];
    let built = Config::<f32, 2>::builder(1e-3, &[(FINITE, None)], LONGITUDINAL, 5.0)
        .differentiator(Some(HighGain::paper()))
        .build_discretized(d);
    check(
        "precomputed first-order hold",
        "first-order-hold",
        built,
        cfg!(feature = "first-order-hold"),
    );
}

#[test]
fn a_design_that_needs_no_optional_feature_builds_and_settles() {
    // Finite-time law, longitudinal constraint, exponential transition: in
    // every build. The double integrator z1'' = u from z1 = 1 settles
    // within the envelope's final width 0.1 well before 10 s.
    let Ok(cfg) = build((FINITE, None), LONGITUDINAL, Transition::Exponential) else {
        panic!("the always-compiled design was rejected");
    };
    let mut c = Controller::new(cfg);
    let (dt, mut x, mut v) = (1e-3_f32, 1.0_f32, 0.0_f32);
    let mut worst_late = 0.0_f32;
    let mut digest = 0xcbf2_9ce4_8422_2325_u64;
    for k in 0..10_000 {
        let u = c.step_state([x, v]).expect("a finite state steps");
        digest = (digest ^ u64::from(u.to_bits())).wrapping_mul(0x0100_0000_01b3);
        v += dt * u.clamp(-100.0, 100.0);
        x += dt * v;
        if k >= 8_000 {
            worst_late = worst_late.max(x.abs());
        }
    }
    assert!(worst_late < 0.1, "|z1| after 8 s: {worst_late}");
    // The features remove code only: the outputs are bit-identical in
    // every build (FNV-1a of the 10,000 outputs' bits, recorded from the
    // default build).
    assert_eq!(
        digest, DIGEST,
        "the outputs differ from the default build's: {digest:#x}"
    );
}

const DIGEST: u64 = 0x701e_75fa_52df_6b03;
