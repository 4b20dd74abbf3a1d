//! Cost of one `Controller::step` with the observer (`ConfigBuilder::observer`) against the plain output-feedback
//! `Controller::step` of the same law and order, in one run (issue 32, "Cost":
//! at most 1.3x).
//!
//! Run with `cargo bench -p famcc-core --bench observed` (about a minute).
//!
//! Both replay the same recorded errors (example 1's and example 3's closed
//! loops, benches/step.rs) in chunks of 1000 samples from saved states, so the
//! time per iteration in microseconds is the time per step in nanoseconds. The
//! observed controllers use the same laws with the observer in place of the differentiator
//! (`mu = 0.02`, `b0 = 1`, `delta = 10`), with the measurement held (`exact`) and
//! with the first-order hold (`foh`). Each runs open (the recorded errors, so
//! the CPU may overlap consecutive plain steps, whose differentiator does not
//! depend on the output) and closed (`/settled-closed`: each sample waits for
//! the previous output, as in a control loop).
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::indexing_slicing,
    clippy::panic
)]

#[allow(dead_code)]
#[path = "step.rs"]
mod step;

use std::time::Duration;

use criterion::{Criterion, Throughput};
use famcc_core::{Controller, Discretization};

type Group<'a> = criterion::BenchmarkGroup<'a, criterion::measurement::WallTime>;

/// The settled chunks of `w` in a closed loop ([`step::run_chunk_closed`]).
fn bench_closed<S: step::Stepper<f64>>(g: &mut Group<'_>, name: &str, w: &step::Workload<S, f64>) {
    let settled = w.settled();
    let mut j = settled.start;
    g.bench_function(format!("{name}/settled-closed"), |b| {
        b.iter(|| {
            let out = step::run_chunk_closed(&w.starts[j], &w.e[j * step::CHUNK..(j + 1) * step::CHUNK]);
            j = if j + 1 == settled.end {
                settled.start
            } else {
                j + 1
            };
            out
        })
    });
}

/// The plain workload `name`, then its law on the observer with each hold
/// (interleaved: each plain workload right before its observed ones), each
/// replayed open (the recorded errors) and in a closed loop.
fn bench_example<const N: usize>(g: &mut Group<'_>, name: &str, w: &step::Workload<Controller<f64, N>, f64>) {
    step::bench_phases(g, &format!("{name}-plain/f64"), w, false);
    bench_closed(g, &format!("{name}-plain/f64"), w);
    for (hold, disc) in [("exact", Discretization::Exact), ("foh", Discretization::Foh)] {
        let name = format!("{name}-observed-{hold}/f64");
        let wo = w.with(step::observed(&w.starts[0], disc));
        step::bench_phases(g, &name, &wo, false);
        bench_closed(g, &name, &wo);
    }
}

fn benches(c: &mut Criterion) {
    let mut g = c.benchmark_group("observed");
    g.throughput(Throughput::Elements(step::CHUNK as u64));
    bench_example(&mut g, "ex1", &step::ex1::<f64>(Discretization::Exact));
    bench_example(&mut g, "ex3", &step::ex3::<f64>(Discretization::Exact));
    g.finish();
}

fn main() {
    let mut c = Criterion::default()
        .sample_size(20)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2))
        .configure_from_args();
    benches(&mut c);
    c.final_summary();
}
