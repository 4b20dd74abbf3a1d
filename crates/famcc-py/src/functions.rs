//! Building blocks as Python functions: transitions, the envelope, skewed
//! laws, the iterative manifold, the corollaries' settling-time bounds.

use crate::args::per_stage;
use crate::array::map_float_or_array;
use crate::errors::{config_err, ConfigFault};
use crate::laws::Law;
use crate::names::TRANSITION;
use crate::orders::to_array;
use crate::orders::with_order;
use crate::skews::SkewSpec;
use famcc_core::config::check_order;
use famcc_core::{bounds, manifold as core_manifold, transition, Envelope, Feedback, SkewedLaw};
use numpy::PyArray1;
use pyo3::prelude::*;

/// Single-ended transition T(z) (eq. (1), trnsT) on a float or an array.
#[pyfunction]
pub fn transition_t<'py>(py: Python<'py>, z: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
    map_float_or_array(py, z, transition::single_ended)
}

/// Double-ended transition S(z) (eq. (2) (trnsS) or an alternative `kind`).
#[pyfunction]
#[pyo3(signature = (z, kind = TRANSITION.default_name()))]
pub fn transition_s<'py>(py: Python<'py>, z: &Bound<'py, PyAny>, kind: &str) -> PyResult<Bound<'py, PyAny>> {
    let k = TRANSITION.parse(kind, "kind")?;
    map_float_or_array(py, z, |v| k.double_ended(v))
}

/// Interval transition U(z) = S(|z|) (eq. (3) (trnsU)).
#[pyfunction]
#[pyo3(signature = (z, kind = TRANSITION.default_name()))]
pub fn transition_u<'py>(py: Python<'py>, z: &Bound<'py, PyAny>, kind: &str) -> PyResult<Bound<'py, PyAny>> {
    let k = TRANSITION.parse(kind, "kind")?;
    map_float_or_array(py, z, |v| k.interval(v))
}

/// The prescribed performance function rho(rho0, eps, settle_time) at t (eq. (4) (rho)).
#[pyfunction]
pub fn rho<'py>(
    py: Python<'py>,
    rho0: f64,
    eps: f64,
    settle_time: f64,
    t: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyAny>> {
    let envelope = Envelope::new(rho0, eps, settle_time).map_err(config_err)?;
    map_float_or_array(py, t, |t| envelope.at(t))
}

/// A skewed law h_m (eqs. (14) (SSMD), (15) (NSMD)), callable on floats and arrays.
///
/// Built by :func:`skewed` from a law and an optional skew; not
/// constructible directly. ``h_m(x)`` is the skewed law, :meth:`inverse`
/// its inverse ``h_v``.
///
/// Examples
/// --------
/// >>> import famcc
/// >>> h = famcc.skewed(famcc.Linear(1.0), famcc.Smooth(eps_s=0.2, eps_z=0.1))
/// >>> y = h(-1.0)
/// >>> round(h.inverse(y), 9)
/// -1.0
/// >>> h.k_p
/// 0.0
#[pyclass(frozen, module = "famcc._core")]
pub struct Skewed {
    law: SkewedLaw<f64>,
    desc: String,
}

#[pymethods]
impl Skewed {
    /// The skewed law's value ``h_m(x)``.
    ///
    /// Parameters
    /// ----------
    /// x : float or array_like
    ///     The stage variable, in its own unit.
    ///
    /// Returns
    /// -------
    /// float or numpy.ndarray
    ///     ``h_m(x)``, unit of ``x`` per s; an array of the shape of ``x``
    ///     for an array.
    fn __call__<'py>(&self, py: Python<'py>, x: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
        let h = self.law;
        map_float_or_array(py, x, |v| h.eval(v))
    }
    /// The inverse ``h_v(y)`` (bounded root search or closed form).
    ///
    /// Parameters
    /// ----------
    /// y : float or array_like
    ///     A value of the law, unit of the stage variable per s.
    ///
    /// Returns
    /// -------
    /// float or numpy.ndarray
    ///     ``x`` with ``h_m(x) = y``; an array of the shape of ``y`` for an
    ///     array.
    fn inverse<'py>(&self, py: Python<'py>, y: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
        let h = self.law;
        map_float_or_array(py, y, |v| famcc_core::constraint::inverse(&h, v))
    }
    /// The NSMD slope k_p (0 for other designs).
    #[getter]
    fn k_p(&self) -> f64 {
        self.law.k_p()
    }
    fn __repr__(&self) -> String {
        self.desc.clone()
    }
}

