//! `famcc.ControllerBank`: n independent controllers with one configuration,
//! stepped together from a NumPy array (Monte-Carlo work).

use crate::controller::PyController;
use crate::dispatch::{with_bank, BankCores};
use crate::errors::{ConfigError, StepError};
use crate::number::{Int, Text};
use crate::spec::Spec;
use crate::state;
use famcc_core::{Controller, Real};
use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;

/// Batches at least this large release the GIL while stepping.
const DETACH_MIN: usize = 2048;
/// Batches at least this large are split across threads.
const PARALLEL_MIN: usize = 16384;

/// n independent copies of a configured controller, stepped together.
///
/// Every copy starts from the controller's configuration and state; each
/// then runs on its own error sample. For Monte Carlo work: one call steps
/// all copies from a NumPy array, large batches release the GIL and are
/// split across threads, and the result equals stepping the copies one by
/// one.
///
/// Parameters
/// ----------
/// controller : Controller
///     The configuration and the state every copy starts from (copied; the
///     controller itself is not changed).
/// n : int
///     The number of copies, ``n >= 1``.
///
/// Raises
/// ------
/// famcc.ConfigError
///     ``n < 1``.
///
/// Examples
/// --------
/// >>> import famcc, numpy as np
/// >>> ctrl = famcc.Controller(2, 1e-3, famcc.FiniteTime(k=1.0, p=0.5),
/// ...                         constraint="lateral", eps=0.1, k_u=5.0)
/// >>> bank = famcc.ControllerBank(ctrl, 3)
/// >>> len(bank)
/// 3
/// >>> v = bank.step(np.array([-1.0, -1.0, 0.5]))
/// >>> bool(v[0] == v[1] == ctrl.step(-1.0))
/// True
#[pyclass(module = "famcc._core")]
pub struct ControllerBank {
    pub(crate) cores: BankCores,
    spec: Spec,
    n: usize,
    /// Overflowed steps in the last call of `step`.
    #[pyo3(get)]
    overflows: usize,
    /// The lanes held by the last call of `step(e, on_nonfinite="hold")`
    /// (their `e` was not finite), in order.
    held: Vec<usize>,
}

/// What `step` does with non-finite entries of `e`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum OnNonFinite {
    /// `StepError` before any controller moves.
    Raise,
    /// Those lanes keep their state and output; the others step.
    Hold,
}

/// Steps one slice of controllers; returns how many steps overflowed. Those
/// controllers consumed their sample (famcc-core's `StepError::Overflow`) and
/// their output is the previous one, as a caller would hold it. A lane whose
/// `e` is not finite (only with `on_nonfinite="hold"`) is held: its step is
/// refused by the core, so its state is unchanged, and it repeats its output.
fn step_slice<T: Real, const N: usize>(v: &mut [Controller<T, N>], e: &[f64], out: &mut [f64]) -> usize {
    let mut failed = 0;
    for ((c, e), o) in v.iter_mut().zip(e).zip(out.iter_mut()) {
        if !e.is_finite() {
            *o = c.diagnostics().v.to_f64_lossless();
            continue;
        }
        match c.step(T::from_f64(*e)) {
            Ok(x) => *o = x.to_f64_lossless(),
            Err(_) => {
                *o = c.diagnostics().v.to_f64_lossless();
                failed += 1;
            }
        }
    }
    failed
}

/// Steps every controller, on up to `threads` threads (the controllers are
/// independent, so the result equals stepping them one by one).
fn step_all(cores: &mut BankCores, e: &[f64], out: &mut [f64], threads: usize) -> usize {
    with_bank!(cores, v => {
        if threads <= 1 {
            step_slice(v, e, out)
        } else {
            let chunk = v.len().div_ceil(threads);
            std::thread::scope(|s| {
                let handles: Vec<_> = v
                    .chunks_mut(chunk)
                    .zip(e.chunks(chunk).zip(out.chunks_mut(chunk)))
                    .map(|(cv, (ce, co))| s.spawn(move || step_slice(cv, ce, co)))
                    .collect();
                handles.into_iter().map(|h| h.join().unwrap_or(0)).sum()
            })
        }
    })
}

