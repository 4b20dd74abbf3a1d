//! One Python class over famcc-core's controllers of every order
//! (1..=MAX_ORDER) in f64 and f32: the enum that holds one of them, and the
//! macros that run code on whichever it holds.

use crate::diagnostics::Diagnostics;
use crate::errors::{config_err, kind, step_err, StepFault};
use crate::names::DType;
use crate::orders::to_array;
use crate::spec::Spec;
use crate::state;
use famcc_core::config::check_order;
use famcc_core::{ConfigError, Controller, Real, StepError};
use pyo3::{PyErr, PyResult};

macro_rules! cores {
    ($($v64:ident, $v32:ident, $n:literal;)*) => {
        /// A famcc-core controller of a run-time-chosen order and float type.
        #[derive(Clone, Debug)]
        #[allow(clippy::large_enum_variant)]
        pub enum Core { $($v64(Controller<f64, $n>), $v32(Controller<f32, $n>),)* }

        /// Many controllers of one order and float type, stored contiguously.
        #[derive(Clone, Debug)]
        pub enum BankCores { $($v64(Vec<Controller<f64, $n>>), $v32(Vec<Controller<f32, $n>>),)* }

        impl Core {
            /// `n` copies of this controller.
            pub fn replicate(&self, n: usize) -> BankCores {
                match self { $(Core::$v64(c) => BankCores::$v64(vec![*c; n]), Core::$v32(c) => BankCores::$v32(vec![*c; n]),)* }
            }
        }

        /// Runs `$body` with `$v` bound to the concrete vector of controllers.
        macro_rules! with_bank {
            ($bank:expr, $v:ident => $body:expr) => {
                match $bank { $(BankCores::$v64($v) => $body, BankCores::$v32($v) => $body,)* }
            };
        }
        pub(crate) use with_bank;

        /// Runs `$body` with `$c` bound to the concrete controller.
        macro_rules! with_core {
            ($core:expr, $c:ident => $body:expr) => {
                match $core { $(Core::$v64($c) => $body, Core::$v32($c) => $body,)* }
            };
        }

        impl Core {
            /// The controller `spec` describes.
            pub fn build(spec: &Spec) -> Result<Self, ConfigError> {
                match (spec.law_order(), spec.dtype) {
                    $(($n, DType::F64) => spec.config::<f64, $n>().map(|c| Core::$v64(Controller::new(c))),
                      ($n, DType::F32) => spec.config::<f32, $n>().map(|c| Core::$v32(Controller::new(c))),)*
                    (n, _) => Err(match check_order(n) {
                        Err(e) => e,
                        Ok(()) => ConfigError::new("order", "is not compiled into this binding"),
                    }),
                }
            }
        }
    };
}

cores! {
    D1, S1, 1; D2, S2, 2; D3, S3, 3; D4, S4, 4; D5, S5, 5; D6, S6, 6; D7, S7, 7; D8, S8, 8;
}

// The variants above are the orders 1..=MAX_ORDER.
const _: () = assert!(famcc_core::config::MAX_ORDER == 8);

/// A finite f64 that is out of range for an f32 core is an overflow, not a
/// non-finite input.
#[inline(always)]
fn check_range<T: Real>(e: f64, ec: T, applied: Option<f64>, ac: Option<T>) -> Result<(), StepError> {
    if e.is_finite() && !ec.is_finite() {
        return Err(StepError::Overflow);
    }
    if let (Some(a), Some(ac)) = (applied, ac) {
        if a.is_finite() && !ac.is_finite() {
            return Err(StepError::Overflow);
        }
    }
    Ok(())
}

impl Core {
    /// The output accuracy the configuration presets (famcc-core's
    /// `Config::output_accuracy`).
    pub fn output_accuracy(&self) -> Option<f64> {
        with_core!(self, c => c.config().output_accuracy().map(|x| x.to_f64_lossless()))
    }

    /// The corollaries' reaching time `T'` for the initial error `z1_0`
    /// (famcc-core's `Config::corollary_time`).
    pub fn corollary_time(&self, z1_0: f64) -> Option<f64> {
        with_core!(self, c => c.config().corollary_time(Real::from_f64(z1_0)).map(|x| x.to_f64_lossless()))
    }

