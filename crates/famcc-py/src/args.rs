//! The arguments of `famcc.Controller(...)`, parsed into a typed [`Spec`]:
//! Python shapes (one value or one per stage, a float or a pair for `eps`,
//! `"auto"`), names of enumerations, lengths that follow from the order.
//! The values themselves are checked by famcc-core when the spec is built.

use crate::differentiator::HighGain;
use crate::errors::{config_err_got, ConfigFault};
use crate::laws::Law;
use crate::names::{ConstraintName, CONSTRAINT, DIRECTION, DTYPE, GAMMA, LATCH, TRANSITION};
use crate::observer::Observer;
use crate::skews::SkewSpec;
use crate::spec::{RhoE, Spec};
use famcc_core::config::{check_order, MAX_ORDER};
use famcc_core::{differentiator, Constraint};
use pyo3::prelude::*;
use pyo3::types::{PyList, PyTuple};

/// The `differentiator` argument: a HighGain, the string "auto", or None.
#[derive(FromPyObject)]
pub enum DiffArg<'py> {
    Gain(Bound<'py, HighGain>),
    Name(String),
    Other(Bound<'py, PyAny>),
}

/// The `rho_e` argument: a float, the string "auto", or None.
#[derive(FromPyObject)]
pub enum RhoArg<'py> {
    Value(f64),
    Name(String),
    Other(Bound<'py, PyAny>),
}

/// The keyword `"auto"`: famcc-core's default.
pub const AUTO: &str = "auto";

/// Every argument of the constructor, as pyo3 extracted it.
pub struct Args<'a, 'py> {
    pub order: i64,
    pub dt: f64,
    pub feedback: Option<&'a Bound<'py, PyAny>>,
    pub skew: Option<&'a Bound<'py, PyAny>>,
    pub constraint: &'a str,
    pub eps: &'a Bound<'py, PyAny>,
    pub settle_time: f64,
    pub k0: f64,
    pub k_u: f64,
    pub gamma: &'a str,
    pub rho_e: Option<RhoArg<'py>>,
    pub differentiator: Option<DiffArg<'py>>,
    pub latch: &'a str,
    pub transition: &'a str,
    pub direction: &'a str,
    pub initial_derivatives: Option<Vec<f64>>,
    pub dtype: &'a str,
    pub integral: bool,
    pub output_limits: Option<(f64, f64)>,
    pub rate_limit: Option<f64>,
    pub initial_output: Option<f64>,
    pub observer: Option<Observer>,
    pub cancellation_limit: Option<f64>,
}

/// One value for every stage, or a list or tuple of exactly `n`; `parameter`
/// and `rule` name the list in the error for a wrong length.
pub fn per_stage<'py, T>(
    obj: &Bound<'py, PyAny>,
    n: usize,
    (parameter, rule): (&str, &str),
    one: impl Fn(&Bound<'py, PyAny>) -> PyResult<T>,
) -> PyResult<Vec<T>> {
    if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
        let items: Vec<Bound<'py, PyAny>> = obj.try_iter()?.collect::<PyResult<_>>()?;
        if items.len() != n {
            let message = format!(
                "{parameter} {rule} = {n} entries (one per stage), got {}",
                items.len()
            );
            return Err(ConfigFault::new(parameter, rule).message(message).into());
        }
        items.iter().map(&one).collect()
    } else {
        (0..n).map(|_| one(obj)).collect()
    }
}

/// `parameter` must be one of the listed kinds (the message shows `got`).
fn not_a(parameter: &str, rule: &str, got: String) -> PyErr {
    ConfigFault::new(parameter, rule).got(got).into()
}

/// The number of stages of the law: `order - 1`, or `order` with integral
/// action.
pub fn stage_count(order: usize, integral: bool) -> usize {
    order - 1 + usize::from(integral)
}

/// The `feedback` argument: one law per stage.
pub fn parse_laws(feedback: Option<&Bound<'_, PyAny>>, order: usize, integral: bool) -> PyResult<Vec<Law>> {
    let n = stage_count(order, integral);
    let rule = if integral {
        "must have order (integral=True: one law per stage of the order + 1 law)"
    } else {
        "must have order - 1"
    };
    match feedback {
        Some(f) if n == 0 => {
            if !f.len().map(|l| l == 0).unwrap_or(false) {
                return Err(ConfigFault::new(
                    "feedback",
                    "must be omitted (or empty) at order 1: there are no stages",
                )
                .into());
            }
            Ok(vec![])
        }
        Some(f) => per_stage(f, n, ("feedback", rule), |o| Law::extract_named(o, "feedback")),
        None if n == 0 => Ok(vec![]),
        None => Err(ConfigFault::new("feedback", "is required for order >= 2 (one law per stage)").into()),
    }
}

/// The `skew` argument: one skew (or None) per stage.
pub fn parse_skews(
    skew: Option<&Bound<'_, PyAny>>,
    order: usize,
    integral: bool,
) -> PyResult<Vec<Option<SkewSpec>>> {
    let n = stage_count(order, integral);
    match skew {
        Some(s) if n > 0 => per_stage(
            s,
            n,
            (
                "skew",
                if integral {
                    "must have order"
                } else {
                    "must have order - 1"
                },
            ),
            SkewSpec::extract,
        ),
        _ => Ok(vec![None; n]),
    }
}

