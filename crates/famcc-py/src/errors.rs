//! Python exception types: `ValueError` subclasses whose message names the
//! parameter (configuration) or the reason (step).

use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::PyErr;

create_exception!(
    _core,
    ConfigError,
    PyValueError,
    "An invalid configuration value; the message names the parameter and the rule."
);
create_exception!(
    _core,
    StepError,
    PyValueError,
    "A step that could not be taken (non-finite input, bad ``dt``, overflow).\n\nFor a non-finite \
     ``e``, ``applied`` or ``dt`` the state is unchanged; an overflow on a valid sample after the first \
     step consumes the sample (hold the previous output)."
);

/// famcc-core's configuration error as a Python `ConfigError`.
pub fn config_err(e: famcc_core::ConfigError) -> PyErr {
    ConfigError::new_err(e.to_string())
}

/// famcc-core's step error as a Python `StepError`.
pub fn step_err(e: famcc_core::StepError) -> PyErr {
    StepError::new_err(e.to_string())
}
