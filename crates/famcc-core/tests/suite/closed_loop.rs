//! Closed-loop outcomes on the paper's six scenarios (docs/design.md §6), both
//! plant variants: controller at 1 kHz, plant by RK4 between samples.
//!
//! Run with `--nocapture` to see the measured figures.
#![allow(clippy::unwrap_used, clippy::indexing_slicing)]

use crate::common;
use common::*;
use famcc_core::bounds;

const DT: f64 = 1e-3;
const T_END: f64 = 10.0;
const T_S: f64 = 1.0;
const EPS_Z: f64 = 0.1;

fn t_prime(example: u8) -> f64 {
    match example {
        1 => bounds::finite_time(1.0, 0.5, -1.0),
        2 => bounds::variable_exponent(1.5, 0.5, 2.0, 3.0),
        _ => bounds::fixed_time(&[(1.0, 0.5, 0.5, 2.0), (2.0, 0.5, 1.0, 2.0)]),
    }
}

fn report(name: &str, r: &Run) {
    let (lo, hi) = r.u_range();
    let first = r.z1.iter().position(|z| z.abs() < EPS_Z).map(|i| r.t[i]);
    println!(
        "{name}: settling {:?} s, first entry {:?} s, max|xi~| {:.6}, u in [{lo:.3}, {hi:.3}], \
         last saturation end {:?}, clamps {}",
        r.settling_time(EPS_Z),
        first,
        r.max_abs_xi(),
        r.last_saturation_end(),
        r.clamp_count
    );
}

/// Invariants of every run: finite, |xi~| < 1 with no clamping, u in limits.
fn check_invariants(r: &Run, limits: (f64, f64)) {
    assert!(!r.nonfinite, "a value became non-finite");
    assert_eq!(r.t.len(), (T_END / DT).round() as usize + 1);
    assert!(r.max_abs_xi() < 1.0, "max |xi~| = {}", r.max_abs_xi());
    assert_eq!(r.clamp_count, 0, "xi~ had to be clamped");
    let (lo, hi) = r.u_range();
    assert!(lo >= limits.0 && hi <= limits.1);
}

fn check_unsaturated(example: u8, variant: Variant) {
    let r = paper_loop(example, variant, UNSAT);
    report(&format!("example {example} {variant:?} unsaturated"), &r);
    check_invariants(&r, UNSAT);
    let bound = T_S + t_prime(example);
    let ts = r.settling_time(EPS_Z).expect("never settled");
    assert!(ts < bound, "settling {ts} s exceeds the bound {bound} s");
}

/// Saturated run: regains |z1| < eps_z by max(T_e, T_s) + T', and the
/// bounds expand while saturated and are nominal after the last expansion.
fn check_saturated(example: u8, variant: Variant, limits: (f64, f64)) -> Run {
    let r = paper_loop(example, variant, limits);
    report(&format!("example {example} {variant:?} saturated {limits:?}"), &r);
    check_invariants(&r, limits);
    check_expansion(&r);
    r
}

fn check_expansion(r: &Run) {
    let sat: Vec<bool> = r.v.iter().zip(&r.u).map(|(v, u)| v != u).collect();
    assert!(sat.iter().any(|s| *s), "the run never saturated");
    assert!(r.expanded.iter().any(|e| *e), "the bounds never expanded");
    for (i, e) in r.expanded.iter().enumerate() {
        let (b, n) = (r.bounds[i], r.nominal[i]);
        if *e {
            assert!(
                b.0 > n.0 || b.1 > n.1,
                "expanded flag without expansion at {}",
                r.t[i]
            );
        } else {
            assert_eq!(b, n, "bounds not nominal at t = {}", r.t[i]);
        }
    }
    // Expansion happens only around saturation: every expanded sample lies
    // within 50 ms of a saturated one.
    for (i, e) in r.expanded.iter().enumerate() {
        if *e {
            let lo = i.saturating_sub(50);
            let hi = (i + 50).min(sat.len() - 1);
            assert!(
                sat[lo..=hi].iter().any(|s| *s),
                "expanded without saturation at {}",
                r.t[i]
            );
        }
    }
    // Back to nominal after the last expansion.
    let last = r.expanded.iter().rposition(|e| *e).unwrap();
    assert!(last + 1 < r.expanded.len(), "still expanded at the end");
}

fn check_recovery(example: u8, r: &Run) {
    let t_e = r.last_saturation_end().unwrap();
    let bound = t_e.max(T_S) + t_prime(example);
    let ts = r.settling_time(EPS_Z).expect("never regained the accuracy");
    assert!(
        ts <= bound,
        "regained at {ts} s, bound max(T_e={t_e}, T_s) + T' = {bound} s"
    );
    check_recovery_per_episode(example, r);
}

