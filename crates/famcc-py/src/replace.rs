//! A [`Spec`] from Python values without text: the named fields of an
//! existing spec changed (`Controller.replace`, `ControllerSpec.replace`),
//! and a whole spec from the keyword arguments of `config()` (unpickling a
//! `ControllerSpec`). Each value is parsed as the constructor parses it
//! (crate::args); the values are checked by famcc-core's builder when the
//! spec is built.

use crate::args::{
    check_initial_derivatives, parse_constraint, parse_differentiator, parse_laws, parse_rho_e, parse_skews,
    Args, DiffArg, RhoArg, AUTO,
};
use crate::names::{constraint_name, CONSTRAINT, DIRECTION, DTYPE, GAMMA, LATCH, TRANSITION};
use crate::number::{Int, Num, Text};
use crate::observer::Observer;
use crate::spec::Spec;
use famcc_core::config::{DEFAULT_K0, DEFAULT_SETTLE_TIME};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The fields `replace` cannot change: they set the shape of the
/// configuration (the number of stages, the type of `eps`).
pub const SHAPE_KEYS: [&str; 3] = ["order", "constraint", "integral"];

/// The value of the argument `name`, extracted as the constructor does
/// (a wrong type names the argument, as pyo3's note does).
fn arg<'a, 'py, T>(v: &'a Bound<'py, PyAny>, name: &str) -> PyResult<T>
where
    T: FromPyObject<'a, 'py>,
    T::Error: Into<PyErr>,
{
    v.extract::<T>().map_err(|e| {
        let e: PyErr = e.into();
        let note = format!("while processing '{name}'");
        // The note is a courtesy: if it cannot be added the error stands.
        let _ = e.value(v.py()).call_method1("add_note", (note,));
        e
    })
}

fn num(v: &Bound<'_, PyAny>, name: &str) -> PyResult<f64> {
    arg::<Num>(v, name).map(|n| n.0)
}

fn opt_num(v: &Bound<'_, PyAny>, name: &str) -> PyResult<Option<f64>> {
    arg::<Option<Num>>(v, name).map(|n| n.map(|n| n.0))
}

fn text(v: &Bound<'_, PyAny>, name: &str) -> PyResult<String> {
    arg::<Text>(v, name).map(|t| t.0)
}

fn initial_derivatives(v: &Bound<'_, PyAny>) -> PyResult<Option<Vec<f64>>> {
    arg::<Option<Vec<Num>>>(v, "initial_derivatives").map(|d| d.map(|d| d.into_iter().map(|x| x.0).collect()))
}

fn output_limits(v: &Bound<'_, PyAny>) -> PyResult<Option<(f64, f64)>> {
    arg::<Option<(Num, Num)>>(v, "output_limits").map(|l| l.map(|(lo, hi)| (lo.0, hi.0)))
}

impl Spec {
    /// This configuration with the fields of `overrides` changed (keyword
    /// names of the constructor; not those of [`SHAPE_KEYS`]).
    pub fn replace(&self, overrides: Option<&Bound<'_, PyDict>>) -> PyResult<Spec> {
        let mut s = self.clone();
        if let Some(kw) = overrides {
            for (key, value) in kw.iter() {
                let key: String = key.extract()?;
                s.set(&key, &value)?;
            }
        }
        Ok(s)
    }

