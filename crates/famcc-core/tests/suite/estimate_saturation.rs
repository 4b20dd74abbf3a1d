//! Issue requirement: "A test shows that [the differentiator's estimate
//! saturation] removes the start-up spike of u in the third-order example."
//!
//! The high-gain differentiator starts from `Zhat = (e0, 0, 0)` while the
//! true `(z2, z3)` are not zero; for a few `mu` (= 10 ms) its estimate of
//! `z3` peaks far beyond the true value (to about -20 in the authors'
//! variant, -64 in the paper's, while the true |z3| stays below 7.3), and
//! the control follows. Saturating the estimates fed to the law,
//! `cfg.estimate_limits = Some([2, 2, 10])`, removes that spike.
//!
//! Why these limits are a-priori knowledge, not tuning: `|z1(0)| = 1` is the
//! first measurement, so `|z1| <= 2` leaves a factor 2. `z2 = x1' - y_d'`
//! and `z3 = x1'' - y_d''` are bounded by the plant's own speed: the
//! reference has unit rates, the plant's drift and disturbance in its
//! x1/x2 equations are of order 1 and the disturbance of its x3 equation
//! has amplitude 10, so a designer can state `|z2| <= 2`, `|z3| <= 10`. The
//! test checks that these limits never clip the true signal: over the whole
//! saturated run the true `|z_i|` (computed from the plant) stay below
//! `limit_i / 1.5`, so the saturation only removes estimation error. A looser
//! `z3` limit (20, three times the true bound) still leaves the paper
//! variant's spike (`|v|` about 250); only the `z3` limit matters here.
//!
//! Measured (1 kHz, RK4 with 10 substeps, limits +-100; |u| = clamped v):
//!
//! | variant | max |u|, 0-20 ms | max |u|, 0-50 ms | max |v|, 0-50 ms | settles |
//! |---|---|---|---|---|
//! | code, no saturation    | 80.5  | 92.7  | 92.7  | 1.262 s |
//! | code, [2, 2, 10]       | 33.0  | 66.6  | 66.6  | 1.252 s |
//! | paper, no saturation   | 100.0 | 100.0 | 282.1 | 0.998 s |
//! | paper, [2, 2, 10]      | 37.1  | 37.1  | 37.1  | 0.953 s |
//!
//! For reference, state feedback with the true `Z` gives max |u| = 33.0 in
//! the first 50 ms (its first sample, `k_u Gamma(1/k0) = 30 ln 3`). In the
//! authors' variant the peaking spike (+80 at 12 ms, the wrong sign: the
//! true z3 is positive) is removed completely; what remains in 20-50 ms
//! (-66) is the estimate's lag behind the true z3 at mu = 0.01, not peaking.
#![allow(clippy::unwrap_used, clippy::indexing_slicing)]

use crate::common;

use common::*;
use famcc_core::Controller;

const DT: f64 = 1e-3;
const T_END: f64 = 10.0;
const LIMITS: [f64; 3] = [2.0, 2.0, 10.0];

/// The true error vector `(z1, z1', z1'')` for `y_d = sin t`, from the
/// plant's exact output derivatives.
fn true_z(p: &Third, t: f64, x: &[f64; 3]) -> [f64; 3] {
    let [y, dy, ddy] = output_derivatives(p, t, x);
    [y - t.sin(), dy - t.cos(), ddy + t.sin()]
}

#[derive(Debug, Default)]
struct Start {
    /// max |u| over the first 20 ms (two differentiator time constants).
    u20: f64,
    /// max |u| over the first 50 ms.
    u50: f64,
    /// max |v| (before the actuator limit) over the first 50 ms.
    v50: f64,
    /// |u| at the first sample.
    u0: f64,
    settling: Option<f64>,
    max_abs_xi: f64,
    clamps: u64,
    /// max |z_i| of the true error vector over the run.
    true_z_max: [f64; 3],
}

