//! The Python names of famcc-core's enumerations: one table per type, used
//! both to parse arguments and to write them back (`repr`, `config()`,
//! pickling). A default argument is the name of the core's `Default`.

use crate::errors::ConfigFault;
use famcc_core::{Direction, Discretization, Gamma, Latch, Transition};
use pyo3::PyResult;

/// The names of an enumeration's values.
pub struct Names<E: 'static> {
    table: &'static [(&'static str, E)],
}

impl<E: Copy + PartialEq> Names<E> {
    /// The value named `name`; the error names the argument `arg` and lists
    /// the choices.
    pub fn parse(&self, name: &str, arg: &str) -> PyResult<E> {
        self.table
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, e)| *e)
            .ok_or_else(|| {
                let list: Vec<String> = self.table.iter().map(|(n, _)| format!("'{n}'")).collect();
                ConfigFault::new(arg, format!("must be one of {}", list.join(", ")))
                    .got(format!("{name:?}"))
                    .into()
            })
    }

    /// The name of `value`.
    pub fn name(&self, value: E) -> &'static str {
        self.table
            .iter()
            .find(|(_, e)| *e == value)
            .map_or("?", |(n, _)| n)
    }

    /// The name of the core's default value.
    pub fn default_name(&self) -> &'static str
    where
        E: Default,
    {
        self.name(E::default())
    }
}

pub const GAMMA: Names<Gamma> = Names {
    table: &[("log", Gamma::Log), ("rational", Gamma::Rational)],
};

pub const LATCH: Names<Latch> = Names {
    table: &[("paper", Latch::Paper), ("authors", Latch::Authors)],
};

pub const DIRECTION: Names<Direction> = Names {
    table: &[
        ("positive", Direction::Positive),
        ("negative", Direction::Negative),
    ],
};

pub const TRANSITION: Names<Transition> = Names {
    table: &[
        ("exponential", Transition::Exponential),
        ("cubic", Transition::Cubic),
        ("quintic", Transition::Quintic),
        ("sine", Transition::Sine),
    ],
};

pub const DISCRETIZATION: Names<Discretization> = Names {
    table: &[
        ("exact", Discretization::Exact),
        ("euler", Discretization::Euler),
        ("tustin", Discretization::Tustin),
        ("foh", Discretization::Foh),
    ],
};

/// The float type of a controller.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum DType {
    #[default]
    F64,
    F32,
}

pub const DTYPE: Names<DType> = Names {
    table: &[("float64", DType::F64), ("float32", DType::F32)],
};

/// The constraint types (the final widths are the `eps` argument). A call
/// that names none gets LoMC, the constraint on `s` itself.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum ConstraintName {
    #[default]
    Longitudinal,
    Lateral,
    Oblique,
}

pub const CONSTRAINT: Names<ConstraintName> = Names {
    table: &[
        ("longitudinal", ConstraintName::Longitudinal),
        ("lateral", ConstraintName::Lateral),
        ("oblique", ConstraintName::Oblique),
    ],
};

/// The type of a core constraint.
pub fn constraint_name(c: &famcc_core::Constraint<f64>) -> ConstraintName {
    match c {
        famcc_core::Constraint::Longitudinal { .. } => ConstraintName::Longitudinal,
        famcc_core::Constraint::Lateral { .. } => ConstraintName::Lateral,
        famcc_core::Constraint::Oblique { .. } => ConstraintName::Oblique,
    }
}

/// The paper's variants (famcc-paper).
pub const VARIANT: Names<famcc_paper::Variant> = Names {
    table: &[
        ("paper", famcc_paper::Variant::Paper),
        ("code", famcc_paper::Variant::Code),
    ],
};
