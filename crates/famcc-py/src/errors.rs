//! famcc's Python exception and warning classes, defined here (the binding
//! imports no Python module of famcc): `ConfigError` and `StepError`
//! (`ValueError`s with structured fields besides the message),
//! `FamccWarning` / `DesignWarning` (`UserWarning`s) and the
//! `ArgumentTypeError` of a wrongly typed argument. `famcc._common`
//! re-exports the warnings.
//!
//! The fields live in the instance's `__dict__` (class defaults None), so
//! `BaseException.__reduce__` pickles them with the message; Python code
//! passes them as keyword arguments (`ConfigError("eps must be > 0",
//! parameter="eps", rule="must be > 0")`). `str(error)` is the message alone.

use pyo3::create_exception;
use pyo3::exceptions::{PyTypeError, PyUserWarning, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString, PyType};
use pyo3::{PyErr, PyErrArguments};
use std::fmt::Display;

create_exception!(
    famcc._core,
    ConfigError,
    PyValueError,
    "An invalid configuration value; the message names the parameter and the rule.\n\n\
     A ``ValueError``: ``str(error)`` is the message; the fields say the same for a program.\n\n\
     Parameters\n----------\n\
     *args\n    The message, as for any exception.\n\
     parameter : str, optional\n    The parameter's name.\n\
     stage : int, optional\n    The stage of a per-stage parameter, from 1.\n\
     rule : str, optional\n    The rule the value broke.\n\n\
     Attributes\n----------\n\
     parameter : str or None\n    The parameter's name as in the API (``'eps'``, ``'k_u'``, ``'feedback'``,\n    \
     ``'differentiator.a'``); None when no single parameter is at fault.\n\
     stage : int or None\n    For a per-stage parameter (``feedback``, ``skew``, a stage's own values), the\n    \
     stage, counted from 1 as in the message ``'stage 1: ...'``; None otherwise.\n\
     rule : str or None\n    The rule the value broke, e.g. ``'must be finite and > 0'``; None when the\n    \
     message has no separate rule.\n\n\
     Examples\n--------\n\
     >>> import famcc\n\
     >>> try:\n\
     ...     famcc.Linear(0.0)\n\
     ... except famcc.ConfigError as error:\n\
     ...     print(error, '|', error.parameter, '|', error.rule)\n\
     k must be finite and > 0 | k | must be finite and > 0"
);
create_exception!(
    famcc._core,
    StepError,
    PyValueError,
    "A step that could not be taken (non-finite input, bad ``dt``, overflow).\n\n\
     For a non-finite ``e``, ``applied`` or ``dt`` the state is unchanged; an overflow on a valid \
     sample after the first step consumes the sample (hold the previous output).\n\n\
     Parameters\n----------\n\
     *args\n    The message, as for any exception.\n\
     kind : str, optional\n    What went wrong (see ``kind`` below).\n\
     parameter : str, optional\n    The input at fault.\n\n\
     Attributes\n----------\n\
     kind : str or None\n    One stable name per cause: ``'non-finite-input'``, ``'non-finite-applied'``,\n    \
     ``'invalid-dt'``, ``'no-differentiator'``, ``'overflow'`` (famcc-core's ``StepError``),\n    \
     ``'wrong-length'`` (a vector of the wrong length) and ``'wrong-type'`` (an input that is\n    \
     not a float vector).\n\
     parameter : str or None\n    The input at fault (``'e'``, ``'y'``, ``'y_d'``, ``'z'``, ``'applied'``, ``'dt'``,\n    \
     ``'differentiator'``); None when no single input is (an overflow).\n\n\
     Examples\n--------\n\
     >>> import famcc\n\
     >>> ctrl = famcc.Controller(1, 1e-3, constraint='longitudinal', eps=0.1, k_u=1.0)\n\
     >>> try:\n\
     ...     ctrl.step(float('nan'))\n\
     ... except famcc.StepError as error:\n\
     ...     print(error.kind, error.parameter)\n\
     non-finite-input e"
);
create_exception!(
    famcc._core,
    FamccWarning,
    PyUserWarning,
    "Base class of the warnings famcc itself emits.\n\n\
     The test suite turns every one of them into an error, so that a warning that famcc's own \
     code triggers is either fixed or expected explicitly."
);
create_exception!(
    famcc._core,
    DesignWarning,
    FamccWarning,
    "A legal but risky choice (or a requirement a design cannot meet).\n\n\
     Emitted by :func:`famcc.design` for every finding that is not ok, and by \
     :class:`famcc.Controller` for risky configurations; the message names the parameter, the \
     rule and a suggested value."
);
create_exception!(
    famcc._core,
    ArgumentTypeError,
    PyTypeError,
    "A ``TypeError`` whose message names the argument.\n\n\
     The compiled constructors raise it for an argument of the wrong type (a ``bool`` where a \
     number is meant, a ``str`` for a float, ...): ``str(error)`` reads ``argument 'dt': must be \
     a real number, not bool``."
);

