//! `famcc.Controller`: the Python methods. Arguments are parsed by
//! [`crate::args`], the controller is famcc-core's ([`Core`]), the rules and
//! defaults are famcc-core's (the signature's defaults name them).

use crate::args::{Args, DiffArg, RhoArg, AUTO};
use crate::diagnostics::Diagnostics;
use crate::dispatch::Core;
use crate::errors::{kind, step_err, ConfigFault, StepFault};
use crate::module::module_function;
use crate::names::{CONSTRAINT, DIRECTION, DTYPE, GAMMA, LATCH, TRANSITION};
use crate::number::{Int, Num, Text};
use crate::observer::Observer;
use crate::spec::ControllerSpec;
use crate::spec::Spec;
use famcc_core::config::{DEFAULT_K0, DEFAULT_SETTLE_TIME};
use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};

// The class docstring (numpydoc, also the stub's) is its own file.
#[doc = include_str!("docs/controller.md")]
#[allow(clippy::doc_lazy_continuation)] // ">>>" doctest prompts are not quotes
#[pyclass(module = "famcc._core", name = "Controller")]
#[derive(Clone)]
pub struct PyController {
    pub core: Core,
    pub spec: Spec,
    /// The health warning was given (once per controller).
    pub(crate) health_warned: bool,
}

