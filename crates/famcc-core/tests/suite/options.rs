//! The options beyond the paper (docs/design.md §3.8, issue 13): integral
//! action with integral separation, output magnitude and rate limits, the
//! bumpless start, `step_output`, the health count, the unstable
//! differentiator's `ConfigError` and `Config::lint`, in f64 and f32.
#![allow(clippy::unwrap_used, clippy::indexing_slicing)]

use crate::common;
use famcc_core::config::Lint;
use famcc_core::{
    Config, ConfigBuilder, Constraint, Controller, Discretization, Feedback, HighGain, Real, Skew,
};
use famcc_paper::designs::{design, Design};
use famcc_paper::{Example, Variant};

const DT: f64 = 1e-3;

/// A double integrator with a load: `x'' = u - d` (`d` = the input that
/// holds it still), `e = x - y_d`; explicit Euler on the velocity first
/// (symplectic), fine at 1 kHz.
struct Plant {
    x: f64,
    v: f64,
    d: f64,
}

impl Plant {
    fn advance(&mut self, u: f64) {
        self.v += DT * (u - self.d);
        self.x += DT * self.v;
    }
}

/// Order-2 plant; law order 3 with integral action (stage laws Linear(2)).
fn builder<T: Real, const N: usize>(k_u: f64) -> ConfigBuilder<T, N> {
    let t = T::from_f64;
    let laws = [(Feedback::Linear { k: t(2.0) }, None::<Skew<T>>); 2];
    let mut a = [T::zero(); N];
    a[0] = t(4.0);
    a[1] = t(4.0);
    Config::<T, N>::builder(
        t(DT),
        &laws[..N - 1],
        Constraint::Longitudinal { eps: t(2.0) },
        t(k_u),
    )
    .settle_time(t(1.0))
    .differentiator(Some(HighGain::new(t(0.01), a, Discretization::Exact)))
}

/// Regulates the loaded double integrator to 0 from `x = 0.5`; the tail's
/// max |e| and the controller.
fn regulate<const N: usize>(b: ConfigBuilder<f64, N>, load: f64, t_end: f64) -> (f64, Controller<f64, N>) {
    let mut c = Controller::new(b.build().unwrap());
    let mut p = Plant {
        x: 0.5,
        v: 0.0,
        d: load,
    };
    let mut tail: f64 = 0.0;
    let steps = (t_end / DT) as usize;
    let mut prev = None;
    for k in 0..steps {
        let u = c.step_output(p.x, 0.0, prev).unwrap();
        assert!(u.is_finite());
        if k > steps - 1000 {
            tail = tail.max(p.x.abs());
        }
        p.advance(u);
        prev = Some(u);
    }
    (tail, c)
}

#[test]
fn integral_action_removes_the_steady_error_under_a_load() {
    let (without, _) = regulate(builder::<f64, 2>(4.0), 1.0, 20.0);
    let (with, c) = regulate(builder::<f64, 3>(4.0).integral(true), 1.0, 20.0);
    println!("steady |e|: without integral {without:.3e}, with {with:.3e}");
    assert!(
        without > 1e-2,
        "the static law keeps an offset under a load ({without})"
    );
    assert!(with < 1e-4, "integral action removes it ({with})");
    // The integral carries the load: I settles where the law outputs d.
    let d = c.diagnostics();
    assert!(d.integral.is_some() && (d.v - 1.0).abs() < 1e-2, "{d:?}");
}

#[test]
fn integral_separation_freezes_the_integral_while_saturated() {
    // A load (2) above the output limit (1.5): the output stays at the limit,
    // the error keeps pushing it up, and the integral must not wind up.
    let b = builder::<f64, 3>(4.0)
        .integral(true)
        .output_limits(Some((-1.5, 1.5)));
    let (_, c) = regulate(b, 2.0, 5.0);
    let d = c.diagnostics();
    assert_eq!(d.v, 1.5);
    assert!(d.v_unlimited > 1.5 && !d.integrating, "{d:?}");
    // Frozen: the integral is no larger than a second of the error's worth.
    let i = d.integral.unwrap();
    assert!(i.abs() < 10.0, "wound up: I = {i}");
}

