//! The runs both builds make, in the same order and with the same output:
//! the closed loops (with their checks) and the test vectors.

use crate::closed_loop::{self, Scenario};
use crate::out::Sink;
use crate::plant::{Second, Third, Variant};
use crate::{designs, vectors};
use famcc_core::ConfigError;

/// Samples of a 10 s run at 1 kHz (t = 0 ... 10 s inclusive).
pub const STEPS: u32 = 10_001;
/// RK4 substeps per 1 ms sample (h = 0.25 ms; the f64 host tests of
/// famcc-core use 10).
pub const SUBSTEPS: u32 = 4;

/// Example 1, authors' plant (disturbance amplitude 3), limits +-100 (never
/// reached after the start-up): `|z1| < 0.1` from the bound
/// `T_s + T_fn' = 1 + 2 = 3 s` on.
pub const EX1: Scenario = Scenario {
    name: "ex1-code-unsat",
    dt: 1e-3,
    steps: STEPS,
    limits: (-100.0, 100.0),
    substeps: SUBSTEPS,
    eps_z: 0.1,
    bound: 3.0,
    settle_time: 1.0,
    saturated: false,
};

/// Example 1 saturated to `[-2.5, 3]` on the authors' plant: saturates,
/// expands, recovers by `max(T_e, T_s) + T_fn'` (T' = 2 s).
pub const EX1_SAT: Scenario = Scenario {
    name: "ex1-code-sat[-2.5,3]",
    limits: (-2.5, 3.0),
    bound: 2.0,
    saturated: true,
    ..EX1
};

/// Example 3, authors' variant (plant and design), limits +-100: `|z1| < 0.1`
/// from `T_s + T_fr' = 1 + 6 = 7 s` on.
pub const EX3: Scenario = Scenario {
    name: "ex3-code-unsat",
    bound: 7.0,
    ..EX1
};

/// Example 3 saturated to `[-7, 9]` (authors' variant): recovers by
/// `max(T_e, T_s) + 6 s`.
pub const EX3_SAT: Scenario = Scenario {
    name: "ex3-code-sat[-7,9]",
    limits: (-7.0, 9.0),
    bound: 6.0,
    saturated: true,
    ..EX1
};

fn config_failed<S: Sink>(out: &mut S, what: &str, e: ConfigError) -> u32 {
    out.s("FAIL ")
        .s(what)
        .s(": config rejected: ")
        .s(e.parameter)
        .s(" ")
        .s(e.rule)
        .nl();
    1
}

/// Runs example 1 on the authors' second-order plant under `sc`, printing
/// its `loop`/`check`/`FAIL` lines; returns the number of failures.
/// `rec(k, e, v)` sees every sample.
pub fn example1_loop<S: Sink>(sc: &Scenario, out: &mut S, rec: &mut dyn FnMut(u32, f32, f32)) -> u32 {
    match designs::example1(Variant::Code, sc.dt) {
        Ok(mut c) => {
            let st = closed_loop::run(sc, &Second(Variant::Code), &mut c, rec);
            closed_loop::check(sc, &st, out)
        }
        Err(e) => config_failed(out, sc.name, e),
    }
}

/// Example 3 (authors' variant) on the third-order plant; see [`example1_loop`].
pub fn example3_loop<S: Sink>(sc: &Scenario, out: &mut S, rec: &mut dyn FnMut(u32, f32, f32)) -> u32 {
    match designs::example3(Variant::Code, sc.dt) {
        Ok(mut c) => {
            let st = closed_loop::run(sc, &Third(Variant::Code), &mut c, rec);
            closed_loop::check(sc, &st, out)
        }
        Err(e) => config_failed(out, sc.name, e),
    }
}

/// Runs the four closed loops ([`EX1`], [`EX1_SAT`], [`EX3`], [`EX3_SAT`]);
/// returns the number of failures. `rec2`/`rec3` see every sample
/// `(k, e, v)` of the unsaturated order-2 and order-3 runs.
pub fn loops<S: Sink>(
    out: &mut S,
    rec2: &mut dyn FnMut(u32, f32, f32),
    rec3: &mut dyn FnMut(u32, f32, f32),
) -> u32 {
    example1_loop(&EX1, out, rec2)
        + example1_loop(&EX1_SAT, out, &mut |_, _, _| {})
        + example3_loop(&EX3, out, rec3)
        + example3_loop(&EX3_SAT, out, &mut |_, _, _| {})
}

/// The test vectors through fresh example 1 and example 3 controllers.
pub fn vectors<S: Sink>(out: &mut S) -> u32 {
    let mut fails = 0;
    match designs::example1(Variant::Code, 1e-3) {
        Ok(mut c) => vectors::dump(&mut c, out),
        Err(e) => fails += config_failed(out, "vectors o2", e),
    }
    match designs::example3(Variant::Code, 1e-3) {
        Ok(mut c) => vectors::dump(&mut c, out),
        Err(e) => fails += config_failed(out, "vectors o3", e),
    }
    fails
}
