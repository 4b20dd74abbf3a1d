//! The exception classes' Python methods (`__init__` with the keyword fields,
//! `ArgumentTypeError.add_note`) and their installation on `famcc._core`; the
//! classes and the Rust faults that raise them are in `errors`.

use crate::bind::set_method;
use crate::errors::{ArgumentTypeError, ConfigError, DesignWarning, FamccWarning, StepError};
use pyo3::exceptions::{PyBaseException, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyInt, PyString, PyTuple};

/// Adds the classes to the module and gives the exceptions their methods.
pub fn install(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    let config = py.get_type::<ConfigError>();
    for name in ["parameter", "stage", "rule"] {
        config.setattr(name, py.None())?;
    }
    set_method(
        &config,
        "__init__",
        config_init,
        "The message, then the fields (keyword-only).",
    )?;
    let step = py.get_type::<StepError>();
    for name in ["kind", "parameter"] {
        step.setattr(name, py.None())?;
    }
    set_method(
        &step,
        "__init__",
        step_init,
        "The message, then the fields (keyword-only).",
    )?;
    let argument = py.get_type::<ArgumentTypeError>();
    set_method(&argument, "add_note", argument_add_note, ADD_NOTE_DOC)?;
    m.add("ConfigError", config)?;
    m.add("StepError", step)?;
    m.add("FamccWarning", py.get_type::<FamccWarning>())?;
    m.add("DesignWarning", py.get_type::<DesignWarning>())?;
    m.add("ArgumentTypeError", argument)?;
    Ok(())
}

/// A keyword field of an exception: its name, its check, and what the check wants.
type Field = (&'static str, fn(&Bound<'_, PyAny>) -> bool, &'static str);

/// `ValueError.__init__(obj, *args)`, then the keyword fields `names` (each
/// checked by `check`) as attributes.
fn init_fields(
    obj: &Bound<'_, PyAny>,
    args: &Bound<'_, PyTuple>,
    kwargs: Option<&Bound<'_, PyDict>>,
    names: &[Field],
) -> PyResult<Py<PyAny>> {
    let py = obj.py();
    let cls = obj.get_type().name()?.to_string();
    let mut values: Vec<Bound<'_, PyAny>> = names.iter().map(|_| py.None().into_bound(py)).collect();
    if let Some(kw) = kwargs {
        for (key, value) in kw.iter() {
            let key: String = key.extract()?;
            let found = names
                .iter()
                .zip(values.iter_mut())
                .find(|((n, _, _), _)| *n == key);
            let Some(((_, ok, what), slot)) = found else {
                return Err(PyTypeError::new_err(format!(
                    "{cls}() got an unexpected keyword argument '{key}'"
                )));
            };
            if !value.is_none() && !ok(&value) {
                return Err(PyTypeError::new_err(format!(
                    "{cls}() argument '{key}' must be {what} or None, not {}",
                    value.get_type().name()?
                )));
            }
            *slot = value;
        }
    }
    let init = py.get_type::<PyValueError>().getattr("__init__")?;
    let mut full = vec![obj.clone()];
    full.extend(args.iter());
    init.call1(PyTuple::new(py, full)?)?;
    for ((name, _, _), value) in names.iter().zip(values) {
        obj.setattr(*name, value)?;
    }
    Ok(py.None())
}

fn is_str(v: &Bound<'_, PyAny>) -> bool {
    v.is_instance_of::<PyString>()
}

/// An int >= 1 (not a bool).
fn is_stage(v: &Bound<'_, PyAny>) -> bool {
    v.is_instance_of::<PyInt>() && !v.is_instance_of::<PyBool>() && v.extract::<usize>().is_ok_and(|s| s >= 1)
}

fn config_init(
    obj: &Bound<'_, PyAny>,
    args: &Bound<'_, PyTuple>,
    kwargs: Option<&Bound<'_, PyDict>>,
) -> PyResult<Py<PyAny>> {
    init_fields(
        obj,
        args,
        kwargs,
        &[
            ("parameter", is_str, "a str"),
            ("stage", is_stage, "an int >= 1"),
            ("rule", is_str, "a str"),
        ],
    )
}

fn step_init(
    obj: &Bound<'_, PyAny>,
    args: &Bound<'_, PyTuple>,
    kwargs: Option<&Bound<'_, PyDict>>,
) -> PyResult<Py<PyAny>> {
    init_fields(
        obj,
        args,
        kwargs,
        &[("kind", is_str, "a str"), ("parameter", is_str, "a str")],
    )
}

const ADD_NOTE_DOC: &str = "Adds a note; the note ``while processing 'name'`` becomes the message's \
     prefix ``argument 'name': `` instead.";

/// pyo3 attributes an argument's extraction error with the note "while
/// processing 'dt'"; `ArgumentTypeError.add_note` moves that name into the
/// message (`argument 'dt': must be ...`). Other notes stay notes.
fn argument_add_note(
    obj: &Bound<'_, PyAny>,
    args: &Bound<'_, PyTuple>,
    kwargs: Option<&Bound<'_, PyDict>>,
) -> PyResult<Py<PyAny>> {
    const PREFIX: &str = "while processing '";
    let py = obj.py();
    let note: Option<String> = match (args.len(), kwargs.map_or(0, |k| k.len())) {
        (1, 0) => args.get_item(0)?.extract().ok(),
        _ => None,
    };
    let current: Bound<'_, PyTuple> = obj.getattr("args")?.cast_into()?;
    if let Some(name) = note
        .as_deref()
        .and_then(|n| n.strip_prefix(PREFIX))
        .and_then(|n| n.strip_suffix('\''))
    {
        if current.len() == 1 {
            let message = format!("argument '{name}': {}", current.get_item(0)?.str()?);
            obj.setattr("args", PyTuple::new(py, [message])?)?;
            return Ok(py.None());
        }
    }
    let add_note = py.get_type::<PyBaseException>().getattr("add_note")?;
    let mut full = vec![obj.clone()];
    full.extend(args.iter());
    Ok(add_note.call(PyTuple::new(py, full)?, kwargs)?.unbind())
}