/// Threads for a batch of `n`: one below `PARALLEL_MIN`, else the machine's
/// parallelism (at most 8).
fn threads_for(n: usize) -> usize {
    if n < PARALLEL_MIN {
        return 1;
    }
    std::thread::available_parallelism()
        .map(|p| p.get().min(8))
        .unwrap_or(1)
}

impl ControllerBank {
    /// The number of controllers.
    pub(crate) fn len(&self) -> usize {
        self.n
    }

    /// `step` on an error slice.
    fn step_errors<'py>(
        &mut self,
        py: Python<'py>,
        e: &[f64],
        on_nonfinite: OnNonFinite,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        if e.len() != self.n {
            return Err(StepError::new_err(format!(
                "e must have length {} (one per controller), got {}",
                self.n,
                e.len()
            )));
        }
        if on_nonfinite == OnNonFinite::Raise {
            if let Some(i) = e.iter().position(|x| !x.is_finite()) {
                return Err(StepError::new_err(format!(
                    "e[{i}] = {} is not finite; no controller was stepped (on_nonfinite=\"hold\" holds \
                     such lanes and steps the others)",
                    e[i]
                )));
            }
        }
        self.held = e
            .iter()
            .enumerate()
            .filter(|(_, x)| !x.is_finite())
            .map(|(i, _)| i)
            .collect();
        let mut out = vec![0.0; self.n];
        let cores = &mut self.cores;
        self.overflows = if self.n >= DETACH_MIN {
            py.detach(|| step_all(cores, e, &mut out, threads_for(e.len())))
        } else {
            step_all(cores, e, &mut out, 1)
        };
        Ok(PyArray1::from_vec(py, out))
    }
}

#[pymethods]
impl ControllerBank {
    #[new]
    fn new(controller: &PyController, n: Int) -> PyResult<Self> {
        let n = n.0;
        let n = usize::try_from(n)
            .ok()
            .filter(|n| *n >= 1)
            .ok_or_else(|| ConfigError::new_err(format!("n must be >= 1 (got {n})")))?;
        Ok(Self {
            cores: controller.core.replicate(n),
            spec: controller.spec.clone(),
            n,
            overflows: 0,
            held: Vec::new(),
        })
    }

    fn __len__(&self) -> usize {
        self.n
    }

