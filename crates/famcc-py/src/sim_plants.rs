//! The plants of `famcc._core.Lockstep`: the paper's plants as lanes
//! (famcc-sim's `PaperLanes`, compiled) and plants written in Python (their
//! right-hand side called back at every RK4 stage).

use crate::errors::ConfigError;
use famcc_paper::Variant;
use famcc_sim::Plant;
use numpy::{PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyList;

/// The paper's second- or third-order plant for many lanes at once, each
/// with its own input-gain factor and disturbance amplitude; lane ``l``
/// computes exactly what ``PaperPlant(order, variant, gain[l], amp[l])``
/// computes.
///
/// Parameters
/// ----------
/// order : int
///     2 or 3.
/// variant : {'paper', 'code'}
/// gain, amp : numpy.ndarray
///     One finite value per lane (``gain > 0``).
#[pyclass(frozen, module = "famcc._core")]
pub struct PaperLanes {
    pub(crate) lanes: famcc_sim::PaperLanes,
}

#[pymethods]
impl PaperLanes {
    #[new]
    fn new(
        order: usize,
        variant: &str,
        gain: PyReadonlyArray1<'_, f64>,
        amp: PyReadonlyArray1<'_, f64>,
    ) -> PyResult<Self> {
        let v = match variant {
            "paper" => Variant::Paper,
            "code" => Variant::Code,
            other => {
                return Err(ConfigError::new_err(format!(
                    "variant must be 'paper' or 'code', got {other:?}"
                )))
            }
        };
        let (gain, amp) = (gain.as_array().to_vec(), amp.as_array().to_vec());
        if gain.is_empty() || gain.len() != amp.len() {
            return Err(ConfigError::new_err(
                "gain and amp must hold one value per lane, equally many (>= 1)",
            ));
        }
        if gain.iter().any(|g| !(g.is_finite() && *g > 0.0)) || amp.iter().any(|a| !a.is_finite()) {
            return Err(ConfigError::new_err(
                "gain must be finite and > 0, amp finite, in every lane",
            ));
        }
        let lanes = match order {
            2 => famcc_sim::PaperLanes::second(v, gain, amp),
            3 => famcc_sim::PaperLanes::third(v, gain, amp),
            n => return Err(ConfigError::new_err(format!("order must be 2 or 3 (got {n})"))),
        };
        Ok(Self { lanes })
    }

    /// Lane 0's exact output derivatives, gain and drift at every sample.
    ///
    /// Parameters
    /// ----------
    /// t : numpy.ndarray
    ///     Times, shape ``(K,)``.
    /// x : numpy.ndarray
    ///     States, shape ``(K, order)``.
    ///
    /// Returns
    /// -------
    /// (numpy.ndarray, numpy.ndarray, numpy.ndarray)
    ///     ``(y, ..., y^(n-1))`` per sample ``(K, order)``, and ``G_a``, ``F_a``
    ///     of ``y^(n) = G_a u + F_a`` ``(K,)``: what ``PaperPlant``'s
    ///     ``output_derivatives`` and ``gain_and_drift`` give sample by sample.
    #[allow(clippy::type_complexity)]
    fn table<'py>(
        &self,
        py: Python<'py>,
        t: PyReadonlyArray1<'py, f64>,
        x: numpy::PyReadonlyArray2<'py, f64>,
    ) -> PyResult<(
        Bound<'py, PyArray2<f64>>,
        Bound<'py, PyArray1<f64>>,
        Bound<'py, PyArray1<f64>>,
    )> {
        let n = self.lanes.order();
        let t = t.as_array();
        let x = x.as_array();
        if x.shape() != [t.len(), n] {
            return Err(PyValueError::new_err(format!(
                "x must have shape ({}, {n})",
                t.len()
            )));
        }
        let (mut d, mut gain, mut drift) = (Vec::with_capacity(t.len() * n), Vec::new(), Vec::new());
        for (k, tk) in t.iter().enumerate() {
            let row: Vec<f64> = x.row(k).to_vec();
            let (dk, g, f) = self.lanes.exact(*tk, &row);
            d.extend_from_slice(&dk);
            gain.push(g);
            drift.push(f);
        }
        Ok((
            PyArray1::from_vec(py, d).reshape([t.len(), n])?,
            PyArray1::from_vec(py, gain),
            PyArray1::from_vec(py, drift),
        ))
    }

    /// The number of lanes.
    fn __len__(&self) -> usize {
        self.lanes.lanes()
    }

    /// ``dx/dt`` of every lane.
    ///
    /// Parameters
    /// ----------
    /// t : float
    ///     Time, s.
    /// x : numpy.ndarray
    ///     The states, shape ``(order, lanes)``.
    /// u : numpy.ndarray
    ///     The inputs, shape ``(lanes,)``.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     Shape ``(order, lanes)``.
    fn rhs<'py>(
        &self,
        py: Python<'py>,
        t: f64,
        x: &Bound<'py, PyAny>,
        u: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let (n, l) = (self.lanes.order(), self.lanes.lanes());
        let np = py.import("numpy")?;
        let xs: Vec<f64> = np
            .call_method1("ascontiguousarray", (x, "float64"))?
            .call_method0("ravel")?
            .extract()?;
        let us: Vec<f64> = np
            .call_method1("broadcast_to", (u, l))?
            .call_method1("astype", ("float64",))?
            .extract()?;
        if xs.len() != n * l {
            return Err(PyValueError::new_err(format!("x must have shape ({n}, {l})")));
        }
        let mut dx = vec![0.0; n * l];
        let Ok(()) = self.lanes.clone().rhs(t, &xs, &us, &mut dx);
        PyArray1::from_vec(py, dx).reshape([n, l])
    }
}

