//! Design rules: a FAMCC configuration from a control engineer's requirements,
//! without simulation (docs/tuning.md has the derivation of every rule).
//!
//! The design uses linear stage laws `h_i(s) = -lambda s`, the longitudinal
//! constraint and the log map Gamma. Near the manifold the law is then linear,
//! `v ~= -(2 k_u / eps_s) s`, and with `ds/dt = G u + ...` the `s`-loop runs at
//! the rate `lambda_s = 2 k_u G / eps_s`. Three time scales are kept apart by
//! one phase budget: the differentiator's bandwidth `omega_d = 2 / mu`, the
//! loop rate `lambda_s` and the manifold's rate `lambda`,
//! `omega_d / lambda_s = lambda_s / lambda = (2 min(n_law, 3) - 1) / B` with
//! `B = 0.8` rad (about 45 degrees of phase margin).
//!
//! With integral action the law acts on the augmented error `(I, e, e', ...)`
//! with `I` the integral of `e` (an order `n + 1` law on a strict-feedback
//! plant of the paper's class), so a constant load is carried by `I` and the
//! error tends to zero; without it the load must be carried by `xi`, which
//! costs an offset `~ u_hold G / (lambda_s lambda^(n-1))`.
//!
//! ```
//! use famcc_core::design::{design, Level, Requirements};
//! // DC motor position: theta'' = 25 V + ..., |V| <= 12 V, 4 V to hold the load.
//! let mut req = Requirements::new(2, 1e-3, (-12.0, 12.0), 0.01, 2.0, 4.0);
//! req.gain = Some(25.0);
//! let d = design(&req).unwrap();
//! assert!(d.integral && d.law_order == 3);
//! assert!(d.checks().iter().all(|c| c.level != Level::Fail));
//! ```

mod coefficients;
mod findings;
mod linear;
mod requirements;
mod rules;

use crate::differentiator::Discretization;

pub use crate::config::MAX_ORDER;
pub use findings::{check, Check, Level, Rule};
pub use requirements::Requirements;
pub use rules::design;

/// The phase budget of the linearized sampled loop, radians.
pub const PHASE_BUDGET: f64 = 0.8;
/// The smallest differentiator time constant, in sample periods.
pub const MU_PER_DT: f64 = 10.0;
/// The slowest differentiator the noise rule may pick, as a fraction of the
/// settling time.
pub const MU_PER_SETTLE: f64 = 0.05;
/// The factor by which the noise rule raises `mu` per trial (the smallest
/// `mu` that meets the rule, to within it).
pub const NOISE_MU_STEP: f64 = 1.05;
/// The largest noise in `s` the noise rule accepts, as a fraction of `eps_s`
/// (the log map stays near its linear part).
pub const NOISE_RATIO: f64 = 0.15;
/// Standard deviations of the input noise the noise rule keeps within the
/// headroom that the hold input leaves on the nearer limit.
pub const NOISE_SIGMAS: f64 = 4.0;
/// The prefilter's time constant as a fraction of `mu` when the design
/// counts measurement noise (`tau = PREFILTER_PER_MU mu`; none without noise).
pub const PREFILTER_PER_MU: f64 = 0.5;
/// The highest plant order at which the noise rule adds the prefilter. Above
/// it the capped time-scale ratio leaves no phase for its lag (measured: the
/// flexible joint of order 4 at `tau = mu / 4` saturates a third of the time
/// without any noise, where without the prefilter it settles).
pub const PREFILTER_ORDER: usize = 3;
/// `xi` at which the law holds `hold_input` (`k_u = hold / (2 atanh(XI_HOLD))`).
pub const XI_HOLD: f64 = 0.5;

/// The smallest gain that holds the input `hold` with the constraint variable
/// at [`XI_HOLD`]: `k_u = |hold| / (2 atanh(XI_HOLD))` (log Gamma, eq. (29):
/// `k_u Gamma(1/2) = k_u ln 3`). Used by [`design`] and by the run-time health
/// rule ([`crate::controller::Health`]).
///
/// ```
/// let k_u = famcc_core::design::k_u_to_hold(2.0);
/// assert!((k_u * 3.0_f64.ln() - 2.0).abs() < 1e-12);
/// ```
pub fn k_u_to_hold(hold: f64) -> f64 {
    num_traits::Float::abs(hold) / (2.0 * num_traits::Float::atanh(XI_HOLD))
}
/// A sampled-loop spectral radius from which the design warns (and widens
/// its time scales when it can).
pub const RADIUS_WARN: f64 = 0.9999;
/// The law order from which the time-scale ratio stops growing.
pub const RATIO_ORDER: usize = 3;
/// The order from which the design limits the estimates (start-up peaking).
pub const ESTIMATE_ORDER: usize = 4;
/// Estimate limit `i` is `ESTIMATE_FACTOR max_error loop_rate^(i-1)`.
pub const ESTIMATE_FACTOR: f64 = 4.0;
/// The largest number of findings a design reports.
pub const MAX_CHECKS: usize = 8;

/// The chosen parameters and the findings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Design {
    /// Order of the law: `n + 1` with integral action, else `n`.
    pub law_order: usize,
    /// The control direction: the sign of the requirements' `gain`
    /// (positive, the paper's, without one).
    pub direction: crate::Direction,
    /// Integral action on.
    pub integral: bool,
    /// Differentiator time constant, s.
    pub mu: f64,
    /// Differentiator coefficients (binomial `(s+2)^m`, `m = n`), first `order` used.
    pub a: [f64; MAX_ORDER],
    /// Differentiator discretization.
    pub discretization: Discretization,
    /// Time constant of the differentiator's low-pass prefilter, s (0: none;
    /// `PREFILTER_PER_MU mu` when the requirements give measurement noise,
    /// up to order [`PREFILTER_ORDER`]).
    pub prefilter: f64,
    /// Stage law rate `lambda` of `h_i(s) = -lambda s`, 1/s.
    pub lambda: f64,
    /// The `s`-loop rate `lambda_s`, 1/s.
    pub loop_rate: f64,
    /// Control gain `k_u`, input units.
    pub k_u: f64,
    /// Final width of the constraint on `s` (`eps` of the controller).
    pub eps_s: f64,
    /// Flexible boundary margin.
    pub rho_e: f64,
    /// Initial-width factor.
    pub k0: f64,
    /// The envelope's preset time `T_s`, s.
    pub settle_time: f64,
    /// Limits on the estimates `|z_hat_i|` (slot `i - 1`), set at order >= 4
    /// when `max_error` is known: `ESTIMATE_FACTOR max_error loop_rate^(i-1)`,
    /// a few times what the loop itself produces, far below the start-up
    /// peaking `~ max_error (2/mu)^(i-1)`. None: no limits.
    pub estimate_limits: Option<[f64; MAX_ORDER]>,
    noise_ratio: f64,
    checks: [Check; MAX_CHECKS],
    n_checks: usize,
}

impl Design {
    /// The findings, in the order they were made.
    pub fn checks(&self) -> &[Check] {
        self.checks.get(..self.n_checks).unwrap_or(&[])
    }

    fn push(&mut self, rule: Rule, level: Level, value: f64, limit: f64, suggestion: f64) {
        if let Some(slot) = self.checks.get_mut(self.n_checks) {
            *slot = Check {
                rule,
                level,
                value,
                limit,
                suggestion,
            };
            self.n_checks += 1;
        }
    }
}