fn run_start(variant: Variant, limits: Option<[f64; 3]>, state_feedback: bool) -> Start {
    let cfg = example3_cfg::<f64>(variant, DT).unwrap();
    let mut ctrl = Controller::new(cfg.to_builder().estimate_limits(limits).build().unwrap());
    let plant = Third::new(variant);
    let (lo, hi) = UNSAT;
    let mut x = plant.x0();
    let mut s = Start::default();
    let mut z1 = Vec::new();
    let steps = (T_END / DT).round() as usize;
    for k in 0..=steps {
        let t = k as f64 * DT;
        let z = true_z(&plant, t, &x);
        for (m, zi) in s.true_z_max.iter_mut().zip(z) {
            *m = m.max(zi.abs());
        }
        let v = if state_feedback {
            ctrl.step_state(z)
        } else {
            ctrl.step(z[0])
        }
        .unwrap();
        assert!(v.is_finite());
        let d = ctrl.diagnostics();
        s.max_abs_xi = s.max_abs_xi.max(d.xi.abs());
        s.clamps = d.clamp_count;
        let u = v.clamp(lo, hi);
        if k == 0 {
            s.u0 = u.abs();
        }
        if k <= 20 {
            s.u20 = s.u20.max(u.abs());
        }
        if k <= 50 {
            s.u50 = s.u50.max(u.abs());
            s.v50 = s.v50.max(v.abs());
        }
        z1.push(z[0]);
        let h = DT / 10.0;
        for j in 0..10 {
            x = rk4(&plant, t + j as f64 * h, &x, u, h);
        }
        assert!(x.iter().all(|xi| xi.is_finite()), "plant diverged at {t}");
    }
    s.settling = match z1.iter().rposition(|z| z.abs() >= 0.1) {
        None => Some(0.0),
        Some(i) if i + 1 < z1.len() => Some((i + 1) as f64 * DT),
        Some(_) => None,
    };
    s
}

/// The limits never clip the true error vector (a margin of 1.5).
fn check_limits_never_clip(s: &Start) {
    for (m, l) in s.true_z_max.iter().zip(LIMITS) {
        assert!(
            m * 1.5 < l,
            "true max |z| {:?} vs limits {LIMITS:?}",
            s.true_z_max
        );
    }
}

fn check_healthy(name: &str, s: &Start) {
    println!("{name}: {s:?}");
    assert!(s.max_abs_xi < 1.0, "{name}: max |xi~| = {}", s.max_abs_xi);
    assert_eq!(s.clamps, 0, "{name}");
    let ts = s.settling.unwrap_or_else(|| panic!("{name}: never settled"));
    assert!(ts < 7.0, "{name}: settling {ts} s");
}

#[test]
fn estimate_saturation_removes_the_start_up_spike_code_variant() {
    let raw = run_start(Variant::Code, None, false);
    let sat = run_start(Variant::Code, Some(LIMITS), false);
    let exact = run_start(Variant::Code, None, true);
    check_healthy("code, no saturation", &raw);
    check_healthy("code, saturated", &sat);
    println!("code, state feedback: {exact:?}");
    check_limits_never_clip(&sat);
    // The peaking spike: 80.5 -> 33.0 within 2 mu (measured).
    assert!(raw.u20 > 2.0 * sat.u20, "0-20 ms: {} vs {}", raw.u20, sat.u20);
    // With saturation nothing in the first 20 ms exceeds the first sample
    // (set by the latch) by more than 20 %; without, it is 2.4 times it.
    assert!(sat.u20 <= 1.2 * sat.u0, "{} vs u0 = {}", sat.u20, sat.u0);
    assert!(raw.u20 > 2.0 * raw.u0);
    // Over 50 ms: 92.7 -> 66.6 (measured; the rest is estimate lag).
    assert!(raw.u50 > 1.3 * sat.u50, "0-50 ms: {} vs {}", raw.u50, sat.u50);
    // State feedback has no spike at all.
    assert!(exact.u50 <= 1.01 * exact.u0);
}

#[test]
fn estimate_saturation_removes_the_start_up_spike_paper_variant() {
    let raw = run_start(Variant::Paper, None, false);
    let sat = run_start(Variant::Paper, Some(LIMITS), false);
    check_healthy("paper, no saturation", &raw);
    check_healthy("paper, saturated", &sat);
    check_limits_never_clip(&sat);
    // Without saturation the law asks for |v| = 282 and the actuator sits at
    // its limit 100; with it, max |u| = 37.1 (measured).
    assert!(raw.v50 > 200.0, "{}", raw.v50);
    assert_eq!(raw.u50, 100.0);
    assert!(raw.u50 > 2.5 * sat.u50, "0-50 ms: {} vs {}", raw.u50, sat.u50);
    assert!(raw.v50 > 5.0 * sat.v50);
    assert!(sat.u20 <= 1.2 * sat.u0, "{} vs u0 = {}", sat.u20, sat.u0);
}

/// Saturation that never binds changes nothing, bit for bit.
#[test]
fn loose_limits_change_nothing() {
    let raw = run_start(Variant::Code, None, false);
    let loose = run_start(Variant::Code, Some([f64::INFINITY, 1e6, 1e6]), false);
    assert_eq!(format!("{raw:?}"), format!("{loose:?}"));
}
