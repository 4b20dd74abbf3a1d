//! The controllers of `famcc._core.Lockstep`: famcc's own (a `Controller`
//! per channel, stepped in place as `Controller.step` steps it; the lanes of
//! `ControllerBank`s, which hold their output on a failed step) and
//! duck-typed Python objects with `step(e, applied=None)`.

use crate::bank::ControllerBank;
use crate::controller::PyController;
use crate::dispatch::{with_bank, BankCores};
use crate::errors::step_err;
use famcc_core::Real;
use famcc_sim::control::step_core;
use famcc_sim::{Controllers, Diag};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// One famcc `Controller` per channel, one lane.
pub struct Single<'py> {
    pub ctrls: Vec<PyRefMut<'py, PyController>>,
}

impl Controllers for Single<'_> {
    type Error = PyErr;

    fn step(&mut self, e: &[f64], applied: Option<&[f64]>, live: &[bool], v: &mut [f64]) -> PyResult<()> {
        if !live.first().copied().unwrap_or(false) {
            return Ok(());
        }
        for (c, ctrl) in self.ctrls.iter_mut().enumerate() {
            let a = applied.and_then(|a| a.get(c).copied());
            let e = e.get(c).copied().unwrap_or(f64::NAN);
            let out = ctrl.core.step(e, a).map_err(|err| step_err(err, "e"))?;
            ctrl.check_health(a)?;
            if let Some(o) = v.get_mut(c) {
                *o = out;
            }
        }
        Ok(())
    }

    fn diagnostics(&self, c: usize, l: usize) -> Option<Diag> {
        if l != 0 {
            return None;
        }
        self.ctrls.get(c).map(|ctrl| ctrl.core.sim_diag())
    }
}

/// The lanes of one channel, served by `ControllerBank`s: `map[l]` is the
/// bank and the position of lane `l`.
pub struct Banks<'py> {
    pub banks: Vec<PyRefMut<'py, ControllerBank>>,
    pub map: Vec<(usize, usize)>,
    pub held: u64,
}

impl Controllers for Banks<'_> {
    type Error = PyErr;

    fn step(&mut self, e: &[f64], applied: Option<&[f64]>, live: &[bool], v: &mut [f64]) -> PyResult<()> {
        for (l, &(b, i)) in self.map.iter().enumerate() {
            if !live.get(l).copied().unwrap_or(false) {
                continue;
            }
            let (el, al) = (
                e.get(l).copied().unwrap_or(f64::NAN),
                applied.and_then(|a| a.get(l).copied()),
            );
            let Some(bank) = self.banks.get_mut(b) else {
                continue;
            };
            let out = with_bank!(&mut bank.cores, cores => match cores.get_mut(i) {
                Some(c) => match step_core(c, el, al) {
                    Ok(x) => Some(x),
                    Err(_) => {
                        self.held += 1;
                        Some(c.diagnostics().v.to_f64_lossless())
                    }
                },
                None => None,
            });
            if let (Some(x), Some(o)) = (out, v.get_mut(l)) {
                *o = x;
            }
        }
        Ok(())
    }

    fn diagnostics(&self, c: usize, l: usize) -> Option<Diag> {
        let &(b, i) = self.map.get(l).filter(|_| c == 0)?;
        let bank = self.banks.get(b)?;
        with_bank!(&bank.cores, cores => cores.get(i).map(Diag::of))
    }

    fn held(&self) -> u64 {
        self.held
    }
}

/// Duck-typed controllers, one per channel and one lane: `step(e,
/// applied=...)`, and (when recorded) their `diagnostics` read after each step.
pub struct Duck<'py> {
    pub objs: Vec<Bound<'py, PyAny>>,
    pub record: bool,
    pub last: Vec<Option<Diag>>,
    pub order: usize,
}

/// `obj.name` as a float, NaN when absent or not a number.
fn number(obj: &Bound<'_, PyAny>, name: &str) -> f64 {
    obj.getattr(name)
        .and_then(|v| v.extract::<f64>())
        .unwrap_or(f64::NAN)
}

