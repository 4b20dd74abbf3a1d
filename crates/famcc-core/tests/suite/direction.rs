//! The control direction (src/direction.rs): a controller with
//! `Direction::Negative` is, output for output and bit for bit, the paper's
//! controller on the reversed input (limits, rate limit, initial output,
//! applied inputs and the observer's `b0` mirrored), with integral action and
//! the bumpless start; it regulates a plant with `G < 0` that the positive
//! direction drives away; an observer whose `b0` has the other sign is named.
#![allow(clippy::unwrap_used, clippy::indexing_slicing)]

use famcc_core::{
    Config, ConfigBuilder, Constraint, Controller, Direction, Discretization, Feedback, HighGain,
};
use proptest::prelude::*;

const DT: f64 = 1e-3;

/// Order 2: FiniteTime on the lateral constraint, with the given output
/// limits, rate limit and initial output.
fn builder2(limits: Option<(f64, f64)>, rate: Option<f64>, u0: Option<f64>) -> ConfigBuilder<f64, 2> {
    Config::<f64, 2>::builder(
        DT,
        &[(Feedback::FiniteTime { k: 2.0, p: 0.6 }, None)],
        Constraint::Lateral { eps: 0.1 },
        4.0,
    )
    .differentiator(Some(HighGain::paper()))
    .output_limits(limits)
    .rate_limit(rate)
    .initial_output(u0)
}

/// Order 3 with integral action: Linear stages, longitudinal, the first-order
/// hold, with the given output limits, rate limit and initial output.
fn builder3(limits: Option<(f64, f64)>, rate: Option<f64>, u0: Option<f64>) -> ConfigBuilder<f64, 3> {
    let a = [4.0, 4.0, 0.0];
    Config::<f64, 3>::builder(
        DT,
        &[
            (Feedback::Linear { k: 2.0 }, None),
            (Feedback::Linear { k: 2.0 }, None),
        ],
        Constraint::Longitudinal { eps: 2.0 },
        3.0,
    )
    .differentiator(Some(HighGain::new(0.01, a, Discretization::Foh)))
    .integral(true)
    .output_limits(limits)
    .rate_limit(rate)
    .initial_output(u0)
}

fn mirrored(limits: Option<(f64, f64)>) -> Option<(f64, f64)> {
    limits.map(|(lo, hi)| (-hi, -lo))
}

/// Steps `pos` and `neg` on the same errors, `neg` told the mirrored applied
/// inputs: every output and error exactly mirrored.
fn assert_mirrored<const N: usize>(
    mut pos: Controller<f64, N>,
    mut neg: Controller<f64, N>,
    stream: &[(f64, Option<f64>)],
) -> Result<(), TestCaseError> {
    for &(e, applied) in stream {
        let a = pos.step_applied(e, applied);
        let b = neg.step_applied(e, applied.map(|u| -u));
        match (a, b) {
            (Ok(u), Ok(v)) => prop_assert_eq!(u.to_bits(), (-v).to_bits(), "e = {}", e),
            (a, b) => prop_assert_eq!(a, b.map(|v| -v)),
        }
        prop_assert_eq!(pos.diagnostics().xi.to_bits(), neg.diagnostics().xi.to_bits());
        prop_assert_eq!(
            pos.diagnostics().integrating,
            neg.diagnostics().integrating,
            "e = {} {:?} {:?}",
            e,
            pos.diagnostics(),
            neg.diagnostics()
        );
    }
    Ok(())
}

