//! The run-time health warning of `famcc.Controller`: the core's
//! `Controller::health` finding (docs/design.md §3.8) as a
//! `famcc.DesignWarning`.

use crate::controller::PyController;
use crate::errors::DesignWarning;
use pyo3::prelude::*;
use std::ffi::CString;

/// Emits `famcc.DesignWarning` (the binding's own class, crate::errors).
pub fn design_warning(py: Python<'_>, message: &str) -> PyResult<()> {
    let text = CString::new(message.replace('\0', " ")).unwrap_or_default();
    PyErr::warn(py, &py.get_type::<DesignWarning>(), &text, 2)
}

impl PyController {
    /// After a successful step: the core's health finding, as a warning
    /// once per controller (nothing to check unless the applied input is
    /// known).
    #[inline]
    pub(crate) fn check_health(&mut self, applied: Option<f64>) -> PyResult<()> {
        if self.health_warned || (applied.is_none() && self.spec.output_limits.is_none()) {
            return Ok(());
        }
        let Some(finding) = self.core.health() else {
            return Ok(());
        };
        self.health_warned = true;
        Python::attach(|py| design_warning(py, &finding.to_string()))
    }
}