    /// Steps controller i with ``e[i]``; returns the outputs.
    ///
    /// Equal to stepping the copies one by one. Large batches release the
    /// GIL and are split across threads. A controller whose law overflows on
    /// a valid sample consumes it and repeats its previous output (counted in
    /// ``overflows``).
    ///
    /// Parameters
    /// ----------
    /// e : numpy.ndarray
    ///     The error samples ``e = y - y_d`` (output minus reference, the
    ///     opposite of a PID's ``setpoint - y``), a contiguous float64 array
    ///     of length ``n``, unit of ``y``.
    /// on_nonfinite : {'raise', 'hold'}, default 'raise'
    ///     'raise': a NaN or infinite entry raises ``StepError`` before any
    ///     controller moves. 'hold': such a lane keeps its state and repeats
    ///     its output, the others step, and ``held`` lists the held lanes.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     The outputs ``v``, float64, length ``n``, input units.
    ///
    /// Raises
    /// ------
    /// famcc.StepError
    ///     ``e`` of the wrong length or not contiguous, or a non-finite entry
    ///     with ``on_nonfinite='raise'``.
    /// famcc.ConfigError
    ///     An unknown ``on_nonfinite``.
    #[pyo3(signature = (e, on_nonfinite = Text(String::from("raise"))),
        text_signature = "(self, /, e, on_nonfinite='raise')")]
    fn step<'py>(
        &mut self,
        py: Python<'py>,
        e: PyReadonlyArray1<'py, f64>,
        on_nonfinite: Text,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let policy = match on_nonfinite.0.as_str() {
            "raise" => OnNonFinite::Raise,
            "hold" => OnNonFinite::Hold,
            other => {
                return Err(ConfigError::new_err(format!(
                    "on_nonfinite must be \"raise\" or \"hold\", got {other:?}"
                )))
            }
        };
        let e = e
            .as_slice()
            .map_err(|_| StepError::new_err("e must be a contiguous float64 array"))?;
        self.step_errors(py, e, policy)
    }

    /// The lanes held by the last `step`, in order (empty unless
    /// `on_nonfinite="hold"` met non-finite entries).
    #[getter]
    fn held<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, pyo3::types::PyTuple>> {
        pyo3::types::PyTuple::new(py, &self.held)
    }

    /// Steps controller i with the error ``e[i] = y[i] - y_d[i]``; as :meth:`step`.
    ///
    /// Parameters
    /// ----------
    /// y : numpy.ndarray
    ///     The measured outputs, float64, length ``n``.
    /// y_d : numpy.ndarray
    ///     The references, float64, length ``n``, unit of ``y``.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     The outputs ``v``, float64, length ``n``, input units.
    ///
    /// Raises
    /// ------
    /// famcc.StepError
    ///     Arrays of different or wrong length, or a non-finite entry.
    fn step_output<'py>(
        &mut self,
        py: Python<'py>,
        y: PyReadonlyArray1<'py, f64>,
        y_d: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let (y, y_d) = (
            y.as_slice()
                .map_err(|_| StepError::new_err("y must be a contiguous float64 array"))?,
            y_d.as_slice()
                .map_err(|_| StepError::new_err("y_d must be a contiguous float64 array"))?,
        );
        if y.len() != y_d.len() {
            return Err(StepError::new_err(format!(
                "y and y_d must have the same length, got {} and {}",
                y.len(),
                y_d.len()
            )));
        }
        let e: Vec<f64> = y.iter().zip(y_d).map(|(y, r)| y - r).collect();
        self.step_errors(py, &e, OnNonFinite::Raise)
    }

    /// The constraint variables xi~ of the last step (NumPy array).
    #[getter]
    fn xi<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let v: Vec<f64> =
            with_bank!(&self.cores, v => v.iter().map(|c| c.diagnostics().xi.to_f64_lossless()).collect());
        PyArray1::from_vec(py, v)
    }

    /// The nominal constraint variables xi of the last step, before the
    /// flexible expansion and the clamp (NumPy array). Above 1 a controller's
    /// state left the nominal constraint set (docs/design.md §8).
    #[getter]
    fn xi_nominal<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let v: Vec<f64> = with_bank!(&self.cores, v => v
            .iter()
            .map(|c| c.diagnostics().xi_nominal.to_f64_lossless())
            .collect());
        PyArray1::from_vec(py, v)
    }

    /// The flexible boundaries' expansion factors of the last step (NumPy
    /// array): 1.0 while a controller's bounds are nominal, > 1 while expanded.
    #[getter]
    fn expansion<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let v: Vec<f64> = with_bank!(&self.cores, v => v
            .iter()
            .map(|c| c.diagnostics().expansion.to_f64_lossless())
            .collect());
        PyArray1::from_vec(py, v)
    }

    /// Resets every controller to the state before its first step.
    fn reset(&mut self) {
        with_bank!(&mut self.cores, v => v.iter_mut().for_each(|c| c.reset()))
    }

    /// A copy of controller i, with its configuration and current state.
    ///
    /// Parameters
    /// ----------
    /// i : int
    ///     The index; negative indices count from the end, as Python's.
    ///
    /// Returns
    /// -------
    /// Controller
    ///     An independent copy (stepping it does not move the bank).
    ///
    /// Raises
    /// ------
    /// IndexError
    ///     ``i`` out of range.
    fn controller(&self, i: Int) -> PyResult<PyController> {
        let given = i.0;
        let n = i64::try_from(self.n).unwrap_or(i64::MAX);
        let i = usize::try_from(if given < 0 { given.saturating_add(n) } else { given })
            .ok()
            .filter(|i| *i < self.n)
            .ok_or_else(|| {
                pyo3::exceptions::PyIndexError::new_err(format!(
                    "index {given} out of range for {} controllers",
                    self.n
                ))
            })?;
        let mut c = PyController::from_spec(self.spec.clone())?;
        let state: Vec<f64> = with_bank!(&self.cores, v => state::to_vec(&v[i]));
        c.set_state_vec(&state)?;
        Ok(c)
    }

    fn __repr__(&self) -> String {
        format!("ControllerBank(n={}, order={})", self.n, self.spec.order)
    }
}
