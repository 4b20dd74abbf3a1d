//! `famcc._core.Lockstep`: famcc-sim's sample-and-hold loop for Python, the
//! one simulator of `famcc.simulate`, `famcc.joints` and campaigns. It
//! translates arguments and records; the loop is famcc-sim's.

use crate::bank::ControllerBank;
use crate::controller::PyController;
use crate::errors::ConfigError;
use crate::sim_ctrls::{with_ctrls_of, CtrlArg};
use crate::sim_plants::{Callback, Kind, PaperLanes};
use famcc_sim::{Controllers, Detail, Failure, Options, Plant, Record, CAMPAIGN_COLUMNS, FULL_COLUMNS};
use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

/// The plant of a run.
enum PlantArg {
    Paper(famcc_sim::PaperLanes),
    Callback(Py<PyAny>, Kind),
}

/// A closed loop run sample by sample (famcc-sim's ``Lockstep``): ``lanes``
/// copies of a plant, ``channels`` controllers per copy; the private engine
/// of :func:`famcc.simulate`, :func:`famcc.joints.simulate_joints` and
/// :func:`famcc.campaign`.
///
/// Parameters
/// ----------
/// plant : PaperLanes or (kind, callable)
///     The paper's plant as lanes, or a Python right-hand side with kind
///     ``'list'`` or ``'array'`` (one lane) or ``'lanes'`` (all at once).
/// controllers : list
///     One ``Controller`` (or duck-typed object with ``step(e, applied=)``)
///     per channel for one lane; or ``ControllerBank`` objects whose lengths
///     add up to ``lanes`` (one channel), lanes in order.
/// dt : float
/// samples, substeps, states : int
/// x0 : sequence of float
///     ``states * lanes`` values, state-major.
/// outputs : list of int
///     Per channel, the index of its output state.
/// limits : list of (float, float) or None
///     Per channel.
/// diverge_at, state_bound : float, optional
/// detail : {'full', 'campaign', 'none'}
/// keep_states : bool
#[pyclass(module = "famcc._core", unsendable)]
pub struct Lockstep {
    sim: famcc_sim::Lockstep,
    plant: PlantArg,
    ctrls: CtrlArg,
    detail: Detail,
    keep_states: bool,
    held: u64,
}

fn shape_err(e: &'static str) -> PyErr {
    ConfigError::new_err(e)
}

