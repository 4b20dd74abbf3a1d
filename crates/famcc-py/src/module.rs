//! The module `famcc._core` as the binding keeps it: pickling names its
//! functions (`__reduce__` of controllers and specs).

use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;

/// The module `famcc._core`, kept at its initialization (pickling names
/// its functions).
static MODULE: PyOnceLock<Py<PyModule>> = PyOnceLock::new();

/// Keeps the module for [`module_function`].
pub fn remember_module(m: &Bound<'_, PyModule>) {
    let _ = MODULE.set(m.py(), m.clone().unbind());
}

/// The function `name` of `famcc._core` (for `__reduce__`).
pub fn module_function<'py>(py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
    match MODULE.get(py) {
        Some(m) => m.bind(py).getattr(name),
        None => py.import("famcc._core")?.getattr(name),
    }
}