    /// The flexible-boundary margin in effect.
    pub fn rho_e(&self) -> Option<f64> {
        with_core!(self, c => c.config().rho_e().map(|x| x.to_f64_lossless()))
    }

    #[inline]
    pub fn step(&mut self, e: f64, applied: Option<f64>) -> Result<f64, StepError> {
        with_core!(self, c => {
            let (ec, ac) = (Real::from_f64(e), applied.map(Real::from_f64));
            check_range(e, ec, applied, ac)?;
            c.step_applied(ec, ac).map(|v| v.to_f64_lossless())
        })
    }

    /// The lint findings of the configuration (famcc-core's `Config::lint`), as text.
    pub fn lint(&self) -> Vec<String> {
        with_core!(self, c => c.config().lint().iter().map(|f| f.to_string()).collect())
    }

    /// The core's health finding (`Controller::health`), if any.
    #[inline]
    pub fn health(&self) -> Option<famcc_core::Health> {
        with_core!(self, c => c.health())
    }

    pub fn step_output(&mut self, y: f64, y_d: f64, applied: Option<f64>) -> Result<f64, StepError> {
        with_core!(self, c => {
            let (yc, ydc, ac) = (Real::from_f64(y), Real::from_f64(y_d), applied.map(Real::from_f64));
            check_range(y, yc, applied, ac)?;
            check_range(y_d, ydc, None, None)?;
            c.step_output(yc, ydc, ac).map(|v| v.to_f64_lossless())
        })
    }

    pub fn step_dt(&mut self, e: f64, dt: f64, applied: Option<f64>) -> Result<f64, StepError> {
        with_core!(self, c => {
            let (ec, ac) = (Real::from_f64(e), applied.map(Real::from_f64));
            check_range(e, ec, applied, ac)?;
            c.step_dt(ec, Real::from_f64(dt), ac).map(|v| v.to_f64_lossless())
        })
    }

    /// A state-feedback step from the plant's `z = (z1..zn)`; with integral
    /// action the core's vector gets a leading slot (its own integral).
    pub fn step_state(&mut self, z: &[f64], applied: Option<f64>, integral: bool) -> PyResult<f64> {
        let off = usize::from(integral);
        with_core!(self, c => {
            let full: Vec<f64> = core::iter::repeat_n(0.0, off).chain(z.iter().copied()).collect();
            let z = to_array(&full).ok_or_else(|| {
                let message = format!("z must have {} entries (one per order), got {}", c.estimate().len() - off, z.len());
                PyErr::from(StepFault::new(kind::WRONG_LENGTH, Some("z"), message))
            })?;
            c.step_state_applied(z, applied.map(Real::from_f64)).map(|v| v.to_f64_lossless()).map_err(|e| step_err(e, "z"))
        })
    }

    pub fn reset(&mut self) {
        with_core!(self, c => c.reset())
    }

    pub fn diagnostics(&self) -> Diagnostics {
        with_core!(self, c => Diagnostics::from_core(&c.diagnostics()))
    }

    pub fn time(&self) -> f64 {
        with_core!(self, c => c.time())
    }

    pub fn estimate(&self) -> Vec<f64> {
        with_core!(self, c => c.estimate().iter().map(|x| x.to_f64_lossless()).collect())
    }

    /// The observer's estimate of the lumped term (0 without one).
    pub fn lumped(&self) -> f64 {
        with_core!(self, c => c.lumped().to_f64_lossless())
    }

    pub fn state(&self) -> Vec<f64> {
        with_core!(self, c => state::to_vec(c))
    }

    pub fn set_state(&mut self, v: &[f64]) -> PyResult<()> {
        with_core!(self, c => state::restore(c, v).map_err(config_err))
    }
}

impl Core {
    /// The last step's diagnostics as famcc-sim records them.
    pub fn sim_diag(&self) -> famcc_sim::Diag {
        with_core!(self, c => famcc_sim::Diag::of(c))
    }
}
