//! The tables between the C ABI's `FAMCC_*` values and famcc-core's
//! enumeration values, and the lookups both ways.

use crate::types::*;
use famcc_core::{ConfigError, Direction, Discretization, Gamma, Latch, Transition};

/// A table of `FAMCC_*` values and the core's enumeration values.
pub(crate) type Table<E> = [(u32, E)];

pub(crate) const TRANSITIONS: [(u32, Transition); 4] = [
    (FamccTransition::Exponential as u32, Transition::Exponential),
    (FamccTransition::Cubic as u32, Transition::Cubic),
    (FamccTransition::Quintic as u32, Transition::Quintic),
    (FamccTransition::Sine as u32, Transition::Sine),
];
pub(crate) const GAMMAS: [(u32, Gamma); 2] = [
    (FamccGamma::Log as u32, Gamma::Log),
    (FamccGamma::Rational as u32, Gamma::Rational),
];
pub(crate) const DIRECTIONS: [(u32, Direction); 2] = [
    (FamccDirection::Positive as u32, Direction::Positive),
    (FamccDirection::Negative as u32, Direction::Negative),
];
pub(crate) const LATCHES: [(u32, Latch); 2] = [
    (FamccLatch::Paper as u32, Latch::Paper),
    (FamccLatch::Authors as u32, Latch::Authors),
];
pub(crate) const DISCRETIZATIONS: [(u32, Discretization); 4] = [
    (FamccDiscretization::Exact as u32, Discretization::Exact),
    (FamccDiscretization::Euler as u32, Discretization::Euler),
    (FamccDiscretization::Tustin as u32, Discretization::Tustin),
    (FamccDiscretization::Foh as u32, Discretization::Foh),
];

/// The core's value of the C value `v` (errors name `name` and the rule).
pub(crate) fn from_c<E: Copy>(
    table: &Table<E>,
    v: u32,
    name: &'static str,
    rule: &'static str,
) -> Result<E, ConfigError> {
    table
        .iter()
        .find(|(c, _)| *c == v)
        .map(|(_, e)| *e)
        .ok_or(ConfigError::new(name, rule))
}

/// The C value of the core's value `e`.
pub(crate) fn to_c<E: Copy + PartialEq>(table: &Table<E>, e: E) -> u32 {
    table.iter().find(|(_, x)| *x == e).map_or(u32::MAX, |(c, _)| *c)
}
