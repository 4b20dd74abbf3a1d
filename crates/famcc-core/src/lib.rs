//! # famcc-core
//!
//! Fully actuated manifold constraint control (FAMCC): a model-free output
//! feedback law that drives the tracking error of an unknown strict-feedback
//! plant to a preset accuracy within a preset time, and keeps working when the
//! actuator saturates (Mu, Hua, Li, Chen, Wei: "Fully actuated manifold
//! constraint based output feedback control for input-constrained uncertain
//! nonlinear systems").
//!
//! This crate is `no_std`, allocation-free and generic over `f32`/`f64`
//! ([`Real`]) and the system order (const `N`). Each paper concept has one
//! module (equation numbers as printed in the paper, LaTeX labels in
//! parentheses; the map is docs/equations.md):
//!
//! | module | paper |
//! |---|---|
//! | [`transition`] | Definitions 1-3, eqs. (1)-(3) (trnsT, trnsS, trnsU) |
//! | [`envelope`] | eq. (4) (rho), the latch after eqs. (21)-(22) (xUxL, yUyL) |
//! | [`gamma`] | the maps Gamma of eq. (29) (uT) |
//! | [`jet`] | time derivatives for eq. (12) (ISFM) |
//! | [`feedback`] | h_p: eqs. (59) lfmi, (37) fn, (61) RFCs, (45) fxe, (58) fvec |
//! | [`skew`] | eqs. (14) SSMD, (15) NSMD |
//! | [`manifold`] | eq. (11) (IS) |
//! | [`constraint`] | eqs. (21)-(22), (26)-(28) (gradient, xyc, xi), (30)-(31) (WxyUxyL, Wxi) |
//! | [`differentiator`] | eq. (34) (HGD) |
//! | [`config`] | the parameters and their rules, the defaults |
//! | [`controller`] | eqs. (29) uT, (32) WuT, (35) uOF |
//! | [`direction`] | beyond the paper's Assumption 1 (`G > 0`): the sign of `G` |
//! | [`bounds`] | Corollaries 1-3 |
//!
//! ```
//! use famcc_core::{Config, Constraint, Controller, Feedback, HighGain};
//! let cfg = Config::<f32, 2>::builder(1e-3, &[(Feedback::FiniteTime { k: 1.0, p: 0.5 }, None)],
//!                                     Constraint::Lateral { eps: 0.1 }, 5.0)
//!     .differentiator(Some(HighGain::paper()))
//!     .build()?;
//! let mut ctrl = Controller::new(cfg);
//! let v = ctrl.step(-1.0)?;           // Result<f32, StepError>, never NaN
//! # assert!(v.is_finite());
//! # Ok::<(), Box<dyn core::error::Error>>(())
//! ```
//!
//! ## Cargo features
//!
//! Every design is compiled by default (feature `all`). A firmware that
//! configures one design can depend on famcc-core with
//! `default-features = false` and that design's features alone: the other
//! variants cost no flash, and [`ConfigBuilder::build`] rejects them with a
//! [`ConfigError`] that names the feature to enable.
//!
//! | feature | compiles |
//! |---|---|
//! | (always) | the linear and finite-time laws, the longitudinal constraint, the exponential, cubic and quintic transitions |
//! | `fixed-time` | [`Feedback::FixedTime`] |
//! | `variable-exponent` | [`Feedback::VariableExponent`], [`Feedback::MoulayDiscontinuous`] |
//! | `skew` | [`Skew`] (SSMD and NSMD) |
//! | `sine` | [`Transition::Sine`] |
//! | `lateral` | [`Constraint::Lateral`] |
//! | `oblique` | [`Constraint::Oblique`] |
//! | `bumpless` | the bumpless start ([`ConfigBuilder::initial_output`]) |
//! | `integral` | integral action ([`ConfigBuilder::integral`]) |
//! | `one-off-period` | steps at another period than `dt` ([`Controller::step_dt`]), and restoring a state taken at one; without it the clock never leaves `T` (no soft-float `f64` on a single-precision FPU) |
//! | `first-order-hold` | the differentiator's [`Discretization::Foh`] (its feedthrough in the step, and its restart, which starts a clock run in `f64`) |
//! | `observer` | the extended high-gain differentiator `ExtendedHighGain` in place of the differentiator, its estimate of the lumped term cancelled, bounded, inside the law ([`ConfigBuilder::observer`]; disturbance estimation, docs/observer.md) |
#![no_std]
#![forbid(unsafe_code)]
#![cfg_attr(
    not(test),
    deny(
        clippy::unwrap_used,
        clippy::expect_used,
        clippy::panic,
        clippy::indexing_slicing
    )
)]
#![warn(missing_docs)]

#[cfg(test)]
extern crate std;

pub mod bounds;
mod compiled;
pub mod config;
pub mod constraint;
pub mod controller;
pub mod design;
pub mod differentiator;
pub mod direction;
pub mod envelope;
pub mod error;
pub mod feedback;
mod float;
pub mod gamma;
pub mod jet;
pub mod manifold;
pub mod skew;
pub mod transition;

#[cfg(feature = "observer")]
pub use config::DEFAULT_CANCELLATION_SHARE;
pub use config::{Config, ConfigBuilder};
pub use constraint::Constraint;
pub use controller::{
    probe_error, probe_errors, Controller, Diagnostics, Health, Snapshot, PROBE_COUNT, PROBE_LIMIT,
    PROBE_PER_DECADE, RECOVERY_SAMPLES, SNAPSHOT_FIELDS,
};
#[cfg(feature = "observer")]
pub use differentiator::{DiscreteExtended, ExtendedHighGain};
pub use differentiator::{DiscreteHgd, Discretization, HighGain};
pub use direction::Direction;
pub use envelope::{Envelope, Latch};
pub use error::{ConfigError, StepError};
pub use feedback::Feedback;
pub use float::Real;
pub use gamma::Gamma;
pub use jet::Jet;
pub use skew::{Skew, SkewKind, SkewedLaw};
pub use transition::Transition;
