//! # famcc-sim
//!
//! The sampled-data simulator behind `famcc.simulate`, `famcc.joints` and
//! `famcc.campaign` (docs/architecture.md): one sample-and-hold loop
//! ([`Lockstep`]) that runs `lanes` independent copies of a closed loop in
//! lockstep, each with `channels` single-output controllers (one per joint of
//! a multi-input plant). At sample `k` (time `t_k = k dt`) every controller
//! reads its error `e_k = y(t_k) - y_d(t_k)` (plus measurement noise), returns
//! `v_k`, and the actuator holds `u_k = clip(v_k)` (plus an input
//! disturbance) until `t_{k+1}` while the plant is integrated with
//! `substeps` steps of famcc-paper's RK4 ([`famcc_paper::rk4`]).
//!
//! The plant ([`Plant`]) and the controllers ([`Controllers`]) are traits:
//! the paper's plants as lanes ([`PaperLanes`]) and famcc-core's controllers
//! ([`control`]) are here; the Python binding adds plants and controllers
//! written in Python. What a run records is a [`Record`]; why a lane
//! stopped is a [`Stop`].
//!
//! ```
//! use famcc_core::Controller;
//! use famcc_paper::designs::{example1, Variant};
//! use famcc_sim::{control::Cores, Detail, Lockstep, Options, PaperLanes, Record};
//! let mut ctrl = [Controller::new(example1::<f64>(Variant::Code, 1e-3)?)];
//! let plant = PaperLanes::second(Variant::Code, vec![1.0], vec![3.0]);
//! let opts = Options::single(1e-3, 3001, 10, 2, Some((-2.5, 3.0)));
//! let mut sim = Lockstep::new(opts, plant.x0())?;
//! let yd: Vec<f64> = (0..3001).map(|k| (k as f64 * 1e-3).sin()).collect();
//! let mut rec = Record::new(Detail::Full, true);
//! let mut cores = Cores::raising(&mut ctrl);
//! sim.run(&mut { plant }, &mut cores, &yd, None, None, &mut rec).map_err(|_| "failed")?;
//! assert_eq!(rec.rows, 3001);
//! assert!(rec.e.last().map_or(false, |e| e.abs() < 0.1));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
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

pub mod control;
mod lockstep;
mod options;
mod plant;
mod record;

pub use control::{Controllers, Diag};
pub use lockstep::{Failure, Lockstep};
pub use options::{Options, Reason, Stop};
pub use plant::{PaperLanes, Plant};
pub use record::{Detail, Record, CAMPAIGN_COLUMNS, FULL_COLUMNS};
