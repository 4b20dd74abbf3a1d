//! Without the flexible boundary (`rho_e = None`, the controller of eq. (29) (uT))
//! nothing keeps a sampled loop inside `|xi| < 1`: a too slow sample rate or a
//! disturbance beyond the design pushes `|xi|` to 1 between samples. By
//! docs/design.md §3.6 the controller then clamps `xi` just below 1, counts
//! the event in `diagnostics().clamp_count` and never returns NaN or
//! infinity. With the flexible boundary on, the same settings never clamp.
//!
//! Measured settings where clamping really happens (run with `--nocapture`):
//! - example 1 (authors' plant, disturbance amplitude 3) sampled at 50 Hz
//!   (dt = 0.02), limits +-100: 437 of 501 samples clamp (f64 and f32), the
//!   output chatters at +-k_u Gamma(1 - eps/2) = +-187.1 (f32: +-86.6) and
//!   never settles; with `rho_e = 0.01` nothing clamps and |z1| < 0.1 from
//!   0.8 s on;
//! - example 1 at 1 kHz with the disturbance scaled by 10 (amplitude 30),
//!   limits +-1000: 8655 of 10001 samples clamp; with `rho_e = 0.01`, 0;
//! - example 3 sampled at 50 Hz (both variants): 24 of 26 (code) / 22 of 24
//!   (paper) samples clamp before the plant itself escapes (|x| > 1e6 at
//!   about 0.5 s; 50 Hz is far too slow for it, with or without `rho_e`);
//!   the controller stays finite and never fails throughout.
#![allow(clippy::unwrap_used, clippy::indexing_slicing)]

use crate::common;

use common::*;
use famcc_core::{Config, Constraint, Controller, Feedback, Gamma, Real};
use famcc_paper::plants::{Clock, Drift, Signal};

/// Example-1 plant with the disturbance amplitude as a parameter (the
/// authors' plant is `Scaled(3.0)`).
struct Scaled(f64);

impl Plant<f64, 2> for Scaled {
    fn x0(&self) -> [f64; 2] {
        Second::new(Variant::Code).x0()
    }
    fn terms<S: Signal<f64>>(&self, c: &Clock<S>, x: &[S; 2]) -> [(S, Drift<S>); 2] {
        // The paper's plant with amplitude 1, and its disturbance scaled.
        let [row1, (g2, [f2, _, _])] = Second::new(Variant::Paper).terms(c, x);
        let extra = (c.sin + c.cos2) * (self.0 - 1.0);
        [row1, (g2, [f2, extra, S::constant(0.0)])]
    }
}

#[derive(Debug, Default)]
struct Outcome {
    steps: usize,
    clamps: u64,
    max_abs_v: f64,
    settling: Option<f64>,
    plant_escaped: bool,
}

