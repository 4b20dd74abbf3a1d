//! `famcc.Controller`: one Python class over the cores of orders 1..=8 in
//! f64 and f32. Parsing and conversion only; the law is famcc-core's.

use crate::errors::{config_err, step_err, ConfigError, StepError};
use crate::laws::{discretization_name, transition_name, HighGain, Law, SkewSpec};
use famcc_core as core_;
use famcc_core::{Constraint, Gamma, Latch, Real, Snapshot, Transition};
use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};

/// Largest order exposed to Python.
pub const MAX_ORDER: usize = 8;

/// The parsed configuration, in f64, kept for `repr`, pickling and banks.
#[derive(Clone, Debug)]
pub struct Spec {
    pub order: usize,
    pub dt: f64,
    pub laws: Vec<(Law, Option<SkewSpec>)>,
    pub constraint: &'static str,
    pub eps: (f64, f64),
    pub settle_time: f64,
    pub k0: f64,
    pub k_u: f64,
    pub gamma: Gamma,
    pub rho_e: Option<f64>,
    /// Keep famcc-core's default margin (min(0.01, eps/10)).
    pub rho_auto: bool,
    pub latch: Latch,
    pub transition: Transition,
    pub differentiator: Option<HighGain>,
    pub initial_derivatives: Option<Vec<f64>>,
    pub f32: bool,
}

fn arr<T: Real, const N: usize>(v: &[f64]) -> Option<[T; N]> {
    if v.len() != N {
        return None;
    }
    let mut out = [T::zero(); N];
    out.iter_mut().zip(v).for_each(|(o, x)| *o = T::c(*x));
    Some(out)
}

impl Spec {
    fn build<T: Real, const N: usize>(&self) -> Result<core_::Controller<T, N>, core_::ConfigError> {
        let laws: Vec<_> = self
            .laws
            .iter()
            .map(|(l, s)| (l.feedback::<T>(), s.map(|s| s.skew::<T>())))
            .collect();
        let constraint = match self.constraint {
            "lateral" => Constraint::Lateral {
                eps: T::c(self.eps.0),
            },
            "oblique" => Constraint::Oblique {
                eps_x: T::c(self.eps.0),
                eps_y: T::c(self.eps.1),
            },
            _ => Constraint::Longitudinal {
                eps: T::c(self.eps.1),
            },
        };
        let mut cfg = core_::Config::<T, N>::new(
            T::c(self.dt),
            &laws,
            constraint,
            T::c(self.settle_time),
            T::c(self.k_u),
        )?;
        cfg.k0 = T::c(self.k0);
        cfg.gamma = self.gamma;
        if !self.rho_auto {
            cfg.rho_e = self.rho_e.map(T::c);
        }
        cfg.latch = self.latch;
        cfg.transition = self.transition;
        if let Some(h) = &self.differentiator {
            let a = arr::<T, N>(&h.a).ok_or(core_::ConfigError::new(
                "a",
                "must have one coefficient per order",
            ))?;
            cfg.differentiator = Some(core_::HighGain::new(T::c(h.mu), a, h.discretization));
            if let Some(l) = &h.limits {
                cfg.estimate_limits = arr::<T, N>(l);
            }
        }
        if let Some(d) = &self.initial_derivatives {
            let mut full = vec![0.0];
            full.extend_from_slice(d);
            cfg.initial_derivatives = arr::<T, N>(&full);
        }
        core_::Controller::new(cfg)
    }
}