#[test]
fn output_limits_and_rate_limits_hold() {
    let b = builder::<f64, 2>(4.0)
        .output_limits(Some((-1.0, 2.0)))
        .rate_limit(Some(50.0))
        .initial_output(Some(0.0));
    let mut c = Controller::new(b.build().unwrap());
    let mut prev = 0.0;
    for k in 0..2000 {
        let e = 3.0 * (k as f64 * 0.01).sin();
        let u = c.step(e).unwrap();
        assert!((-1.0..=2.0).contains(&u));
        assert!(
            (u - prev).abs() <= 50.0 * DT * (1.0 + 1e-12),
            "rate at {k}: {prev} -> {u}"
        );
        assert_eq!(c.diagnostics().v, u);
        prev = u;
    }
}

#[test]
fn bumpless_start_from_a_given_output() {
    for u0 in [-3.0, -0.5, 0.0, 0.7, 2.5] {
        // With integral action: I_0 is chosen.
        let b = builder::<f64, 3>(4.0).integral(true).initial_output(Some(u0));
        let v = Controller::new(b.build().unwrap()).step(0.05).unwrap();
        assert!((v - u0).abs() < 1e-6 * (1.0 + u0.abs()), "integral: {v} vs {u0}");
        // Without: the latch is rescaled when the sign of s_0 agrees (e = -1:
        // s_0 = -2 < 0, the law pushes v > 0) and the widths allow it.
        let b = builder::<f64, 2>(4.0).initial_output(Some(u0));
        let v = Controller::new(b.build().unwrap()).step(-1.0).unwrap();
        if u0 > 0.0 {
            assert!((v - u0).abs() < 1e-6 * (1.0 + u0.abs()), "latch: {v} vs {u0}");
        } else {
            // Infeasible (the opposite sign): the nearest feasible output.
            assert!((0.0..0.1).contains(&v), "nearest for {u0}: {v}");
        }
    }
    // Infeasible because the widths cannot go below the final ones (|s_0| =
    // 0.2 against eps = 2: |xi_0| <= 0.1): the nearest, -k_u Gamma(-0.1).
    let b = builder::<f64, 2>(4.0).initial_output(Some(2.5));
    let v = Controller::new(b.build().unwrap()).step(-0.1).unwrap();
    assert!((v - 8.0 * 0.1_f64.atanh()).abs() < 1e-6, "{v}");
}

#[test]
fn an_unreachable_first_output_with_the_flexible_boundary_stops_at_the_nominal_bounds() {
    // LoMC, eps = 2, rho_e = 0.5: the bounds stay nominal while |xi| <= 1 -
    // rho_e / eps = 0.75. e = -1 gives s_0 = -2 and the usual latch xi_0 =
    // -0.5; the latch may narrow to the final width (xi_0 = -1), but the
    // bumpless start stops at the nominal limit: v_0 = -k_u Gamma(-0.75) =
    // 8 atanh(0.75), not the 8 atanh(0.5) of a limit 1 - rho_e.
    let b = builder::<f64, 2>(4.0).rho_e(Some(0.5)).initial_output(Some(1e3));
    let mut c = Controller::new(b.build().unwrap());
    let v = c.step(-1.0).unwrap();
    let xi = c.diagnostics().xi_nominal;
    assert!((xi + 0.75).abs() < 1e-5, "xi {xi}");
    assert!((v - 8.0 * 0.75_f64.atanh()).abs() < 1e-4, "v {v}");
}

#[test]
fn bumpless_start_in_f32() {
    let b = builder::<f32, 3>(4.0).integral(true).initial_output(Some(1.25));
    let v = Controller::new(b.build().unwrap()).step(0.05).unwrap();
    assert!((v - 1.25).abs() < 1e-3, "{v}");
}

