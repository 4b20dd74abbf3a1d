//! The run-time health warning of `famcc.Controller` (docs/design.md §3.8):
//! bounds expanded while the actuator had headroom, and `famcc.DesignWarning`.

use crate::controller::PyController;
use pyo3::exceptions::PyUserWarning;
use pyo3::prelude::*;
use std::ffi::CString;

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
    /// After a successful step: the health warning, once, when the bounds
    /// expanded while the actuator had headroom (only counted when the
    /// applied input is known, so nothing to check otherwise).
    #[inline]
    pub(crate) fn check_health(&mut self, applied: Option<f64>) -> PyResult<()> {
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
