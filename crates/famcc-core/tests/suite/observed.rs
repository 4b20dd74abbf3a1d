//! The law on the extended differentiator with the lumped term cancelled
//! (`ConfigBuilder::observer`, docs/observer.md): on a plant with a constant
//! load and a 20 % error in the nominal input gain, the holding-input floor of
//! the plain output-feedback controller goes, with the barrier kept (|xi| < 1)
//! and the command bounded; its configuration rules are named; its state
//! survives a snapshot; the output limits bound the total command.

use famcc_core::{
    Config, ConfigError, Constraint, Controller, Direction, Discretization, ExtendedHighGain, Feedback,
    HighGain, StepError,
};

const DT: f64 = 1e-3;
const G: f64 = 1.5; // the plant's true input gain
const LOAD: f64 = 2.0; // a constant load (input units x G)

/// `y'' = -0.5 y' - sin y + G u + LOAD`: one sample period with `u` held (RK4, 10 substeps).
fn plant_step(x: [f64; 2], u: f64) -> [f64; 2] {
    let f = |x: [f64; 2]| [x[1], -0.5 * x[1] - x[0].sin() + G * u + LOAD];
    let h = DT / 10.0;
    let mut x = x;
    for _ in 0..10 {
        let k1 = f(x);
        let k2 = f([x[0] + h / 2.0 * k1[0], x[1] + h / 2.0 * k1[1]]);
        let k3 = f([x[0] + h / 2.0 * k2[0], x[1] + h / 2.0 * k2[1]]);
        let k4 = f([x[0] + h * k3[0], x[1] + h * k3[1]]);
        for i in 0..2 {
            x[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
    }
    x
}

fn law(differentiator: Option<HighGain<f64, 2>>) -> Config<f64, 2> {
    Config::<f64, 2>::builder(
        DT,
        &[(Feedback::FiniteTime { k: 1.0, p: 0.7 }, None)],
        Constraint::Lateral { eps: 0.1 },
        5.0,
    )
    .differentiator(differentiator)
    .build()
    .expect("a valid law")
}

/// The law with the observer `obs`, the cancellation bounded by `delta`.
fn observed(obs: ExtendedHighGain<f64, 2>, delta: f64) -> Result<Controller<f64, 2>, ConfigError> {
    let cfg = law(None)
        .to_builder()
        .direction(Direction::of(obs.b0).unwrap_or_default())
        .observer(Some(obs))
        .cancellation_limit(Some(delta))
        .build()?;
    Ok(Controller::new(cfg))
}

/// 10 s regulating y to 0 from y = 1: the largest |e| over the last 2 s, the
/// largest |u|, and the largest |xi| after the first step.
fn run(mut step: impl FnMut(f64) -> (f64, f64)) -> (f64, f64, f64) {
    let (mut x, mut tail, mut u_max, mut xi_max) = ([1.0, 0.0], 0.0_f64, 0.0_f64, 0.0_f64);
    for k in 0..10_000 {
        let e = x[0];
        let (u, xi) = step(e);
        assert!(u.is_finite());
        if k > 0 {
            xi_max = xi_max.max(xi.abs());
        }
        if k >= 8_000 {
            tail = tail.max(e.abs());
        }
        u_max = u_max.max(u.abs());
        x = plant_step(x, u);
    }
    (tail, u_max, xi_max)
}

#[test]
fn the_cancellation_removes_the_holding_input_floor() {
    let mut plain = Controller::new(law(Some(HighGain::paper())));
    let (floor, _, xi_plain) = run(|e| (plain.step(e).unwrap(), plain.diagnostics().xi));
    for hold in [Discretization::Exact, Discretization::Foh] {
        let obs = ExtendedHighGain::binomial(0.02, 1.2 * G).with_discretization(hold); // b0 20 % high
        let mut ctrl = observed(obs, 4.0).unwrap();
        let (tail, u_max, xi) = run(|e| (ctrl.step(e).unwrap(), ctrl.diagnostics().xi));
        // The plain loop holds -LOAD / G = -1.33 through xi: |e| ~ eps tanh(1.33 / 10) ~ 0.013.
        assert!(floor > 5e-3, "the plain controller's floor {floor}");
        assert!(
            tail < 0.1 * floor,
            "{hold:?}: steady |e| {tail} against the plain floor {floor}"
        );
        assert!(
            xi < 1.0 && xi_plain < 1.0,
            "{hold:?}: max |xi| {xi} (plain {xi_plain})"
        );
        assert!(u_max < 5.0 * 1.0 + 4.0 + 1.0, "{hold:?}: max |u| {u_max}");
        // The cancellation carries the load: at rest u = -c holds it, c -> LOAD / G
        // whatever b0 (Lhat lumps the gain error in), and the law's v goes to 0.
        let c = ctrl.diagnostics().cancellation;
        assert!((c - LOAD / G).abs() < 1e-3, "{hold:?}: cancellation {c}");
    }
}

#[test]
fn the_cancellation_is_bounded() {
    // delta below what the load needs: c sits at the bound, the law holds the rest.
    let obs = ExtendedHighGain::binomial(0.02, G);
    let mut ctrl = observed(obs, 0.5).unwrap();
    let (tail, _, xi) = run(|e| (ctrl.step(e).unwrap(), ctrl.diagnostics().xi));
    assert_eq!(ctrl.diagnostics().cancellation, 0.5);
    assert!(tail < 0.1 && xi < 1.0, "steady |e| {tail}, max |xi| {xi}");
}

#[test]
fn bad_configurations_and_inputs_are_named() {
    let obs = ExtendedHighGain::binomial(0.02, G);
    let err = |b: famcc_core::ConfigBuilder<f64, 2>| b.build().unwrap_err().parameter;
    let with = |d: Option<f64>| law(None).to_builder().observer(Some(obs)).cancellation_limit(d);
    assert_eq!(
        err(with(Some(1.0)).differentiator(Some(HighGain::paper()))),
        "differentiator"
    );
    assert_eq!(err(with(Some(0.0))), "cancellation_limit");
    assert_eq!(err(with(Some(f64::NAN))), "cancellation_limit");
    // No bound and no finite output limits to take it from.
    assert_eq!(err(with(None)), "cancellation_limit");
    assert_eq!(
        err(with(None).output_limits(Some((-1.0, f64::INFINITY)))),
        "cancellation_limit"
    );
    // A bound without an observer bounds nothing.
    assert_eq!(
        err(law(None).to_builder().cancellation_limit(Some(1.0))),
        "cancellation_limit"
    );
    let integral = Config::<f64, 2>::builder(
        DT,
        &[(Feedback::Linear { k: 1.0 }, None)],
        Constraint::Longitudinal { eps: 0.1 },
        5.0,
    )
    .integral(true)
    .observer(Some(obs))
    .cancellation_limit(Some(1.0));
    assert_eq!(err(integral), "integral");
    let bad = ExtendedHighGain { b0: 0.0, ..obs };
    assert_eq!(observed(bad, 1.0).unwrap_err().parameter, "b0");
    // The default bound: half the output range.
    let cfg = with(None).output_limits(Some((-3.0, 5.0))).build().unwrap();
    assert_eq!(cfg.cancellation_limit(), Some(4.0));
    assert_eq!(cfg.observer(), Some(&obs));
    assert_eq!(cfg.to_builder().build(), Ok(cfg));
    let mut ctrl = observed(obs, 1.0).unwrap();
    assert_eq!(ctrl.step(f64::NAN), Err(StepError::NonFiniteInput));
    assert_eq!(
        ctrl.step_applied(0.1, Some(f64::INFINITY)),
        Err(StepError::NonFiniteApplied)
    );
    let before = ctrl;
    assert_eq!(ctrl.step(f64::INFINITY), Err(StepError::NonFiniteInput));
    assert_eq!(ctrl, before); // nothing changed
    let u = ctrl.step(0.3).unwrap();
    ctrl.reset();
    assert_eq!(ctrl, before);
    assert_eq!(ctrl.step(0.3), Ok(u));
}

#[test]
fn an_applied_input_drives_the_observer() {
    // Told that the actuator gave 0 instead of the command, the observer's next
    // estimate differs from the one that takes the command as applied.
    let obs = ExtendedHighGain::binomial(0.02, G);
    let mut a = observed(obs, 1.0).unwrap();
    let mut b = a;
    let ua = a.step(0.5).unwrap();
    assert_eq!(b.step(0.5), Ok(ua));
    a.step(0.49).unwrap();
    b.step_applied(0.49, Some(0.0)).unwrap();
    assert!(ua != 0.0 && a.estimate() != b.estimate());
}

mod adversarial {
    use super::*;
    use proptest::prelude::*;

    fn finite_or_wild() -> impl Strategy<Value = f64> {
        prop_oneof![
            3 => -1.0_f64..1.0,
            1 => -1e6_f64..1e6,
            1 => prop::sample::select(vec![1e300, -1e300, 1e-300, f64::MAX, -f64::MAX, f64::NAN, f64::INFINITY, 0.0]),
        ]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]

        /// Any inputs: no panic, every Ok finite, a non-finite input changes
        /// nothing; after any prefix, a moderate tail is Ok again within a few samples.
        #[test]
        fn it_recovers_from_any_input(
            mu in 0.005_f64..0.1,
            b0 in prop_oneof![-20.0_f64..-0.05, 0.05_f64..20.0],
            delta in 0.01_f64..50.0,
            foh in any::<bool>(),
            prefix in prop::collection::vec((finite_or_wild(), prop::option::of(finite_or_wild())), 0..30),
            tail in prop::collection::vec(-1.0_f64..1.0, 40),
        ) {
            let hold = if foh { Discretization::Foh } else { Discretization::Exact };
            let obs = ExtendedHighGain::binomial(mu, b0).with_discretization(hold);
            let mut ctrl = observed(obs, delta).unwrap();
            for (e, applied) in prefix {
                let before = ctrl;
                match ctrl.step_applied(e, applied) {
                    Ok(u) => prop_assert!(u.is_finite()),
                    Err(StepError::NonFiniteInput | StepError::NonFiniteApplied) => prop_assert_eq!(ctrl, before),
                    Err(_) => {}
                }
            }
            let mut results = Vec::new();
            for e in tail {
                let r = ctrl.step(e);
                if let Ok(u) = r {
                    prop_assert!(u.is_finite());
                }
                results.push(r.is_ok());
            }
            prop_assert!(results[5..].iter().all(|&ok| ok), "moderate tail: {:?}", results);
        }
    }
}
