//! # famcc-core
//!
//! Fully actuated manifold constraint control (FAMCC): a model-free output
//! feedback law that drives the tracking error of an unknown strict-feedback
//! plant to a preset accuracy within a preset time, and keeps working when the
//! actuator saturates (Mu, Hua, Li, Chen, Wei: "Fully actuated manifold
//! constraint based output feedback control for input-constrained uncertain
//! nonlinear systems").
//!
//! This crate is `no_std` (unless the `std` feature is on), allocation-free
//! and generic over `f32`/`f64` ([`Real`]) and the system order (const `N`).
//! Each paper concept has one module:
//!
//! | module | paper |
//! |---|---|
//! | [`transition`] | Definitions 1-3, eqs. trnsT, trnsS, trnsU |
//! | [`envelope`] | eq. rho, the latch of eqs. xUxL/yUyL |
//! | [`gamma`] | the maps Gamma of eq. uT |
//! | [`jet`] | time derivatives for eq. ISFM |
//! | [`feedback`] | h_p: eqs. lfmi, fn, RFCs, fxe, fvec |
//! | [`skew`] | eqs. SSMD, NSMD |
//! | [`manifold`] | eq. IS |
//! | [`constraint`] | eqs. gradient, xyc, xi |
//! | [`flexible`] | eqs. WxyUxyL, Wxi |
//! | `differentiator` | eq. HGD |
//! | [`controller`] | eqs. uT, WuT, uOF |
//! | [`bounds`] | Corollaries 1-3 |
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

#[cfg(any(test, feature = "std"))]
extern crate std;

pub mod bounds;
mod config;
pub mod constraint;
pub mod controller;
pub mod design;
pub mod differentiator;
pub mod envelope;
pub mod error;
pub mod feedback;
pub mod flexible;
mod float;
pub mod gamma;
pub mod jet;
pub mod manifold;
pub mod skew;
pub mod transition;

pub use config::{Config, Constraint};
pub use constraint::ConstraintKind;
pub use controller::{Controller, Diagnostics, Snapshot};
pub use differentiator::{DiscreteHgd, Discretization, HighGain};
pub use envelope::{Envelope, Latch};
pub use error::{ConfigError, StepError};
pub use feedback::Feedback;
pub use float::Real;
pub use gamma::Gamma;
pub use jet::Jet;
pub use skew::{Skew, SkewKind, SkewedLaw};
pub use transition::Transition;