/// The `differentiator` argument at `order`.
pub fn parse_differentiator(arg: Option<DiffArg<'_>>, order: usize) -> PyResult<Option<HighGain>> {
    const RULE: &str = "must be a HighGain, 'auto' or None";
    match arg {
        None => Ok(None),
        Some(DiffArg::Name(s)) if s == AUTO => differentiator::needed_at(order)
            .then(|| HighGain::auto(order))
            .transpose(),
        Some(DiffArg::Name(s)) => Err(not_a("differentiator", RULE, format!("{s:?}"))),
        Some(DiffArg::Other(o)) => Err(not_a("differentiator", RULE, o.repr()?.to_string())),
        Some(DiffArg::Gain(h)) => {
            let h = h.get().clone();
            if h.a.len() != order {
                let rule = format!("must have {order} coefficients (the order)");
                let message = format!("differentiator.a {rule}, got {}", h.a.len());
                return Err(ConfigFault::new("differentiator.a", rule).message(message).into());
            }
            Ok(Some(h))
        }
    }
}

/// The `initial_derivatives` argument: `z2..zn`, `order - 1` of them.
pub fn check_initial_derivatives(d: Option<&[f64]>, order: usize) -> PyResult<()> {
    match d {
        Some(d) if d.len() != order - 1 => {
            let rule = format!("must have order - 1 = {} entries (z2..zn)", order - 1);
            let message = format!("initial_derivatives {rule}, got {}", d.len());
            Err(ConfigFault::new("initial_derivatives", rule)
                .message(message)
                .into())
        }
        _ => Ok(()),
    }
}

/// The `rho_e` argument.
pub fn parse_rho_e(arg: Option<RhoArg<'_>>) -> PyResult<RhoE> {
    const RULE: &str = "must be a float, 'auto' or None";
    match arg {
        None => Ok(RhoE::Given(None)),
        Some(RhoArg::Value(v)) => Ok(RhoE::Given(Some(v))),
        Some(RhoArg::Name(s)) if s == AUTO => Ok(RhoE::Default),
        Some(RhoArg::Name(s)) => Err(not_a("rho_e", RULE, format!("{s:?}"))),
        Some(RhoArg::Other(o)) => Err(not_a("rho_e", RULE, o.repr()?.to_string())),
    }
}

impl Args<'_, '_> {
    /// The typed specification.
    pub fn parse(self) -> PyResult<Spec> {
        let order = usize::try_from(self.order).unwrap_or(0);
        check_order(order).map_err(|e| config_err_got(e, self.order))?;
        if self.integral && order >= MAX_ORDER {
            let rule = format!(
                "needs order <= {} (the law has order + 1 <= MAX_ORDER = {MAX_ORDER})",
                MAX_ORDER - 1
            );
            let message = format!("integral=True {rule}, got {order}");
            return Err(ConfigFault::new("integral", rule).message(message).into());
        }
        let laws = parse_laws(self.feedback, order, self.integral)?;
        let skews = parse_skews(self.skew, order, self.integral)?;
        let constraint = parse_constraint(CONSTRAINT.parse(self.constraint, "constraint")?, self.eps)?;
        // The observer replaces the differentiator: "auto" then means none.
        let differentiator = match (&self.observer, &self.differentiator) {
            (Some(_), Some(DiffArg::Name(s))) if s == AUTO => None,
            _ => parse_differentiator(self.differentiator, order)?,
        };
        check_initial_derivatives(self.initial_derivatives.as_deref(), order)?;
        let rho_e = parse_rho_e(self.rho_e)?;
        Ok(Spec {
            order,
            dt: self.dt,
            stages: laws.into_iter().zip(skews).collect(),
            constraint,
            settle_time: self.settle_time,
            k0: self.k0,
            k_u: self.k_u,
            gamma: GAMMA.parse(self.gamma, "gamma")?,
            rho_e,
            latch: LATCH.parse(self.latch, "latch")?,
            transition: TRANSITION.parse(self.transition, "transition")?,
            direction: DIRECTION.parse(self.direction, "direction")?,
            differentiator,
            initial_derivatives: self.initial_derivatives,
            dtype: DTYPE.parse(self.dtype, "dtype")?,
            integral: self.integral,
            output_limits: self.output_limits,
            rate_limit: self.rate_limit,
            initial_output: self.initial_output,
            observer: self.observer,
            cancellation_limit: self.cancellation_limit,
        })
    }
}

/// The constraint of a type with the `eps` argument: a float, or the pair
/// `(eps_x, eps_y)` for the oblique type.
pub fn parse_constraint(kind: ConstraintName, eps: &Bound<'_, PyAny>) -> PyResult<Constraint<f64>> {
    if kind == ConstraintName::Oblique {
        let (eps_x, eps_y): (f64, f64) = eps.extract().map_err(|_| {
            PyErr::from(ConfigFault::new(
                "eps",
                "must be a pair (eps_x, eps_y) for the oblique constraint",
            ))
        })?;
        return Ok(Constraint::Oblique { eps_x, eps_y });
    }
    let eps: f64 = eps
        .extract()
        .map_err(|_| PyErr::from(ConfigFault::new("eps", "must be a float")))?;
    Ok(match kind {
        ConstraintName::Lateral => Constraint::Lateral { eps },
        _ => Constraint::Longitudinal { eps },
    })
}