fn pair(obj: &Bound<'_, PyAny>, name: &str) -> [f64; 2] {
    obj.getattr(name)
        .and_then(|v| v.extract::<(f64, f64)>())
        .map_or([f64::NAN; 2], |(a, b)| [a, b])
}

/// A duck-typed controller's `diagnostics`, as far as it has the attributes.
fn read(d: &Bound<'_, PyAny>, order: usize) -> PyResult<Diag> {
    let mut out = Diag::unknown(order);
    out.xi = d.getattr("xi")?.extract()?;
    out.s = d.getattr("s")?.extract()?;
    out.s_prev = d.getattr("s_prev")?.extract()?;
    out.ds_prev = d.getattr("ds_prev")?.extract()?;
    out.bounds = pair(d, "bounds");
    out.nominal_bounds = pair(d, "nominal_bounds");
    out.xi_nominal = number(d, "xi_nominal");
    out.expansion = number(d, "expansion");
    out.expanded = d.getattr("expanded")?.is_truthy()?;
    out.clamp_count = d.getattr("clamp_count")?.extract()?;
    out.unsaturated_expansions = d
        .getattr("unsaturated_expansions")
        .ok()
        .and_then(|v| v.extract().ok());
    let z: Vec<f64> = d.getattr("z_hat")?.extract()?;
    for (o, z) in out.z_hat.iter_mut().zip(z) {
        *o = z;
    }
    Ok(out)
}

impl Controllers for Duck<'_> {
    type Error = PyErr;

    fn step(&mut self, e: &[f64], applied: Option<&[f64]>, live: &[bool], v: &mut [f64]) -> PyResult<()> {
        if !live.first().copied().unwrap_or(false) {
            return Ok(());
        }
        for (c, obj) in self.objs.iter().enumerate() {
            let kw = PyDict::new(obj.py());
            kw.set_item("applied", applied.and_then(|a| a.get(c).copied()))?;
            let out = obj.call_method("step", (e.get(c).copied().unwrap_or(f64::NAN),), Some(&kw))?;
            let x: f64 = out.extract()?;
            if let Some(o) = v.get_mut(c) {
                *o = x;
            }
            if self.record {
                let d = read(&obj.getattr("diagnostics")?, self.order)?;
                if let Some(slot) = self.last.get_mut(c) {
                    *slot = Some(d);
                }
            }
        }
        Ok(())
    }

    fn diagnostics(&self, c: usize, l: usize) -> Option<Diag> {
        if l != 0 {
            return None;
        }
        self.last.get(c).copied().flatten()
    }
}

/// The controllers of a run.
pub enum CtrlArg {
    Single(Vec<Py<PyController>>),
    Banks(Vec<Py<ControllerBank>>, Vec<(usize, usize)>),
    Duck(Vec<Py<PyAny>>, Vec<Option<famcc_sim::Diag>>),
}

/// Runs `f` with the run's controllers borrowed (mutably, for the block).
pub fn with_ctrls_of<'py>(
    py: Python<'py>,
    ctrls: &mut CtrlArg,
    record: bool,
    order: usize,
    f: impl FnOnce(&mut dyn Controllers<Error = PyErr>) -> PyResult<()>,
) -> PyResult<()> {
    match ctrls {
        CtrlArg::Single(v) => {
            let ctrls = v
                .iter()
                .map(|c| c.bind(py).try_borrow_mut().map_err(PyErr::from))
                .collect::<PyResult<Vec<_>>>()?;
            f(&mut Single { ctrls })
        }
        CtrlArg::Banks(banks, map) => {
            let banks = banks
                .iter()
                .map(|b| b.bind(py).try_borrow_mut().map_err(PyErr::from))
                .collect::<PyResult<Vec<_>>>()?;
            f(&mut Banks {
                banks,
                map: map.clone(),
                held: 0,
            })
        }
        CtrlArg::Duck(objs, last) => {
            let objs = objs.iter().map(|o| o.bind(py).clone()).collect();
            let mut d = Duck {
                objs,
                record,
                last: std::mem::take(last),
                order,
            };
            let r = f(&mut d);
            *last = d.last;
            r
        }
    }
}
