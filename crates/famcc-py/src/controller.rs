//! `famcc.Controller`: the Python methods. Arguments are parsed by
//! [`crate::args`], the controller is famcc-core's ([`Core`]), the rules and
//! defaults are famcc-core's (the signature's defaults name them).

use crate::args::{Args, DiffArg, RhoArg, AUTO};
use crate::diagnostics::Diagnostics;
use crate::dispatch::Core;
use crate::errors::{config_err, step_err, ConfigError, StepError};
use crate::names::{CONSTRAINT, DTYPE, GAMMA, LATCH, TRANSITION};
use crate::spec::{RhoE, Spec};
use famcc_core::config::{DEFAULT_K0, DEFAULT_SETTLE_TIME};
use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};

/// The FAMCC controller (see `famcc.Controller` for the documentation).
#[pyclass(module = "famcc._core", name = "Controller")]
#[derive(Clone)]
pub struct PyController {
    pub core: Core,
    pub spec: Spec,
}

impl PyController {
    /// Builds the controller of `spec`, whose `rho_e` then shows the margin
    /// in effect.
    pub fn from_spec(mut spec: Spec) -> PyResult<Self> {
        let core = Core::build(&spec).map_err(config_err)?;
        spec.rho_e = RhoE::Given(core.rho_e());
        Ok(Self { core, spec })
    }

    pub fn set_state_vec(&mut self, v: &[f64]) -> PyResult<()> {
        self.core.set_state(v)
    }
}

#[pymethods]
impl PyController {
    #[new]
    #[pyo3(signature = (order, dt, feedback = None, *, skew = None, constraint = CONSTRAINT.default_name(), eps,
        settle_time = DEFAULT_SETTLE_TIME, k0 = DEFAULT_K0, k_u, gamma = GAMMA.default_name(),
        rho_e = Some(RhoArg::Name(String::from(AUTO))), differentiator = Some(DiffArg::Name(String::from(AUTO))),
        latch = LATCH.default_name(), transition = TRANSITION.default_name(), initial_derivatives = None,
        dtype = DTYPE.default_name()))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        order: i64,
        dt: f64,
        feedback: Option<&Bound<'_, PyAny>>,
        skew: Option<&Bound<'_, PyAny>>,
        constraint: &str,
        eps: &Bound<'_, PyAny>,
        settle_time: f64,
        k0: f64,
        k_u: f64,
        gamma: &str,
        rho_e: Option<RhoArg<'_>>,
        differentiator: Option<DiffArg<'_>>,
        latch: &str,
        transition: &str,
        initial_derivatives: Option<Vec<f64>>,
        dtype: &str,
    ) -> PyResult<Self> {
        let spec = Args {
            order,
            dt,
            feedback,
            skew,
            constraint,
            eps,
            settle_time,
            k0,
            k_u,
            gamma,
            rho_e,
            differentiator,
            latch,
            transition,
            initial_derivatives,
            dtype,
        }
        .parse()?;
        Self::from_spec(spec)
    }

    /// Sample period, s.
    #[getter]
    fn dt(&self) -> f64 {
        self.spec.dt
    }

    /// System order n.
    #[getter]
    fn order(&self) -> usize {
        self.spec.order
    }

    /// "float64" or "float32".
    #[getter]
    fn dtype(&self) -> &'static str {
        DTYPE.name(self.spec.dtype)
    }

    /// Time of the next sample, s.
    #[getter]
    fn time(&self) -> f64 {
        self.core.time()
    }

    /// One output-feedback step: error sample `e = y - y_d` in, control `v` out.
    /// `applied` is the input the actuator really gave at the previous sample,
    /// when known (diagnostics then report the saturation gap).
    #[pyo3(signature = (e, applied = None))]
    #[inline]
    fn step(&mut self, e: f64, applied: Option<f64>) -> PyResult<f64> {
        self.core.step(e, applied).map_err(step_err)
    }

    /// One step with a one-off sample period `dt` (s).
    #[pyo3(signature = (e, dt, applied = None))]
    fn step_dt(&mut self, e: f64, dt: f64, applied: Option<f64>) -> PyResult<f64> {
        self.core.step_dt(e, dt, applied).map_err(step_err)
    }

    /// One state-feedback step with the measured error vector `z = (z1..zn)`.
    #[pyo3(signature = (z, applied = None))]
    fn step_state(&mut self, z: &Bound<'_, PyAny>, applied: Option<f64>) -> PyResult<f64> {
        let z: Vec<f64> = z
            .extract()
            .map_err(|_| StepError::new_err("z must be a sequence of floats"))?;
        self.core.step_state(&z, applied)
    }

    /// Back to the state before the first step.
    fn reset(&mut self) {
        self.core.reset()
    }

    /// What the last step did.
    #[getter]
    fn diagnostics(&self) -> Diagnostics {
        self.core.diagnostics()
    }

    /// The estimate the next step will use (NumPy array).
    #[getter]
    fn estimate<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_vec(py, self.core.estimate())
    }

    /// The state as a float vector, laid out as `STATE_FIELDS` followed by
    /// the estimate `z_hat[0..order]`.
    fn state<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_vec(py, self.core.state())
    }

    /// Continues from a vector returned by `state()`.
    fn set_state(&mut self, state: PyReadonlyArray1<'_, f64>) -> PyResult<()> {
        let v = state
            .as_slice()
            .map_err(|_| ConfigError::new_err("state must be a contiguous float vector"))?;
        self.core.set_state(v)
    }

    /// The configuration as keyword arguments of the constructor.
    fn config<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        self.spec.kwargs(py)
    }

    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        let kw = self.spec.kwargs(py)?;
        let mut parts = Vec::new();
        for (k, v) in kw.iter() {
            parts.push(format!("{}={}", k.str()?, v.repr()?));
        }
        Ok(format!("Controller({})", parts.join(", ")))
    }

    fn __copy__(&self) -> Self {
        self.clone()
    }

    fn __deepcopy__(&self, _memo: &Bound<'_, PyAny>) -> Self {
        self.clone()
    }

    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)> {
        let py = slf.py();
        let this = slf.borrow();
        let f = py.import("famcc._core")?.getattr("_controller_from_state")?;
        let args = PyTuple::new(
            py,
            [
                this.spec.kwargs(py)?.into_any(),
                PyList::new(py, this.core.state())?.into_any(),
            ],
        )?;
        Ok((f, args))
    }
}

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