#[test]
fn step_output_is_step_of_y_minus_y_d() {
    let cfg = builder::<f64, 3>(4.0).integral(true).build().unwrap();
    let (mut a, mut b) = (Controller::new(cfg), Controller::new(cfg));
    for k in 0..200 {
        let (y, y_d) = ((k as f64 * 0.03).cos(), 0.2);
        assert_eq!(a.step_output(y, y_d, None).unwrap(), b.step(y - y_d).unwrap());
    }
    assert!(a.step_output(f64::NAN, 0.0, None).is_err());
    assert!(a.step_output(f64::MAX, -f64::MAX, None).is_err());
    assert_eq!(a.snapshot(), b.snapshot());
}

#[test]
fn snapshot_carries_the_integral() {
    let cfg = builder::<f64, 3>(4.0).integral(true).build().unwrap();
    let mut a = Controller::new(cfg);
    for k in 0..300 {
        a.step(0.3 * (k as f64 * 0.02).sin() - 0.1).unwrap();
    }
    assert!(a.diagnostics().integral.unwrap() != 0.0);
    let mut b = Controller::new(cfg);
    b.restore(&a.snapshot()).unwrap();
    for k in 0..300 {
        let e = (k as f64 * 0.05).cos() * 0.2;
        assert_eq!(a.step(e).unwrap().to_bits(), b.step(e).unwrap().to_bits());
    }
}

#[test]
fn the_health_count_sees_expansions_with_headroom() {
    // k_u far too small for the load (2 / ln 3 is needed): the bounds expand
    // for good although the actuator (limits +-100) has room.
    let b = builder::<f64, 2>(0.3)
        .output_limits(Some((-100.0, 100.0)))
        .rho_e(Some(0.1));
    let (_, c) = regulate(b, 2.0, 3.0);
    assert!(c.unsaturated_expansions() > 100, "{}", c.unsaturated_expansions());
    assert_eq!(c.unsaturated_expansions(), c.diagnostics().unsaturated_expansions);
    // Without the output limits and without `applied`, nothing is known.
    let mut c = Controller::new(builder::<f64, 2>(0.3).rho_e(Some(0.1)).build().unwrap());
    let mut p = Plant {
        x: 0.5,
        v: 0.0,
        d: 2.0,
    };
    for _ in 0..3000 {
        let u = c.step(p.x).unwrap();
        p.advance(u);
    }
    assert_eq!(c.unsaturated_expansions(), 0);
}

#[test]
fn the_health_rule_fires_exactly_at_half_the_settling_time_and_suggests_the_hold_gain() {
    // T_s = 1 s at 1 kHz: persistent from 500 expansions with headroom.
    let b = builder::<f64, 2>(0.3)
        .output_limits(Some((-100.0, 100.0)))
        .rho_e(Some(0.1));
    let mut c = Controller::new(b.build().unwrap());
    assert_eq!(c.persistent_expansions(), 500);
    let mut p = Plant {
        x: 0.5,
        v: 0.0,
        d: 2.0,
    };
    let (mut prev, mut fired) = (None, None);
    for k in 0..4000 {
        let u = c.step_output(p.x, 0.0, prev).unwrap();
        p.advance(u);
        prev = Some(u);
        let n = c.unsaturated_expansions();
        assert_eq!(c.health().is_some(), n >= 500, "step {k}: {n} expansions");
        if fired.is_none() && n >= 500 {
            fired = c.health().map(|h| (h, c.diagnostics().v_unlimited.abs()));
        }
    }
    let (h, v) = fired.expect("k_u = 0.3 cannot hold the load 2 within the bounds");
    assert_eq!(h.expansions, 500);
    // The cure: the larger of 2 k_u and |v| / ln 3, v the law's last output.
    assert_eq!(h.hold, v);
    assert!(
        (h.suggested_k_u - f64::max(0.6, v / 3.0_f64.ln())).abs() < 1e-15,
        "{h:?}"
    );
    let text = h.to_string();
    assert!(text.contains("expanded 500 times"), "{text}");
    assert!(
        text.contains(&format!("raise k_u to {:.3}", h.suggested_k_u)),
        "{text}"
    );
    // A gain that holds the load never fires (nor does a loop that never
    // learns its applied input).
    let (_, good) = regulate(
        builder::<f64, 2>(h.suggested_k_u)
            .output_limits(Some((-100.0, 100.0)))
            .rho_e(Some(0.1)),
        2.0,
        4.0,
    );
    assert_eq!(good.health(), None, "{}", good.unsaturated_expansions());
    // The threshold: at least one sample, whatever T_s / dt.
    let tiny = builder::<f64, 2>(1.0).settle_time(1e-6).build().unwrap();
    assert_eq!(Controller::new(tiny).persistent_expansions(), 1);
    let f32c = Controller::new(builder::<f32, 2>(1.0).settle_time(0.25).build().unwrap());
    assert_eq!(f32c.persistent_expansions(), 125);
}

