//! Reliability (docs/design.md §3.7, §3.9, §3.10): bounded recovery from
//! any finite input, validation of configurations that could never run, a
//! clock exact for 10^10 steps, and `restore` checking every field. The
//! randomized counterpart is `tests/suite/fuzz.rs`.
#![allow(clippy::unwrap_used, clippy::indexing_slicing)]

use crate::common;

use common::{rk4, Second, Third, Variant};
use famcc_core::{
    Config, Constraint, Controller, Discretization, Feedback, HighGain, Real, Skew, StepError,
    RECOVERY_SAMPLES,
};

/// The lock-up of issue 15: f32, order 2, the discontinuous law, LoMC, the
/// exact differentiator; four finite samples used to lock it for good.
#[test]
fn the_reported_lock_up_recovers() {
    let cfg = Config::<f32, 2>::builder(
        1e-3,
        &[(
            Feedback::MoulayDiscontinuous {
                beta: 1.0,
                lambda: 1.0,
                mu: 0.5,
            },
            None,
        )],
        Constraint::Longitudinal { eps: 0.1 },
        5.0,
    )
    .differentiator(Some(HighGain::paper()))
    .build()
    .unwrap();
    let mut c = Controller::new(cfg);
    for e in [-f32::MAX, 1e19, 3.4e38, f32::MAX] {
        let _ = c.step(e);
    }
    let results: Vec<_> = (0..20).map(|_| c.step(0.1)).collect();
    assert!(
        results[RECOVERY_SAMPLES - 1..].iter().all(Result::is_ok),
        "{results:?}"
    );
}

/// Consecutive failed steps after one outlier in the closed loop of the
/// paper's example (the caller holds its last output meanwhile), and whether
/// the loop is back within `eps` at the end.
fn outage<T: Real, const N: usize>(
    mut c: Controller<T, N>,
    plant: impl Fn(f64, &[f64; N], f64) -> [f64; N],
    x0: [f64; N],
    outlier: f64,
) -> (usize, f64) {
    let dt = c.config().dt().to_f64_lossless();
    let (mut x, mut u, mut failed, mut last) = (x0, 0.0, 0, 0.0);
    for k in 0..10_000 {
        let t = k as f64 * dt;
        let e = x[0] - t.sin();
        let sample = if k == 5_000 { outlier } else { e };
        match c.step(T::from_f64(sample)) {
            Ok(v) => u = v.to_f64_lossless().clamp(-100.0, 100.0),
            Err(err) => {
                assert_eq!(err, StepError::Overflow);
                failed += 1;
            }
        }
        x = rk4(&Wrap(&plant), t, &x, u, dt);
        last = e.abs();
    }
    (failed, last)
}

struct Wrap<'a, F>(&'a F);

impl<const N: usize, F: Fn(f64, &[f64; N], f64) -> [f64; N]> common::TimePlant<N> for Wrap<'_, F> {
    fn initial_state(&self) -> [f64; N] {
        [0.0; N]
    }
    fn rate(&self, t: f64, x: &[f64; N], u: f64) -> [f64; N] {
        (self.0)(t, x, u)
    }
}