/// The stable names of a step error's cause (`StepError.kind`).
pub mod kind {
    pub const NON_FINITE_INPUT: &str = "non-finite-input";
    pub const NON_FINITE_APPLIED: &str = "non-finite-applied";
    pub const INVALID_DT: &str = "invalid-dt";
    pub const NO_DIFFERENTIATOR: &str = "no-differentiator";
    pub const OVERFLOW: &str = "overflow";
    /// A vector of the wrong length (`z`, a bank's arrays).
    pub const WRONG_LENGTH: &str = "wrong-length";
    /// An input that is not a float vector.
    pub const WRONG_TYPE: &str = "wrong-type";
}

/// A `ConfigError` to raise: the message and its fields.
#[derive(Clone, Debug)]
pub struct ConfigFault {
    message: String,
    parameter: Option<String>,
    stage: Option<usize>,
    rule: Option<String>,
}

impl ConfigFault {
    /// `parameter` broke `rule`; the message is `"{parameter} {rule}"`.
    pub fn new(parameter: &str, rule: impl Into<String>) -> Self {
        let rule = rule.into();
        Self {
            message: format!("{parameter} {rule}"),
            parameter: Some(parameter.to_owned()),
            stage: None,
            rule: Some(rule),
        }
    }

    /// Appends `" (got {got})"` to the message.
    pub fn got(mut self, got: impl Display) -> Self {
        self.message = format!("{} (got {got})", self.message);
        self
    }

    /// Another message for the same fields.
    pub fn message(mut self, message: impl Into<String>) -> Self {
        self.message = message.into();
        self
    }

    /// famcc-core's error: its parameter, stage (from 1) and rule.
    pub fn core(e: famcc_core::ConfigError) -> Self {
        Self {
            message: e.to_string(),
            parameter: Some(e.parameter.to_owned()),
            stage: e.stage.map(|i| i + 1),
            rule: Some(e.rule.to_owned()),
        }
    }
}

impl From<ConfigFault> for PyErr {
    fn from(f: ConfigFault) -> PyErr {
        PyErr::new::<ConfigError, _>(f)
    }
}

impl PyErrArguments for ConfigFault {
    /// The exception instance itself (raised as is).
    fn arguments(self, py: Python<'_>) -> Py<PyAny> {
        let fill = |kw: &Bound<'_, PyDict>| -> PyResult<()> {
            kw.set_item("parameter", self.parameter.as_deref())?;
            kw.set_item("stage", self.stage)?;
            kw.set_item("rule", self.rule.as_deref())
        };
        instance(py, &py.get_type::<ConfigError>(), &self.message, fill)
    }
}

/// A `StepError` to raise: the message, the kind and the input at fault.
#[derive(Clone, Debug)]
pub struct StepFault {
    message: String,
    kind: &'static str,
    parameter: Option<&'static str>,
}

impl StepFault {
    /// A step error of `kind` (see [`kind`]) about `parameter`.
    pub fn new(kind: &'static str, parameter: Option<&'static str>, message: impl Into<String>) -> Self {
        Self {
            message: message.into(),
            kind,
            parameter,
        }
    }
}

impl From<StepFault> for PyErr {
    fn from(f: StepFault) -> PyErr {
        PyErr::new::<StepError, _>(f)
    }
}

impl PyErrArguments for StepFault {
    fn arguments(self, py: Python<'_>) -> Py<PyAny> {
        let fill = |kw: &Bound<'_, PyDict>| -> PyResult<()> {
            kw.set_item("kind", self.kind)?;
            kw.set_item("parameter", self.parameter)
        };
        instance(py, &py.get_type::<StepError>(), &self.message, fill)
    }
}

/// `cls(message, **fields)` (the message alone if that fails, which the
/// class's `__init__` cannot for these fields).
fn instance<'py>(
    py: Python<'py>,
    cls: &Bound<'py, PyType>,
    message: &str,
    fill: impl FnOnce(&Bound<'py, PyDict>) -> PyResult<()>,
) -> Py<PyAny> {
    let build = || -> PyResult<Py<PyAny>> {
        let kw = PyDict::new(py);
        fill(&kw)?;
        Ok(cls.call((message,), Some(&kw))?.unbind())
    };
    build().unwrap_or_else(|_| PyString::new(py, message).into_any().unbind())
}

/// famcc-core's configuration error as a Python `ConfigError`.
pub fn config_err(e: famcc_core::ConfigError) -> PyErr {
    ConfigFault::core(e).into()
}

/// famcc-core's configuration error, the message followed by `(got {got})`.
pub fn config_err_got(e: famcc_core::ConfigError, got: impl Display) -> PyErr {
    let f = ConfigFault::core(e);
    let message = format!("{} (got {got})", f.message);
    f.message(message).into()
}

/// famcc-core's step error as a Python `StepError`; `input` names the
/// measured input of the call (`"e"`, `"z"`, ...).
pub fn step_err(e: famcc_core::StepError, input: &'static str) -> PyErr {
    use famcc_core::StepError as E;
    let (k, parameter) = match e {
        E::NonFiniteInput => (kind::NON_FINITE_INPUT, Some(input)),
        E::NonFiniteApplied => (kind::NON_FINITE_APPLIED, Some("applied")),
        E::InvalidDt => (kind::INVALID_DT, Some("dt")),
        E::NoDifferentiator => (kind::NO_DIFFERENTIATOR, Some("differentiator")),
        E::Overflow => (kind::OVERFLOW, None),
    };
    StepFault::new(k, parameter, e.to_string()).into()
}
