//! Element-wise evaluation on a float or an array-like.

use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray1};
use pyo3::prelude::*;

/// Evaluates `f` on a float (returns a float) or on an array-like (returns
/// a float64 array of the same length).
pub fn map_float_or_array<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    f: impl Fn(f64) -> f64,
) -> PyResult<Bound<'py, PyAny>> {
    if let Ok(v) = x.extract::<f64>() {
        return Ok(f(v).into_pyobject(py)?.into_any());
    }
    let np = py.import("numpy")?;
    let arr = np.call_method1("asarray", (x, "float64"))?;
    let flat: PyReadonlyArray1<f64> = arr.call_method0("ravel")?.extract()?;
    let out: Vec<f64> = flat.as_array().iter().map(|v| f(*v)).collect();
    let res = PyArray1::from_vec(py, out);
    Ok(res
        .reshape(arr.getattr("shape")?.extract::<Vec<usize>>()?)?
        .into_any())
}
