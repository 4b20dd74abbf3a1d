//! Which designs this build compiles (Cargo features).
//!
//! Every law, skew, transition and constraint type is compiled by default
//! (feature `all`); the features and what each compiles are listed in the
//! crate documentation ("Cargo features"). A variant compiled out costs no
//! flash: every function's arm for it is gone, and these checks make
//! [`crate::ConfigBuilder::build`] reject it with a [`ConfigError`] that
//! names the feature (tests/compiled_out.rs).

use crate::error::ConfigError;
use crate::{Constraint, Discretization, Feedback, SkewKind, Transition};

/// `Err` naming the feature when `parameter`'s variant is compiled out.
const fn require(compiled: bool, parameter: &'static str, rule: &'static str) -> Result<(), ConfigError> {
    if compiled {
        Ok(())
    } else {
        Err(ConfigError::new(parameter, rule))
    }
}

/// Checks that the law `h` is compiled into this build.
pub(crate) fn law<T>(h: &Feedback<T>) -> Result<(), ConfigError> {
    match h {
        Feedback::Linear { .. } | Feedback::FiniteTime { .. } => Ok(()),
        Feedback::FixedTime { .. } => require(
            cfg!(feature = "fixed-time"),
            "law",
            "fixed-time is compiled out of this build: enable famcc-core's Cargo feature `fixed-time`",
        ),
        Feedback::VariableExponent { .. } | Feedback::MoulayDiscontinuous { .. } => require(
            cfg!(feature = "variable-exponent"),
            "law",
            "variable-exponent is compiled out of this build: enable famcc-core's Cargo feature \
             `variable-exponent`",
        ),
    }
}

/// Checks that a skew of `kind` is compiled into this build.
pub(crate) fn skew<T>(_kind: &SkewKind<T>) -> Result<(), ConfigError> {
    require(
        cfg!(feature = "skew"),
        "skew",
        "is compiled out of this build: enable famcc-core's Cargo feature `skew`",
    )
}

/// Checks that the transition `t` is compiled into this build.
pub(crate) fn transition(t: Transition) -> Result<(), ConfigError> {
    require(
        cfg!(feature = "sine") || t != Transition::Sine,
        "transition",
        "sine is compiled out of this build: enable famcc-core's Cargo feature `sine`",
    )
}

/// Checks that the constraint type `c` is compiled into this build.
pub(crate) fn constraint<T>(c: &Constraint<T>) -> Result<(), ConfigError> {
    match c {
        Constraint::Longitudinal { .. } => Ok(()),
        Constraint::Lateral { .. } => require(
            cfg!(feature = "lateral"),
            "constraint",
            "lateral is compiled out of this build: enable famcc-core's Cargo feature `lateral`",
        ),
        Constraint::Oblique { .. } => require(
            cfg!(feature = "oblique"),
            "constraint",
            "oblique is compiled out of this build: enable famcc-core's Cargo feature `oblique`",
        ),
    }
}

/// Checks that the run-time options a configuration sets are compiled into
/// this build: the bumpless start (`initial_output`) and integral action.
pub(crate) fn options(initial_output: bool, integral: bool) -> Result<(), ConfigError> {
    require(
        !initial_output || cfg!(feature = "bumpless"),
        "initial_output",
        "(the bumpless start) is compiled out of this build: enable famcc-core's Cargo feature `bumpless`",
    )?;
    require(
        !integral || cfg!(feature = "integral"),
        "integral",
        "(integral action) is compiled out of this build: enable famcc-core's Cargo feature `integral`",
    )
}

/// True when the first-order hold is compiled: without it no recursion has a
/// feedthrough, and the step's and the restart's code for it is gone.
pub(crate) const FIRST_ORDER_HOLD: bool = cfg!(feature = "first-order-hold");

/// The error of a differentiator (or a precomputed recursion) with the
/// first-order hold in a build without it.
pub(crate) const FOH_COMPILED_OUT: &str =
    "foh (the first-order hold) is compiled out of this build: enable famcc-core's Cargo feature \
     `first-order-hold`";

/// Checks that the discretization `d` is compiled into this build.
pub(crate) fn discretization(d: Discretization) -> Result<(), ConfigError> {
    require(
        FIRST_ORDER_HOLD || d != Discretization::Foh,
        "discretization",
        FOH_COMPILED_OUT,
    )
}

/// True when a step (or a restored state) may take the period `dt`, the
/// nominal period being `nominal`: always with one-off periods compiled
/// (`step_dt`), otherwise only the nominal one.
#[inline(always)]
pub(crate) fn period_allowed<T: PartialEq>(dt: T, nominal: T) -> bool {
    cfg!(feature = "one-off-period") || dt == nominal
}

/// True when the clock's run goes on at the period `dt`: `dt` is the run's
/// `period`, or one-off periods are compiled out, so that every step and
/// every restored state has the nominal period and no run restarts (in
/// `f64`, soft-float on a single-precision FPU).
#[inline(always)]
pub(crate) fn continues_run<T: PartialEq>(dt: T, period: T) -> bool {
    !cfg!(feature = "one-off-period") || dt == period
}

/// True when one-off periods are compiled (the step rediscretizes for one).
pub(crate) const ONE_OFF_PERIOD: bool = cfg!(feature = "one-off-period");

/// The error of a restored state whose period is not the nominal one in a
/// build without one-off periods.
pub(crate) const PERIOD_COMPILED_OUT: ConfigError = ConfigError::new(
    "state.period",
    "differs from dt, and one-off periods are compiled out of this build: enable famcc-core's Cargo \
     feature `one-off-period`",
);