/// The outage of a single outlier (1e300 in f64, f32::MAX in f32) on the
/// paper's three examples: one sample, the outlier's own (docs/design.md
/// §3.7); the loop is back within the accuracy by the end.
#[test]
fn one_outlier_costs_one_sample_on_the_papers_examples() {
    use common::TimePlant;
    use famcc_paper::designs;
    let p2 = Second::new(Variant::Code);
    let p3 = Third::new(Variant::Code);
    let f2 = |t: f64, x: &[f64; 2], u: f64| p2.rate(t, x, u);
    let f3 = |t: f64, x: &[f64; 3], u: f64| p3.rate(t, x, u);
    let runs = [
        (
            "example 1 f64",
            outage(
                Controller::new(designs::example1(Variant::Code, 1e-3).unwrap()),
                f2,
                p2.initial_state(),
                1e300,
            ),
            0.1,
        ),
        (
            "example 2 f64",
            outage(
                Controller::new(designs::example2(Variant::Code, 1e-3).unwrap()),
                f2,
                p2.initial_state(),
                1e300,
            ),
            0.15,
        ),
        (
            "example 3 f64",
            outage(
                Controller::new(designs::example3(Variant::Code, 1e-3).unwrap()),
                f3,
                p3.initial_state(),
                1e300,
            ),
            0.1,
        ),
        (
            "example 1 f32",
            outage(
                Controller::new(designs::example1::<f32>(Variant::Code, 1e-3).unwrap()),
                f2,
                p2.initial_state(),
                f32::MAX.into(),
            ),
            0.1,
        ),
        (
            "example 2 f32",
            outage(
                Controller::new(designs::example2::<f32>(Variant::Code, 1e-3).unwrap()),
                f2,
                p2.initial_state(),
                f32::MAX.into(),
            ),
            0.15,
        ),
        (
            "example 3 f32",
            outage(
                Controller::new(designs::example3::<f32>(Variant::Code, 1e-3).unwrap()),
                f3,
                p3.initial_state(),
                f32::MAX.into(),
            ),
            0.1,
        ),
    ];
    for (name, (failed, last), eps) in runs {
        println!("{name}: {failed} failed step(s) after the outlier, |z1| = {last:.2e} at 10 s");
        assert!(failed <= 1, "{name}: {failed} failed steps");
        assert!(last < eps, "{name}: |z1| = {last} at the end");
    }
}

fn lomc<T: Real, const N: usize>() -> famcc_core::ConfigBuilder<T, N> {
    let laws = [(Feedback::Linear { k: T::one() }, None); 8];
    Config::<T, N>::builder(
        T::from_f64(1e-3),
        &laws[..N - 1],
        Constraint::Longitudinal {
            eps: T::from_f64(0.1),
        },
        T::from_f64(5.0),
    )
    .differentiator(Some(HighGain::paper()))
}

fn rejected<T: Real, const N: usize>(b: famcc_core::ConfigBuilder<T, N>) -> &'static str {
    b.build().unwrap_err().parameter
}

/// Configurations whose first step could not succeed for a moderate input
/// are rejected, naming the parameter (the list, in both types).
#[test]
fn configs_that_cannot_run_are_rejected_by_name() {
    fn check<T: Real>(huge: f64, tiny: f64) {
        let f = T::from_f64;
        let mu = HighGain::new(f(tiny), [f(4.0), f(4.0)], Discretization::Exact);
        assert_eq!(rejected(lomc::<T, 2>().differentiator(Some(mu))), "mu");
        assert_eq!(rejected(lomc::<T, 2>().k_u(f(huge))), "k_u");
        assert_eq!(rejected(lomc::<T, 2>().k0(f(huge))), "k0");
        assert_eq!(rejected(lomc::<T, 2>().dt(f(tiny))), "dt");
        assert_eq!(rejected(lomc::<T, 2>().settle_time(f(huge))), "settle_time");
        let ft = Feedback::FixedTime {
            alpha: f(huge),
            p: f(0.5),
            beta: f(1.0),
            q: f(2.0),
        };
        let b = Config::<T, 2>::builder(
            f(1e-3),
            &[(ft, None)],
            Constraint::Longitudinal { eps: f(0.1) },
            f(5.0),
        );
        assert_eq!(rejected(b), "alpha");
        for (skew, name) in [
            (Skew::smooth(f(huge), f(0.1)), "eps_s"),
            (Skew::nonsingular(f(0.1), f(0.1), f(huge)), "k_pp"),
        ] {
            let b = Config::<T, 2>::builder(
                f(1e-3),
                &[(Feedback::FiniteTime { k: f(1.0), p: f(0.5) }, Some(skew))],
                Constraint::Longitudinal { eps: f(0.1) },
                f(5.0),
            );
            assert_eq!(rejected(b), name);
        }
        assert_eq!(
            rejected(lomc::<T, 2>().constraint(Constraint::Longitudinal { eps: f(huge) })),
            "eps"
        );
        let mut d = [T::zero(); 6];
        d[2] = f(huge);
        assert_eq!(
            rejected(lomc::<T, 4>().initial_derivatives(d[..4].try_into().ok())),
            "initial_derivatives"
        );
        assert_eq!(
            rejected(lomc::<T, 5>().initial_derivatives(d[..5].try_into().ok())),
            "initial_derivatives"
        );
        assert_eq!(
            rejected(lomc::<T, 6>().initial_derivatives(Some(d))),
            "initial_derivatives"
        );
    }
    check::<f64>(1e308, 1e-300);
    check::<f32>(3e38, 1e-38);
}

