//! What the loop must achieve ([`Requirements`]) and the rules the
//! requirements themselves must satisfy before a design is computed.

use super::{MAX_ORDER, MU_PER_DT, PHASE_BUDGET};
use crate::error::ConfigError;

/// What the loop must achieve, and the little the design needs to know of the
/// plant. Units: `dt`, `settle_time` in s; `eps` in the output's unit;
/// `u_limits`, `hold_input` in the input's unit; `gain` in output units per
/// `s^order` per input unit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Requirements {
    /// System order `n` (relative degree of the output), 1 to [`MAX_ORDER`].
    pub order: usize,
    /// Sample period, s.
    pub dt: f64,
    /// Actuator limits `(lo, hi)`, `lo < hi`.
    pub u_limits: (f64, f64),
    /// Required output accuracy `|y - y_d| < eps` after settling.
    pub eps: f64,
    /// Required settling time, s.
    pub settle_time: f64,
    /// A bound on `|F/G|`: the input that holds the error still along the
    /// reference (e.g. the voltage that holds a motor's load torque).
    pub hold_input: f64,
    /// A bound on the input gain `|G|` of `y^(n) = G u + F`, with the sign of
    /// `G`: a negative gain gives the negative control direction
    /// ([`crate::Direction`]) and the rules use `|G|`. Without it the loop's
    /// rate cannot be set, the direction is the paper's, and the design warns.
    pub gain: Option<f64>,
    /// Standard deviation of the measurement noise on `y`.
    pub noise_std: f64,
    /// Integral action; `None` chooses it (on when `gain` is known and
    /// `order < MAX_ORDER`).
    pub integral: Option<bool>,
    /// The phase budget `B` of the linearized loop, rad ([`PHASE_BUDGET`]):
    /// larger is faster and less damped.
    pub phase_budget: f64,
    /// The smallest differentiator time constant in sample periods
    /// ([`MU_PER_DT`]).
    pub mu_per_dt: f64,
    /// The envelope's preset time `T_s` as a fraction of `settle_time` (0.5).
    pub settle_fraction: f64,
    /// The largest error `|y - y_d|` the loop must recover from (e.g. a set
    /// point step), output units. At order >= 4 it sets the estimate limits
    /// that keep the differentiator's start-up peaking out of the law.
    pub max_error: Option<f64>,
}

impl Requirements {
    /// Requirements with no gain bound, no noise and automatic integral action.
    pub fn new(
        order: usize,
        dt: f64,
        u_limits: (f64, f64),
        eps: f64,
        settle_time: f64,
        hold_input: f64,
    ) -> Self {
        Self {
            order,
            dt,
            u_limits,
            eps,
            settle_time,
            hold_input,
            gain: None,
            noise_std: 0.0,
            integral: None,
            phase_budget: PHASE_BUDGET,
            mu_per_dt: MU_PER_DT,
            settle_fraction: 0.5,
            max_error: None,
        }
    }

    pub(super) fn validate(&self) -> Result<(), ConfigError> {
        let pos = |x: f64, name| {
            if x.is_finite() && x > 0.0 {
                Ok(())
            } else {
                Err(ConfigError::new(name, "must be finite and > 0"))
            }
        };
        crate::config::check_order(self.order)?;
        pos(self.dt, "dt")?;
        pos(self.eps, "eps")?;
        pos(self.settle_time, "settle_time")?;
        let (lo, hi) = self.u_limits;
        if !(lo.is_finite() && hi.is_finite() && lo < hi) {
            return Err(ConfigError::new("u_limits", "must be finite with lo < hi"));
        }
        if !(self.hold_input.is_finite() && self.hold_input >= 0.0) {
            return Err(ConfigError::new("hold_input", "must be finite and >= 0"));
        }
        if self.gain.is_some_and(|g| !(g.is_finite() && g != 0.0)) {
            return Err(ConfigError::new(
                "gain",
                "must be finite and nonzero (negative when the output falls as the input rises: \
                 the design then reverses the control direction)",
            ));
        }
        if let Some(m) = self.max_error {
            pos(m, "max_error")?;
        }
        if !(self.noise_std.is_finite() && self.noise_std >= 0.0) {
            return Err(ConfigError::new("noise_std", "must be finite and >= 0"));
        }
        pos(self.phase_budget, "phase_budget")?;
        if self.phase_budget >= core::f64::consts::FRAC_PI_2 {
            return Err(ConfigError::new(
                "phase_budget",
                "must be below pi/2 (90 degrees)",
            ));
        }
        pos(self.mu_per_dt, "mu_per_dt")?;
        if !(self.settle_fraction > 0.0 && self.settle_fraction < 1.0) {
            return Err(ConfigError::new("settle_fraction", "must be between 0 and 1"));
        }
        if self.integral == Some(true) && self.order >= MAX_ORDER {
            return Err(ConfigError::new(
                "integral",
                "needs order < 8 (the law's order is n + 1)",
            ));
        }
        if self.integral == Some(true) && self.gain.is_none() {
            return Err(ConfigError::new("gain", "is needed with integral action"));
        }
        Ok(())
    }
}
