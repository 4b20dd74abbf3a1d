//! Numeric arguments of the constructors: a real number or an integer, never
//! a bool (`order=True` is a mistake, not 1), and a `TypeError` whose message
//! names the argument.
//!
//! pyo3 attributes an argument's extraction error with a note ("while
//! processing 'dt'"); the errors raised here are the binding's
//! `ArgumentTypeError`s (crate::errors), which move that name into the
//! message itself: `argument 'dt': must be a real number, not bool`.

use crate::errors::ArgumentTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyString};
use pyo3::Borrowed;

/// A real-number argument (a float or an int, not a bool).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Num(pub f64);

/// An integer argument (not a bool).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Int(pub i64);

/// A text argument (a `str`).
#[derive(Clone, Debug, PartialEq)]
pub struct Text(pub String);

/// The error for a wrong argument type, an `ArgumentTypeError`.
fn type_error(what: &str, obj: Borrowed<'_, '_, PyAny>) -> PyErr {
    let got = obj
        .get_type()
        .name()
        .map(|n| n.to_string())
        .unwrap_or_else(|_| String::from("?"));
    ArgumentTypeError::new_err(format!("must be {what}, not {got}"))
}

/// `FromPyObject` for a newtype over a number: bool is refused, as is
/// anything that does not extract to the inner type.
macro_rules! number_newtype {
    ($name:ident, $inner:ty, $what:literal) => {
        impl<'a, 'py> FromPyObject<'a, 'py> for $name {
            type Error = PyErr;
            fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
                if obj.is_instance_of::<PyBool>() {
                    return Err(type_error($what, obj));
                }
                obj.extract::<$inner>()
                    .map($name)
                    .map_err(|_| type_error($what, obj))
            }
        }
    };
}

number_newtype!(Num, f64, "a real number");
number_newtype!(Int, i64, "an integer");

impl<'a, 'py> FromPyObject<'a, 'py> for Text {
    type Error = PyErr;
    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        match obj.cast::<PyString>() {
            Ok(s) => Ok(Text(s.to_string())),
            Err(_) => Err(type_error("a str", obj)),
        }
    }
}
