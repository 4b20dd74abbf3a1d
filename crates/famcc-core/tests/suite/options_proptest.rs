//! Properties of the options beyond the paper (docs/design.md §3.8) over
//! arbitrary limits and error sequences:
//!
//! - the returned output is within the magnitude limits, and within the rate
//!   window of the previous output;
//! - the integral is frozen while the output is beyond a limit and the error
//!   pushes it further, and it only ever moves by `dt e`;
//! - a snapshot (which carries the integral) restores into a controller that
//!   continues bit-identically;
//! - the health count never decreases.
#![allow(clippy::unwrap_used, clippy::indexing_slicing)]

use famcc_core::{Config, Constraint, Controller, Discretization, Feedback, HighGain};
use proptest::prelude::*;

const DT: f64 = 1e-3;

fn controller(
    integral: bool,
    limits: Option<(f64, f64)>,
    rate: Option<f64>,
    u0: Option<f64>,
) -> Controller<f64, 3> {
    let laws = [(Feedback::Linear { k: 2.0 }, None); 2];
    let a = if integral {
        [4.0, 4.0, 0.0]
    } else {
        [4.0, 6.0, 4.0]
    };
    let cfg = Config::<f64, 3>::builder(DT, &laws, Constraint::Longitudinal { eps: 0.5 }, 3.0)
        .differentiator(Some(HighGain::new(0.01, a, Discretization::Exact)))
        .integral(integral)
        .output_limits(limits)
        .rate_limit(rate)
        .initial_output(u0)
        .build()
        .unwrap();
    Controller::new(cfg)
}

fn limits() -> impl Strategy<Value = (f64, f64)> {
    (-10.0..0.0f64, 0.01..10.0f64).prop_map(|(lo, w)| (lo, lo + w))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, ..ProptestConfig::default() })]

    #[test]
    fn the_output_is_within_the_limits_and_the_rate(
        integral in any::<bool>(),
        (lo, hi) in limits(),
        rate in prop::option::of(1.0..1e4f64),
        u0 in prop::option::of(-5.0..5.0f64),
        es in prop::collection::vec(-5.0..5.0f64, 1..200),
    ) {
        let mut c = controller(integral, Some((lo, hi)), rate, u0);
        let mut prev: Option<f64> = None;
        for &e in &es {
            let Ok(u) = c.step(e) else { continue };
            prop_assert!(lo <= u && u <= hi, "{u} outside [{lo}, {hi}]");
            if let (Some(r), Some(p)) = (rate, prev) {
                // The rate window applies from an output within the limits.
                prop_assert!((u - p).abs() <= r * DT * (1.0 + 1e-12) + 1e-12, "{p} -> {u}");
            }
            prop_assert_eq!(c.diagnostics().v, u);
            prev = Some(u);
        }
    }

    #[test]
    fn the_integral_is_frozen_while_saturated_in_the_pushing_direction(
        (lo, hi) in limits(),
        es in prop::collection::vec(-2.0..2.0f64, 2..300),
    ) {
        let mut c = controller(true, Some((lo, hi)), None, None);
        let mut last: Option<(f64, f64)> = None; // (I used, e) of the previous step
        let mut frozen_expected = false;
        for &e in &es {
            if c.step(e).is_err() {
                last = None;
                continue;
            }
            let d = c.diagnostics();
            let i = d.integral.unwrap();
            if let Some((i_prev, e_prev)) = last {
                if frozen_expected {
                    prop_assert_eq!(i, i_prev, "wound up while saturated");
                } else {
                    prop_assert!(i == i_prev || i == i_prev + DT * e_prev);
                }
            }
            let pushing = (d.v_unlimited > hi && e < 0.0) || (d.v_unlimited < lo && e > 0.0);
            prop_assert!(!(pushing && d.integrating));
            frozen_expected = !d.integrating;
            last = Some((i, e));
        }
    }

    #[test]
    fn a_snapshot_with_the_integral_restores_bit_identically(
        integral in any::<bool>(),
        lim in prop::option::of(limits()),
        rate in prop::option::of(1.0..1e4f64),
        es in prop::collection::vec(-3.0..3.0f64, 1..100),
        more in prop::collection::vec(-3.0..3.0f64, 1..100),
    ) {
        let mut a = controller(integral, lim, rate, None);
        for &e in &es {
            let _ = a.step(e);
        }
        let mut b = controller(integral, lim, rate, None);
        b.restore(&a.snapshot()).unwrap();
        let health = a.unsaturated_expansions();
        for &e in &more {
            let (ra, rb) = (a.step(e), b.step(e));
            prop_assert_eq!(ra.map(f64::to_bits), rb.map(f64::to_bits));
            prop_assert_eq!(a.diagnostics().integral.map(f64::to_bits), b.diagnostics().integral.map(f64::to_bits));
        }
        prop_assert!(a.unsaturated_expansions() >= health);
    }
}
