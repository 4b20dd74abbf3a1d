//! Rust functions as methods of the exception classes of [`crate::errors`].
//!
//! Those classes are made by `type()` (pyo3's `create_exception!`, the only
//! way to subclass `ValueError` under the abi3-py311 limited API), so their
//! methods are set on the class afterwards. A plain built-in function does
//! not bind `self`; [`Method`] is a descriptor that does, like a Python
//! function in a class body.

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple, PyType};

/// A method's body: the instance, the positional and the keyword arguments.
pub type MethodFn =
    for<'py> fn(&Bound<'py, PyAny>, &Bound<'py, PyTuple>, Option<&Bound<'py, PyDict>>) -> PyResult<Py<PyAny>>;

/// A method of a class made at run time (binds the instance on access).
#[pyclass(frozen, module = "famcc._core", name = "_Method")]
pub struct Method {
    f: MethodFn,
    /// The method's docstring.
    #[pyo3(get, name = "__doc__")]
    doc: &'static str,
}

/// A [`Method`] bound to an instance.
#[pyclass(frozen, module = "famcc._core", name = "_BoundMethod")]
pub struct BoundMethod {
    f: MethodFn,
    obj: Py<PyAny>,
}

#[pymethods]
impl Method {
    /// On an instance, the method bound to it; on the class, the method itself.
    fn __get__(
        slf: &Bound<'_, Self>,
        obj: Option<&Bound<'_, PyAny>>,
        owner: Option<&Bound<'_, PyType>>,
    ) -> PyResult<Py<PyAny>> {
        let _ = owner;
        match obj {
            Some(o) if !o.is_none() => {
                let bound = BoundMethod {
                    f: slf.get().f,
                    obj: o.clone().unbind(),
                };
                Ok(Bound::new(slf.py(), bound)?.into_any().unbind())
            }
            _ => Ok(slf.clone().into_any().unbind()),
        }
    }

    /// Called on the class: the first argument is the instance.
    #[pyo3(signature = (obj, *args, **kwargs))]
    fn __call__(
        &self,
        obj: &Bound<'_, PyAny>,
        args: &Bound<'_, PyTuple>,
        kwargs: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Py<PyAny>> {
        (self.f)(obj, args, kwargs)
    }
}

#[pymethods]
impl BoundMethod {
    #[pyo3(signature = (*args, **kwargs))]
    fn __call__(
        &self,
        py: Python<'_>,
        args: &Bound<'_, PyTuple>,
        kwargs: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Py<PyAny>> {
        (self.f)(self.obj.bind(py), args, kwargs)
    }
}

/// Sets `f` as the method `name` of the class `cls`, with the docstring `doc`.
pub fn set_method(cls: &Bound<'_, PyType>, name: &str, f: MethodFn, doc: &'static str) -> PyResult<()> {
    cls.setattr(name, Bound::new(cls.py(), Method { f, doc })?)
}