#[pymethods]
impl PyController {
    #[new]
    #[pyo3(signature = (order, dt, feedback = None, *, skew = None, constraint = text(CONSTRAINT.default_name()), eps,
        settle_time = Num(DEFAULT_SETTLE_TIME), k0 = Num(DEFAULT_K0), k_u, gamma = text(GAMMA.default_name()),
        rho_e = Some(RhoArg::Name(String::from(AUTO))), differentiator = Some(DiffArg::Name(String::from(AUTO))),
        latch = text(LATCH.default_name()), transition = text(TRANSITION.default_name()), initial_derivatives = None,
        dtype = text(DTYPE.default_name()), integral = false, output_limits = None, rate_limit = None,
        initial_output = None, observer = None, cancellation_limit = None, direction = text(DIRECTION.default_name())),
        // The defaults above are famcc-core's; pyo3 shows only literal ones, so
        // the Python signature spells them out (tests/test_docs.py checks that
        // each equals the default in effect).
        text_signature = "(order, dt, feedback=None, *, skew=None, constraint='longitudinal', eps, \
            settle_time=1.0, k0=2.0, k_u, gamma='log', rho_e='auto', differentiator='auto', latch='paper', \
            transition='exponential', initial_derivatives=None, dtype='float64', integral=False, \
            output_limits=None, rate_limit=None, initial_output=None, observer=None, cancellation_limit=None, \
            direction='positive')")]
    #[allow(clippy::too_many_arguments)]
    fn new(
        order: Int,
        dt: Num,
        feedback: Option<&Bound<'_, PyAny>>,
        skew: Option<&Bound<'_, PyAny>>,
        constraint: Text,
        eps: &Bound<'_, PyAny>,
        settle_time: Num,
        k0: Num,
        k_u: Num,
        gamma: Text,
        rho_e: Option<RhoArg<'_>>,
        differentiator: Option<DiffArg<'_>>,
        latch: Text,
        transition: Text,
        initial_derivatives: Option<Vec<Num>>,
        dtype: Text,
        integral: bool,
        output_limits: Option<(Num, Num)>,
        rate_limit: Option<Num>,
        initial_output: Option<Num>,
        observer: Option<Bound<'_, Observer>>,
        cancellation_limit: Option<Num>,
        direction: Text,
        py: Python<'_>,
    ) -> PyResult<Self> {
        // Numbers are never bools, and a wrong type names its argument
        // (crate::number).
        let spec = Args {
            order: order.0,
            dt: dt.0,
            feedback,
            skew,
            constraint: &constraint.0,
            eps,
            settle_time: settle_time.0,
            k0: k0.0,
            k_u: k_u.0,
            gamma: &gamma.0,
            rho_e,
            differentiator,
            latch: &latch.0,
            transition: &transition.0,
            initial_derivatives: initial_derivatives.map(|d| d.into_iter().map(|x| x.0).collect()),
            dtype: &dtype.0,
            integral,
            output_limits: output_limits.map(|(lo, hi)| (lo.0, hi.0)),
            rate_limit: rate_limit.map(|r| r.0),
            initial_output: initial_output.map(|u| u.0),
            observer: observer.map(|o| o.get().clone()),
            cancellation_limit: cancellation_limit.map(|c| c.0),
            direction: &direction.0,
        }
        .parse()?;
        Self::from_spec_warned(py, spec)
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

    /// One output-feedback step: the error sample in, the control out.
    ///
    /// Parameters
    /// ----------
    /// e : float
    ///     The error sample ``e = y - y_d`` (output minus reference, the
    ///     opposite of a PID's ``setpoint - y``), unit of ``y``.
    /// applied : float, default None
    ///     The input the actuator really gave at the previous sample, input
    ///     units, when known (``diagnostics.saturation_gap`` then reports the
    ///     gap, and the health warning can fire).
    ///
    /// Returns
    /// -------
    /// float
    ///     The control ``v`` (input units), after ``output_limits`` and
    ///     ``rate_limit`` when configured.
    ///
    /// Raises
    /// ------
    /// famcc.StepError
    ///     A non-finite ``e`` or ``applied`` (the state is unchanged), or an
    ///     overflow of the law.
    ///
    /// Warns
    /// -----
    /// famcc.DesignWarning
    ///     Once, when the bounds keep expanding while the actuator has
    ///     headroom: ``k_u`` too small for the plant.
    #[pyo3(signature = (e, applied = None))]
    #[inline]
    fn step(&mut self, e: f64, applied: Option<f64>) -> PyResult<f64> {
        let v = self.core.step(e, applied).map_err(|x| step_err(x, "e"))?;
        self.check_health(applied)?;
        Ok(v)
    }

    /// One step from the measured output and the reference.
    ///
    /// The error is ``e = y - y_d`` (the opposite of a PID's
    /// ``setpoint - y``); otherwise as :meth:`step`.
    ///
    /// Parameters
    /// ----------
    /// y : float
    ///     The measured output.
    /// y_d : float
    ///     The reference, unit of ``y``.
    /// applied : float, default None
    ///     The input the actuator really gave at the previous sample, input
    ///     units, when known.
    ///
    /// Returns
    /// -------
    /// float
    ///     The control ``v``, input units.
    ///
    /// Raises
    /// ------
    /// famcc.StepError
    ///     A non-finite input (the state is unchanged), or an overflow.
    #[pyo3(signature = (y, y_d, applied = None))]
    fn step_output(&mut self, y: f64, y_d: f64, applied: Option<f64>) -> PyResult<f64> {
        let v = self
            .core
            .step_output(y, y_d, applied)
            .map_err(|x| step_err(x, if y.is_finite() { "y_d" } else { "y" }))?;
        self.check_health(applied)?;
        Ok(v)
    }

    /// One step with a one-off sample period.
    ///
    /// Parameters
    /// ----------
    /// e : float
    ///     The error sample ``e = y - y_d``, unit of ``y``.
    /// dt : float
    ///     The time since the previous sample, s (``> 0``); the configured
    ///     ``dt`` is unchanged.
    /// applied : float, default None
    ///     The input the actuator really gave at the previous sample, input
    ///     units, when known.
    ///
    /// Returns
    /// -------
    /// float
    ///     The control ``v``, input units.
    ///
    /// Raises
    /// ------
    /// famcc.StepError
    ///     A non-finite input or a bad ``dt`` (the state is unchanged), or an
    ///     overflow.
    #[pyo3(signature = (e, dt, applied = None))]
    fn step_dt(&mut self, e: f64, dt: f64, applied: Option<f64>) -> PyResult<f64> {
        let v = self.core.step_dt(e, dt, applied).map_err(|x| step_err(x, "e"))?;
        self.check_health(applied)?;
        Ok(v)
    }

    /// One state-feedback step with the measured error vector.
    ///
    /// Parameters
    /// ----------
    /// z : sequence of float or numpy.ndarray
    ///     The error vector ``z = (z1, ..., zn)``, ``order`` entries,
    ///     ``z1 = y - y_d`` and ``z_k`` its (k-1)-th derivative (unit of ``y``
    ///     per s^(k-1)). With integral action the controller prepends its own
    ///     integral.
    /// applied : float, default None
    ///     The input the actuator really gave at the previous sample, input
    ///     units, when known.
    ///
    /// Returns
    /// -------
    /// float
    ///     The control ``v``, input units.
    ///
    /// Raises
    /// ------
    /// famcc.StepError
    ///     ``z`` not a float sequence of the right length, a non-finite
    ///     input, or an overflow.
    #[pyo3(signature = (z, applied = None))]
    fn step_state(&mut self, z: &Bound<'_, PyAny>, applied: Option<f64>) -> PyResult<f64> {
        let z: Vec<f64> = z
            .extract()
            .map_err(|_| StepFault::new(kind::WRONG_TYPE, Some("z"), "z must be a sequence of floats"))?;
        let v = self.core.step_state(&z, applied, self.spec.integral)?;
        self.check_health(applied)?;
        Ok(v)
    }

    /// The legal but risky choices of this configuration.
    ///
    /// Returns
    /// -------
    /// list of str
    ///     One message per finding (each was emitted as a
    ///     ``famcc.DesignWarning`` at construction); empty when none.
    fn lint(&self) -> Vec<String> {
        self.core.lint()
    }

    /// The configuration (a :class:`ControllerSpec`): what the controller
    /// guarantees (``spec.output_accuracy()``, ``spec.corollary_time(z1_0)``)
    /// and copies of it (``spec.replace(...).build()``).
    #[getter]
    fn spec(&self) -> ControllerSpec {
        ControllerSpec {
            spec: self.spec.clone(),
        }
    }

    /// True with integral action.
    #[getter]
    fn integral(&self) -> bool {
        self.spec.integral
    }

    /// Back to the state before the first step (the configuration is kept).
    fn reset(&mut self) {
        self.core.reset()
    }

    /// What the last step did.
    #[getter]
    fn diagnostics(&self) -> Diagnostics {
        self.core.diagnostics()
    }

    /// The estimate the next step will use (NumPy array; with integral
    /// action the integral `I` first, then the plant's `z1..zn`).
    #[getter]
    fn estimate<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_vec(py, self.core.estimate())
    }

    /// The observer's estimate ``Lhat`` of the lumped term, output units
    /// per s^n (0.0 without an observer; ``Lhat / b0`` is what it cancels).
    #[getter]
    fn lumped(&self) -> f64 {
        self.core.lumped()
    }

    /// The state as a float vector.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     float64, laid out as ``STATE_FIELDS`` followed by the estimate
    ///     ``z_hat[0..order]`` (with integral action ``order + 1`` entries:
    ///     the integral ``I`` first). :meth:`set_state` continues from it.
    fn state<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_vec(py, self.core.state())
    }

    /// Continues from a vector returned by :meth:`state`.
    ///
    /// Parameters
    /// ----------
    /// state : numpy.ndarray
    ///     A contiguous float64 vector from :meth:`state` of a controller
    ///     with the same configuration.
    ///
    /// Raises
    /// ------
    /// famcc.ConfigError
    ///     A vector of the wrong length or layout.
    fn set_state(&mut self, state: PyReadonlyArray1<'_, f64>) -> PyResult<()> {
        let v = state
            .as_slice()
            .map_err(|_| ConfigFault::new("state", "must be a contiguous float vector"))?;
        self.core.set_state(v)
    }

    /// The configuration as keyword arguments of the constructor.
    ///
    /// Returns
    /// -------
    /// dict
    ///     ``Controller(**ctrl.config())`` builds an equal controller; 'auto'
    ///     values appear resolved (``rho_e`` the margin in effect,
    ///     ``differentiator`` a :class:`HighGain` or None).
    fn config<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        self.spec.kwargs(py)
    }

    #[doc = include_str!("docs/replace.md")]
    #[allow(clippy::doc_lazy_continuation)] // ">>>" doctest prompts are not quotes
    #[pyo3(signature = (**overrides))]
    fn replace(&self, py: Python<'_>, overrides: Option<&Bound<'_, PyDict>>) -> PyResult<Self> {
        Self::from_spec_warned(py, self.spec.replace(overrides)?)
    }

    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        self.spec.repr(py, "Controller")
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
        let f = module_function(py, "_controller_from_state")?;
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

/// A signature default for a text argument.
fn text(s: &str) -> Text {
    Text(String::from(s))
}
