//! The run-time health warning of `famcc.Controller`: the core's
//! `Controller::health` finding (docs/design.md §3.8) as a
//! `famcc.DesignWarning`.

use crate::controller::PyController;
use pyo3::exceptions::PyUserWarning;
use pyo3::prelude::*;
use std::ffi::CString;

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
