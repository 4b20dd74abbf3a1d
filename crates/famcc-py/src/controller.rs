//! `famcc.Controller`: the Python methods. Arguments are parsed by
//! [`crate::args`], the controller is famcc-core's ([`Core`]), the rules and
//! defaults are famcc-core's (the signature's defaults name them).

use crate::args::{Args, DiffArg, RhoArg, AUTO};
use crate::diagnostics::Diagnostics;
use crate::dispatch::Core;
use crate::errors::{config_err, step_err, ConfigError, StepError};
use crate::names::{CONSTRAINT, DTYPE, GAMMA, LATCH, TRANSITION};
use crate::number::{Int, Num, Text};
use crate::spec::{RhoE, Spec};
use famcc_core::config::{DEFAULT_K0, DEFAULT_SETTLE_TIME};
use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::exceptions::PyUserWarning;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};
use std::ffi::CString;

/// The FAMCC controller: fully actuated manifold constraint control.
///
/// A model-free output-feedback controller for an unknown strict-feedback
/// plant of order n (eq. (5) (SFS)). It drives the tracking error to the
/// preset accuracy ``eps`` within the preset time ``settle_time`` and keeps
/// working when the actuator saturates. The sign convention of every step
/// method is ``e = y - y_d`` (the output minus the reference: the opposite of
/// a PID's ``setpoint - y``); :meth:`step_output` takes ``y`` and ``y_d`` and
/// forms it.
///
/// Parameters
/// ----------
/// order : int
///     The plant's order n (the relative degree of the output),
///     ``1 <= order <= MAX_ORDER``.
/// dt : float
///     Sample period, s (``> 0``); :meth:`step_dt` takes a one-off period.
/// feedback : Linear, FiniteTime, FixedTime, VariableExponent, MoulayDiscontinuous or a sequence of them, default None
///     The stage laws ``h_p`` of the iterative manifold (eq. (11) (IS)): one
///     law for every stage, or a list of ``order - 1`` (``order`` with
///     integral action), first stage first. Required at order >= 2; omitted
///     (or empty) at order 1, which has no stages.
/// skew : Smooth, Nonsingular, None or a sequence of them, default None
///     The skews of the stage laws (eqs. (14) (SSMD), (15) (NSMD)): one for
///     every stage, or one per stage (a None entry: that stage unskewed).
///     None: no stage is skewed.
/// constraint : {'longitudinal', 'lateral', 'oblique'}, default 'longitudinal'
///     The manifold constraint (paper Step C1): LoMC constrains ``s``
///     itself, LaMC ``s_{n-1} - h_v(ds_{n-1})``, OMC the oblique combination
///     of both (eq. (27) (xyc)).
/// eps : float or (float, float)
///     Final half-widths of the constraint (required): ``eps_y`` (unit of
///     ``s``) for 'longitudinal', ``eps_x`` (unit of ``s_{n-1}``) for
///     'lateral', the pair ``(eps_x, eps_y)`` for 'oblique'. With the
///     paper's choice ``eps_x = eps_z`` at order 2 it is the output accuracy,
///     in the unit of ``y``.
/// settle_time : float, default 1.0
///     Preset settling time ``T_s`` of the envelopes (eqs. (21) (xUxL),
///     (22) (yUyL)), s (``> 0``).
/// k0 : float, default 2.0
///     Initial-width factor of the envelopes, dimensionless, ``k0 > 1``
///     (eqs. (21)-(22)).
/// k_u : float
///     Control gain ``k_u > 0`` (required), input units: the output is
///     ``v = -k_u Gamma(xi)`` (eq. (29) (uT)).
/// gamma : {'log', 'rational'}, default 'log'
///     The map ``Gamma`` of eq. (29) (uT): 'log' is
///     ``ln((1 + xi)/(1 - xi)) = 2 atanh(xi)``, 'rational' is
///     ``xi / ((1 + xi)(1 - xi))``.
/// rho_e : float, 'auto' or None, default 'auto'
///     The flexible-boundary margin ``rho_e`` of eq. (30) (WxyUxyL), in the
///     unit of the constrained variable: 'auto' is ``min(0.01, eps / 10)``
///     (the smallest final width), None turns the flexible boundary off.
///     :meth:`config` shows the margin in effect.
/// differentiator : HighGain, 'auto' or None, default 'auto'
///     The high-gain differentiator (eq. (34) (HGD)) that estimates
///     ``e', ..., e^(n-1)`` from ``e`` (eq. (35) (uOF)): 'auto' is the
///     paper's (exact) up to order 3 and
///     ``HighGain.default(order, discretization="tustin")`` above, none at
///     order 1 (which needs none); None: state feedback only
///     (:meth:`step_state`).
/// latch : {'paper', 'authors'}, default 'paper'
///     How the envelopes' initial width is latched from the first sample's
///     offset ``s0``: 'paper' (text after eq. (22) (yUyL))
///     ``rho0 = k0 max(|s0|, eps)``, 'authors' (the authors' code)
///     ``rho0 = max(k0 |s0|, eps)``.
/// transition : {'exponential', 'cubic', 'quintic', 'sine'}, default 'exponential'
///     The transition ``S`` of the flexible boundary: 'exponential' is the
///     paper's eq. (2) (trnsS), C-infinity; 'cubic' ``3z^2 - 2z^3``;
///     'quintic' ``10z^3 - 15z^4 + 6z^5``; 'sine' ``(1 - cos(pi z)) / 2``.
/// initial_derivatives : sequence of float, default None
///     The differentiator's initial estimates of ``(z2, ..., zn)``
///     (``order - 1`` entries, ``z_k`` in the unit of ``e`` per s^(k-1));
///     None: zeros.
/// dtype : {'float64', 'float32'}, default 'float64'
///     The float type of the core's arithmetic (the API takes and returns
///     Python floats either way).
/// integral : bool, default False
///     Integral action (docs/design.md §3.8). The law of order
///     ``n + 1`` acts on ``(I, e, e', ..., e^(n-1))`` with ``I`` the exact integral
///     of the measured error (rectangle rule), so a constant load is carried by
///     ``I`` and the error tends to 0. ``feedback`` and ``skew`` then have ``order``
///     entries (one per stage of the order ``n + 1`` law), the differentiator keeps
///     ``order`` coefficients (it runs on ``e``), ``initial_derivatives`` stay the
///     plant's ``(z2..zn)``. The integral is separated (anti-windup): ``e`` is
///     integrated only while ``|s| <= eps`` (the final band) and not while the
///     output is beyond a known limit with ``e`` pushing it further. Needs
///     ``order < MAX_ORDER``.
/// output_limits : (float, float), default None
///     Magnitude limits ``(lo, hi)`` of the output, ``lo < hi``, input units.
///     :meth:`step` returns the limited output; it counts as the
///     applied input for the integral separation and the health count, and
///     ``diagnostics.v_unlimited`` keeps the law's own output.
/// rate_limit : float, default None
///     The output's largest rate of change, input units per second.
/// initial_output : float, default None
///     Bumpless start, input units: the first step's output equals
///     ``initial_output`` when that is feasible (with integral action by the
///     choice of ``I_0``; without, by rescaling the latched widths), else the
///     nearest feasible output.
///
/// Raises
/// ------
/// famcc.ConfigError
///     An invalid value or combination; the message names the parameter
///     and the rule.
///
/// Warns
/// -----
/// famcc.DesignWarning
///     At construction, once per legal but risky choice (:meth:`lint`): dt too
///     coarse for mu, a last-stage law that chatters when sampled, rho_e too
///     large for eps, no estimate limits at differentiator order >= 4, the
///     exact ZOH at order >= 4. While stepping with the applied input known
///     (``applied`` passed or ``output_limits`` set), once, when the bounds
///     were expanded although the actuator had headroom for half the envelope's
///     settling time in total (``diagnostics.unsaturated_expansions >=
///     0.5 settle_time / dt``: persistent, not a start-up transient or the
///     recovery after a saturation): ``k_u`` too small for the plant.
///
/// See Also
/// --------
/// ControllerBank : n copies stepped together from an array.
/// famcc.design : a design from the plant's limits and the wanted accuracy.
///
/// Notes
/// -----
/// The output is the flexible manifold constraint controller
/// ``v = -k_u Gamma(xi~)`` (eqs. (31) (Wxi), (32) (WuT)) on the iterative
/// manifold ``s = s_n`` (eq. (11) (IS)), fed by the differentiator's
/// estimate (eq. (35) (uOF)). The defaults are famcc-core's (every example
/// of the paper). A controller can be copied, pickled, and continued from
/// :meth:`state`.
///
/// Examples
/// --------
/// Example 1 of the paper (LaMC, finite-time law):
///
/// >>> import famcc
/// >>> ctrl = famcc.Controller(2, 1e-3, famcc.FiniteTime(k=1.0, p=0.5),
/// ...                         constraint="lateral", eps=0.1, k_u=5.0)
/// >>> round(ctrl.step(-1.0), 4)
/// 5.4931
/// >>> ctrl.config()["settle_time"], ctrl.config()["k0"]
/// (1.0, 2.0)
#[pyclass(module = "famcc._core", name = "Controller")]
#[derive(Clone)]
pub struct PyController {
    pub core: Core,
    pub spec: Spec,
    /// The health warning was given (once per controller).
    health_warned: bool,
}