fn stream() -> impl Strategy<Value = Vec<(f64, Option<f64>)>> {
    prop::collection::vec(
        (-2.0_f64..2.0, prop::option::weighted(0.3, -5.0_f64..5.0)),
        1..120,
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn a_negative_direction_is_the_law_on_the_reversed_input(
        limited in any::<bool>(),
        lo in -3.0_f64..-0.2,
        hi in 0.2_f64..3.0,
        rate in prop::option::of(5.0_f64..500.0),
        u0 in prop::option::of(-2.0_f64..2.0),
        order3 in any::<bool>(),
        stream in stream(),
    ) {
        let limits = limited.then_some((lo, hi));
        let neg_u0 = u0.map(|u| -u);
        if order3 {
            let pos = builder3(limits, rate, u0).build().unwrap();
            let neg = builder3(mirrored(limits), rate, neg_u0).direction(Direction::Negative).build().unwrap();
            assert_mirrored(Controller::new(pos), Controller::new(neg), &stream)?;
        } else {
            let pos = builder2(limits, rate, u0).build().unwrap();
            let neg = builder2(mirrored(limits), rate, neg_u0).direction(Direction::Negative).build().unwrap();
            assert_mirrored(Controller::new(pos), Controller::new(neg), &stream)?;
        }
    }
}

#[cfg(feature = "observer")]
proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    /// With the observer: `b0 -> -b0` and the reversed input give the same
    /// estimates, so the mirrored outputs (the cancellation included).
    #[test]
    fn the_observer_follows_the_direction(
        b0 in 0.1_f64..20.0,
        mu in 0.005_f64..0.1,
        foh in any::<bool>(),
        stream in stream(),
    ) {
        let hold = if foh { Discretization::Foh } else { Discretization::Exact };
        let obs = |b0: f64| Some(famcc_core::ExtendedHighGain::binomial(mu, b0).with_discretization(hold));
        let b = |b0: f64, limits| builder2(limits, None, None)
            .differentiator(None)
            .observer(obs(b0))
            .cancellation_limit(Some(3.0));
        let pos = b(b0, Some((-1.0, 4.0))).build().unwrap();
        let neg = b(-b0, Some((-4.0, 1.0))).direction(Direction::Negative).build().unwrap();
        assert_mirrored(Controller::new(pos), Controller::new(neg), &stream)?;
    }
}

/// `y'' = -y' + G u + 1` with `G = -2`, from `y = 0.5` to 0 under |u| <= 5:
/// the largest |e| over the last second of 6 s (semi-implicit Euler).
fn regulate(direction: Direction) -> f64 {
    let cfg = builder2(Some((-5.0, 5.0)), None, None)
        .direction(direction)
        .build()
        .unwrap();
    let mut c = Controller::new(cfg);
    let (mut y, mut v, mut tail) = (0.5_f64, 0.0_f64, 0.0_f64);
    for k in 0..6_000 {
        let u = c.step(y).unwrap_or(0.0);
        for _ in 0..10 {
            v += DT / 10.0 * (-v - 2.0 * u + 1.0);
            y += DT / 10.0 * v;
        }
        if k >= 5_000 {
            tail = tail.max(y.abs());
        }
    }
    tail
}

#[test]
fn a_negative_gain_plant_is_regulated_only_in_its_direction() {
    let right = regulate(Direction::Negative);
    assert!(right < 0.1, "negative direction: tail {right}");
    let wrong = regulate(Direction::Positive);
    assert!(
        wrong >= 0.1 || wrong.is_nan(),
        "positive direction on G < 0 settled: tail {wrong}"
    );
}

#[cfg(feature = "observer")]
#[test]
fn an_observer_of_the_other_sign_is_named() {
    let obs = |b0: f64| Some(famcc_core::ExtendedHighGain::binomial(0.02, b0));
    for (b0, dir) in [(-1.5, Direction::Positive), (1.5, Direction::Negative)] {
        let err = builder2(None, None, None)
            .differentiator(None)
            .observer(obs(b0))
            .cancellation_limit(Some(2.0))
            .direction(dir)
            .build()
            .unwrap_err();
        assert_eq!(err.parameter, "b0", "{err}");
        assert!(err.to_string().contains("direction"), "{err}");
    }
}

#[test]
fn the_direction_survives_to_builder() {
    let cfg = builder2(None, None, None)
        .direction(Direction::Negative)
        .build()
        .unwrap();
    assert_eq!(cfg.direction(), Direction::Negative);
    assert_eq!(cfg.to_builder().build().unwrap(), cfg);
    assert_eq!(
        builder2(None, None, None).build().unwrap().direction(),
        Direction::Positive
    );
}
