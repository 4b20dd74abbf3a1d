//! The differentiator's low-pass prefilter (`HighGain::with_prefilter`, not in
//! the paper): the estimate a controller keeps against a by-hand recursion,
//! its restart, and its state carried by a snapshot.
#![allow(
    clippy::unwrap_used,
    clippy::indexing_slicing,
    clippy::float_cmp,
    clippy::needless_range_loop
)]

use famcc_core::{Config, Constraint, Controller, Discretization, Feedback, HighGain, Snapshot};

const DT: f64 = 1e-3;
const MU: f64 = 0.01;
const TAU: f64 = 0.004;

fn config(tau: f64, d: Discretization) -> Result<Config<f64, 2>, famcc_core::ConfigError> {
    let h = HighGain::new(MU, [4.0, 4.0], d).with_prefilter(tau);
    Config::<f64, 2>::builder(
        DT,
        &[(Feedback::Linear { k: 2.0 }, None)],
        Constraint::Longitudinal { eps: 0.5 },
        5.0,
    )
    .differentiator(Some(h))
    .build()
}

fn controller(tau: f64) -> Controller<f64, 2> {
    Controller::new(config(tau, Discretization::Euler).unwrap())
}

/// A sampled sine with an alternating disturbance (a noise of the highest
/// frequency the samples carry).
fn sample(k: usize) -> f64 {
    0.3 * (2.0 * k as f64 * DT).sin() + if k % 2 == 0 { 0.01 } else { -0.01 }
}

/// Euler by hand: `Phi = I + M dt` with `M = [[-a1/mu, 1], [-a2/mu^2, 0]]`,
/// `Gamma = (a1/mu, a2/mu^2) dt`; the prefilter `f_k = f + b (e_k - f)` with
/// `b = 1 - exp(-dt/tau)` and `f_0 = e_0`; the first estimate `(e_0, 0)`.
fn by_hand(steps: usize) -> std::vec::Vec<[f64; 2]> {
    let (h1, h2) = (4.0 / MU, 4.0 / (MU * MU));
    let b = 1.0 - (-DT / TAU).exp();
    let mut out = std::vec::Vec::new();
    let (mut z, mut f) = ([sample(0), 0.0], sample(0));
    for k in 0..steps {
        let e = sample(k);
        if k > 0 {
            f += b * (e - f);
        }
        z = [
            z[0] + DT * (-h1 * z[0] + z[1]) + DT * h1 * f,
            z[1] - DT * h2 * z[0] + DT * h2 * f,
        ];
        out.push(z);
    }
    out
}

#[test]
fn a_prefilter_feeds_the_differentiator_the_low_pass_error() {
    let mut c = controller(TAU);
    let want = by_hand(400);
    for (k, w) in want.iter().enumerate() {
        c.step(sample(k)).unwrap();
        for i in 0..2 {
            let got = c.estimate()[i];
            assert!(
                (got - w[i]).abs() <= 1e-9 * (1.0 + w[i].abs()),
                "step {k}, z_hat[{i}]: {got} vs {}",
                w[i]
            );
        }
        assert!((c.snapshot().filtered - if k == 0 { sample(0) } else { 0.0 }).abs() < 1.0);
    }
    // The alternating disturbance reaches the derivative estimate attenuated:
    // its sample-to-sample swing is smaller than without the prefilter.
    let swing = |c: &mut Controller<f64, 2>| {
        let mut prev = 0.0;
        let mut worst: f64 = 0.0;
        for k in 0..400 {
            c.step(sample(k)).unwrap();
            let z2 = c.estimate()[1];
            if k > 200 {
                worst = worst.max((z2 - prev).abs());
            }
            prev = z2;
        }
        worst
    };
    let (with, without) = (swing(&mut controller(TAU)), swing(&mut controller(0.0)));
    assert!(
        with < 0.5 * without,
        "swing {with} with the prefilter, {without} without"
    );
}

#[test]
fn without_a_prefilter_the_differentiator_reads_the_sample_itself() {
    let mut c = controller(0.0);
    for k in 0..50 {
        c.step(sample(k)).unwrap();
        assert_eq!(c.snapshot().filtered, sample(k));
    }
    let d = HighGain::new(MU, [4.0, 4.0], Discretization::Exact)
        .discretize(DT)
        .unwrap();
    assert_eq!(d.prefilter, 1.0);
    assert_eq!(d.filter(7.0, -0.0).to_bits(), (-0.0_f64).to_bits());
}

#[test]
fn a_snapshot_carries_the_prefilter_state() {
    let mut a = controller(TAU);
    for k in 0..60 {
        a.step(sample(k)).unwrap();
    }
    let snap = a.snapshot();
    let mut flat = [0.0; Snapshot::<f64, 2>::LEN];
    snap.to_array(&mut flat).unwrap();
    assert_eq!(
        flat[Snapshot::<f64, 2>::FIELDS
            .iter()
            .position(|f| *f == "filtered")
            .unwrap()],
        snap.filtered
    );
    let mut b = controller(TAU);
    b.restore(&Snapshot::from_array(&flat).unwrap()).unwrap();
    for k in 60..120 {
        assert_eq!(a.step(sample(k)), b.step(sample(k)), "step {k}");
    }
    // Another prefilter state gives another estimate: the field is used.
    let mut moved = snap;
    moved.filtered += 1.0;
    let (mut c, mut d) = (controller(TAU), controller(TAU));
    c.restore(&snap).unwrap();
    d.restore(&moved).unwrap();
    c.step(0.0).unwrap();
    d.step(0.0).unwrap();
    assert_ne!(c.estimate(), d.estimate());
    moved.filtered = f64::INFINITY;
    assert_eq!(
        controller(TAU).restore(&moved).unwrap_err().parameter,
        "state.filtered"
    );
}

#[test]
fn the_prefilter_restarts_at_the_sample_after_an_unusable_one() {
    let mut c = controller(TAU);
    for k in 0..20 {
        c.step(sample(k)).unwrap();
    }
    // A sample that takes the estimate out of range is consumed; the estimate
    // and the prefilter restart (from a zero error, the sample being the outlier).
    assert!(c.step(1e300).is_err());
    assert_eq!(c.snapshot().filtered, 0.0);
    // A moderate sample then steps again, from the restarted filter.
    let before = c.snapshot().filtered;
    c.step(0.2).unwrap();
    let b = 1.0 - (-DT / TAU).exp();
    assert!((c.snapshot().filtered - (before + b * (0.2 - before))).abs() < 1e-15);
}

#[test]
fn a_negative_or_non_finite_prefilter_is_rejected_by_name() {
    for tau in [-1e-3, f64::NAN, f64::INFINITY] {
        let e = config(tau, Discretization::Exact).unwrap_err();
        assert_eq!(e.parameter, "prefilter", "tau = {tau}");
    }
}
