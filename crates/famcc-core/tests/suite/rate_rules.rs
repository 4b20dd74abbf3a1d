//! The sample-rate rules of the default differentiator (issue 14):
//! `auto_mu`, `auto_discretization_at`, `HighGain::auto_at`, and their use
//! by `design`.

use famcc_core::design::{design, Requirements};
use famcc_core::differentiator::{
    auto_discretization_at, auto_mu, FOH_MIN_MU_PER_DT, FOH_SAMPLE_DELAY, PAPER_MU, PAPER_MU_PER_DT,
    SAMPLE_DELAY,
};
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
fn slower_rates_keep_the_loop_delay_and_never_go_below_their_floor() {
    for order in 1..=8 {
        for k in 1..=80 {
            let dt = 1e-3 * f64::from(k) * 0.5;
            let mu = auto_mu(order, dt);
            let disc = HighGain::<f64, 8>::auto_at(order, dt).discretization;
            assert_eq!(
                disc,
                auto_discretization_at(order, dt, mu),
                "order {order} dt {dt}"
            );
            // what the sampling costs with this discretization, in periods
            let (delay, floor) = match disc {
                Discretization::Foh => (FOH_SAMPLE_DELAY, FOH_MIN_MU_PER_DT * dt),
                _ => (SAMPLE_DELAY, dt.min(PAPER_MU)),
            };
            assert!(
                mu <= PAPER_MU.max(floor) && mu >= floor.min(PAPER_MU) - 1e-18,
                "order {order} dt {dt}: mu {mu}"
            );
            if mu > floor && mu < PAPER_MU {
                // the differentiator's delay plus the sampling delay is the paper's at 1 kHz
                let total = order as f64 * mu / 2.0 + delay * dt;
                let paper = order as f64 * PAPER_MU / 2.0 + SAMPLE_DELAY * 1e-3;
                assert!((total - paper).abs() < 1e-12, "order {order} dt {dt}");
            }
            if order <= 3 {
                // the exact hold at the paper's mu and rate (1 kHz and
                // faster), the first-order hold beyond; never Tustin
                let want = if PAPER_MU >= PAPER_MU_PER_DT * dt {
                    Discretization::Exact
                } else {
                    Discretization::Foh
                };
                assert_eq!(disc, want, "order {order} dt {dt}");
            } else {
                assert_eq!(disc, Discretization::Tustin, "order {order} dt {dt}");
                // never slower at a slower rate, unless held at the floor dt
                assert!(auto_mu(order, dt + 1e-4) <= mu.max((dt + 1e-4).min(PAPER_MU)));
            }
        }
    }
    // 200 Hz: 0.5 dt + n mu / 2 = 1.5 ms + n 5 ms
    assert!((auto_mu(2, 5e-3) - 0.009).abs() < 1e-15);
    assert!((auto_mu(3, 5e-3) - (0.01 - 0.002 / 3.0)).abs() < 1e-15);
    // 500 Hz: the paper's mu with the first-order hold
    let h = HighGain::<f64, 3>::auto_at(3, 2e-3);
    assert_eq!((h.mu, h.discretization), (PAPER_MU, Discretization::Foh));
    // 50 Hz: mu held at dt / 2
    let h = HighGain::<f64, 2>::auto_at(2, 2e-2);
    assert_eq!((h.mu, h.discretization), (1e-2, Discretization::Foh));
}

#[test]
fn the_discretization_follows_dt_over_mu() {
    assert_eq!(auto_discretization_at(2, 1e-3, 0.01), Discretization::Exact);
    assert_eq!(auto_discretization_at(2, 1e-3 * 1.01, 0.01), Discretization::Foh);
    // the design's own ratio, mu = 10 dt, at any dt: exact
    for dt in [1e-4, 3e-4, 7e-3, 1.0 / 300.0, 0.1] {
        assert_eq!(auto_discretization_at(3, dt, 10.0 * dt), Discretization::Exact);
    }
    assert_eq!(auto_discretization_at(2, 0.011, 0.01), Discretization::Foh);
    assert_eq!(auto_discretization_at(3, 0.05, 0.01), Discretization::Foh);
    for order in 4..=8 {
        assert_eq!(auto_discretization_at(order, 1e-5, 0.01), Discretization::Tustin);
    }
    let h = HighGain::<f64, 3>::auto_at(3, 5e-3);
    assert_eq!(h.discretization, Discretization::Foh);
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
    assert_eq!(d.discretization, Discretization::Foh);
}
