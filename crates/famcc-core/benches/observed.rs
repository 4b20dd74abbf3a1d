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
//! with the first-order hold (`foh`).
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
use famcc_core::{Controller, Discretization, ExtendedHighGain, Real};

/// The law of `plain` without its differentiator, on the observer.
fn observed<T: Real, const N: usize>(plain: &Controller<T, N>, hold: Discretization) -> Controller<T, N> {
    let obs = ExtendedHighGain::binomial(T::from_f64(0.02), T::one()).with_discretization(hold);
    let cfg = plain
        .config()
        .to_builder()
        .differentiator(None)
        .observer(Some(obs))
        .cancellation_limit(Some(T::from_f64(10.0)))
        .build()
        .unwrap();
    Controller::new(cfg)
}

type Group<'a> = criterion::BenchmarkGroup<'a, criterion::measurement::WallTime>;

/// The plain workload `name`, then its law on the observer with each hold
/// (interleaved: each plain workload right before its observed ones).
fn bench_example<const N: usize>(g: &mut Group<'_>, name: &str, w: &step::Workload<Controller<f64, N>, f64>) {
    step::bench_phases(g, &format!("{name}-plain/f64"), w, false);
    for (hold, disc) in [("exact", Discretization::Exact), ("foh", Discretization::Foh)] {
        let name = format!("{name}-observed-{hold}/f64");
        step::bench_phases(g, &name, &w.with(observed(&w.starts[0], disc)), false);
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
