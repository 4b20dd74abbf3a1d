//! The observer's part of the controller's state and step options
//! (docs/observer.md): a snapshot carries `Lhat` and continues bit for bit,
//! a plain controller refuses a state with one, the output limits bound the
//! total command, a one-off period rediscretizes the observer, and a
//! state-feedback step keeps the observer tracking.

use famcc_core::{Config, Constraint, Controller, ExtendedHighGain, Feedback, Snapshot};

const DT: f64 = 1e-3;

fn builder() -> famcc_core::ConfigBuilder<f64, 2> {
    Config::<f64, 2>::builder(
        DT,
        &[(Feedback::FiniteTime { k: 1.0, p: 0.7 }, None)],
        Constraint::Lateral { eps: 0.1 },
        5.0,
    )
}

fn observed(limits: Option<(f64, f64)>) -> Controller<f64, 2> {
    let obs = ExtendedHighGain::binomial(0.02, 1.5);
    let cfg = builder()
        .observer(Some(obs))
        .cancellation_limit(Some(3.0))
        .output_limits(limits)
        .build()
        .unwrap();
    Controller::new(cfg)
}

/// An error sample of a slow decaying oscillation with a bias (the observer
/// then holds a nonzero Lhat).
fn e(k: usize) -> f64 {
    let t = k as f64 * DT;
    0.3 + (-t).exp() * (3.0 * t).sin()
}

#[test]
fn a_snapshot_carries_the_lumped_estimate() {
    let mut a = observed(None);
    for k in 0..500 {
        a.step(e(k)).unwrap();
    }
    let snap = a.snapshot();
    assert!(snap.lhat != 0.0 && snap.lhat == a.lumped());
    let mut flat = [0.0; Snapshot::<f64, 2>::LEN];
    snap.to_array(&mut flat).unwrap();
    let at = Snapshot::<f64, 2>::FIELDS
        .iter()
        .position(|f| *f == "lhat")
        .unwrap();
    assert_eq!(flat[at], snap.lhat);
    let mut b = observed(None);
    b.restore(&Snapshot::from_array(&flat).unwrap()).unwrap();
    for k in 500..700 {
        assert_eq!(a.step(e(k)), b.step(e(k)));
        assert_eq!(a.lumped(), b.lumped());
    }
    // Without Lhat the continuation differs: the state is really used.
    let mut c = observed(None);
    c.restore(&Snapshot { lhat: 0.0, ..snap }).unwrap();
    let mut d = observed(None);
    d.restore(&snap).unwrap();
    assert_ne!(c.step(e(500)), d.step(e(500)));
    // Out of range, or into a controller without an observer: named.
    let wild = Snapshot {
        lhat: f64::MAX,
        ..snap
    };
    assert_eq!(d.restore(&wild).unwrap_err().parameter, "state.lhat");
    let plain_cfg = builder().build().unwrap();
    let mut plain = Controller::new(plain_cfg);
    plain.step_state([0.1, 0.0]).unwrap();
    let theirs = Snapshot {
        lhat: 0.5,
        ..plain.snapshot()
    };
    assert_eq!(plain.restore(&theirs).unwrap_err().parameter, "state.lhat");
}

#[test]
fn the_output_limits_bound_the_total_command() {
    let mut ctrl = observed(Some((-2.0, 2.0)));
    let mut at_limit = 0;
    for k in 0..3000 {
        // A large error drives v and c together to one side.
        let u = ctrl.step(2.0 * e(k)).unwrap();
        assert!((-2.0..=2.0).contains(&u), "u = {u} outside the limits");
        let d = ctrl.diagnostics();
        assert_eq!(d.v, u);
        assert!(d.cancellation.abs() <= 3.0);
        at_limit += usize::from(u.abs() == 2.0 && d.v_unlimited.abs() > 2.0);
    }
    assert!(
        at_limit > 0,
        "the limits were never reached: the test tests nothing"
    );
}

#[test]
fn a_one_off_period_rediscretizes_the_observer() {
    // At the nominal period step_dt is step; at another it differs, and a
    // controller stepped at 2 ms throughout tracks as one built for 2 ms.
    let (mut a, mut b) = (observed(None), observed(None));
    for k in 0..50 {
        assert_eq!(a.step(e(k)), b.step_dt(e(k), DT, None));
    }
    let mut c = observed(None);
    let obs = ExtendedHighGain::binomial(0.02, 1.5);
    let cfg2 = builder()
        .dt(2.0 * DT)
        .observer(Some(obs))
        .cancellation_limit(Some(3.0))
        .build()
        .unwrap();
    let mut d = Controller::new(cfg2);
    for k in 0..400 {
        let (uc, ud) = (
            c.step_dt(e(2 * k), 2.0 * DT, None).unwrap(),
            d.step(e(2 * k)).unwrap(),
        );
        assert!(
            (uc - ud).abs() <= 1e-9 * (1.0 + ud.abs()),
            "k {k}: {uc} against {ud}"
        );
    }
    assert!(c.lumped() != 0.0 && (c.lumped() - d.lumped()).abs() <= 1e-9 * (1.0 + d.lumped().abs()));
}

#[test]
fn a_state_feedback_step_keeps_the_observer_tracking() {
    // The law uses the measured vector; the observer still tracks z1, so a
    // later output-feedback step starts from a converged estimate.
    let (mut a, mut b) = (observed(None), observed(None));
    for k in 0..1000 {
        let ek = e(k);
        let de = (e(k + 1) - e(k.saturating_sub(1))) / (2.0 * DT);
        a.step_state([ek, de]).unwrap();
        assert_eq!(a.diagnostics().z_hat, [ek, de]);
        b.step(ek).unwrap();
    }
    assert!((a.estimate()[0] - e(999)).abs() < 1e-3);
    assert!(a.lumped() != 0.0);
}
