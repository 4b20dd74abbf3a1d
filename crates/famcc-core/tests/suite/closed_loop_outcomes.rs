//! Measured closed-loop outcomes against committed values: a 10 % regression fails.
//!
//! `closed_loop.rs` checks the paper's claims (the corollaries' settling-time
//! bounds 3 s, 4.32 s and 7 s), which are 2-7x looser than what famcc measures,
//! so a controller twice as slow still passes it. This file pins what the six
//! scenarios *measure*, in both variants (docs/design.md §6.2): settling time,
//! first entry, max |nominal xi|, the input range, the final error and the
//! saturated fraction, each against [`COMMITTED`] with the tolerance of [`TOL`]
//! (settling within 5 %). The random-plant suite has its own committed values
//! in `closed_loop_random.rs`.
//!
//! After an intended change of behaviour, print the new table with
//! `FAMCC_PRINT_OUTCOMES=1 cargo test -p famcc-core --test suite -- closed_loop_outcomes:: --nocapture`,
//! paste it over [`COMMITTED`] and say why in the commit.
#![allow(clippy::unwrap_used, clippy::indexing_slicing)]

use crate::common;
use common::*;

const EPS_Z: f64 = 0.1;

/// What one run measured. `None`: never settled / never entered.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Outcome {
    settling_time: Option<f64>,
    first_entry: Option<f64>,
    max_abs_xi_nominal: f64,
    u_min: f64,
    u_max: f64,
    /// max |z1| over the last second.
    final_abs_z1: f64,
    saturated_fraction: f64,
}

/// `(relative, absolute)` tolerance per metric: a value passes within either.
/// Settling and first entry: 5 % or two samples; the final error: 10 % or 2e-3.
const TOL: [(&str, f64, f64); 7] = [
    ("settling_time", 0.05, 2e-3),
    ("first_entry", 0.05, 2e-3),
    ("max_abs_xi_nominal", 0.02, 1e-3),
    ("u_min", 0.05, 0.05),
    ("u_max", 0.05, 0.05),
    ("final_abs_z1", 0.10, 2e-3),
    ("saturated_fraction", 0.0, 0.01),
];

fn close(got: Option<f64>, want: Option<f64>, rel: f64, abs: f64) -> bool {
    match (got, want) {
        (Some(g), Some(w)) => (g - w).abs() <= abs.max(rel * w.abs()),
        (None, None) => true,
        _ => false,
    }
}

fn fields(o: &Outcome) -> [Option<f64>; 7] {
    [
        o.settling_time,
        o.first_entry,
        Some(o.max_abs_xi_nominal),
        Some(o.u_min),
        Some(o.u_max),
        Some(o.final_abs_z1),
        Some(o.saturated_fraction),
    ]
}

/// The metrics that differ beyond their tolerance: `(name, got, want)`.
fn mismatches(got: &Outcome, want: &Outcome) -> Vec<(&'static str, Option<f64>, Option<f64>)> {
    fields(got)
        .into_iter()
        .zip(fields(want))
        .zip(TOL)
        .filter(|((g, w), (_, rel, abs))| !close(*g, *w, *rel, *abs))
        .map(|((g, w), (name, _, _))| (name, g, w))
        .collect()
}

const SAT1: (f64, f64) = (-2.5, 3.0);
const SAT2: (f64, f64) = (-2.0, 3.0);
const SAT3: (f64, f64) = (-7.0, 9.0);

/// The scenario names of `famcc.scenarios` with their example and limits.
const SCENARIOS: [(&str, u8, (f64, f64)); 6] = [
    ("finite-time", 1, UNSAT),
    ("finite-time-saturated", 1, SAT1),
    ("variable-exponent", 2, UNSAT),
    ("variable-exponent-saturated", 2, SAT2),
    ("rfc", 3, UNSAT),
    ("rfc-saturated", 3, SAT3),
];

fn measure(r: &Run) -> Outcome {
    assert!(!r.nonfinite, "a value became non-finite");
    let (u_min, u_max) = r.u_range();
    Outcome {
        settling_time: r.settling_time(EPS_Z),
        first_entry: r.first_entry(EPS_Z),
        max_abs_xi_nominal: r.max_abs_xi_nominal(),
        u_min,
        u_max,
        final_abs_z1: r.final_abs_z1(1.0),
        saturated_fraction: r.saturated_fraction(),
    }
}

fn name_of(scenario: &str, variant: Variant) -> String {
    format!(
        "{scenario}/{}",
        if variant == Variant::Code { "code" } else { "paper" }
    )
}