macro_rules! cores {
    ($($v64:ident, $v32:ident, $n:literal;)*) => {
        /// A famcc-core controller of a runtime-chosen order and float type.
        #[derive(Clone, Debug)]
        #[allow(clippy::large_enum_variant)]
        pub enum Core { $($v64(core_::Controller<f64, $n>), $v32(core_::Controller<f32, $n>),)* }

        impl Core {
            pub fn build(spec: &Spec) -> PyResult<Self> {
                match (spec.order, spec.f32) {
                    $(($n, false) => spec.build::<f64, $n>().map(Core::$v64).map_err(config_err),
                      ($n, true) => spec.build::<f32, $n>().map(Core::$v32).map_err(config_err),)*
                    (n, _) => Err(ConfigError::new_err(format!("order must be between 1 and {MAX_ORDER} (got {n})"))),
                }
            }
        }

        /// Many controllers of one order and float type, stored contiguously.
        #[derive(Clone, Debug)]
        pub enum BankCores { $($v64(Vec<core_::Controller<f64, $n>>), $v32(Vec<core_::Controller<f32, $n>>),)* }

        impl Core {
            /// `n` copies of this controller.
            pub fn replicate(&self, n: usize) -> BankCores {
                match self { $(Core::$v64(c) => BankCores::$v64(vec![*c; n]), Core::$v32(c) => BankCores::$v32(vec![*c; n]),)* }
            }
        }

        /// Runs `$body` with `$v` bound to the concrete vector of controllers.
        macro_rules! with_bank {
            ($bank:expr, $v:ident => $body:expr) => {
                match $bank { $(BankCores::$v64($v) => $body, BankCores::$v32($v) => $body,)* }
            };
        }
        pub(crate) use with_bank;

        /// Runs `$body` with `$c` bound to the concrete controller.
        macro_rules! with_core {
            ($core:expr, $c:ident => $body:expr) => {
                match $core { $(Core::$v64($c) => $body, Core::$v32($c) => $body,)* }
            };
        }

        /// Validates a differentiator for its order.
        pub fn validate_high_gain(h: &HighGain) -> PyResult<()> {
            match h.a.len() {
                $($n => {
                    let a = arr::<f64, $n>(&h.a).unwrap_or([0.0; $n]);
                    core_::HighGain::new(h.mu, a, h.discretization).validate().map_err(config_err)
                })*
                n => Err(ConfigError::new_err(format!("a must have 1 to {MAX_ORDER} coefficients, got {n}"))),
            }
        }
    };
}

cores! {
    D1, S1, 1; D2, S2, 2; D3, S3, 3; D4, S4, 4; D5, S5, 5; D6, S6, 6; D7, S7, 7; D8, S8, 8;
}

/// Diagnostics of the last step (read-only).
#[pyclass(frozen, module = "famcc._core")]
#[derive(Clone, Debug)]
pub struct Diagnostics {
    /// Time of the last sample, s.
    #[pyo3(get)]
    t: f64,
    /// Constraint variable used for the output (flexible xi~).
    #[pyo3(get)]
    xi: f64,
    /// Nominal constraint variable xi (eq. xi).
    #[pyo3(get)]
    xi_nominal: f64,
    /// Manifold value s = s_n.
    #[pyo3(get)]
    s: f64,
    stages: Vec<f64>,
    /// s_{n-1}.
    #[pyo3(get)]
    s_prev: f64,
    /// d/dt s_{n-1}.
    #[pyo3(get)]
    ds_prev: f64,
    /// Flexible upper bounds (x~_U, y~_U).
    #[pyo3(get)]
    bounds: (f64, f64),
    /// Nominal upper bounds (x_U, y_U).
    #[pyo3(get)]
    nominal_bounds: (f64, f64),
    z_hat: Vec<f64>,
    /// True when the flexible bounds were expanded.
    #[pyo3(get)]
    expanded: bool,
    /// Expansion factor of the flexible bounds (flexible / nominal, 1.0 when nominal).
    #[pyo3(get)]
    expansion: f64,
    /// v_{k-1} - applied, when `applied` was passed.
    #[pyo3(get)]
    saturation_gap: Option<f64>,
    /// Steps at which |xi| had to be clamped below 1.
    #[pyo3(get)]
    clamp_count: u64,
    /// The output v.
    #[pyo3(get)]
    v: f64,
}

impl Diagnostics {
    fn from_core<T: Real, const N: usize>(d: &core_::Diagnostics<T, N>) -> Self {
        let f = |x: T| x.to_f64_lossless();
        Self {
            t: f(d.t),
            xi: f(d.xi),
            xi_nominal: f(d.xi_nominal),
            s: f(d.s),
            stages: d.stages.iter().map(|x| f(*x)).collect(),
            s_prev: f(d.s_prev),
            ds_prev: f(d.ds_prev),
            bounds: (f(d.bounds.0), f(d.bounds.1)),
            nominal_bounds: (f(d.nominal_bounds.0), f(d.nominal_bounds.1)),
            z_hat: d.z_hat.iter().map(|x| f(*x)).collect(),
            expanded: d.expanded,
            expansion: f(d.expansion),
            saturation_gap: d.saturation_gap.map(f),
            clamp_count: d.clamp_count,
            v: f(d.v),
        }
    }
}

