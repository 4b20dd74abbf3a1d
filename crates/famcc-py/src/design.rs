//! `famcc_core::design` for Python: the rules' numbers, translated to a
//! dict, and the design's configuration as a `ControllerSpec`.

use crate::differentiator::HighGain;
use crate::errors::config_err;
use crate::laws::{Law, Linear};
use crate::names::DType;
use crate::spec::ControllerSpec;
use crate::spec::{RhoE, Spec};
use famcc_core::design::{self, Design, Level, Requirements, Rule};
use famcc_core::{Constraint, Gamma};
use pyo3::prelude::*;
use pyo3::types::PyDict;

fn rule_name(r: Rule) -> &'static str {
    match r {
        Rule::SampledLoop => "sampled-loop",
        Rule::SettleTime => "settle-time",
        Rule::Accuracy => "accuracy",
        Rule::Noise => "noise",
        Rule::HoldInput => "hold-input",
        Rule::GainUnknown => "gain-unknown",
        Rule::EstimateLimits => "estimate-limits",
    }
}

fn level_name(l: Level) -> &'static str {
    match l {
        Level::Ok => "ok",
        Level::Warn => "warn",
        Level::Fail => "fail",
    }
}

/// The controller of a design: linear stage laws `Linear(lambda)`, the
/// longitudinal constraint of width `eps_s`, the log map, the
/// differentiator at order >= 2 (as `Design.controller_kwargs` states it).
fn design_spec(d: &Design, req: &Requirements) -> Spec {
    let order = req.order;
    let law = Law::Linear(Linear { k: d.lambda });
    let differentiator = (order > 1).then(|| HighGain {
        mu: d.mu,
        a: d.a.get(..order).unwrap_or(&[]).to_vec(),
        discretization: d.discretization,
        limits: d.estimate_limits.map(|l| l.get(..order).unwrap_or(&[]).to_vec()),
        prefilter: d.prefilter,
    });
    Spec {
        order,
        dt: req.dt,
        stages: vec![(law, None); d.law_order.saturating_sub(1)],
        constraint: Constraint::Longitudinal { eps: d.eps_s },
        settle_time: d.settle_time,
        k0: d.k0,
        k_u: d.k_u,
        gamma: Gamma::Log,
        rho_e: RhoE::Given(Some(d.rho_e)),
        latch: Default::default(),
        transition: Default::default(),
        direction: d.direction,
        differentiator,
        initial_derivatives: None,
        dtype: DType::F64,
        integral: d.integral,
        output_limits: None,
        rate_limit: None,
        initial_output: None,
        observer: None,
        cancellation_limit: None,
    }
}

/// The design rules of famcc-core: the chosen numbers, the findings
/// `(rule, level, value, limit, suggestion)` and, under `"controller"`,
/// the configuration (a `ControllerSpec`).
#[pyfunction]
#[pyo3(signature = (order, dt, u_limits, eps, settle_time, hold_input, gain=None, noise_std=0.0, integral=None, phase_budget=None, mu_per_dt=None, settle_fraction=None, max_error=None))]
#[allow(clippy::too_many_arguments)]
pub fn design_rules<'py>(
    py: Python<'py>,
    order: usize,
    dt: f64,
    u_limits: (f64, f64),
    eps: f64,
    settle_time: f64,
    hold_input: f64,
    gain: Option<f64>,
    noise_std: f64,
    integral: Option<bool>,
    phase_budget: Option<f64>,
    mu_per_dt: Option<f64>,
    settle_fraction: Option<f64>,
    max_error: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let mut req = Requirements::new(order, dt, u_limits, eps, settle_time, hold_input);
    req.gain = gain;
    req.noise_std = noise_std;
    req.integral = integral;
    if let Some(b) = phase_budget {
        req.phase_budget = b;
    }
    if let Some(m) = mu_per_dt {
        req.mu_per_dt = m;
    }
    if let Some(f) = settle_fraction {
        req.settle_fraction = f;
    }
    req.max_error = max_error;
    let d = design::design(&req).map_err(config_err)?;
    let out = PyDict::new(py);
    out.set_item("law_order", d.law_order)?;
    out.set_item("integral", d.integral)?;
    out.set_item("direction", crate::names::DIRECTION.name(d.direction))?;
    out.set_item("mu", d.mu)?;
    out.set_item("a", d.a.get(..order).unwrap_or(&[]).to_vec())?;
    out.set_item(
        "discretization",
        crate::names::DISCRETIZATION.name(d.discretization),
    )?;
    out.set_item("prefilter", d.prefilter)?;
    out.set_item("lambda", d.lambda)?;
    out.set_item("loop_rate", d.loop_rate)?;
    out.set_item("k_u", d.k_u)?;
    out.set_item("eps_s", d.eps_s)?;
    out.set_item("rho_e", d.rho_e)?;
    out.set_item("k0", d.k0)?;
    out.set_item("settle_time", d.settle_time)?;
    out.set_item(
        "estimate_limits",
        d.estimate_limits.map(|l| l.get(..order).unwrap_or(&[]).to_vec()),
    )?;
    let checks: Vec<(&str, &str, f64, f64, f64)> = d
        .checks()
        .iter()
        .map(|c| {
            (
                rule_name(c.rule),
                level_name(c.level),
                c.value,
                c.limit,
                c.suggestion,
            )
        })
        .collect();
    out.set_item("checks", checks)?;
    let spec = ControllerSpec {
        spec: design_spec(&d, &req),
    };
    out.set_item("controller", spec)?;
    Ok(out)
}