/// Corollaries 1-3 (ii) for every saturation episode, not only the last: when
/// the controller leaves saturation at T_e and does not saturate again before
/// max(T_e, T_s) + T', then |z1| < eps_z from that time until the next
/// saturation starts. With periodic disturbances the last episode's bound can
/// lie past the horizon; the earlier episodes still test the claim.
fn check_recovery_per_episode(example: u8, r: &Run) -> usize {
    let sat: Vec<bool> = r.v.iter().zip(&r.u).map(|(v, u)| v != u).collect();
    let mut checked = 0;
    let mut i = 0;
    while i < sat.len() {
        if !sat[i] {
            i += 1;
            continue;
        }
        let mut end = i;
        while end < sat.len() && sat[end] {
            end += 1;
        }
        // Episode [i, end): exit time T_e = t[end]; next start or the horizon.
        let Some(&t_e) = r.t.get(end) else { break };
        let next = (end..sat.len()).find(|k| sat[*k]).unwrap_or(sat.len());
        let due = t_e.max(T_S) + t_prime(example);
        for k in end..next {
            if r.t[k] >= due {
                assert!(
                    r.z1[k].abs() < EPS_Z,
                    "|z1| = {} at t = {} s: saturation ended at {t_e} s, accuracy due by {due} s",
                    r.z1[k].abs(),
                    r.t[k]
                );
                checked += 1;
            }
        }
        i = end;
    }
    checked
}

#[test]
fn example1_unsaturated() {
    check_unsaturated(1, Variant::Paper);
    check_unsaturated(1, Variant::Code);
}

#[test]
fn example2_unsaturated() {
    check_unsaturated(2, Variant::Paper);
    check_unsaturated(2, Variant::Code);
}

#[test]
fn example3_unsaturated() {
    check_unsaturated(3, Variant::Paper);
    check_unsaturated(3, Variant::Code);
}

#[test]
fn example1_saturated() {
    let r = check_saturated(1, Variant::Code, (-2.5, 3.0));
    check_recovery(1, &r);
}

#[test]
fn example2_saturated() {
    let r = check_saturated(2, Variant::Code, (-2.0, 3.0));
    check_recovery(2, &r);
}

#[test]
fn example3_saturated_code() {
    let r = check_saturated(3, Variant::Code, (-7.0, 9.0));
    check_recovery(3, &r);
}

/// Over 20 s the code-variant plants saturate periodically (-F/G leaves the
/// limits once per disturbance period): every episode must be followed by the
/// recovery the corollaries promise, wherever the next one leaves room.
#[test]
fn saturated_recovery_after_every_episode_20s() {
    let cases: [(u8, (f64, f64)); 3] = [(1, (-2.5, 3.0)), (2, (-2.0, 3.0)), (3, (-7.0, 9.0))];
    for (ex, limits) in cases {
        let r = match ex {
            1 => run(
                &Second::new(Variant::Code),
                &mut example1::<f64>(Variant::Code, DT),
                20.0,
                limits,
                10,
            ),
            2 => run(
                &Second::new(Variant::Code),
                &mut example2::<f64>(Variant::Code, DT),
                20.0,
                limits,
                10,
            ),
            _ => run(
                &Third::new(Variant::Code),
                &mut example3::<f64>(Variant::Code, DT),
                20.0,
                limits,
                10,
            ),
        };
        assert!(!r.nonfinite);
        assert!(r.max_abs_xi() < 1.0 && r.clamp_count == 0);
        let checked = check_recovery_per_episode(ex, &r);
        println!("example {ex} code saturated, 20 s: {checked} samples checked after recoveries");
        // Example 3: T' = 6 s is longer than the gaps between episodes (the
        // disturbance period is 2 pi s), so its claim never falls due here.
        if ex != 3 {
            assert!(checked > 100, "the claim was tested on only {checked} samples");
        }
    }
}

/// With the paper's own numbers the saturated third-order run never regains
/// 0.1 accuracy within 10 s (docs/design.md §6.4): it stays finite with |xi~| < 1.
#[test]
fn example3_saturated_paper_stays_bounded() {
    let limits = (-7.0, 9.0);
    let r = paper_loop(3, Variant::Paper, limits);
    report("example 3 Paper saturated (-7, 9)", &r);
    check_invariants(&r, limits);
}

/// The paper-variant saturated second-order runs (disturbance amplitude 1)
/// barely saturate; they must still keep every invariant and settle.
#[test]
fn second_order_paper_variant_saturated() {
    for (ex, limits) in [(1, (-2.5, 3.0)), (2, (-2.0, 3.0))] {
        let r = paper_loop(ex, Variant::Paper, limits);
        report(&format!("example {ex} Paper saturated {limits:?}"), &r);
        check_invariants(&r, limits);
        let t_e = r.last_saturation_end().unwrap_or(0.0);
        let ts = r.settling_time(EPS_Z).unwrap();
        assert!(ts <= t_e.max(T_S) + t_prime(ex));
    }
}