#[pymethods]
impl Lockstep {
    #[new]
    #[pyo3(signature = (plant, controllers, *, dt, samples, substeps, states, x0, outputs, limits, diverge_at=None, state_bound=None, detail="full", keep_states=true))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        plant: &Bound<'_, PyAny>,
        controllers: Vec<Bound<'_, PyAny>>,
        dt: f64,
        samples: usize,
        substeps: usize,
        states: usize,
        x0: Vec<f64>,
        outputs: Vec<usize>,
        limits: Vec<Option<(f64, f64)>>,
        diverge_at: Option<f64>,
        state_bound: Option<f64>,
        detail: &str,
        keep_states: bool,
    ) -> PyResult<Self> {
        let detail = match detail {
            "full" => Detail::Full,
            "campaign" => Detail::Campaign,
            "none" => Detail::None,
            other => {
                return Err(ConfigError::new_err(format!(
                    "detail must be 'full', 'campaign' or 'none', got {other:?}"
                )))
            }
        };
        let plant = if let Ok(p) = plant.cast::<PaperLanes>() {
            PlantArg::Paper(p.get().lanes.clone())
        } else {
            let (kind, f): (String, Bound<'_, PyAny>) = plant.extract()?;
            let kind = match kind.as_str() {
                "list" => Kind::List,
                "array" => Kind::Array,
                "lanes" => Kind::Lanes,
                "step" => Kind::Step,
                other => {
                    return Err(ConfigError::new_err(format!(
                        "plant kind must be 'list', 'array', 'lanes' or 'step', got {other:?}"
                    )))
                }
            };
            PlantArg::Callback(f.unbind(), kind)
        };
        let lanes = x0.len() / states.max(1);
        let ctrls =
            if controllers.iter().all(|c| c.is_instance_of::<ControllerBank>()) && !controllers.is_empty() {
                let mut map = Vec::new();
                let mut banks = Vec::new();
                for (b, c) in controllers.into_iter().enumerate() {
                    let bank = c.cast_into::<ControllerBank>()?;
                    map.extend((0..bank.borrow().len()).map(|i| (b, i)));
                    banks.push(bank.unbind());
                }
                if map.len() != lanes {
                    return Err(ConfigError::new_err(format!(
                        "the banks hold {} controllers for {lanes} lanes",
                        map.len()
                    )));
                }
                CtrlArg::Banks(banks, map)
            } else if controllers.iter().all(|c| c.is_instance_of::<PyController>()) {
                CtrlArg::Single(
                    controllers
                        .into_iter()
                        .map(|c| c.cast_into::<PyController>().map(Bound::unbind))
                        .collect::<Result<_, _>>()?,
                )
            } else {
                let n = controllers.len();
                CtrlArg::Duck(
                    controllers.into_iter().map(Bound::unbind).collect(),
                    vec![None; n],
                )
            };
        let channels = outputs.len();
        let per_lane = match &ctrls {
            CtrlArg::Banks(..) => 1,
            _ => lanes,
        };
        if matches!(ctrls, CtrlArg::Single(_) | CtrlArg::Duck(..)) && (per_lane != 1 || channels == 0) {
            return Err(shape_err(
                "controllers other than banks serve one lane, one per channel",
            ));
        }
        let n_ctrl = match &ctrls {
            CtrlArg::Single(v) => v.len(),
            CtrlArg::Duck(v, _) => v.len(),
            CtrlArg::Banks(..) => 1,
        };
        if n_ctrl != channels {
            return Err(shape_err(
                "controllers must have one entry per channel (one bank list for one channel)",
            ));
        }
        let opts = Options {
            dt,
            samples,
            substeps,
            lanes,
            states,
            outputs,
            limits,
            diverge_at,
            state_bound,
        };
        let sim = famcc_sim::Lockstep::new(opts, x0).map_err(shape_err)?;
        Ok(Self {
            sim,
            plant,
            ctrls,
            detail,
            keep_states,
            held: 0,
        })
    }

    /// The diagnostics columns per channel and lane of ``run``'s ``'diag'``.
    #[getter]
    fn diag_columns<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        let cols: Vec<&str> = match self.detail {
            Detail::None => Vec::new(),
            Detail::Campaign => CAMPAIGN_COLUMNS.to_vec(),
            Detail::Full => FULL_COLUMNS.to_vec(),
        };
        PyTuple::new(py, cols)
    }

    /// The next sample's index.
    #[getter]
    fn sample(&self) -> usize {
        self.sim.sample()
    }

    /// True when the run is over (every lane stopped, or the last sample done).
    #[getter]
    fn done(&self) -> bool {
        self.sim.done()
    }

    /// Failed steps held so far (banks).
    #[getter]
    fn held(&self) -> u64 {
        self.held
    }

    /// The plant's states now, state-major.
    #[getter]
    fn state<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, self.sim.state())
    }

    /// Per lane, ``(samples_kept, reason)`` of a lane that stopped, else None.
    #[getter]
    fn stops(&self) -> Vec<Option<(usize, &'static str)>> {
        self.sim
            .stops()
            .iter()
            .map(|s| s.map(|s| (s.samples, s.reason.name())))
            .collect()
    }

    /// Per channel and lane, the last diagnostics' ``(clamp_count,
    /// unsaturated_expansions)`` (None when the controller reports none).
    fn counts(&mut self, py: Python<'_>) -> Vec<Option<(u64, Option<u64>)>> {
        let (c, l) = (self.sim.options().channels(), self.sim.options().lanes);
        let mut out = Vec::with_capacity(c * l);
        self.with_ctrls(py, |ctrls| {
            for i in 0..c * l {
                out.push(
                    ctrls
                        .diagnostics(i / l, i % l)
                        .map(|d| (d.clamp_count, d.unsaturated_expansions)),
                );
            }
            Ok(())
        })
        .ok();
        out
    }

    /// Runs the next ``len(yd) / (channels * lanes)`` samples.
    ///
    /// Parameters
    /// ----------
    /// yd, noise, disturbance : numpy.ndarray
    ///     Contiguous float64, ``[row][channel][lane]``; noise and disturbance
    ///     may be None.
    ///
    /// Returns
    /// -------
    /// dict
    ///     ``rows`` and float64 vectors ``e``, ``e_measured``, ``v``, ``u``,
    ///     ``d`` (``rows * channels * lanes``), ``x`` (``rows * states *
    ///     lanes``, when kept), ``diag`` (``rows * channels * lanes * width``)
    ///     and ``width``; ``plant_error`` (the exception) when the plant's
    ///     right-hand side raised: the block ends there.
    #[pyo3(signature = (yd, noise=None, disturbance=None))]
    fn run<'py>(
        &mut self,
        py: Python<'py>,
        yd: PyReadonlyArray1<'py, f64>,
        noise: Option<PyReadonlyArray1<'py, f64>>,
        disturbance: Option<PyReadonlyArray1<'py, f64>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let yd = yd
            .as_slice()
            .map_err(|_| PyValueError::new_err("yd must be contiguous"))?;
        let noise = noise
            .as_ref()
            .map(|n| n.as_slice())
            .transpose()
            .map_err(|_| PyValueError::new_err("noise must be contiguous"))?;
        let dist = disturbance
            .as_ref()
            .map(|d| d.as_slice())
            .transpose()
            .map_err(|_| PyValueError::new_err("disturbance must be contiguous"))?;
        let mut rec = Record::new(self.detail, self.keep_states);
        let mut plant_error = None;
        let (states, lanes, channels) = (
            self.sim.options().states,
            self.sim.options().lanes,
            self.sim.options().channels(),
        );
        let plant = match &self.plant {
            PlantArg::Paper(p) => Err(p.clone()),
            PlantArg::Callback(f, kind) => Ok(Callback {
                f: f.bind(py).clone(),
                kind: *kind,
                states,
                lanes,
                channels,
            }),
        };
        let sim = &mut self.sim;
        let mut held = 0;
        let record = self.detail != Detail::None;
        let result = with_ctrls_of(py, &mut self.ctrls, record, states / channels.max(1), |ctrls| {
            let r = match plant {
                Err(mut p) => sim
                    .run(&mut p, ctrls, yd, noise, dist, &mut rec)
                    .map_err(|f| match f {
                        Failure::Shape(s) => Failure::Shape(s),
                        Failure::Controller(k, e) => Failure::Controller(k, e),
                        Failure::Plant(_, never) => match never {},
                    }),
                Ok(mut p) => run_with(sim, &mut p, ctrls, yd, noise, dist, &mut rec),
            };
            held = ctrls.held();
            match r {
                Ok(()) => Ok(()),
                Err(Failure::Shape(s)) => Err(shape_err(s)),
                Err(Failure::Controller(_, e)) => Err(e),
                Err(Failure::Plant(_, e)) => {
                    plant_error = Some(e);
                    Ok(())
                }
            }
        });
        self.held += held;
        result?;
        let out = PyDict::new(py);
        out.set_item("rows", rec.rows)?;
        out.set_item("width", rec.width)?;
        for (name, v) in [
            ("e", rec.e),
            ("e_measured", rec.e_measured),
            ("v", rec.v),
            ("u", rec.u),
            ("d", rec.d),
            ("x", rec.x),
            ("diag", rec.diag),
        ] {
            out.set_item(name, PyArray1::from_vec(py, v))?;
        }
        if let Some(e) = plant_error {
            out.set_item("plant_error", e.into_value(py))?;
        }
        Ok(out)
    }
}

fn run_with<P: Plant, C: Controllers + ?Sized>(
    sim: &mut famcc_sim::Lockstep,
    plant: &mut P,
    ctrls: &mut C,
    yd: &[f64],
    noise: Option<&[f64]>,
    dist: Option<&[f64]>,
    rec: &mut Record,
) -> Result<(), Failure<P::Error, C::Error>> {
    sim.run(plant, ctrls, yd, noise, dist, rec)
}

impl Lockstep {
    fn with_ctrls(
        &mut self,
        py: Python<'_>,
        f: impl FnOnce(&mut dyn Controllers<Error = PyErr>) -> PyResult<()>,
    ) -> PyResult<()> {
        let o = self.sim.options();
        let order = o.states / o.channels().max(1);
        with_ctrls_of(py, &mut self.ctrls, false, order, f)
    }
}
