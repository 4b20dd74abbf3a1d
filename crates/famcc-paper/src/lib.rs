//! # famcc-paper
//!
//! The paper's three example designs and its two plants, in both variants
//! (docs/design.md §6): the one place where their numbers are written.
//! famcc-core's tests and benches, the firmware's closed loops
//! (`embedded/`), the C ABI's tests and the Python scenarios (through the
//! binding) all take them from here.
//!
//! - [`designs`]: examples 1-3 as validated [`famcc_core::Config`]s, their
//!   input limits and the corollaries' settling bounds;
//! - [`plants`]: the second- and third-order plants in strict-feedback form
//!   (eq. (5), SFS), generic over `f32`/`f64`, with their exact output
//!   derivatives and their gain and drift (eq. (7), FAS) from jets;
//! - [`rk4`]: the one RK4 step of the project (any state length).
//!
//! `no_std`, no heap, no panics, like famcc-core.
//!
//! ```
//! use famcc_core::Controller;
//! use famcc_paper::designs::{self, Variant};
//! use famcc_paper::plants::{self, Clock, Plant, SecondOrder};
//! let mut ctrl = Controller::new(designs::example1::<f64>(Variant::Code, 1e-3)?);
//! let plant = SecondOrder::new(Variant::Code);
//! let mut x = plant.x0();
//! for k in 0..1000 {
//!     let t = k as f64 * 1e-3;
//!     let u = ctrl.step(x[0] - t.sin())?.clamp(-100.0, 100.0);
//!     let clocks = [Clock::at(t), Clock::at(t + 0.5e-3), Clock::at(t + 1e-3)];
//!     x = plants::rk4(&plant, &clocks, &x, u, 1e-3);
//! }
//! assert!((x[0] - 1.0_f64.sin()).abs() < 0.5);
//! # Ok::<(), Box<dyn core::error::Error>>(())
//! ```
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

pub mod designs;
pub mod plants;
pub mod rk4;
pub mod variant;

pub use designs::Example;
pub use variant::Variant;