#[pymethods]
impl Diagnostics {
    /// The estimate the output was computed from (NumPy array).
    #[getter]
    fn z_hat<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.z_hat)
    }
    /// s_1..s_n (NumPy array).
    #[getter]
    fn stages<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.stages)
    }
    fn __repr__(&self) -> String {
        format!(
            "Diagnostics(t={:?}, xi={:?}, s={:?}, bounds={:?}, nominal_bounds={:?}, z_hat={:?}, expanded={}, clamp_count={})",
            self.t,
            self.xi,
            self.s,
            self.bounds,
            self.nominal_bounds,
            self.z_hat,
            if self.expanded { "True" } else { "False" },
            self.clamp_count
        )
    }
}

/// A finite f64 that is out of range for an f32 core is an overflow, not a
/// non-finite input.
#[inline(always)]
fn check_range<T: Real>(e: f64, ec: T, applied: Option<f64>, ac: Option<T>) -> Result<(), core_::StepError> {
    if e.is_finite() && !ec.is_finite() {
        return Err(core_::StepError::Overflow);
    }
    if let (Some(a), Some(ac)) = (applied, ac) {
        if a.is_finite() && !ac.is_finite() {
            return Err(core_::StepError::Overflow);
        }
    }
    Ok(())
}

/// Length of the flat state vector for an order.
fn state_len(order: usize) -> usize {
    7 + order
}

/// The flat state vector of a controller.
pub fn snapshot_vec<T: Real, const N: usize>(c: &core_::Controller<T, N>) -> Vec<f64> {
    snapshot_to_vec(&c.snapshot())
}

fn snapshot_to_vec<T: Real, const N: usize>(s: &Snapshot<T, N>) -> Vec<f64> {
    let mut v = vec![
        if s.started { 1.0 } else { 0.0 },
        s.t_base.to_f64_lossless(),
        s.k as f64,
        s.rho0_x.to_f64_lossless(),
        s.rho0_y.to_f64_lossless(),
        s.clamp_count as f64,
        s.last_v.to_f64_lossless(),
    ];
    v.extend(s.zhat.iter().map(|x| x.to_f64_lossless()));
    v
}

fn vec_to_snapshot<T: Real, const N: usize>(v: &[f64]) -> PyResult<Snapshot<T, N>> {
    let bad = || ConfigError::new_err(format!("state must be a float vector of length {}", state_len(N)));
    if v.len() != state_len(N) {
        return Err(bad());
    }
    let count = |x: f64, name: &str| {
        if x.is_finite() && x >= 0.0 && x.fract() == 0.0 && x <= 9.007_199_254_740_992e15 {
            Ok(x as u64)
        } else {
            Err(ConfigError::new_err(format!(
                "state: {name} must be a non-negative integer"
            )))
        }
    };
    Ok(Snapshot {
        started: v[0] != 0.0,
        t_base: T::c(v[1]),
        k: count(v[2], "k")?,
        rho0_x: T::c(v[3]),
        rho0_y: T::c(v[4]),
        clamp_count: count(v[5], "clamp_count")?,
        last_v: T::c(v[6]),
        zhat: arr::<T, N>(&v[7..]).ok_or_else(bad)?,
    })
}

impl Core {
    pub fn order(&self) -> usize {
        with_core!(self, c => c.estimate().len())
    }

    /// The flexible-boundary margin in effect.
    pub fn rho_e(&self) -> Option<f64> {
        with_core!(self, c => c.config().rho_e.map(|x| x.to_f64_lossless()))
    }

    #[inline]
    pub fn step(&mut self, e: f64, applied: Option<f64>) -> Result<f64, core_::StepError> {
        with_core!(self, c => {
            let (ec, ac) = (Real::c(e), applied.map(Real::c));
            check_range(e, ec, applied, ac)?;
            c.step_applied(ec, ac).map(|v| v.to_f64_lossless())
        })
    }

