//! `famcc._core._CallFloor`: the benchmarks' baseline for a method call.

use pyo3::prelude::*;

/// The floor of a Python-to-Rust method call, for the benchmarks
/// (`benches/bench_step.py`): a `&mut self` method that takes and returns a
/// float, like `Controller.step`, and does nothing else.
#[pyclass(module = "famcc._core", name = "_CallFloor")]
#[derive(Default)]
pub struct CallFloor;

#[pymethods]
impl CallFloor {
    #[new]
    fn new() -> Self {
        Self
    }

    /// Returns `e`.
    fn step(&mut self, e: f64) -> f64 {
        e
    }
}
