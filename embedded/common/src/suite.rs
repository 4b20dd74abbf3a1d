//! The runs both builds make, in the same order and with the same output:
//! the closed loops (with their checks) and the test vectors. The designs,
//! plants, limits and settling bounds are the paper's (famcc-paper), in f32.
//! The configurations are built from differentiator recursions precomputed
//! on the build host ([`precomputed`], build.rs), so neither build runs the
//! matrix exponential.

use crate::closed_loop::{self, Scenario};
use crate::out::Sink;
use crate::vectors;
use famcc_core::{ConfigError, Controller};
use famcc_paper::designs::{self, Example, Variant, ACCURACY, HORIZON, SAMPLE_PERIOD};
use famcc_paper::plants::{Plant, SecondOrder, ThirdOrder};

/// Samples of a run over the paper's horizon at 1 kHz (t = 0 ... 10 s inclusive).
pub const STEPS: u32 = (HORIZON / SAMPLE_PERIOD + 0.5) as u32 + 1;
/// RK4 substeps per 1 ms sample (h = 0.25 ms; the f64 host tests of
/// famcc-core use 10).
pub const SUBSTEPS: u32 = 4;

/// The designs' differentiator recursions, computed on the build host by
/// the code of `ConfigBuilder::build` (build.rs).
pub mod precomputed {
    include!(concat!(env!("OUT_DIR"), "/precomputed.rs"));
}

/// Example 1 in the authors' variant (f32, 1 kHz), from its precomputed
/// recursion.
pub fn example1() -> Result<Controller<f32, 2>, ConfigError> {
    designs::example1_builder(Variant::Code, SAMPLE_PERIOD as f32)
        .build_discretized(precomputed::EXAMPLE1)
        .map(Controller::new)
}

/// Example 3 in the authors' variant (f32, 1 kHz), from its precomputed
/// recursion.
pub fn example3() -> Result<Controller<f32, 3>, ConfigError> {
    designs::example3_builder(Variant::Code, SAMPLE_PERIOD as f32)
        .build_discretized(precomputed::EXAMPLE3)
        .map(Controller::new)
}

/// The run of `example` (authors' variant, 10 s at 1 kHz) with its
/// scenario's limits: unsaturated (+-100, never reached after the start-up),
/// `|z1| < 0.1` from `T_s + T'` on; saturated, recovery by `max(T_e, T_s) + T'`.
fn scenario(name: &'static str, example: Example, saturated: bool, settle_time: f32) -> Scenario {
    let t_prime = designs::corollary_bound::<f32>(example);
    Scenario {
        name,
        dt: SAMPLE_PERIOD as f32,
        steps: STEPS,
        limits: designs::input_limits(example, saturated),
        substeps: SUBSTEPS,
        eps_z: ACCURACY as f32,
        bound: if saturated { t_prime } else { settle_time + t_prime },
        settle_time,
        saturated,
    }
}

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

/// Runs example 1 on the authors' second-order plant, unsaturated
/// (`ex1-code-unsat`, bound `T_s + T_fn' = 3 s`) or saturated to `[-2.5, 3]`
/// (`ex1-code-sat[-2.5,3]`), printing its `loop`/`check`/`FAIL` lines;
/// returns the number of failures. `rec(k, e, v)` sees every sample.
pub fn example1_loop<S: Sink>(saturated: bool, out: &mut S, rec: &mut dyn FnMut(u32, f32, f32)) -> u32 {
    let name = if saturated {
        "ex1-code-sat[-2.5,3]"
    } else {
        "ex1-code-unsat"
    };
    let plant = SecondOrder::new(Variant::Code);
    example_loop(name, Example::FiniteTime, saturated, example1(), &plant, out, rec)
}

/// Example 3 (authors' variant: eps_y = 3, eps_s1 = 0.1, x(0) = (1, 0.5, 4))
/// on the third-order plant, unsaturated (bound `T_s + T_fr' = 7 s`) or
/// saturated to `[-7, 9]`; see [`example1_loop`].
pub fn example3_loop<S: Sink>(saturated: bool, out: &mut S, rec: &mut dyn FnMut(u32, f32, f32)) -> u32 {
    let name = if saturated {
        "ex3-code-sat[-7,9]"
    } else {
        "ex3-code-unsat"
    };
    let plant = ThirdOrder::new(Variant::Code);
    example_loop(name, Example::Rfc, saturated, example3(), &plant, out, rec)
}

fn example_loop<const N: usize, P: Plant<f32, N>, S: Sink>(
    name: &'static str,
    example: Example,
    saturated: bool,
    ctrl: Result<Controller<f32, N>, ConfigError>,
    plant: &P,
    out: &mut S,
    rec: &mut dyn FnMut(u32, f32, f32),
) -> u32 {
    match ctrl {
        Ok(mut c) => {
            let sc = scenario(name, example, saturated, c.config().settle_time());
            let st = closed_loop::run(&sc, plant, &mut c, rec);
            closed_loop::check(&sc, &st, out)
        }
        Err(e) => config_failed(out, name, e),
    }
}

/// Runs the four closed loops (examples 1 and 3, unsaturated and
/// saturated); returns the number of failures. `rec2`/`rec3` see every
/// sample `(k, e, v)` of the unsaturated order-2 and order-3 runs.
pub fn loops<S: Sink>(
    out: &mut S,
    rec2: &mut dyn FnMut(u32, f32, f32),
    rec3: &mut dyn FnMut(u32, f32, f32),
) -> u32 {
    example1_loop(false, out, rec2)
        + example1_loop(true, out, &mut |_, _, _| {})
        + example3_loop(false, out, rec3)
        + example3_loop(true, out, &mut |_, _, _| {})
}

/// The test vectors through fresh example 1 and example 3 controllers.
pub fn vectors<S: Sink>(out: &mut S) -> u32 {
    let mut fails = 0;
    match example1() {
        Ok(mut c) => vectors::dump(&mut c, out),
        Err(e) => fails += config_failed(out, "vectors o2", e),
    }
    match example3() {
        Ok(mut c) => vectors::dump(&mut c, out),
        Err(e) => fails += config_failed(out, "vectors o3", e),
    }
    fails
}
