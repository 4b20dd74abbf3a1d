//! The clock (docs/design.md §3.10) is exact to one sample for 10^10 steps
//! and more, in f32 and f64, on `step` and `step_dt`; `restore` checks every
//! field of a snapshot, and the counters saturate instead of overflowing
//! (this file runs with overflow checks on: the test profile, Cargo.toml).
#![allow(clippy::unwrap_used, clippy::indexing_slicing)]

use famcc_core::{Config, Constraint, Controller, HighGain, Real, Snapshot};

fn controller<T: Real>() -> Controller<T, 2> {
    let laws = [(famcc_core::Feedback::Linear { k: T::one() }, None)];
    let cfg = Config::<T, 2>::builder(
        T::from_f64(1e-3),
        &laws,
        Constraint::Lateral {
            eps: T::from_f64(0.1),
        },
        T::from_f64(5.0),
    )
    .differentiator(Some(HighGain::paper()))
    .build()
    .unwrap();
    Controller::new(cfg)
}

/// A started controller moved to sample `k` of a run at `period`.
fn at<T: Real>(k: u64, period: T) -> Controller<T, 2> {
    let mut c = controller::<T>();
    c.step(T::from_f64(0.1)).unwrap();
    let mut s = c.snapshot();
    s.k = k;
    s.period = period;
    c.restore(&s).unwrap();
    c
}

#[test]
fn the_clock_is_exact_after_ten_billion_steps() {
    fn check<T: Real>() {
        let dt = T::from_f64(1e-3);
        for period in [dt, T::from_f64(2.5e-3)] {
            let k0 = 10_000_000_000u64;
            let mut c = at::<T>(k0, period);
            let p = period.to_f64_lossless();
            for j in 0..1000u64 {
                let t = c.time();
                assert_eq!(t, (k0 + j) as f64 * p, "{}", core::any::type_name::<T>());
                let r = if period == dt {
                    c.step(T::from_f64(0.1))
                } else {
                    c.step_dt(T::from_f64(0.1), period, None)
                };
                r.unwrap();
                assert_eq!(c.diagnostics().t, t);
                assert!(c.time() > t, "the clock stalled at {t}");
            }
            assert!(c.time() > 1e7);
        }
    }
    check::<f32>();
    check::<f64>();
}

/// `step_dt` with changing periods: one rounding per change, far below a
/// sample after 5 10^4 changes (the f32 clock used to freeze at 32,768 s).
#[test]
fn changing_periods_do_not_drift() {
    fn check<T: Real>() {
        let mut c = at::<T>(100_000_000, T::from_f64(1e-3)); // t = 1e5 s
        let periods = [T::from_f64(1e-3), T::from_f64(1.1e-3), T::from_f64(0.9e-3)];
        let mut exact = c.time();
        let mut compensation = 0.0_f64;
        for j in 0..50_000usize {
            let dt = periods[j % 3];
            c.step_dt(T::from_f64(0.1), dt, None).unwrap();
            // Kahan summation of the exact periods, as a reference.
            let y = dt.to_f64_lossless() - compensation;
            let t = exact + y;
            compensation = (t - exact) - y;
            exact = t;
        }
        assert!((c.time() - exact).abs() < 1e-6, "{} vs {exact}", c.time());
    }
    check::<f32>();
    check::<f64>();
}

#[test]
fn saturated_counters_step_without_overflow() {
    let mut c = controller::<f64>();
    c.step(0.1).unwrap();
    let mut s = c.snapshot();
    s.k = u64::MAX;
    s.clamp_count = u64::MAX;
    c.restore(&s).unwrap();
    for _ in 0..3 {
        c.step(5.0).unwrap();
        assert!(c.time().is_finite());
    }
    assert_eq!(c.samples(), u64::MAX);
    assert_eq!(c.diagnostics().clamp_count, u64::MAX);
    // The flat layout caps the counts at 2^53 (exact in f64).
    let mut flat = [0.0; Snapshot::<f64, 2>::LEN];
    c.snapshot().to_array(&mut flat).unwrap();
    assert_eq!(flat[2], 9_007_199_254_740_992.0);
}