/// Closed loop with `y_d = sin t`, checking at every sample: finite output,
/// `|xi| < 1`, and that `clamp_count` grows by one exactly at the samples
/// where `xi` was clamped (without the flexible boundary `xi = xi_nominal`
/// unless clamped), with the clamped value just below 1 and the output
/// `-k_u Gamma(xi)`. Stops early if the plant escapes (`|x| > 1e6`).
fn run_checked<T: Real, const N: usize, P: TimePlant<N>>(
    plant: &P,
    ctrl: &mut Controller<T, N>,
    t_end: f64,
    limits: (f64, f64),
) -> Outcome {
    let cfg = *ctrl.config();
    let flexible = cfg.rho_e().is_some();
    let dt = cfg.dt().to_f64_lossless();
    let eps = T::epsilon();
    let steps = (t_end / dt).round() as usize;
    let mut x = plant.initial_state();
    let mut out = Outcome::default();
    let mut z1 = Vec::with_capacity(steps + 1);
    let mut clamps = 0;
    for k in 0..=steps {
        let t = k as f64 * dt;
        let e = x[0] - t.sin();
        let v = ctrl
            .step(T::from_f64(e))
            .unwrap_or_else(|err| panic!("step failed at t = {t}: {err}"));
        let d = ctrl.diagnostics();
        assert!(v.is_finite(), "non-finite output at t = {t}");
        assert_eq!(v, d.v);
        assert!(d.xi.abs() < T::one(), "|xi| = {:?} at t = {t}", d.xi);
        let clamped = d.clamp_count > clamps;
        assert!(d.clamp_count - clamps <= 1);
        clamps = d.clamp_count;
        if clamped {
            // Clamped to (nearly) the largest value below 1, on the side of
            // the nominal xi, and the output follows from the clamped value.
            assert!(
                d.xi.abs() >= T::one() - T::from_f64(2.0) * eps,
                "clamped to {:?}",
                d.xi
            );
            assert_eq!(d.xi > T::zero(), d.xi_nominal > T::zero());
            assert!(d.xi_nominal.abs() >= d.xi.abs());
            assert_eq!(v, -cfg.k_u() * cfg.gamma().eval(d.xi));
        } else if !flexible {
            assert_eq!(d.xi, d.xi_nominal, "xi changed without a clamp at t = {t}");
        }
        let vf = v.to_f64_lossless();
        out.max_abs_v = out.max_abs_v.max(vf.abs());
        let u = vf.clamp(limits.0, limits.1);
        z1.push(e);
        out.steps = k + 1;
        let sub = 10;
        let h = dt / sub as f64;
        for j in 0..sub {
            x = rk4(plant, t + j as f64 * h, &x, u, h);
        }
        if x.iter().any(|xi| !xi.is_finite() || xi.abs() > 1e6) {
            out.plant_escaped = true;
            break;
        }
    }
    out.clamps = clamps;
    out.settling = if out.plant_escaped {
        None
    } else {
        match z1.iter().rposition(|z| z.abs() >= 0.1) {
            None => Some(0.0),
            Some(i) if i + 1 < z1.len() => Some((i + 1) as f64 * dt),
            Some(_) => None,
        }
    };
    out
}

fn without_rho_e<T: Real, const N: usize>(c: Controller<T, N>) -> Controller<T, N> {
    Controller::new(c.config().to_builder().rho_e(None).build().unwrap())
}

#[test]
fn example1_at_50_hz_clamps_only_without_flexible_boundary() {
    let dt = 0.02;
    let plant = Second::new(Variant::Code);
    let mut plain = without_rho_e(example1::<f64>(Variant::Code, dt));
    let r = run_checked(&plant, &mut plain, 10.0, UNSAT);
    println!("example 1, 50 Hz, rho_e = None: {r:?}");
    assert!(!r.plant_escaped);
    assert_eq!(r.steps, 501);
    assert!(r.clamps > 100, "expected frequent clamping, got {}", r.clamps);
    // The clamped output: k_u Gamma(1 - eps/2) = 5 * 2 atanh(1 - 2^-53) ~ 187.1.
    assert!(r.max_abs_v > 150.0 && r.max_abs_v < 200.0, "{}", r.max_abs_v);

    let mut flex = example1::<f64>(Variant::Code, dt);
    let r = run_checked(&plant, &mut flex, 10.0, UNSAT);
    println!("example 1, 50 Hz, rho_e = 0.01: {r:?}");
    assert_eq!(r.clamps, 0);
    assert!(r.settling.unwrap() < 3.0, "{:?}", r.settling);
}

#[test]
fn example1_f32_at_50_hz_clamps_and_stays_finite() {
    let plant = Second::new(Variant::Code);
    let mut plain = without_rho_e(example1::<f32>(Variant::Code, 0.02));
    let r = run_checked(&plant, &mut plain, 10.0, UNSAT);
    println!("example 1 f32, 50 Hz, rho_e = None: {r:?}");
    assert!(!r.plant_escaped);
    assert!(r.clamps > 100, "{}", r.clamps);
    // f32: k_u * 2 atanh(1 - 2^-23) ~ 5 * 16.6.
    assert!(r.max_abs_v > 70.0 && r.max_abs_v < 100.0, "{}", r.max_abs_v);
}