    fn step_dt(&mut self, e: f64, dt: f64, applied: Option<f64>) -> Result<f64, core_::StepError> {
        with_core!(self, c => {
            let (ec, ac) = (Real::c(e), applied.map(Real::c));
            check_range(e, ec, applied, ac)?;
            c.step_dt(ec, Real::c(dt), ac).map(|v| v.to_f64_lossless())
        })
    }

    fn step_state(&mut self, z: &[f64], applied: Option<f64>) -> PyResult<f64> {
        with_core!(self, c => {
            let z = arr(z).ok_or_else(|| StepError::new_err(format!("z must have {} entries (one per order), got {}", c.estimate().len(), z.len())))?;
            c.step_state_applied(z, applied.map(Real::c)).map(|v| v.to_f64_lossless()).map_err(step_err)
        })
    }

    fn reset(&mut self) {
        with_core!(self, c => c.reset())
    }

    fn diagnostics(&self) -> Diagnostics {
        with_core!(self, c => Diagnostics::from_core(&c.diagnostics()))
    }

    fn time(&self) -> f64 {
        with_core!(self, c => c.time().to_f64_lossless())
    }

    fn estimate(&self) -> Vec<f64> {
        with_core!(self, c => c.estimate().iter().map(|x| x.to_f64_lossless()).collect())
    }

    fn state(&self) -> Vec<f64> {
        with_core!(self, c => snapshot_to_vec(&c.snapshot()))
    }

    fn set_state(&mut self, v: &[f64]) -> PyResult<()> {
        with_core!(self, c => {
            let snap = vec_to_snapshot(v)?;
            c.restore(&snap).map_err(config_err)
        })
    }
}

/// The FAMCC controller (see `famcc.Controller` for the documentation).
#[pyclass(module = "famcc._core", name = "Controller")]
#[derive(Clone)]
pub struct PyController {
    pub core: Core,
    pub spec: Spec,
}

fn parse_per_stage<'py, T>(
    obj: &Bound<'py, PyAny>,
    n: usize,
    name: &str,
    one: impl Fn(&Bound<'py, PyAny>) -> PyResult<T>,
) -> PyResult<Vec<T>> {
    if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
        let items: Vec<Bound<'py, PyAny>> = obj.try_iter()?.collect::<PyResult<_>>()?;
        if items.len() != n {
            return Err(ConfigError::new_err(format!(
                "{name} must have order - 1 = {n} entries (one per stage), got {}",
                items.len()
            )));
        }
        items.iter().map(&one).collect()
    } else {
        (0..n).map(|_| one(obj)).collect()
    }
}