/// Initial derivatives within the builder's magnitude limit that still make
/// the first step overflow are blamed on themselves (the probe runs the
/// configuration again without them), not on the law that overflows: a
/// fixed-time stage of exponent 5 is fine for `|e| <= 1e3` but not for an
/// initial `e'` of 1e9 (f32) or 1e70 (f64).
#[test]
fn initial_derivatives_that_overflow_the_first_step_are_named() {
    fn check<T: Real>(large: f64) {
        let f = T::from_f64;
        let fixed = Feedback::FixedTime {
            alpha: T::one(),
            p: f(0.5),
            beta: f(2.0),
            q: f(5.0),
        };
        let b = Config::<T, 3>::builder(
            f(1e-3),
            &[(Feedback::Linear { k: T::one() }, None), (fixed, None)],
            Constraint::Longitudinal { eps: f(0.1) },
            f(5.0),
        );
        let moderate = [T::zero(), f(1e3), f(1e3)];
        assert!(b.initial_derivatives(Some(moderate)).build().is_ok());
        let err = b
            .initial_derivatives(Some([T::zero(), f(large), f(large)]))
            .build()
            .unwrap_err();
        assert_eq!(err.parameter, "initial_derivatives");
        assert!(err.rule.contains("first step overflows"), "{}", err.rule);
    }
    check::<f32>(1e9);
    check::<f64>(1e70);
}

/// A law that overflows in a band of moderate errors and not at the ends
/// of the range: Moulay's exponent tends to `lambda/mu` (about 103 here),
/// composed with a fixed-time and two variable-exponent stages. Every step
/// after the first overflowed for a constant error between about 17 and 600,
/// while 0, 1 and ±1e3 stepped fine. The probe's grid of moderate errors
/// must reject it (found by an adversarial run of random configurations).
#[test]
fn a_law_that_overflows_inside_the_moderate_range_is_rejected() {
    let laws = [
        (
            Feedback::MoulayDiscontinuous {
                beta: 0.7696,
                lambda: 1.2175,
                mu: 0.011832,
            },
            Some(Skew::nonsingular(0.0074166, 0.0032432, 1.86935)),
        ),
        (
            Feedback::FixedTime {
                alpha: 0.83272,
                p: 0.52365,
                beta: 1.03218,
                q: 2.25478,
            },
            Some(Skew::nonsingular(1.14147, 0.62555, 1.4085)),
        ),
        (
            Feedback::VariableExponent {
                k: 5.75849,
                r_b: 0.56693,
                r_1: 1.3642,
                r_t: 2.94366,
            },
            Some(Skew::nonsingular(0.77806, 0.32459, 0.28781)),
        ),
        (
            Feedback::VariableExponent {
                k: 3.31708,
                r_b: 0.23381,
                r_1: 1.22919,
                r_t: 2.88891,
            },
            Some(Skew::smooth(0.048194, 0.031738)),
        ),
    ];
    let b = Config::<f64, 5>::builder(1e-3, &laws, Constraint::Lateral { eps: 0.14859 }, 12.92)
        .settle_time(0.6676)
        .rho_e(None)
        .differentiator(Some(HighGain::new(
            0.16688,
            [5.0, 10.0, 10.0, 5.0, 1.0],
            Discretization::Tustin,
        )));
    // (Before the grid, the probe's four errors 0, 1, ±1e3 accepted it.)
    let err = b.build().unwrap_err();
    assert!(["mu", "feedback"].contains(&err.parameter), "{err:?}");
}