/// The health warning fires once the bounds were expanded with headroom
/// for this fraction of the envelope's settling time `T_s` (in samples).
const HEALTH_FRACTION: f64 = 0.5;

/// `2 atanh 0.5 = ln 3`: `k_u` must exceed the hold input divided by it.
const TWO_ATANH_HALF: f64 = 1.0986122886681098;

/// Emits `famcc.DesignWarning` (a `UserWarning` when famcc's Python package
/// is not importable).
pub fn design_warning(py: Python<'_>, message: &str) -> PyResult<()> {
    let category = match py
        .import("famcc._common")
        .and_then(|m| m.getattr("DesignWarning"))
    {
        Ok(c) => c,
        Err(_) => py.get_type::<PyUserWarning>().into_any(),
    };
    let text = CString::new(message.replace('\0', " ")).unwrap_or_default();
    PyErr::warn(py, &category, &text, 2)
}

impl PyController {
    /// Builds the controller of `spec`, whose `rho_e` then shows the margin
    /// in effect.
    pub fn from_spec(mut spec: Spec) -> PyResult<Self> {
        let core = Core::build(&spec).map_err(config_err)?;
        spec.rho_e = RhoE::Given(core.rho_e());
        Ok(Self {
            core,
            spec,
            health_warned: false,
        })
    }

