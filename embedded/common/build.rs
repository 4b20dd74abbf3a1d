//! Precomputes, on the build host, the differentiator recursions of the
//! designs in `suite.rs` (examples 1 and 3, authors' variant, f32, 1 kHz) by
//! the same code `ConfigBuilder::build` runs, and writes them as constants
//! (`$OUT_DIR/precomputed.rs`, exact bit patterns). The firmware builds its
//! configurations with `ConfigBuilder::build_discretized`, so it never runs
//! (or links) the f64 matrix exponential.
use std::fmt::Write as _;
use std::{env, fs, path::PathBuf};

use famcc_core::DiscreteHgd;
use famcc_paper::designs::{self, Variant, SAMPLE_PERIOD};

fn constant<const N: usize>(out: &mut String, name: &str, what: &str, d: &DiscreteHgd<f32, N>) {
    let bits = |v: f32| format!("f32::from_bits({:#010x})", v.to_bits());
    let row = |r: &[f32; N]| r.iter().map(|v| bits(*v)).collect::<Vec<_>>().join(", ");
    let phi = d
        .phi
        .iter()
        .map(|r| format!("[{}]", row(r)))
        .collect::<Vec<_>>()
        .join(", ");
    let _ = writeln!(
        out,
        "/// {what}: the differentiator's recursion, computed on the build host.\n\
         pub const {name}: DiscreteHgd<f32, {N}> = DiscreteHgd {{ phi: [{phi}], gamma: [{}], prefilter: {}, \
         feedthrough: [{}] }};",
        row(&d.gamma),
        bits(d.prefilter),
        row(&d.feedthrough)
    );
}

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    let dt = SAMPLE_PERIOD as f32;
    let mut out = String::from("use famcc_core::DiscreteHgd;\n");
    match (
        designs::example1::<f32>(Variant::Code, dt),
        designs::example3::<f32>(Variant::Code, dt),
    ) {
        (Ok(c1), Ok(c3)) => match (c1.discretized(), c3.discretized()) {
            (Some(d1), Some(d3)) => {
                constant(&mut out, "EXAMPLE1", "Example 1 (f32, 1 kHz)", &d1);
                constant(&mut out, "EXAMPLE3", "Example 3 (f32, 1 kHz)", &d3);
            }
            _ => panic!("the examples have no differentiator"),
        },
        (r1, r3) => panic!(
            "the examples' designs are rejected: {:?} {:?}",
            r1.err(),
            r3.err()
        ),
    }
    let path = PathBuf::from(env::var("OUT_DIR").expect("OUT_DIR")).join("precomputed.rs");
    fs::write(path, out).expect("write precomputed.rs");
}
