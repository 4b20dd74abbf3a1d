//! The paper's designs and plants (famcc-paper) for the Python scenarios
//! and plants: `famcc.scenarios` and `famcc.plants` hold no numbers of
//! their own.

use crate::errors::ConfigFault;
use crate::names::{DType, VARIANT};
use crate::spec::Spec;
use famcc_paper::designs::{self, Design, Example, SAMPLE_PERIOD};
use famcc_paper::plants::{self, Clock, Plant, SecondOrder, ThirdOrder};
use famcc_paper::Variant;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

fn example(n: u32) -> PyResult<Example> {
    Example::from_number(n).ok_or_else(|| ConfigFault::new("example", "must be 1, 2 or 3").got(n).into())
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

/// The plant's nominal input gain `G0` of the example (the observer's `b0`).
#[pyfunction]
pub fn paper_nominal_gain(example: u32) -> PyResult<f64> {
    Ok(designs::nominal_gain::<f64>(self::example(example)?))
}

#[derive(Clone, Copy, Debug)]
enum Which {
    Second(SecondOrder),
    Third(ThirdOrder),
}

/// One of the paper's plants: order 2 (examples 1-2) or 3 (example 3).
///
/// The second-order plant of eq. (44) (System_sim) or the third-order plant
/// of eq. (68) (System_sim3), in variant 'paper' (as printed) or 'code' (as
/// the authors ran it; docs/errata.md): right-hand side, exact output
/// derivatives, gain and drift. ``famcc.plants`` builds on it.
///
/// Parameters
/// ----------
/// order : int
///     2 or 3.
/// variant : {'paper', 'code'}
///     The paper's printed plant or the authors' code.
/// gain : float, default 1.0
///     Factor on the input gain, dimensionless, finite and ``> 0``.
/// amp : float, default None
///     The disturbance amplitude, in the unit of the state's last entry per
///     s; None: the variant's.
/// x0 : sequence of float, default None
///     The initial state, ``order`` finite entries; None: the variant's.
///
/// Raises
/// ------
/// famcc.ConfigError
///     An order other than 2 or 3, an unknown variant, or a value above out
///     of range.
///
/// Examples
/// --------
/// >>> from famcc import _core
/// >>> plant = _core.PaperPlant(2, "paper")
/// >>> len(plant.x0), len(plant.rhs(0.0, plant.x0, 0.0))
/// (2, 2)
#[pyclass(frozen, module = "famcc._core")]
pub struct PaperPlant {
    which: Which,
}

fn tuple<'py, const N: usize>(py: Python<'py>, v: [f64; N]) -> PyResult<Bound<'py, PyTuple>> {
    PyTuple::new(py, v)
}

#[pymethods]
impl PaperPlant {
    #[new]
    #[pyo3(signature = (order, variant, gain = 1.0, amp = None, x0 = None))]
    fn new(order: usize, variant: &str, gain: f64, amp: Option<f64>, x0: Option<Vec<f64>>) -> PyResult<Self> {
        let v = self::variant(variant)?;
        if !(gain.is_finite() && gain > 0.0) {
            return Err(ConfigFault::new("gain", "must be finite and > 0")
                .got(gain)
                .into());
        }
        if let Some(a) = amp {
            if !a.is_finite() {
                return Err(ConfigFault::new("amp", "must be finite").got(a).into());
            }
        }
        let bad_x0 = |n: usize| PyErr::from(ConfigFault::new("x0", format!("must hold {n} finite numbers")));
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
            n => return Err(ConfigFault::new("order", "must be 2 or 3").got(n).into()),
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

    /// The right-hand side ``dx/dt``.
    ///
    /// Parameters
    /// ----------
    /// t : float
    ///     Time, s.
    /// x : sequence of float
    ///     The state, ``order`` entries.
    /// u : float
    ///     The input (after any saturation), input units.
    ///
    /// Returns
    /// -------
    /// tuple of float
    ///     ``dx/dt``, ``order`` entries.
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

    /// The output and its derivatives, exactly.
    ///
    /// Parameters
    /// ----------
    /// t : float
    ///     Time, s.
    /// x : sequence of float
    ///     The state, ``order`` entries.
    ///
    /// Returns
    /// -------
    /// tuple of float
    ///     ``(y, y', ..., y^(n-1))``.
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

    /// The gain and drift of the fully actuated form (eq. (7) (FAS)).
    ///
    /// Parameters
    /// ----------
    /// t : float
    ///     Time, s.
    /// x : sequence of float
    ///     The state, ``order`` entries.
    ///
    /// Returns
    /// -------
    /// (float, float)
    ///     ``(G_a, F_a)`` with ``y^(n) = G_a u + F_a``.
    fn gain_and_drift(&self, t: f64, x: &Bound<'_, PyAny>) -> PyResult<(f64, f64)> {
        Ok(match self.which {
            Which::Second(p) => plants::gain_and_drift(&p, t, &x.extract()?),
            Which::Third(p) => plants::gain_and_drift(&p, t, &x.extract()?),
        })
    }
}