/// Measured at 1 kHz, RK4 with 10 substeps, 10 s (x86_64, f64).
#[rustfmt::skip]
const COMMITTED: &[(&str, Outcome)] = &[
    ("finite-time/code", Outcome { settling_time: Some(1.27), first_entry: Some(1.27), max_abs_xi_nominal: 0.5007071188701315, u_min: -2.295522214015406, u_max: 5.50249414443255, final_abs_z1: 0.016260763671394562, saturated_fraction: 0.0 }),
    ("finite-time/paper", Outcome { settling_time: Some(1.332), first_entry: Some(1.332), max_abs_xi_nominal: 0.5007079053518816, u_min: -1.1662632667390267, u_max: 5.5025046407646, final_abs_z1: 0.00548180659076869, saturated_fraction: 0.0 }),
    ("finite-time-saturated/code", Outcome { settling_time: Some(5.691), first_entry: Some(1.274), max_abs_xi_nominal: 2.254140644202936, u_min: -2.293783364661451, u_max: 3.0, final_abs_z1: 0.016260820286368827, saturated_fraction: 0.11688831116888311 }),
    ("finite-time-saturated/paper", Outcome { settling_time: Some(1.337), first_entry: Some(1.337), max_abs_xi_nominal: 0.5007098639104185, u_min: -1.1646885707264507, u_max: 3.0, final_abs_z1: 0.005481806600037831, saturated_fraction: 0.0029997000299970002 }),
    ("variable-exponent/code", Outcome { settling_time: Some(0.631), first_entry: Some(0.631), max_abs_xi_nominal: 0.9170028031728555, u_min: -6.279422742511796, u_max: 3.5294782743402937, final_abs_z1: 0.0011854099076885616, saturated_fraction: 0.0 }),
    ("variable-exponent/paper", Outcome { settling_time: Some(0.909), first_entry: Some(0.909), max_abs_xi_nominal: 0.5017110843194852, u_min: -2.2063607981390287, u_max: 2.1997745524241696, final_abs_z1: 0.00023203569505581, saturated_fraction: 0.0 }),
    ("variable-exponent-saturated/code", Outcome { settling_time: Some(5.581), first_entry: Some(0.602), max_abs_xi_nominal: 11.937694026237441, u_min: -2.0, u_max: 3.0, final_abs_z1: 0.0011854099076885616, saturated_fraction: 0.2883711628837116 }),
    ("variable-exponent-saturated/paper", Outcome { settling_time: Some(0.909), first_entry: Some(0.909), max_abs_xi_nominal: 0.5018358187959993, u_min: -2.0, u_max: 2.1997745524241696, final_abs_z1: 0.00023203715115499568, saturated_fraction: 0.0008999100089991 }),
    ("rfc/code", Outcome { settling_time: Some(1.262), first_entry: Some(1.262), max_abs_xi_nominal: 0.9129089018636812, u_min: -92.6827701571814, u_max: 80.54334921628707, final_abs_z1: 0.016880006728058894, saturated_fraction: 0.0 }),
    ("rfc/paper", Outcome { settling_time: Some(0.998), first_entry: Some(0.998), max_abs_xi_nominal: 2.923104575815444, u_min: -56.22207469059302, u_max: 100.0, final_abs_z1: 0.016906403494213823, saturated_fraction: 0.0020997900209979003 }),
    ("rfc-saturated/code", Outcome { settling_time: Some(1.86), first_entry: Some(1.86), max_abs_xi_nominal: 2.041841158691742, u_min: -7.0, u_max: 9.0, final_abs_z1: 0.017054870287421947, saturated_fraction: 0.37076292370762925 }),
    ("rfc-saturated/paper", Outcome { settling_time: None, first_entry: Some(1.05), max_abs_xi_nominal: 7.106867957793345, u_min: -7.0, u_max: 9.0, final_abs_z1: 0.6690267758038422, saturated_fraction: 0.9405059494050595 }),
];

fn committed(name: &str) -> Outcome {
    COMMITTED
        .iter()
        .find(|(n, _)| *n == name)
        .unwrap_or_else(|| panic!("no committed outcome for {name}"))
        .1
}

fn check(scenario: &str, example: u8, limits: (f64, f64), variant: Variant) {
    let name = name_of(scenario, variant);
    let got = measure(&paper_loop(example, variant, limits));
    if std::env::var_os("FAMCC_PRINT_OUTCOMES").is_some() {
        println!("    (\"{name}\", {got:?}),");
        return;
    }
    let bad = mismatches(&got, &committed(&name));
    assert!(
        bad.is_empty(),
        "{name}: (metric, measured, committed) beyond {TOL:?}: {bad:?}"
    );
}

#[test]
fn example1_outcomes() {
    for (scenario, ex, limits) in SCENARIOS.iter().filter(|s| s.1 == 1) {
        check(scenario, *ex, *limits, Variant::Code);
        check(scenario, *ex, *limits, Variant::Paper);
    }
}

#[test]
fn example2_outcomes() {
    for (scenario, ex, limits) in SCENARIOS.iter().filter(|s| s.1 == 2) {
        check(scenario, *ex, *limits, Variant::Code);
        check(scenario, *ex, *limits, Variant::Paper);
    }
}

#[test]
fn example3_outcomes() {
    for (scenario, ex, limits) in SCENARIOS.iter().filter(|s| s.1 == 3) {
        check(scenario, *ex, *limits, Variant::Code);
        check(scenario, *ex, *limits, Variant::Paper);
    }
}

#[test]
fn every_scenario_and_variant_is_committed() {
    let mut names: Vec<String> = SCENARIOS
        .iter()
        .flat_map(|(s, _, _)| [name_of(s, Variant::Code), name_of(s, Variant::Paper)])
        .collect();
    let mut have: Vec<String> = COMMITTED.iter().map(|(n, _)| n.to_string()).collect();
    names.sort();
    have.sort();
    assert_eq!(names, have);
}

/// The settling-time tolerance is tighter than a 10 % regression for every
/// case that settles later than 0.1 s, and so is the first entry's.
#[test]
fn the_tolerance_would_catch_a_ten_percent_slower_loop() {
    let (_, rel, abs) = TOL[0];
    for (name, o) in COMMITTED.iter() {
        for t in [o.settling_time, o.first_entry].into_iter().flatten() {
            if t > 0.1 {
                assert!(!close(Some(1.1 * t), Some(t), rel, abs), "{name}: {t}");
                assert!(!close(Some(0.9 * t), Some(t), rel, abs), "{name}: {t}");
            }
        }
    }
}
