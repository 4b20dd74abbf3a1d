//! The arguments of `famcc.Controller(...)`, parsed into a typed [`Spec`]:
//! Python shapes (one value or one per stage, a float or a pair for `eps`,
//! `"auto"`), names of enumerations, lengths that follow from the order.
//! The values themselves are checked by famcc-core when the spec is built.

use crate::differentiator::HighGain;
use crate::errors::ConfigError;
use crate::laws::Law;
use crate::names::{ConstraintName, CONSTRAINT, DTYPE, GAMMA, LATCH, TRANSITION};
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
    pub initial_derivatives: Option<Vec<f64>>,
    pub dtype: &'a str,
    pub integral: bool,
    pub output_limits: Option<(f64, f64)>,
    pub rate_limit: Option<f64>,
    pub initial_output: Option<f64>,
}

/// One value for every stage, or a list or tuple of exactly `n`.
pub fn per_stage<'py, T>(
    obj: &Bound<'py, PyAny>,
    n: usize,
    what: &str,
    one: impl Fn(&Bound<'py, PyAny>) -> PyResult<T>,
) -> PyResult<Vec<T>> {
    if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
        let items: Vec<Bound<'py, PyAny>> = obj.try_iter()?.collect::<PyResult<_>>()?;
        if items.len() != n {
            return Err(ConfigError::new_err(format!(
                "{what} = {n} entries (one per stage), got {}",
                items.len()
            )));
        }
        items.iter().map(&one).collect()
    } else {
        (0..n).map(|_| one(obj)).collect()
    }
}

fn not_a(what: &str, got: String) -> PyErr {
    ConfigError::new_err(format!("{what} (got {got})"))
}

impl Args<'_, '_> {
    /// The typed specification.
    pub fn parse(self) -> PyResult<Spec> {
        let order = usize::try_from(self.order).unwrap_or(0);
        check_order(order).map_err(|e| ConfigError::new_err(format!("{e} (got {})", self.order)))?;
        if self.integral && order >= MAX_ORDER {
            return Err(ConfigError::new_err(format!(
                "integral=True needs order <= {} (the law has order + 1 <= MAX_ORDER = {MAX_ORDER}), got {order}",
                MAX_ORDER - 1
            )));
        }
        // Stages of the law: order - 1, or order with integral action.
        let n = order - 1 + usize::from(self.integral);
        let stages_rule = if self.integral {
            "feedback must have order (integral=True: one law per stage of the order + 1 law)"
        } else {
            "feedback must have order - 1"
        };
        let laws: Vec<Law> = match self.feedback {
            Some(f) if n == 0 => {
                if !f.len().map(|l| l == 0).unwrap_or(false) {
                    return Err(ConfigError::new_err(
                        "feedback must be omitted (or empty) at order 1: there are no stages",
                    ));
                }
                vec![]
            }
            Some(f) => per_stage(f, n, stages_rule, |o| Law::extract_named(o, "feedback"))?,
            None if n == 0 => vec![],
            None => {
                return Err(ConfigError::new_err(
                    "feedback is required for order >= 2 (one law per stage)",
                ))
            }
        };
        let skews: Vec<Option<SkewSpec>> = match self.skew {
            Some(s) if n > 0 => per_stage(
                s,
                n,
                if self.integral {
                    "skew must have order"
                } else {
                    "skew must have order - 1"
                },
                SkewSpec::extract,
            )?,
            _ => vec![None; n],
        };
        let constraint = parse_constraint(CONSTRAINT.parse(self.constraint, "constraint")?, self.eps)?;
        let differentiator = match self.differentiator {
            None => None,
            Some(DiffArg::Name(s)) if s == AUTO => differentiator::needed_at(order)
                .then(|| HighGain::auto(order))
                .transpose()?,
            Some(DiffArg::Name(s)) => {
                return Err(not_a(
                    "differentiator must be a HighGain, 'auto' or None",
                    format!("{s:?}"),
                ))
            }
            Some(DiffArg::Other(o)) => {
                return Err(not_a(
                    "differentiator must be a HighGain, 'auto' or None",
                    o.repr()?.to_string(),
                ))
            }
            Some(DiffArg::Gain(h)) => {
                let h = h.get().clone();
                if h.a.len() != order {
                    return Err(ConfigError::new_err(format!(
                        "differentiator.a must have {order} coefficients (the order), got {}",
                        h.a.len()
                    )));
                }
                Some(h)
            }
        };
        if let Some(d) = &self.initial_derivatives {
            if d.len() != order - 1 {
                return Err(ConfigError::new_err(format!(
                    "initial_derivatives must have order - 1 = {} entries (z2..zn), got {}",
                    order - 1,
                    d.len()
                )));
            }
        }
        let rho_e = match self.rho_e {
            None => RhoE::Given(None),
            Some(RhoArg::Value(v)) => RhoE::Given(Some(v)),
            Some(RhoArg::Name(s)) if s == AUTO => RhoE::Default,
            Some(RhoArg::Name(s)) => {
                return Err(not_a("rho_e must be a float, 'auto' or None", format!("{s:?}")))
            }
            Some(RhoArg::Other(o)) => {
                return Err(not_a(
                    "rho_e must be a float, 'auto' or None",
                    o.repr()?.to_string(),
                ))
            }
        };
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
            differentiator,
            initial_derivatives: self.initial_derivatives,
            dtype: DTYPE.parse(self.dtype, "dtype")?,
            integral: self.integral,
            output_limits: self.output_limits,
            rate_limit: self.rate_limit,
            initial_output: self.initial_output,
        })
    }
}

/// The constraint of a type with the `eps` argument: a float, or the pair
/// `(eps_x, eps_y)` for the oblique type.
fn parse_constraint(kind: ConstraintName, eps: &Bound<'_, PyAny>) -> PyResult<Constraint<f64>> {
    if kind == ConstraintName::Oblique {
        let (eps_x, eps_y): (f64, f64) = eps.extract().map_err(|_| {
            ConfigError::new_err("eps must be a pair (eps_x, eps_y) for the oblique constraint")
        })?;
        return Ok(Constraint::Oblique { eps_x, eps_y });
    }
    let eps: f64 = eps
        .extract()
        .map_err(|_| ConfigError::new_err("eps must be a float"))?;
    Ok(match kind {
        ConstraintName::Lateral => Constraint::Lateral { eps },
        _ => Constraint::Longitudinal { eps },
    })
}