fn prepare(law: &Bound<'_, PyAny>, skew: Option<&Bound<'_, PyAny>>, name: &str) -> PyResult<SkewedLaw<f64>> {
    let l = Law::extract_named(law, name)?;
    let s = match skew {
        Some(s) => SkewSpec::extract(s)?,
        None => None,
    };
    SkewedLaw::new(l.feedback::<f64>(), s.map(|s| s.skew::<f64>())).map_err(config_err)
}

/// `skewed(law, skew)`: the callable h_m built on `law` with `skew`.
#[pyfunction]
#[pyo3(signature = (law, skew = None))]
pub fn skewed(law: &Bound<'_, PyAny>, skew: Option<&Bound<'_, PyAny>>) -> PyResult<Skewed> {
    let desc = format!(
        "skewed({}, {})",
        law.repr()?,
        skew.map(|s| s.repr().map(|r| r.to_string()))
            .transpose()?
            .unwrap_or_else(|| "None".into())
    );
    Ok(Skewed {
        law: prepare(law, skew, "law")?,
        desc,
    })
}

/// `manifold(z, feedback, skew=None)`: s_1..s_n of eq. (11) (IS) for the
/// error vector z = (z1..zn); `feedback`/`skew` one value or one per stage.
#[pyfunction]
#[pyo3(signature = (z, feedback, skew = None))]
pub fn manifold<'py>(
    py: Python<'py>,
    z: Vec<f64>,
    feedback: &Bound<'py, PyAny>,
    skew: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let n = z.len().saturating_sub(1);
    const RULE: &str = "must have len(z) - 1";
    let laws = per_stage(feedback, n, ("feedback", RULE), |o| Ok(o.clone()))?;
    let skews: Vec<Option<Bound<'py, PyAny>>> = match skew {
        Some(s) => per_stage(s, n, ("skew", RULE), |o| Ok(Some(o.clone())))?,
        None => vec![None; n],
    };
    let prepared: Vec<SkewedLaw<f64>> = laws
        .iter()
        .zip(skews.iter())
        .map(|(l, s)| prepare(l, s.as_ref(), "feedback"))
        .collect::<PyResult<_>>()?;
    check_order(z.len()).map_err(|e| {
        let message = format!("z: one entry per order, {e} (got {})", z.len());
        PyErr::from(ConfigFault::new("z", "must have one entry per order").message(message))
    })?;
    if z.iter().any(|v| !v.is_finite()) {
        return Err(ConfigFault::new("z", "must be finite").into());
    }
    let stages = with_order!(z.len(), N => to_array::<f64, N>(&z)
        .map(|a| core_manifold::evaluate::<f64, N>(&a, &prepared).stages.to_vec()), _ => None);
    let stages = stages.ok_or_else(|| PyErr::from(ConfigFault::new("z", "must have one entry per order")))?;
    Ok(PyArray1::from_vec(py, stages))
}

/// T_fn' = |z1(0)|^(1-p) / (k (1-p)) (Corollary 1), seconds.
#[pyfunction]
pub fn finite_time(k: f64, p: f64, z1_0: f64) -> PyResult<f64> {
    Feedback::FiniteTime { k, p }.validate().map_err(config_err)?;
    Ok(bounds::finite_time(k, p, z1_0))
}

/// T_fxe' (Corollary 2), seconds.
#[pyfunction]
pub fn variable_exponent(k: f64, r_b: f64, r_1: f64, r_t: f64) -> PyResult<f64> {
    Feedback::VariableExponent { k, r_b, r_1, r_t }
        .validate()
        .map_err(config_err)?;
    Ok(bounds::variable_exponent(k, r_b, r_1, r_t))
}

/// T_fr' (Corollary 3) for stages given as (alpha, p, beta, q), seconds.
#[pyfunction]
pub fn fixed_time(stages: Vec<(f64, f64, f64, f64)>) -> PyResult<f64> {
    for (i, &(alpha, p, beta, q)) in stages.iter().enumerate() {
        Feedback::FixedTime { alpha, p, beta, q }
            .validate()
            .map_err(|e| config_err(e.at_stage(i)))?;
    }
    Ok(bounds::fixed_time(&stages))
}