/// The `differentiator` argument: a HighGain, the string "auto", or None.
#[derive(FromPyObject)]
pub enum DiffArg<'py> {
    Gain(Bound<'py, HighGain>),
    Name(String),
    Other(Bound<'py, PyAny>),
}

/// The `rho_e` argument: a float, the string "auto", or None.
#[derive(FromPyObject)]
pub enum RhoArg<'py> {
    Value(f64),
    Name(String),
    Other(Bound<'py, PyAny>),
}

fn choice(value: &str, name: &str, allowed: &[&'static str]) -> PyResult<&'static str> {
    allowed.iter().copied().find(|a| *a == value).ok_or_else(|| {
        let list: Vec<String> = allowed.iter().map(|a| format!("'{a}'")).collect();
        ConfigError::new_err(format!(
            "{name} must be one of {} (got {value:?})",
            list.join(", ")
        ))
    })
}

fn finite(x: f64, name: &str) -> PyResult<f64> {
    if x.is_finite() {
        Ok(x)
    } else {
        Err(ConfigError::new_err(format!("{name} must be finite (got {x})")))
    }
}

#[pymethods]
impl PyController {
    #[new]
    #[pyo3(signature = (order, dt, feedback = None, *, skew = None, constraint = "longitudinal", eps,
        settle_time = 1.0, k0 = 2.0, k_u, gamma = "log", rho_e = Some(RhoArg::Name(String::from("auto"))), differentiator = Some(DiffArg::Name(String::from("auto"))),
        latch = "paper", transition = "exponential", initial_derivatives = None, dtype = "float64"))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
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
        let order = match usize::try_from(order) {
            Ok(n) if (1..=MAX_ORDER).contains(&n) => n,
            _ => {
                return Err(ConfigError::new_err(format!(
                    "order must be between 1 and {MAX_ORDER} (got {order})"
                )))
            }
        };
        let n = order - 1;
        let laws: Vec<Law> = match feedback {
            Some(f) if n == 0 => {
                let empty = f.len().map(|l| l == 0).unwrap_or(false);
                if !empty {
                    return Err(ConfigError::new_err(
                        "feedback must be omitted (or empty) at order 1: there are no stages",
                    ));
                }
                vec![]
            }
            Some(f) => parse_per_stage(f, n, "feedback", |o| Law::extract_named(o, "feedback"))?,
            None if n == 0 => vec![],
            None => {
                return Err(ConfigError::new_err(
                    "feedback is required for order >= 2 (one law per stage)",
                ))
            }
        };
        let skews: Vec<Option<SkewSpec>> = match skew {
            Some(s) if n > 0 => parse_per_stage(s, n, "skew", SkewSpec::extract)?,
            _ => vec![None; n],
        };
        let constraint = choice(constraint, "constraint", &["longitudinal", "lateral", "oblique"])?;
        let eps = if constraint == "oblique" {
            let (x, y): (f64, f64) = eps.extract().map_err(|_| {
                ConfigError::new_err("eps must be a pair (eps_x, eps_y) for the oblique constraint")
            })?;
            (x, y)
        } else {
            let e: f64 = eps
                .extract()
                .map_err(|_| ConfigError::new_err("eps must be a float"))?;
            if constraint == "lateral" {
                (e, 0.0)
            } else {
                (0.0, e)
            }
        };
        let gamma = match choice(gamma, "gamma", &["log", "rational"])? {
            "rational" => Gamma::Rational,
            _ => Gamma::Log,
        };
        let latch = match choice(latch, "latch", &["paper", "authors"])? {
            "authors" => Latch::Authors,
            _ => Latch::Paper,
        };
        let transition = crate::laws::parse_transition(transition, "transition")?;
        let f32_ = choice(dtype, "dtype", &["float64", "float32"])? == "float32";
        let differentiator = match differentiator {
            None => None,
            Some(DiffArg::Name(s)) if s == "auto" => {
                (order > 1).then(|| HighGain::default_for(order)).transpose()?
            }
            Some(DiffArg::Name(s)) => {
                return Err(ConfigError::new_err(format!(
                    "differentiator must be a HighGain, 'auto' or None (got {s:?})"
                )))
            }
            Some(DiffArg::Other(o)) => {
                return Err(ConfigError::new_err(format!(
                    "differentiator must be a HighGain, 'auto' or None (got {})",
                    o.repr()?
                )))
            }
            Some(DiffArg::Gain(h)) => {
                let h = h.get().clone();
                if h.a.len() != order {
                    return Err(ConfigError::new_err(format!(
                        "differentiator.a must have {order} coefficients (the order), got {}",
                        h.a.len()
                    )));
                }
                Some(h)
            }
        };
        if let Some(d) = &initial_derivatives {
            if d.len() != n {
                return Err(ConfigError::new_err(format!(
                    "initial_derivatives must have order - 1 = {n} entries (z2..zn), got {}",
                    d.len()
                )));
            }
        }
        let (rho_e, rho_auto) = match rho_e {
            None => (None, false),
            Some(RhoArg::Value(v)) => (Some(v), false),
            Some(RhoArg::Name(s)) if s == "auto" => (None, true),
            Some(RhoArg::Name(s)) => {
                return Err(ConfigError::new_err(format!(
                    "rho_e must be a float, 'auto' or None (got {s:?})"
                )))
            }
            Some(RhoArg::Other(o)) => {
                return Err(ConfigError::new_err(format!(
                    "rho_e must be a float, 'auto' or None (got {})",
                    o.repr()?
                )))
            }
        };
        let mut spec = Spec {
            order,
            dt: finite(dt, "dt")?,
            laws: laws.into_iter().zip(skews).collect(),
            constraint,
            eps,
            settle_time,
            k0,
            k_u,
            gamma,
            rho_e,
            rho_auto,
            latch,
            transition,
            differentiator,
            initial_derivatives,
            f32: f32_,
        };
        let _ = py;
        let core = Core::build(&spec)?;
        spec.rho_e = core.rho_e();
        spec.rho_auto = false;
        Ok(Self { core, spec })
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
        if self.spec.f32 {
            "float32"
        } else {
            "float64"
        }
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

    /// The state as a float vector: [started, t_base, k, rho0_x, rho0_y,
    /// clamp_count, last_v, z_hat...].
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

    /// A no-op method: the floor of a Python-to-Rust method call (benchmarks).
    fn _noop(&mut self, e: f64) -> f64 {
        e
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

impl PyController {
    pub fn set_state_vec(&mut self, v: &[f64]) -> PyResult<()> {
        self.core.set_state(v)
    }
}

impl HighGain {
    pub fn default_for(order: usize) -> PyResult<Self> {
        Ok(HighGain {
            mu: 0.01,
            a: crate::laws::default_coefficients(order)?,
            discretization: core_::Discretization::Exact,
            limits: None,
        })
    }
}

impl Spec {
    /// The constructor's keyword arguments for this configuration.
    pub fn kwargs<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        d.set_item("order", self.order)?;
        d.set_item("dt", self.dt)?;
        let laws = PyList::empty(py);
        let skews = PyList::empty(py);
        for (l, s) in &self.laws {
            laws.append(match *l {
                Law::Linear(x) => x.into_pyobject(py)?.into_any(),
                Law::FiniteTime(x) => x.into_pyobject(py)?.into_any(),
                Law::FixedTime(x) => x.into_pyobject(py)?.into_any(),
                Law::VariableExponent(x) => x.into_pyobject(py)?.into_any(),
                Law::Moulay(x) => x.into_pyobject(py)?.into_any(),
            })?;
            skews.append(match *s {
                None => py.None().into_bound(py),
                Some(SkewSpec::Smooth(x)) => x.into_pyobject(py)?.into_any(),
                Some(SkewSpec::Nonsingular(x)) => x.into_pyobject(py)?.into_any(),
            })?;
        }
        d.set_item("feedback", laws)?;
        d.set_item("skew", skews)?;
        d.set_item("constraint", self.constraint)?;
        match self.constraint {
            "oblique" => d.set_item("eps", (self.eps.0, self.eps.1))?,
            "lateral" => d.set_item("eps", self.eps.0)?,
            _ => d.set_item("eps", self.eps.1)?,
        }
        d.set_item("settle_time", self.settle_time)?;
        d.set_item("k0", self.k0)?;
        d.set_item("k_u", self.k_u)?;
        d.set_item(
            "gamma",
            if self.gamma == Gamma::Log {
                "log"
            } else {
                "rational"
            },
        )?;
        d.set_item("rho_e", self.rho_e)?;
        match &self.differentiator {
            Some(h) => d.set_item("differentiator", h.clone().into_pyobject(py)?)?,
            None => d.set_item("differentiator", py.None())?,
        }
        d.set_item(
            "latch",
            if self.latch == Latch::Paper {
                "paper"
            } else {
                "authors"
            },
        )?;
        d.set_item("transition", transition_name(self.transition))?;
        d.set_item("initial_derivatives", self.initial_derivatives.clone())?;
        d.set_item("dtype", if self.f32 { "float32" } else { "float64" })?;
        let _ = discretization_name;
        Ok(d)
    }
}

/// Unpickling: rebuild from keyword arguments and continue from the state.
#[pyfunction]
pub fn _controller_from_state<'py>(
    py: Python<'py>,
    kwargs: &Bound<'py, PyDict>,
    state: Vec<f64>,
) -> PyResult<Bound<'py, PyAny>> {
    let cls = py.import("famcc._core")?.getattr("Controller")?;
    let kw = kwargs.copy()?;
    let order = kw
        .get_item("order")?
        .ok_or_else(|| ConfigError::new_err("order missing"))?;
    let dt = kw
        .get_item("dt")?
        .ok_or_else(|| ConfigError::new_err("dt missing"))?;
    kw.del_item("order")?;
    kw.del_item("dt")?;
    let obj = cls.call((order, dt), Some(&kw))?;
    let mut c: PyRefMut<'_, PyController> = obj.extract()?;
    c.core.set_state(&state)?;
    drop(c);
    Ok(obj)
}