#[test]
fn an_unstable_discretized_differentiator_is_a_config_error() {
    let euler = |dt: f64| {
        Config::<f64, 2>::builder(
            dt,
            &[(Feedback::Linear { k: 1.0 }, None)],
            Constraint::Lateral { eps: 0.1 },
            5.0,
        )
        .differentiator(Some(HighGain::new(0.01, [4.0, 4.0], Discretization::Euler)))
        .build()
    };
    // Euler: eigenvalue 1 - 2 dt / mu (double): unstable from dt = mu on.
    assert!(euler(1e-3).is_ok());
    let e = euler(0.05).unwrap_err();
    assert_eq!(e.parameter, "dt");
    assert!(e.rule.contains("spectral radius"), "{e}");
    assert!(euler(0.01).is_err(), "marginal (|lambda| = 1) is rejected");
    // Exact and Tustin are stable at any dt.
    for d in [Discretization::Exact, Discretization::Tustin] {
        let cfg = Config::<f64, 2>::builder(
            1.0,
            &[(Feedback::Linear { k: 1.0 }, None)],
            Constraint::Lateral { eps: 0.1 },
            5.0,
        )
        .differentiator(Some(HighGain::new(0.01, [4.0, 4.0], d)))
        .build();
        assert!(cfg.is_ok(), "{d:?}");
    }
}

#[test]
fn the_papers_designs_have_no_lint_findings() {
    for ex in [Example::FiniteTime, Example::VariableExponent, Example::Rfc] {
        for variant in [Variant::Paper, Variant::Code] {
            let (found, empty): (Vec<String>, bool) = match design::<f64>(ex, variant, DT).unwrap() {
                Design::Order2(c) => {
                    let l = c.lint();
                    (l.iter().map(|f| f.to_string()).collect(), l.is_empty())
                }
                Design::Order3(c) => {
                    let l = c.lint();
                    (l.iter().map(|f| f.to_string()).collect(), l.is_empty())
                }
            };
            assert!(found.is_empty(), "{ex:?} {variant:?}: {found:?}");
            assert!(empty, "{ex:?} {variant:?}: Findings::is_empty");
        }
    }
}