    pub fn set_state_vec(&mut self, v: &[f64]) -> PyResult<()> {
        self.core.set_state(v)
    }

    /// After a successful step: the health warning, once, when the bounds
    /// expanded while the actuator had headroom (only counted when the
    /// applied input is known, so nothing to check otherwise).
    #[inline]
    fn check_health(&mut self, applied: Option<f64>) -> PyResult<()> {
        if self.health_warned || (applied.is_none() && self.spec.output_limits.is_none()) {
            return Ok(());
        }
        let n = self.core.unsaturated_expansions();
        // Persistent, not a transient: expanded with headroom for half the
        // envelope's settling time in total (the flexible boundary's recovery
        // after a saturation, or a start-up transient, stays below it).
        let persistent = (HEALTH_FRACTION * self.spec.settle_time / self.spec.dt)
            .ceil()
            .max(1.0);
        if (n as f64) < persistent {
            return Ok(());
        }
        self.health_warned = true;
        let (v, k_u) = self.core.last_unlimited();
        let suggested = (2.0 * k_u).max(v.abs() / TWO_ATANH_HALF);
        Python::attach(|py| {
            design_warning(
                py,
                &format!(
                    "k_u too small for this plant: the bounds expanded {n} times while the actuator had \
                     headroom; raise k_u to {suggested:.3} (k_u >= |u_hold| / (2 atanh 0.5), u_hold the \
                     input that holds the error still, about |v| = {:.3} here) or lower rho_e",
                    v.abs()
                ),
            )
        })
    }
}

#[pymethods]
impl PyController {
    #[new]
    #[pyo3(signature = (order, dt, feedback = None, *, skew = None, constraint = text(CONSTRAINT.default_name()), eps,
        settle_time = Num(DEFAULT_SETTLE_TIME), k0 = Num(DEFAULT_K0), k_u, gamma = text(GAMMA.default_name()),
        rho_e = Some(RhoArg::Name(String::from(AUTO))), differentiator = Some(DiffArg::Name(String::from(AUTO))),
        latch = text(LATCH.default_name()), transition = text(TRANSITION.default_name()), initial_derivatives = None,
        dtype = text(DTYPE.default_name()), integral = false, output_limits = None, rate_limit = None,
        initial_output = None),
        // The defaults above are famcc-core's; pyo3 shows only literal ones, so
        // the Python signature spells them out (tests/test_docs.py checks that
        // each equals the default in effect).
        text_signature = "(order, dt, feedback=None, *, skew=None, constraint='longitudinal', eps, \
            settle_time=1.0, k0=2.0, k_u, gamma='log', rho_e='auto', differentiator='auto', latch='paper', \
            transition='exponential', initial_derivatives=None, dtype='float64', integral=False, \
            output_limits=None, rate_limit=None, initial_output=None)")]
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
        }
        .parse()?;
        let c = Self::from_spec(spec)?;
        // Legal but risky choices (famcc-core's Config::lint), once each.
        for finding in c.core.lint() {
            design_warning(py, &finding)?;
        }
        Ok(c)
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
        let v = self.core.step(e, applied).map_err(step_err)?;
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
        let v = self.core.step_output(y, y_d, applied).map_err(step_err)?;
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
        let v = self.core.step_dt(e, dt, applied).map_err(step_err)?;
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
            .map_err(|_| StepError::new_err("z must be a sequence of floats"))?;
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
            .map_err(|_| ConfigError::new_err("state must be a contiguous float vector"))?;
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

/// A signature default for a text argument.
fn text(s: &str) -> Text {
    Text(String::from(s))
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
