//! The sample-rate rules of the default differentiator (issue 14):
//! `auto_mu`, `auto_discretization_at`, `HighGain::auto_at`, and their use
//! by `design`.

use famcc_core::design::{design, Requirements};
use famcc_core::differentiator::{auto_discretization_at, auto_mu, EXACT_DT_PER_MU, PAPER_MU, SAMPLE_DELAY};
use famcc_core::{Discretization, HighGain};

#[test]
fn at_one_khz_and_faster_the_default_is_the_papers() {
    for dt in [1e-3, 5e-4, 1e-4, 1e-5] {
        assert_eq!(auto_mu(2, dt), PAPER_MU);
        assert_eq!(HighGain::<f64, 2>::auto_at(2, dt), HighGain::paper());
        assert_eq!(HighGain::<f64, 3>::auto_at(3, dt), HighGain::paper());
        assert_eq!(HighGain::<f64, 4>::auto_at(4, dt), HighGain::auto());
    }
}

#[test]
fn slower_rates_keep_the_loop_delay_and_never_go_below_dt() {
    for order in 1..=8 {
        for k in 1..=40 {
            let dt = 1e-3 * f64::from(k) * 0.5;
            let mu = auto_mu(order, dt);
            assert!(
                // at dt > PAPER_MU: the paper's mu (with the exact hold)
                mu <= PAPER_MU.max(dt) && mu >= dt.min(PAPER_MU),
                "order {order} dt {dt}: mu {mu}"
            );
            if dt > 1e-3 && mu > dt {
                // the differentiator's delay plus the sampling delay is the paper's at 1 kHz
                let total = order as f64 * mu / 2.0 + SAMPLE_DELAY * dt;
                let paper = order as f64 * PAPER_MU / 2.0 + SAMPLE_DELAY * 1e-3;
                assert!((total - paper).abs() < 1e-12, "order {order} dt {dt}");
            }
            // never slower at a slower rate, unless held at the floor dt
            assert!(auto_mu(order, dt + 1e-4) <= mu.max((dt + 1e-4).min(PAPER_MU)));
        }
    }
    assert!((auto_mu(3, 5e-3) - 0.006).abs() < 1e-15);
    assert_eq!(auto_mu(2, 5e-3), 5e-3);
    // 50 Hz: the paper's mu with the exact hold (Tustin would ring at dt > mu)
    assert_eq!(HighGain::<f64, 2>::auto_at(2, 2e-2), HighGain::paper());
}

#[test]
fn the_discretization_follows_dt_over_mu() {
    assert_eq!(auto_discretization_at(2, 2e-3, 0.01), Discretization::Exact);
    assert_eq!(
        auto_discretization_at(2, EXACT_DT_PER_MU * 0.01 * 1.01, 0.01),
        Discretization::Tustin
    );
    assert_eq!(auto_discretization_at(2, 0.011, 0.01), Discretization::Exact);
    assert_eq!(auto_discretization_at(2, 0.01, 0.01), Discretization::Tustin);
    for order in 4..=8 {
        assert_eq!(auto_discretization_at(order, 1e-5, 0.01), Discretization::Tustin);
    }
    let h = HighGain::<f64, 3>::auto_at(3, 5e-3);
    assert_eq!(h.discretization, Discretization::Tustin);
    assert!(h.discretize(5e-3).unwrap().spectral_radius() < 1.0);
}

#[test]
fn design_picks_the_discretization_by_the_same_rule() {
    let mut req = Requirements::new(3, 1e-3, (-10.0, 10.0), 0.01, 2.0, 1.0);
    req.gain = Some(2.0);
    assert_eq!(design(&req).unwrap().discretization, Discretization::Exact);
    // a differentiator of 3 samples: dt / mu = 0.33 > 0.2
    req.mu_per_dt = 3.0;
    let d = design(&req).unwrap();
    assert_eq!(d.discretization, auto_discretization_at(3, req.dt, d.mu));
    assert_eq!(d.discretization, Discretization::Tustin);
}
