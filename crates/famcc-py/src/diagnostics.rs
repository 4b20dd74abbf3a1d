//! `famcc.Diagnostics`: what a controller did at its last step (read-only).

use famcc_core::Real;
use numpy::PyArray1;
use pyo3::prelude::*;

/// What a controller's last step did (read-only).
///
/// Returned by ``Controller.diagnostics``; not constructed directly. A
/// snapshot: it does not change when the controller steps again. The
/// attributes are the quantities of the step in the paper's notation:
/// the constraint variables ``xi`` (eq. (28) (xi)) and ``xi~`` (eq. (31)
/// (Wxi)), the manifold ``s`` (eq. (11) (IS)), the envelopes' bounds
/// (eqs. (21) (xUxL), (22) (yUyL)) and their flexible expansion (eq. (30)
/// (WxyUxyL)), and the estimate ``z_hat`` of the differentiator (eq. (34)
/// (HGD)).
///
/// Examples
/// --------
/// >>> import famcc
/// >>> ctrl = famcc.Controller(2, 1e-3, famcc.FiniteTime(k=1.0, p=0.5),
/// ...                         constraint="lateral", eps=0.1, k_u=5.0)
/// >>> v = ctrl.step(-1.0)
/// >>> d = ctrl.diagnostics
/// >>> d.v == v, d.t, d.expanded, d.saturation_gap is None
/// (True, 0.0, False, True)
/// >>> abs(d.xi) < 1.0
/// True
#[pyclass(frozen, module = "famcc._core")]
#[derive(Clone, Debug)]
pub struct Diagnostics {
    /// Time of the last sample, s.
    #[pyo3(get)]
    t: f64,
    /// Constraint variable used for the output (flexible xi~).
    #[pyo3(get)]
    xi: f64,
    /// Nominal constraint variable xi (eq. (28)).
    #[pyo3(get)]
    xi_nominal: f64,
    /// Manifold value s = s_n.
    #[pyo3(get)]
    s: f64,
    stages: Vec<f64>,
    /// s_{n-1}.
    #[pyo3(get)]
    s_prev: f64,
    /// d/dt s_{n-1}.
    #[pyo3(get)]
    ds_prev: f64,
    /// Flexible upper bounds (x~_U, y~_U).
    #[pyo3(get)]
    bounds: (f64, f64),
    /// Nominal upper bounds (x_U, y_U).
    #[pyo3(get)]
    nominal_bounds: (f64, f64),
    z_hat: Vec<f64>,
    /// True when the flexible bounds were expanded.
    #[pyo3(get)]
    expanded: bool,
    /// Expansion factor of the flexible bounds (flexible / nominal, 1.0 when nominal).
    #[pyo3(get)]
    expansion: f64,
    /// v_{k-1} - applied, when `applied` was passed.
    #[pyo3(get)]
    saturation_gap: Option<f64>,
    /// Steps at which |xi| had to be clamped below 1.
    #[pyo3(get)]
    clamp_count: u64,
    /// The output returned (after the output limits, when configured).
    #[pyo3(get)]
    v: f64,
    /// The law's output -k_u Gamma(xi) - cancellation before the output limits.
    #[pyo3(get)]
    v_unlimited: f64,
    /// The observer's cancellation clip(Lhat / b0, -delta, delta) in the
    /// output (0.0 without an observer).
    #[pyo3(get)]
    cancellation: f64,
    /// The integral I of the error the output used (integral=True), else None.
    #[pyo3(get)]
    integral: Option<f64>,
    /// True when this step added its sample to I (False while the integral
    /// separation froze it, and without integral action).
    #[pyo3(get)]
    integrating: bool,
    /// Steps so far at which the bounds were expanded while the actuator was
    /// known to have headroom (`applied` passed or output limits set).
    #[pyo3(get)]
    unsaturated_expansions: u64,
}

impl Diagnostics {
    pub fn from_core<T: Real, const N: usize>(d: &famcc_core::Diagnostics<T, N>) -> Self {
        let f = |x: T| x.to_f64_lossless();
        Self {
            t: d.t,
            xi: f(d.xi),
            xi_nominal: f(d.xi_nominal),
            s: f(d.s),
            stages: d.stages.iter().map(|x| f(*x)).collect(),
            s_prev: f(d.s_prev),
            ds_prev: f(d.ds_prev),
            bounds: (f(d.bounds.0), f(d.bounds.1)),
            nominal_bounds: (f(d.nominal_bounds.0), f(d.nominal_bounds.1)),
            // With integral action the core's estimate is (I, z_hat_1..z_hat_n): the
            // integral has its own getter, z_hat is the plant's error estimate.
            z_hat: d
                .z_hat
                .iter()
                .skip(usize::from(d.integral.is_some()))
                .map(|x| f(*x))
                .collect(),
            expanded: d.expanded,
            expansion: f(d.expansion),
            saturation_gap: d.saturation_gap.map(f),
            clamp_count: d.clamp_count,
            v: f(d.v),
            v_unlimited: f(d.v_unlimited),
            cancellation: f(d.cancellation),
            integral: d.integral.map(f),
            integrating: d.integrating,
            unsaturated_expansions: d.unsaturated_expansions,
        }
    }
}

#[pymethods]
impl Diagnostics {
    /// The estimate of the error vector (z_1..z_n) the output was computed from
    /// (NumPy array; with integral action the integral is `integral`).
    #[getter]
    fn z_hat<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.z_hat)
    }
    /// s_1..s_n (NumPy array).
    #[getter]
    fn stages<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.stages)
    }
    fn __repr__(&self) -> String {
        format!(
            "Diagnostics(t={:?}, xi={:?}, s={:?}, bounds={:?}, nominal_bounds={:?}, z_hat={:?}, expanded={}, clamp_count={})",
            self.t,
            self.xi,
            self.s,
            self.bounds,
            self.nominal_bounds,
            self.z_hat,
            if self.expanded { "True" } else { "False" },
            self.clamp_count
        )
    }
}