#[test]
fn restore_checks_every_field() {
    let mut c = controller::<f32>();
    c.step(0.1).unwrap();
    let good = c.snapshot();
    let mut flat = [0.0; Snapshot::<f32, 2>::LEN];
    good.to_array(&mut flat).unwrap();
    let field = |name: &str| {
        famcc_core::SNAPSHOT_FIELDS
            .iter()
            .position(|f| *f == name)
            .unwrap()
    };
    let bad = [
        ("started", f64::NAN),
        ("started", 2.0),
        ("started", -1.0),
        ("t_base", f64::INFINITY),
        ("t_base", -1.0),
        ("k", -1.0),
        ("k", 1.5),
        ("k", 2f64.powi(60)),
        ("rho0_x", 0.01),
        ("rho0_x", 1e40), // inf as an f32
        ("last_v", f64::NAN),
        ("period", 0.0),
        ("config", 12345.0),
    ];
    for (name, value) in bad {
        let mut v = flat;
        v[field(name)] = value;
        let before = c;
        let r = Snapshot::<f32, 2>::from_array(&v).and_then(|s| c.restore(&s));
        assert!(r.is_err(), "{name} = {value} accepted");
        assert_eq!(c, before);
    }
    for z in [f64::NAN, 1e20, 1e40] {
        let mut v = flat;
        v[famcc_core::SNAPSHOT_FIELDS.len()] = z;
        assert!(
            Snapshot::<f32, 2>::from_array(&v)
                .and_then(|s| c.restore(&s))
                .is_err(),
            "z_hat {z}"
        );
    }
    // Not started: the rest must be the initial state.
    let mut s = good;
    s.started = false;
    assert_eq!(c.restore(&s).unwrap_err().parameter, "state.started");
    // Another configuration's state.
    let other = Controller::new(c.config().to_builder().k_u(6.0).build().unwrap());
    assert_eq!(
        c.restore(&other.snapshot()).unwrap_err().parameter,
        "state.config"
    );
    assert_eq!(c.restore(&good), Ok(()));
}

#[test]
fn restore_refuses_a_time_that_overflows() {
    // t_base and k period each finite, their sum t_base + k period not: the
    // clock could never say the time, so the snapshot is refused by t_base.
    let mut c = controller::<f64>();
    c.step(0.1).unwrap();
    let mut s = c.snapshot();
    s.t_base = 1.5e308;
    s.period = 1e298;
    s.k = 10_000_000_000;
    assert_eq!(c.restore(&s).unwrap_err().parameter, "state.t_base");
    // Far out but finite is a time like any other as far as t_base goes.
    s.t_base = 1.0e307;
    s.period = 1e-3;
    s.k = 1_000;
    assert_ne!(c.restore(&s).err().map(|e| e.parameter), Some("state.t_base"));
}

#[test]
fn a_clock_far_out_takes_a_new_period_like_any_other() {
    // A run at 1e300 s that changes to a 1e10 s period (both in range): the
    // new run starts at this sample's time, and its end 1e300 + 1e10 is
    // finite, so the step is taken (a product base * dt would overflow).
    let mut c = controller::<f64>();
    c.step(0.1).unwrap();
    let mut s = c.snapshot();
    s.t_base = 1e300;
    s.k = 0;
    c.restore(&s).unwrap();
    assert!(c.step_dt(0.1, 1e10, None).is_ok());
    assert_eq!(c.diagnostics().t, 1e300);
    assert_eq!(c.snapshot().t_base, 1e300);
    assert_eq!(c.snapshot().k, 1);
}

/// A run that changes its period keeps the law's time: 50 samples at 1 ms,
/// 25 at 2 ms, then the 1 ms period again, meet the run that stayed at 1 ms
/// at its sample at 0.1 s with the same envelopes (the law time of a new run
/// starts from the run's base, `min(base, T_s)`, not from 0).
#[test]
fn a_changed_period_keeps_the_law_time() {
    let (mut a, mut b) = (controller::<f64>(), controller::<f64>());
    for _ in 0..=100 {
        a.step(0.1).unwrap();
    }
    for _ in 0..50 {
        b.step(0.1).unwrap();
    }
    for _ in 0..25 {
        b.step_dt(0.1, 2e-3, None).unwrap();
    }
    b.step(0.1).unwrap();
    let (da, db) = (a.diagnostics(), b.diagnostics());
    assert!(
        (da.t - 0.1).abs() < 1e-12 && (db.t - 0.1).abs() < 1e-12,
        "{} {}",
        da.t,
        db.t
    );
    // The envelopes still shrink at 0.1 s (T_s = 1 s), so a law time off by
    // a sample or more would show.
    assert!(da.nominal_bounds.0 > 0.1 * 1.5, "{:?}", da.nominal_bounds);
    let rel = (da.nominal_bounds.0 - db.nominal_bounds.0).abs() / da.nominal_bounds.0;
    assert!(rel < 1e-9, "{:?} vs {:?}", da.nominal_bounds, db.nominal_bounds);
}