/// How a Python plant's right-hand side is called.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// `rhs(t, x, u)` with `x` a list of floats (one lane), `u` a float
    /// (or a list, one per channel); returns a sequence of floats.
    List,
    /// The same with `x` a float64 NumPy vector.
    Array,
    /// `rhs(t, x, u)` for every lane at once: `x` of shape `(states, lanes)`,
    /// `u` of shape `(lanes,)` (or `(channels, lanes)`); returns a
    /// C-contiguous float64 array of shape `(states, lanes)`.
    Lanes,
    /// A plant that advances itself (a simulator with its own integrator):
    /// `advance(t, x, u, dt)` returns the states at `t + dt` under `u` held,
    /// `x` and `u` laid out as for `Lanes` when there are several lanes or
    /// channels, else as for `Array`; the loop never calls a right-hand side.
    Step,
}

/// A plant whose right-hand side is a Python callable.
pub struct Callback<'py> {
    pub f: Bound<'py, PyAny>,
    pub kind: Kind,
    pub states: usize,
    pub lanes: usize,
    pub channels: usize,
}

impl Callback<'_> {
    fn call(&self, t: f64, x: &[f64], u: &[f64]) -> PyResult<Bound<'_, PyAny>> {
        let py = self.f.py();
        match self.kind {
            Kind::Step => Err(PyValueError::new_err(
                "a plant that advances itself has no right-hand side",
            )),
            Kind::List | Kind::Array => {
                let xs = if self.kind == Kind::List {
                    PyList::new(py, x)?.into_any()
                } else {
                    PyArray1::from_slice(py, x).into_any()
                };
                match u {
                    [one] if self.channels == 1 => self.f.call1((t, xs, *one)),
                    _ => self.f.call1((t, xs, PyList::new(py, u)?)),
                }
            }
            Kind::Lanes => {
                let (xs, us) = self.lane_args(x, u)?;
                self.f.call1((t, xs, us))
            }
        }
    }

    /// `x` as `(states, lanes)` and `u` as `(lanes,)` or `(channels, lanes)`.
    fn lane_args<'a>(&'a self, x: &[f64], u: &[f64]) -> PyResult<(Bound<'a, PyAny>, Bound<'a, PyAny>)> {
        let py = self.f.py();
        let xs = PyArray1::from_slice(py, x).reshape([self.states, self.lanes])?;
        let us = if self.channels == 1 {
            PyArray1::from_slice(py, u).into_any()
        } else {
            PyArray1::from_slice(py, u)
                .reshape([self.channels, self.lanes])?
                .into_any()
        };
        Ok((xs.into_any(), us))
    }

    /// `advance(t, x, u, dt)` of a [`Kind::Step`] plant.
    fn call_step(&self, t: f64, dt: f64, x: &[f64], u: &[f64]) -> PyResult<Bound<'_, PyAny>> {
        let py = self.f.py();
        if self.lanes == 1 && self.channels == 1 {
            let one = u.first().copied().unwrap_or(f64::NAN);
            return self.f.call1((t, PyArray1::from_slice(py, x), one, dt));
        }
        let (xs, us) = self.lane_args(x, u)?;
        self.f.call1((t, xs, us, dt))
    }

    /// Copies what the plant returned into `to` (one value per state and lane).
    fn fill(&self, out: &Bound<'_, PyAny>, to: &mut [f64], what: &str) -> PyResult<()> {
        let want = to.len();
        let got = if let Ok(a) = out.cast::<PyArray1<f64>>() {
            let r = a.readonly();
            let s = r.as_slice()?;
            to.iter_mut().zip(s).for_each(|(o, v)| *o = *v);
            s.len()
        } else if let Ok(a) = out.cast::<PyArray2<f64>>() {
            let r = a.readonly();
            let s = r.as_slice()?;
            to.iter_mut().zip(s).for_each(|(o, v)| *o = *v);
            s.len()
        } else {
            let v: Vec<f64> = out.extract()?;
            to.iter_mut().zip(&v).for_each(|(o, x)| *o = *x);
            v.len()
        };
        if got != want {
            return Err(PyValueError::new_err(format!(
                "the plant's {what} returned {got} values, expected {want} (one per state{})",
                if self.lanes > 1 { " and lane" } else { "" }
            )));
        }
        Ok(())
    }
}

impl Plant for Callback<'_> {
    type Error = PyErr;

    fn advance(&mut self, t: f64, dt: f64, x: &mut [f64], u: &[f64]) -> PyResult<bool> {
        if self.kind != Kind::Step {
            return Ok(false);
        }
        let out = self.call_step(t, dt, x, u)?;
        self.fill(&out, x, "advance")?;
        Ok(true)
    }

    fn rhs(&mut self, t: f64, x: &[f64], u: &[f64], dx: &mut [f64]) -> PyResult<()> {
        let out = self.call(t, x, u)?;
        self.fill(&out, dx, "right-hand side")
    }
}