#[test]
fn example1_with_ten_times_the_disturbance_clamps_at_1_khz() {
    let plant = Scaled(30.0);
    let limits = (-1000.0, 1000.0);
    let mut plain = without_rho_e(example1::<f64>(Variant::Code, 1e-3));
    let r = run_checked(&plant, &mut plain, 10.0, limits);
    println!("example 1, 1 kHz, disturbance x10, rho_e = None: {r:?}");
    assert!(!r.plant_escaped);
    assert!(r.clamps > 1000, "{}", r.clamps);

    let mut flex = example1::<f64>(Variant::Code, 1e-3);
    let r = run_checked(&plant, &mut flex, 10.0, limits);
    println!("example 1, 1 kHz, disturbance x10, rho_e = 0.01: {r:?}");
    assert!(!r.plant_escaped);
    assert_eq!(r.clamps, 0);
}

#[test]
fn example3_at_50_hz_clamps_and_stays_finite_until_the_plant_escapes() {
    for variant in [Variant::Code, Variant::Paper] {
        let plant = Third::new(variant);
        let mut plain = without_rho_e(example3::<f64>(variant, 0.02));
        let r = run_checked(&plant, &mut plain, 5.0, UNSAT);
        println!("example 3 {variant:?}, 50 Hz, rho_e = None: {r:?}");
        assert!(r.clamps >= 10, "{}", r.clamps);
        // 50 Hz is far too slow for this plant (docs/design.md §7.1: it needs ~500 Hz): the
        // loop is lost either way, but the controller itself never fails.
        let mut flex = example3::<f64>(variant, 0.02);
        let r = run_checked(&plant, &mut flex, 5.0, UNSAT);
        println!("example 3 {variant:?}, 50 Hz, rho_e = 0.01: {r:?}");
        assert_eq!(r.clamps, 0);
    }
}

/// State feedback far outside the envelope: every step clamps, for both
/// Gamma maps and both float types, and the output is `-k_u Gamma(xi)` at
/// the clamped `xi` (finite: Gamma is only infinite at exactly 1).
#[test]
fn clamping_by_state_feedback_is_counted_per_step() {
    fn check<T: Real>(gamma: Gamma) {
        let cfg = Config::<T, 2>::builder(
            T::from_f64(1e-3),
            &[(Feedback::Linear { k: T::from_f64(2.0) }, None)],
            Constraint::Longitudinal {
                eps: T::from_f64(0.1),
            },
            T::from_f64(5.0),
        )
        .rho_e(None)
        .gamma(gamma)
        .build()
        .unwrap();
        let mut c = Controller::new(cfg);
        // Latch at s0 = 1: y_U(0) = 2.
        let v0 = c.step_state([T::from_f64(0.5), T::zero()]).unwrap();
        assert_eq!(c.diagnostics().clamp_count, 0);
        assert!(v0 < T::zero());
        for (k, big) in [1e3, -1e3, 1e30, -4.0, 3.0].into_iter().enumerate() {
            let v = c.step_state([T::from_f64(big), T::zero()]).unwrap();
            let d = c.diagnostics();
            assert_eq!(d.clamp_count, k as u64 + 1, "gamma {gamma:?} z1 = {big}");
            assert!(v.is_finite());
            assert!(d.xi.abs() < T::one() && d.xi.abs() >= T::one() - T::from_f64(2.0) * T::epsilon());
            assert_eq!(v < T::zero(), big > 0.0, "v = {v:?} for z1 = {big}");
            assert_eq!(v, -cfg.k_u() * gamma.eval(d.xi));
        }
        // Back inside: no further clamp, the count is kept.
        c.step_state([T::from_f64(0.01), T::zero()]).unwrap();
        assert_eq!(c.diagnostics().clamp_count, 5);
        assert!(c.diagnostics().xi.abs() < T::from_f64(0.5));
        // reset clears it.
        c.reset();
        assert_eq!(c.diagnostics().clamp_count, 0);
    }
    check::<f64>(Gamma::Log);
    check::<f64>(Gamma::Rational);
    check::<f32>(Gamma::Log);
    check::<f32>(Gamma::Rational);
}