    /// Sets the field `key` from a Python value.
    fn set(&mut self, key: &str, v: &Bound<'_, PyAny>) -> PyResult<()> {
        let (order, integral) = (self.order, self.integral);
        match key {
            "dt" => self.dt = num(v, key)?,
            "feedback" => {
                let laws = parse_laws((!v.is_none()).then_some(v), order, integral)?;
                self.stages.iter_mut().zip(laws).for_each(|(st, l)| st.0 = l);
            }
            "skew" => {
                let skews = parse_skews(Some(v), order, integral)?;
                self.stages.iter_mut().zip(skews).for_each(|(st, s)| st.1 = s);
            }
            "eps" => self.constraint = parse_constraint(constraint_name(&self.constraint), v)?,
            "settle_time" => self.settle_time = num(v, key)?,
            "k0" => self.k0 = num(v, key)?,
            "k_u" => self.k_u = num(v, key)?,
            "gamma" => self.gamma = GAMMA.parse(&text(v, key)?, key)?,
            "rho_e" => self.rho_e = parse_rho_e(arg::<Option<RhoArg<'_>>>(v, key)?)?,
            "differentiator" => {
                self.differentiator = parse_differentiator(arg::<Option<DiffArg<'_>>>(v, key)?, order)?
            }
            "latch" => self.latch = LATCH.parse(&text(v, key)?, key)?,
            "transition" => self.transition = TRANSITION.parse(&text(v, key)?, key)?,
            "initial_derivatives" => {
                let d = initial_derivatives(v)?;
                check_initial_derivatives(d.as_deref(), order)?;
                self.initial_derivatives = d;
            }
            "dtype" => self.dtype = DTYPE.parse(&text(v, key)?, key)?,
            "output_limits" => self.output_limits = output_limits(v)?,
            "rate_limit" => self.rate_limit = opt_num(v, key)?,
            "initial_output" => self.initial_output = opt_num(v, key)?,
            "observer" => {
                self.observer = arg::<Option<Bound<'_, Observer>>>(v, key)?.map(|o| o.get().clone())
            }
            "cancellation_limit" => self.cancellation_limit = opt_num(v, key)?,
            "direction" => self.direction = DIRECTION.parse(&text(v, key)?, key)?,
            k if SHAPE_KEYS.contains(&k) => {
                return Err(PyTypeError::new_err(format!(
                    "replace() cannot change '{k}' (it sets the shape of the configuration: \
                     the number of stages or the type of eps); build a new famcc.Controller"
                )))
            }
            other => {
                return Err(PyTypeError::new_err(format!(
                    "replace() got an unexpected keyword argument '{other}'"
                )))
            }
        }
        Ok(())
    }
}

/// The keyword arguments `spec_from_kwargs` knows.
const KEYS: [&str; 23] = [
    "order",
    "dt",
    "feedback",
    "skew",
    "constraint",
    "eps",
    "settle_time",
    "k0",
    "k_u",
    "gamma",
    "rho_e",
    "differentiator",
    "latch",
    "transition",
    "initial_derivatives",
    "dtype",
    "integral",
    "output_limits",
    "rate_limit",
    "initial_output",
    "observer",
    "cancellation_limit",
    "direction",
];

/// The spec of the constructor's keyword arguments (as `config()` gives
/// them), parsed as the constructor parses them; a missing argument takes
/// the constructor's default.
pub fn spec_from_kwargs(kw: &Bound<'_, PyDict>) -> PyResult<Spec> {
    for key in kw.keys() {
        let key: String = key.extract()?;
        if !KEYS.contains(&key.as_str()) {
            return Err(PyTypeError::new_err(format!(
                "ControllerSpec got an unexpected keyword argument '{key}'"
            )));
        }
    }
    let get = |k: &str| -> PyResult<Option<Bound<'_, PyAny>>> { kw.get_item(k) };
    let need = |k: &str| -> PyResult<Bound<'_, PyAny>> {
        get(k)?.ok_or_else(|| PyTypeError::new_err(format!("ControllerSpec needs the argument '{k}'")))
    };
    let or_num = |k: &str, d: f64| -> PyResult<f64> { get(k)?.map_or(Ok(d), |v| num(&v, k)) };
    let or_text =
        |k: &str, d: &str| -> PyResult<String> { get(k)?.map_or(Ok(d.to_owned()), |v| text(&v, k)) };
    let order = arg::<Int>(&need("order")?, "order")?.0;
    let feedback = get("feedback")?.filter(|v| !v.is_none());
    let skew = get("skew")?.filter(|v| !v.is_none());
    let eps = need("eps")?;
    let rho_e = get("rho_e")?;
    let differentiator = get("differentiator")?;
    let (constraint, gamma, latch, transition, dtype) = (
        or_text("constraint", CONSTRAINT.default_name())?,
        or_text("gamma", GAMMA.default_name())?,
        or_text("latch", LATCH.default_name())?,
        or_text("transition", TRANSITION.default_name())?,
        or_text("dtype", DTYPE.default_name())?,
    );
    let direction = or_text("direction", DIRECTION.default_name())?;
    let opt = |k: &str| -> PyResult<Option<f64>> { get(k)?.map_or(Ok(None), |v| opt_num(&v, k)) };
    Args {
        order,
        dt: num(&need("dt")?, "dt")?,
        feedback: feedback.as_ref(),
        skew: skew.as_ref(),
        constraint: &constraint,
        eps: &eps,
        settle_time: or_num("settle_time", DEFAULT_SETTLE_TIME)?,
        k0: or_num("k0", DEFAULT_K0)?,
        k_u: num(&need("k_u")?, "k_u")?,
        gamma: &gamma,
        rho_e: match &rho_e {
            Some(v) => arg::<Option<RhoArg<'_>>>(v, "rho_e")?,
            None => Some(RhoArg::Name(String::from(AUTO))),
        },
        differentiator: match &differentiator {
            Some(v) => arg::<Option<DiffArg<'_>>>(v, "differentiator")?,
            None => Some(DiffArg::Name(String::from(AUTO))),
        },
        latch: &latch,
        transition: &transition,
        initial_derivatives: get("initial_derivatives")?.map_or(Ok(None), |v| initial_derivatives(&v))?,
        dtype: &dtype,
        integral: get("integral")?.map_or(Ok(false), |v| arg::<bool>(&v, "integral"))?,
        output_limits: get("output_limits")?.map_or(Ok(None), |v| output_limits(&v))?,
        rate_limit: opt("rate_limit")?,
        initial_output: opt("initial_output")?,
        observer: get("observer")?.map_or(Ok(None), |v| {
            arg::<Option<Bound<'_, Observer>>>(&v, "observer").map(|o| o.map(|o| o.get().clone()))
        })?,
        cancellation_limit: opt("cancellation_limit")?,
        direction: &direction,
    }
    .parse()
}