#[test]
fn lint_names_the_parameter_rule_and_suggestion() {
    let linear = [(Feedback::Linear { k: 2.0 }, None); 3];
    // Tustin (the order-4 default) warns only once dt > mu (here dt / mu = 2);
    // at dt / mu = 0.5 it does not.
    let tustin = |dt: f64| {
        Config::<f64, 4>::builder(dt, &linear, Constraint::Longitudinal { eps: 1.0 }, 5.0)
            .differentiator(Some(HighGain::auto()))
            .rho_e(Some(0.5))
            .build()
            .unwrap()
    };
    let mild: Vec<Lint> = tustin(5e-3).lint().iter().map(|f| f.lint).collect();
    assert_eq!(mild, [Lint::WideMargin, Lint::Peaking]);
    let cfg = tustin(2e-2);
    let f = cfg.lint();
    let lints: Vec<Lint> = f.iter().map(|f| f.lint).collect();
    assert_eq!(lints, [Lint::CoarseSampling, Lint::WideMargin, Lint::Peaking]);
    assert!(!f.is_empty() && f.len() == 3);
    // The coarse sampling's suggestion: a period of mu / 10 (value = dt / mu).
    let coarse = f.get(Lint::CoarseSampling).unwrap();
    let mu = 2e-2 / coarse.value;
    let famcc_core::config::Suggestion::Value(dt) = coarse.suggestion else {
        panic!("{coarse:?}")
    };
    assert!((dt - mu / 10.0).abs() < 1e-12 * mu, "{dt} vs mu {mu}");
    for finding in f.iter() {
        let text = finding.to_string();
        assert!(
            text.starts_with(finding.parameter) && text.contains("rule: ") && text.contains("suggested"),
            "{text}"
        );
    }
    // A finite-time law on the last stage of a fast longitudinal loop chatters.
    let ft = [
        (Feedback::Linear { k: 1.0 }, None),
        (Feedback::FiniteTime { k: 20.0, p: 0.5 }, None),
    ];
    let cfg = Config::<f64, 3>::builder(1e-3, &ft, Constraint::Longitudinal { eps: 0.01 }, 5.0)
        .differentiator(Some(HighGain::paper()))
        .build()
        .unwrap();
    let chatter = cfg.lint();
    let c = chatter.get(Lint::Chatter).unwrap();
    assert_eq!((c.parameter, c.stage), ("k", Some(1)));
    // ... and not with a Nonsingular skew.
    let nsmd = Skew::nonsingular(0.1, 0.1, 0.2);
    let ft = [
        (Feedback::Linear { k: 1.0 }, None),
        (Feedback::FiniteTime { k: 20.0, p: 0.5 }, Some(nsmd)),
    ];
    if let Ok(cfg) = Config::<f64, 3>::builder(1e-3, &ft, Constraint::Longitudinal { eps: 0.01 }, 5.0)
        .differentiator(Some(HighGain::paper()))
        .build()
    {
        assert!(cfg.lint().get(Lint::Chatter).is_none());
    }
    // The exact ZOH at order >= 4 aliases.
    let cfg = Config::<f64, 4>::builder(1e-3, &linear, Constraint::Longitudinal { eps: 1.0 }, 5.0)
        .differentiator(Some(HighGain::new(
            0.01,
            [8.0, 24.0, 32.0, 16.0],
            Discretization::Exact,
        )))
        .estimate_limits(Some([10.0, 1e2, 1e3, 1e4]))
        .build()
        .unwrap();
    let lints: Vec<Lint> = cfg.lint().iter().map(|f| f.lint).collect();
    assert_eq!(lints, [Lint::Aliasing]);
}

#[test]
fn integral_and_limits_in_f32() {
    let b = builder::<f32, 3>(4.0)
        .integral(true)
        .output_limits(Some((-1.5, 1.5)))
        .rate_limit(Some(100.0));
    let mut c = Controller::new(b.build().unwrap());
    let (mut x, mut v) = (0.5_f32, 0.0_f32);
    let mut prev = None;
    for _ in 0..20000 {
        let u = c.step_output(x, 0.0, prev).unwrap();
        assert!((-1.5..=1.5).contains(&u) && u.is_finite());
        v += 1e-3 * (u - 1.0);
        x += 1e-3 * v;
        prev = Some(u);
    }
    let d = c.diagnostics();
    assert!(d.integral.is_some_and(f32::is_finite));
    assert!(x.abs() < 1e-2, "x = {x}");
}

#[test]
fn the_chatter_lint_suggests_the_gain_at_its_rule() {
    // The suggested k of the last stage puts the chatter amplitude at the
    // rule's 1 % of the accuracy: just below it is quiet, just above warns,
    // for the lateral (accuracy eps_x) and longitudinal (eps_y) constraints.
    use famcc_core::config::Suggestion;
    for constraint in [
        Constraint::Lateral { eps: 0.01 },
        Constraint::Longitudinal { eps: 0.01 },
    ] {
        let lint_at = |k: f64| {
            let ft = [
                (Feedback::Linear { k: 1.0 }, None),
                (Feedback::FiniteTime { k, p: 0.5 }, None),
            ];
            Config::<f64, 3>::builder(1e-3, &ft, constraint, 5.0)
                .differentiator(Some(HighGain::paper()))
                .build()
                .unwrap()
                .lint()
        };
        let found = lint_at(20.0);
        let Suggestion::Value(k) = found.get(Lint::Chatter).unwrap().suggestion else {
            panic!("a number for k");
        };
        assert!(k > 0.0 && k < 20.0, "{constraint:?}: {k}");
        assert!(
            lint_at(0.98 * k).get(Lint::Chatter).is_none(),
            "{constraint:?}: {k}"
        );
        assert!(
            lint_at(1.02 * k).get(Lint::Chatter).is_some(),
            "{constraint:?}: {k}"
        );
    }
}