/// The probe's grid: zero and both signs of 49 magnitudes from 1e-3 to 1e3,
/// 8 a decade, each a constant ratio from the last.
#[test]
fn the_probe_grid_spans_the_moderate_range() {
    use famcc_core::{probe_error, probe_errors, PROBE_COUNT, PROBE_LIMIT, PROBE_PER_DECADE};
    let all: Vec<f64> = probe_errors().collect();
    assert_eq!(all.len(), PROBE_COUNT);
    assert_eq!(all.iter().filter(|e| **e == 0.0).count(), 1);
    let pos: Vec<f64> = all.iter().copied().filter(|e| *e > 0.0).collect();
    assert_eq!(pos.len(), 6 * PROBE_PER_DECADE + 1);
    assert!((pos[0] - 1e-3).abs() < 1e-18 && pos[pos.len() - 1] == PROBE_LIMIT);
    let ratio = 10f64.powf(1.0 / PROBE_PER_DECADE as f64);
    for w in pos.windows(2) {
        assert!((w[1] / w[0] - ratio).abs() < 1e-9, "{w:?}");
    }
    for (i, e) in all.iter().enumerate() {
        assert_eq!(*e, probe_error(i));
        assert!(e.abs() <= PROBE_LIMIT);
        if *e > 0.0 {
            assert!(all.contains(&-e));
        }
    }
}

/// The first-order hold restarts as the held input does: the sample after a
/// restart adds no feedthrough to the restarted estimate. Found by the fuzz
/// (f32, order 4): a law that overflows on the differentiator's peaking, a
/// first sample at 0 and then a slowly moving error near 936. Each restart
/// met the error's increment with zero derivatives, so every sample failed
/// for good; now it recovers like the exact hold (Ok every other sample at
/// worst, never two errors in a row).
#[test]
fn a_first_order_hold_controller_recovers_after_a_restart() {
    let laws = [
        (
            Feedback::VariableExponent {
                k: 2.071_232_5,
                r_b: 0.5,
                r_1: 2.355_641_5,
                r_t: 3.539_051_4,
            },
            Some(Skew::nonsingular(0.2, 0.1, 0.5)),
        ),
        (
            Feedback::FixedTime {
                alpha: 0.2,
                p: 0.3,
                beta: 0.2,
                q: 2.942_681_6,
            },
            Some(Skew::nonsingular(0.2, 0.1, 0.5)),
        ),
        (
            Feedback::MoulayDiscontinuous {
                beta: 0.2,
                lambda: 0.2,
                mu: 0.870_724_5,
            },
            None,
        ),
    ];
    let mut a = [0.0_f32; 4];
    famcc_core::differentiator::paper_coefficients(&mut a);
    for d in [Discretization::Foh, Discretization::Exact] {
        let cfg = Config::<f32, 4>::builder(1e-3, &laws, Constraint::Longitudinal { eps: 0.02 }, 0.5)
            .differentiator(Some(HighGain::new(0.005, a, d)))
            .build()
            .unwrap();
        let mut c = Controller::new(cfg);
        c.step(0.0).unwrap();
        let ok: Vec<bool> = (0..40)
            .map(|k| {
                let e = 935.565_76 + 0.1 * (k as f32 * 0.01).sin();
                c.step(e).is_ok()
            })
            .collect();
        let first = ok.iter().position(|x| *x);
        assert!(first.is_some_and(|i| i < RECOVERY_SAMPLES), "{d:?}: {ok:?}");
        assert!(ok.windows(2).all(|w| w[0] || w[1]), "{d:?}: {ok:?}");
    }
}
