//! The private `famcc._core` extension module: a thin pyo3 layer over
//! famcc-core. It holds no control logic.

use pyo3::prelude::*;

/// The famcc-core version this extension was built from.
#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