#[test]
fn an_unreachable_first_output_with_integral_action_is_the_nearest_reachable() {
    // u0 = +-1e3 lies beyond what the first latch allows (|xi_0| <= 1/k0 =
    // 0.5, |v_0| <= k_u Gamma(0.5) = 4 ln 3): I_0 gives the nearest output,
    // on the side of u0.
    for u0 in [1e3, -1e3] {
        let b = builder::<f64, 3>(4.0).integral(true).initial_output(Some(u0));
        let mut c = Controller::new(b.build().unwrap());
        let v = c.step(0.05).unwrap();
        let xi = c.diagnostics().xi;
        assert_eq!(v.signum(), u0.signum(), "u0 {u0}: v {v}");
        assert!((xi.abs() - 0.5).abs() < 1e-6, "u0 {u0}: xi {xi}");
        assert!((v.abs() - 4.0 * 3.0_f64.ln()).abs() < 1e-5, "u0 {u0}: v {v}");
    }
}

/// Replays the error samples `z1` into a fresh `ctrl` twice: with `step`,
/// and telling it each time that the actuator applied its previous output
/// exactly (a told input takes the step's general path, with the limits'
/// and the health count's arithmetic). Nothing is limited or revealed, so
/// the outputs and the diagnostics agree bit for bit, apart from the
/// saturation gap (0 once told) and the health count (the told input shows
/// headroom).
fn told_input_changes_nothing<T: Real, const N: usize>(ctrl: Controller<T, N>, z1: &[f64]) {
    let (mut quiet, mut told) = (ctrl, ctrl);
    let mut last = None;
    for (k, &e) in z1.iter().enumerate() {
        let e = T::from_f64(e);
        let a = quiet.step(e).unwrap();
        let b = told.step_applied(e, last).unwrap();
        last = Some(b);
        assert_eq!(
            a.to_f64_lossless().to_bits(),
            b.to_f64_lossless().to_bits(),
            "sample {k}"
        );
        let (mut dq, mut dt) = (quiet.diagnostics(), told.diagnostics());
        assert_eq!(
            dt.saturation_gap.map(|g| g.to_f64_lossless()),
            (k > 0).then_some(0.0)
        );
        dq.saturation_gap = None;
        dt.saturation_gap = None;
        dt.unsaturated_expansions = dq.unsaturated_expansions;
        assert_eq!(format!("{dq:?}"), format!("{dt:?}"), "sample {k}");
    }
}

#[test]
fn a_told_input_equal_to_the_last_output_changes_nothing_in_the_papers_loops() {
    for variant in Variant::ALL {
        for (n, example) in Example::ALL.into_iter().enumerate() {
            // The paper's loop, unsaturated: its expansions show in the told
            // run's health count, and nowhere else.
            let run = common::paper_loop(n as u8 + 1, variant, common::UNSAT);
            assert!(!run.nonfinite);
            match design::<f64>(example, variant, DT).unwrap() {
                Design::Order2(c) => told_input_changes_nothing(Controller::new(c), &run.z1),
                Design::Order3(c) => told_input_changes_nothing(Controller::new(c), &run.z1),
            }
            match design::<f32>(example, variant, DT as f32).unwrap() {
                Design::Order2(c) => told_input_changes_nothing(Controller::new(c), &run.z1),
                Design::Order3(c) => told_input_changes_nothing(Controller::new(c), &run.z1),
            }
        }
    }
}

