//! A specification as the constructor's keyword arguments (`config()`,
//! `repr`, pickling, the paper's designs), and unpickling.

use crate::controller::PyController;
use crate::errors::ConfigFault;
use crate::names::{constraint_name, CONSTRAINT, DIRECTION, DTYPE, GAMMA, LATCH, TRANSITION};
use crate::spec::{RhoE, Spec};
use famcc_core::{Constraint, Direction};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

/// The keyword arguments of `config()` (and so of `repr` and pickling), in order.
const CONFIG_KEYS: [&str; 16] = [
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
];

/// The keyword arguments of a design (everything but `dt` and the options
/// the paper's designs leave at their defaults), in order.
const DESIGN_KEYS: [&str; 12] = [
    "order",
    "feedback",
    "skew",
    "constraint",
    "eps",
    "k_u",
    "differentiator",
    "settle_time",
    "k0",
    "rho_e",
    "gamma",
    "latch",
];

impl Spec {
    /// The constructor's keyword arguments for this configuration: a list
    /// with one law and one skew (or None) per stage.
    pub fn kwargs<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for key in CONFIG_KEYS {
            d.set_item(key, self.item(py, key, false)?)?;
        }
        // The options beyond the paper, only when used (so the paper's
        // configurations keep their keyword arguments and repr).
        if self.integral {
            d.set_item("integral", true)?;
        }
        if let Some(l) = self.output_limits {
            d.set_item("output_limits", l)?;
        }
        if let Some(r) = self.rate_limit {
            d.set_item("rate_limit", r)?;
        }
        if let Some(u) = self.initial_output {
            d.set_item("initial_output", u)?;
        }
        if let Some(o) = &self.observer {
            d.set_item("observer", o.clone())?;
        }
        if let Some(c) = self.cancellation_limit {
            d.set_item("cancellation_limit", c)?;
        }
        if self.direction != Direction::Positive {
            d.set_item("direction", DIRECTION.name(self.direction))?;
        }
        Ok(d)
    }

    /// `Class(key=value, ...)` of [`Spec::kwargs`].
    pub fn repr(&self, py: Python<'_>, class: &str) -> PyResult<String> {
        let mut parts = Vec::new();
        for (k, v) in self.kwargs(py)?.iter() {
            parts.push(format!("{}={}", k.str()?, v.repr()?));
        }
        Ok(format!("{class}({})", parts.join(", ")))
    }

    /// The keyword arguments of the design alone (no `dt`): the law and the
    /// skew as single objects at order 2, no `skew` when there is none.
    pub fn design_kwargs<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for key in DESIGN_KEYS {
            if key == "skew" && self.stages.iter().all(|(_, s)| s.is_none()) {
                continue;
            }
            d.set_item(key, self.item(py, key, self.stages.len() == 1)?)?;
        }
        Ok(d)
    }

    /// The value of one keyword argument; per-stage values as one object
    /// when `single`.
    fn item<'py>(&self, py: Python<'py>, key: &str, single: bool) -> PyResult<Bound<'py, PyAny>> {
        let per_stage = |objects: Vec<Bound<'py, PyAny>>| -> PyResult<Bound<'py, PyAny>> {
            match (single, objects.as_slice()) {
                (true, [one]) => Ok(one.clone()),
                _ => Ok(PyList::new(py, objects)?.into_any()),
            }
        };
        Ok(match key {
            "order" => self.order.into_pyobject(py)?.into_any(),
            "dt" => self.dt.into_pyobject(py)?.into_any(),
            "feedback" => per_stage(
                self.stages
                    .iter()
                    .map(|(l, _)| l.to_object(py))
                    .collect::<PyResult<_>>()?,
            )?,
            "skew" => per_stage(
                self.stages
                    .iter()
                    .map(|(_, s)| s.map_or_else(|| Ok(py.None().into_bound(py)), |s| s.to_object(py)))
                    .collect::<PyResult<_>>()?,
            )?,
            "constraint" => CONSTRAINT
                .name(constraint_name(&self.constraint))
                .into_pyobject(py)?
                .into_any(),
            "eps" => match self.constraint {
                Constraint::Oblique { eps_x, eps_y } => (eps_x, eps_y).into_pyobject(py)?.into_any(),
                Constraint::Lateral { eps } | Constraint::Longitudinal { eps } => {
                    eps.into_pyobject(py)?.into_any()
                }
            },
            "settle_time" => self.settle_time.into_pyobject(py)?.into_any(),
            "k0" => self.k0.into_pyobject(py)?.into_any(),
            "k_u" => self.k_u.into_pyobject(py)?.into_any(),
            "gamma" => GAMMA.name(self.gamma).into_pyobject(py)?.into_any(),
            "rho_e" => match self.rho_e {
                RhoE::Given(r) => r.into_pyobject(py)?.into_any(),
                RhoE::Default => crate::args::AUTO.into_pyobject(py)?.into_any(),
            },
            "differentiator" => match &self.differentiator {
                Some(h) => h.clone().into_pyobject(py)?.into_any(),
                None => py.None().into_bound(py),
            },
            "latch" => LATCH.name(self.latch).into_pyobject(py)?.into_any(),
            "transition" => TRANSITION.name(self.transition).into_pyobject(py)?.into_any(),
            "initial_derivatives" => self.initial_derivatives.clone().into_pyobject(py)?.into_any(),
            "dtype" => DTYPE.name(self.dtype).into_pyobject(py)?.into_any(),
            other => return Err(ConfigFault::new(other, "is no keyword argument").into()),
        })
    }
}

/// Unpickling: rebuild from keyword arguments and continue from the state.
#[pyfunction]
pub fn _controller_from_state<'py>(
    py: Python<'py>,
    kwargs: &Bound<'py, PyDict>,
    state: Vec<f64>,
) -> PyResult<Bound<'py, PyAny>> {
    let cls = py.get_type::<PyController>();
    let kw = kwargs.copy()?;
    let order = kw
        .get_item("order")?
        .ok_or_else(|| ConfigFault::new("order", "missing"))?;
    let dt = kw
        .get_item("dt")?
        .ok_or_else(|| ConfigFault::new("dt", "missing"))?;
    kw.del_item("order")?;
    kw.del_item("dt")?;
    let obj = cls.call((order, dt), Some(&kw))?;
    let mut c: PyRefMut<'_, PyController> = obj.extract()?;
    c.set_state_vec(&state)?;
    drop(c);
    Ok(obj)
}
