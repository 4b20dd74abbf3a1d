//! The paper's designs and plants (famcc-paper) for the Python scenarios
//! and plants: `famcc.scenarios` and `famcc.plants` hold no numbers of
//! their own.

use crate::errors::ConfigError;
use crate::names::{DType, VARIANT};
use crate::spec::Spec;
use famcc_paper::designs::{self, Design, Example, SAMPLE_PERIOD};
use famcc_paper::plants::{self, Clock, Plant, SecondOrder, ThirdOrder};
use famcc_paper::Variant;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

fn example(n: u32) -> PyResult<Example> {
    Example::from_number(n)
        .ok_or_else(|| ConfigError::new_err(format!("example must be 1, 2 or 3 (got {n})")))
}

fn variant(name: &str) -> PyResult<Variant> {
    VARIANT.parse(name, "variant")
}

/// The keyword arguments of `famcc.Controller` (without `dt`) for the
/// paper's example 1, 2 or 3 in variant "paper" or "code".
#[pyfunction]
pub fn paper_design<'py>(py: Python<'py>, example: u32, variant: &str) -> PyResult<Bound<'py, PyDict>> {
    // The designs do not depend on the sample period; they are read from the
    // one the scenarios run at.
    let design = designs::design::<f64>(self::example(example)?, self::variant(variant)?, SAMPLE_PERIOD)
        .map_err(crate::errors::config_err)?;
    let spec = match &design {
        Design::Order2(c) => Spec::from_config(c, DType::F64),
        Design::Order3(c) => Spec::from_config(c, DType::F64),
    };
    spec.design_kwargs(py)
}

/// The settling bound `T'` (s) of the example's corollary.
#[pyfunction]
pub fn paper_corollary_bound(example: u32) -> PyResult<f64> {
    Ok(designs::corollary_bound::<f64>(self::example(example)?))
}

/// The actuator limits `(lo, hi)` of the example's scenario, saturated or not.
#[pyfunction]
pub fn paper_input_limits(example: u32, saturated: bool) -> PyResult<(f64, f64)> {
    Ok(designs::input_limits::<f64>(self::example(example)?, saturated))
}

#[derive(Clone, Copy, Debug)]
enum Which {
    Second(SecondOrder),
    Third(ThirdOrder),
}

/// One of the paper's plants (order 2: examples 1-2, order 3: example 3) in
/// variant "paper" or "code": right-hand side, exact output derivatives,
/// gain and drift.
#[pyclass(frozen, module = "famcc._core")]
pub struct PaperPlant {
    which: Which,
}

fn tuple<'py, const N: usize>(py: Python<'py>, v: [f64; N]) -> PyResult<Bound<'py, PyTuple>> {
    PyTuple::new(py, v)
}

#[pymethods]
impl PaperPlant {
    /// `gain` scales the input gain, `amp` is the disturbance amplitude (the
    /// variant's when None) and `x0` the initial state (the variant's when None).
    #[new]
    #[pyo3(signature = (order, variant, gain = 1.0, amp = None, x0 = None))]
    fn new(order: usize, variant: &str, gain: f64, amp: Option<f64>, x0: Option<Vec<f64>>) -> PyResult<Self> {
        let v = self::variant(variant)?;
        if !(gain.is_finite() && gain > 0.0) {
            return Err(ConfigError::new_err(format!(
                "gain must be finite and > 0 (got {gain})"
            )));
        }
        if let Some(a) = amp {
            if !a.is_finite() {
                return Err(ConfigError::new_err(format!("amp must be finite (got {a})")));
            }
        }
        let bad_x0 = |n: usize| ConfigError::new_err(format!("x0 must hold {n} finite numbers"));
        let which = match order {
            2 => {
                let mut p = SecondOrder::new(v);
                p.gain = gain;
                p.amp = amp.unwrap_or(p.amp);
                if let Some(x) = x0 {
                    p.x0 = <[f64; 2]>::try_from(x.as_slice()).map_err(|_| bad_x0(2))?;
                }
                if p.x0.iter().any(|v| !v.is_finite()) {
                    return Err(bad_x0(2));
                }
                Which::Second(p)
            }
            3 => {
                let mut p = ThirdOrder::new(v);
                p.gain = gain;
                p.amp = amp.unwrap_or(p.amp);
                if let Some(x) = x0 {
                    p.x0 = <[f64; 3]>::try_from(x.as_slice()).map_err(|_| bad_x0(3))?;
                }
                if p.x0.iter().any(|v| !v.is_finite()) {
                    return Err(bad_x0(3));
                }
                Which::Third(p)
            }
            n => return Err(ConfigError::new_err(format!("order must be 2 or 3 (got {n})"))),
        };
        Ok(Self { which })
    }

    /// The initial state.
    #[getter]
    fn x0<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        match self.which {
            Which::Second(p) => tuple(py, p.x0()),
            Which::Third(p) => tuple(py, p.x0()),
        }
    }

    /// `dx/dt` at time `t` (s), state `x` and input `u`, as a tuple.
    fn rhs<'py>(
        &self,
        py: Python<'py>,
        t: f64,
        x: &Bound<'py, PyAny>,
        u: f64,
    ) -> PyResult<Bound<'py, PyTuple>> {
        let c = Clock::at(t);
        match self.which {
            Which::Second(p) => tuple(py, p.rhs(&c, &x.extract()?, u)),
            Which::Third(p) => tuple(py, p.rhs(&c, &x.extract()?, u)),
        }
    }

    /// `(y, y', ..., y^(n-1))` at time `t` and state `x`, exactly.
    fn output_derivatives<'py>(
        &self,
        py: Python<'py>,
        t: f64,
        x: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyTuple>> {
        match self.which {
            Which::Second(p) => tuple(py, plants::output_derivatives(&p, t, &x.extract()?)),
            Which::Third(p) => tuple(py, plants::output_derivatives(&p, t, &x.extract()?)),
        }
    }

    /// `(G_a, F_a)` with `y^(n) = G_a u + F_a` at time `t` and state `x`.
    fn gain_and_drift(&self, t: f64, x: &Bound<'_, PyAny>) -> PyResult<(f64, f64)> {
        Ok(match self.which {
            Which::Second(p) => plants::gain_and_drift(&p, t, &x.extract()?),
            Which::Third(p) => plants::gain_and_drift(&p, t, &x.extract()?),
        })
    }
}