#[test]
fn an_output_out_of_the_integrals_search_range_gives_the_nearest_one_searched() {
    // A first-stage gain of 1e-30 needs |I_0| ~ 1e30 to move s_1 by eps, far
    // beyond the search (eps 2^-20 doubled 96 times): no sign change is
    // found, and the I_0 searched whose output is nearest u0 is taken, so
    // the output moves (slightly) towards u0, on the side of u0.
    let laws = [
        (Feedback::Linear { k: 1e-30 }, None),
        (Feedback::Linear { k: 2.0 }, None),
    ];
    let b = Config::<f64, 3>::builder(1e-3, &laws, Constraint::Longitudinal { eps: 2.0 }, 4.0)
        .differentiator(Some(HighGain::new(0.01, [4.0, 4.0, 0.0], Discretization::Exact)))
        .integral(true);
    let first = |u0: Option<f64>| {
        Controller::new(b.initial_output(u0).build().unwrap())
            .step(0.05)
            .unwrap()
    };
    let (plain, up, down) = (first(None), first(Some(1e3)), first(Some(-1e3)));
    assert!(down < plain && plain < up, "{down} < {plain} < {up}");
    for u0 in [-1.0, 0.5, 3.0] {
        let v = first(Some(u0));
        assert!(down <= v && v <= up, "{u0}: {v} within {down} .. {up}");
    }
}

#[test]
fn step_state_applied_is_step_state_with_the_input_told() {
    // Untold, it is `step_state` bit for bit; told the previous output, the
    // saturation gap it reports is 0 (the actuator applied it exactly).
    let cfg = builder::<f64, 2>(4.0).build().unwrap();
    let (mut a, mut b) = (Controller::new(cfg), Controller::new(cfg));
    let mut last = None;
    for k in 0..200 {
        let t = k as f64 * DT;
        let z = [0.3 * (2.0 * t).cos(), -0.6 * (2.0 * t).sin()];
        let va = a.step_state(z).unwrap();
        let vb = b
            .step_state_applied(z, if k < 100 { None } else { last })
            .unwrap();
        assert!(
            va != 0.0,
            "sample {k}: a zero output would not tell the steps apart"
        );
        assert_eq!(va.to_bits(), vb.to_bits(), "sample {k}");
        let gap = b.diagnostics().saturation_gap;
        assert_eq!(gap, (k >= 100).then_some(0.0), "sample {k}");
        last = Some(vb);
    }
}

#[test]
fn the_integrals_search_stops_at_half_the_estimate_range() {
    // f32 (estimate range 2^64): with k_1 = k_2 = 1e-9 the integral enters
    // s_0 as 1e-18 I_0, and eps = 100 gives xi_0 = s_0 / 200. The first
    // output -k_u Gamma(0.125) needs s_0 = 25, I_0 = 2.5e19: beyond the
    // search, which stops at half the range (2^63 = 9.2e18). The nearest
    // searched I_0 is taken, within the range, and its output lies between
    // the plain start's and u0.
    let laws = [
        (Feedback::Linear { k: 1e-9_f32 }, None),
        (Feedback::Linear { k: 1e-9 }, None),
    ];
    let b = Config::<f32, 3>::builder(1e-3, &laws, Constraint::Longitudinal { eps: 100.0 }, 4.0)
        .differentiator(Some(HighGain::new(0.01, [4.0, 4.0, 0.0], Discretization::Exact)))
        .integral(true);
    let u0 = -4.0 * 2.0 * 0.125_f32.atanh();
    let plain = Controller::new(b.build().unwrap()).step(0.05).unwrap();
    let mut c = Controller::new(b.initial_output(Some(u0)).build().unwrap());
    let v = c.step(0.05).unwrap();
    let i0 = c.snapshot().zhat[0];
    assert!(i0.abs() <= 2.0_f32.powi(63), "I_0 {i0}");
    assert!(
        i0.abs() >= 2.0_f32.powi(62),
        "I_0 {i0}: the search went as far as it may"
    );
    assert!(u0 < v && v < plain, "{u0} < {v} < {plain}");
}
