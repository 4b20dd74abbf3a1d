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

mod linear;

use crate::differentiator::{auto_discretization_at, Discretization};
use crate::error::ConfigError;
use num_traits::Float as F;

pub use crate::config::MAX_ORDER;
/// The phase budget of the linearized sampled loop, radians.
pub const PHASE_BUDGET: f64 = 0.8;
/// The smallest differentiator time constant, in sample periods.
pub const MU_PER_DT: f64 = 10.0;
/// The slowest differentiator the noise rule may pick, as a fraction of the
/// settling time.
pub const MU_PER_SETTLE: f64 = 0.05;
/// `xi` at which the law holds `hold_input` (`k_u = hold / (2 atanh(XI_HOLD))`).
pub const XI_HOLD: f64 = 0.5;
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
    /// A bound on the input gain `|G|` of `y^(n) = G u + F`. Without it the
    /// loop's rate cannot be set and the design warns.
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

    fn validate(&self) -> Result<(), ConfigError> {
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
        if let Some(g) = self.gain {
            pos(g, "gain")?;
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

/// How a finding bears on the design.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Level {
    /// The rule holds.
    Ok,
    /// Legal but risky, or not checkable with what was given.
    Warn,
    /// The requirement cannot be met as stated.
    Fail,
}

/// What a finding is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rule {
    /// The linearized sampled loop (nominal chain-of-integrators plant with
    /// gain `G`) is stable: `value` is its spectral radius, `limit` 1.
    SampledLoop,
    /// The manifold is fast enough for the settling time: `value = lambda`,
    /// `limit` the rate the settling time needs, `suggestion` the shortest
    /// settling time this sample rate allows.
    SettleTime,
    /// Without integral action: the offset under the hold input is within
    /// `eps` (`value` the offset, `limit = eps`, `suggestion` the smallest
    /// feasible `eps`).
    Accuracy,
    /// The noise in `s` is small against the band and the input range
    /// (`value` its std over `eps_s`, `limit` 0.15).
    Noise,
    /// The actuator can hold the load (`value = hold_input`, `limit` the
    /// larger limit magnitude).
    HoldInput,
    /// The input gain was not given: the loop rate is not checked.
    GainUnknown,
    /// At order >= 4 the estimates are limited (`value` the limit on `z_1`),
    /// which needs `max_error`; without it the finding warns.
    EstimateLimits,
}

/// One named finding, with its numbers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Check {
    /// What the finding is about.
    pub rule: Rule,
    /// Ok, warn or fail.
    pub level: Level,
    /// The measured quantity.
    pub value: f64,
    /// The bound it is compared with.
    pub limit: f64,
    /// A value that would satisfy the rule (see [`Rule`]), or NaN.
    pub suggestion: f64,
}

/// The chosen parameters and the findings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Design {
    /// Order of the law: `n + 1` with integral action, else `n`.
    pub law_order: usize,
    /// Integral action on.
    pub integral: bool,
    /// Differentiator time constant, s.
    pub mu: f64,
    /// Differentiator coefficients (binomial `(s+2)^m`, `m = n`), first `order` used.
    pub a: [f64; MAX_ORDER],
    /// Differentiator discretization.
    pub discretization: Discretization,
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

fn binomial(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

/// The manifold coefficients of `s = (D + lambda)^(n_law - 1) z1`: slot `j`
/// multiplies `z_(j+1)`.
fn manifold(n_law: usize, lambda: f64) -> [f64; MAX_ORDER] {
    let mut c = [0.0; MAX_ORDER];
    for (j, cj) in c.iter_mut().enumerate().take(n_law) {
        *cj = binomial(n_law - 1, j) * F::powi(lambda, (n_law - 1 - j) as i32);
    }
    c
}

/// Sets `mu` (raised for noise), the loop rate, `lambda` and `eps_s` for a
/// time-scale ratio; returns the noise in `s` over `eps_s`.
fn time_scales(d: &mut Design, req: &Requirements, ratio: f64, k_u: f64) -> Result<f64, ConfigError> {
    let n = req.order;
    let n_law = d.law_order;
    let (lo, hi) = req.u_limits;
    let mut noise_ratio = 0.0;
    for _ in 0..200 {
        d.discretization = auto_discretization_at(n, req.dt, d.mu);
        d.loop_rate = F::min(2.0 / d.mu / ratio, 0.4 / req.dt);
        d.lambda = if n_law > 1 { d.loop_rate / ratio } else { 0.0 };
        d.eps_s = match req.gain {
            Some(g) => 2.0 * k_u * g / d.loop_rate,
            None => 0.8 * req.eps * F::powi(d.lambda, (n_law - 1) as i32),
        };
        if req.noise_std == 0.0 || n == 1 {
            break;
        }
        let sigma_s = req.noise_std * linear::noise_gain(d, n, req.dt)?;
        noise_ratio = sigma_s / d.eps_s;
        let u_noise = 6.0 * 2.0 * k_u * sigma_s / d.eps_s;
        if noise_ratio <= 0.15 && u_noise <= 0.05 * (hi - lo) {
            break;
        }
        if d.mu * 1.1 > MU_PER_SETTLE * req.settle_time {
            break;
        }
        d.mu *= 1.1;
    }
    Ok(noise_ratio)
}

/// Computes the design (see the module documentation and docs/tuning.md).
pub fn design(req: &Requirements) -> Result<Design, ConfigError> {
    req.validate()?;
    let n = req.order;
    let integral = req.integral.unwrap_or(req.gain.is_some() && n < MAX_ORDER);
    let n_law = n + usize::from(integral);
    let (lo, hi) = req.u_limits;
    let u_scale = 0.5 * (hi - lo);
    let u_far = F::max(lo.abs(), hi.abs());
    let mut a = [0.0; MAX_ORDER];
    for (k, ak) in a.iter_mut().enumerate().take(n) {
        *ak = binomial(n, k + 1) * F::powi(2.0, (k + 1) as i32);
    }
    // Exact ZOH up to order 3 while dt <= 0.2 mu, Tustin otherwise (reset
    // whenever mu changes, in `time_scales`).
    let discretization = auto_discretization_at(n, req.dt, req.mu_per_dt * req.dt);
    // The phase model counts n_law - 1 stage lags and n_law differentiator lags;
    // beyond a law of order 3 that overcounts (measured: flexible joint and
    // integrator chains of orders 4-6 settle only with the order-3 ratio, and
    // stay stable with it), so the ratio stops growing at order 3.
    let k_u = F::max(req.hold_input, 0.05 * u_scale) / (2.0 * F::atanh(XI_HOLD));
    let mut d = Design {
        law_order: n_law,
        integral,
        mu: req.mu_per_dt * req.dt,
        a,
        discretization,
        lambda: 0.0,
        loop_rate: 0.0,
        k_u,
        eps_s: 0.0,
        rho_e: 0.0,
        k0: 2.0,
        settle_time: req.settle_fraction * req.settle_time,
        checks: [Check {
            rule: Rule::GainUnknown,
            level: Level::Ok,
            value: 0.0,
            limit: 0.0,
            suggestion: f64::NAN,
        }; MAX_CHECKS],
        estimate_limits: None,
        noise_ratio: 0.0,
        n_checks: 0,
    };
    // Where the capped ratio leaves the linearized sampled loop unstable (or
    // nearly so), widen the time scales by 20 % steps up to the uncapped ratio.
    let full = (2 * n_law - 1) as f64 / req.phase_budget;
    let mut ratio = (2 * n_law.min(RATIO_ORDER) - 1) as f64 / req.phase_budget;
    let mut noise_ratio;
    loop {
        d.mu = req.mu_per_dt * req.dt;
        noise_ratio = time_scales(&mut d, req, ratio, k_u)?;
        let stable = match req.gain {
            Some(g) => linear::loop_radius(&d, n, req.dt, g)? < RADIUS_WARN,
            None => true,
        };
        if stable || ratio >= full {
            break;
        }
        ratio = F::min(ratio * 1.2, full);
    }
    let margin = F::max(2.0 * F::exp(-u_far / k_u), 1e-6);
    d.rho_e = d.eps_s * F::min(margin, 1e-3);
    d.noise_ratio = noise_ratio;
    if n >= ESTIMATE_ORDER {
        if let Some(m) = req.max_error {
            let mut lim = [0.0; MAX_ORDER];
            for (i, l) in lim.iter_mut().enumerate().take(n) {
                *l = ESTIMATE_FACTOR * m * F::powi(d.loop_rate, i as i32);
            }
            d.estimate_limits = Some(lim);
        }
    }
    check(&mut d, req)?;
    Ok(d)
}

/// Recomputes a design's findings against the requirements, e.g. after a
/// parameter was changed by hand (the findings of [`design`] are replaced).
///
/// ```
/// use famcc_core::design::{check, design, Level, Requirements, Rule};
/// let mut req = Requirements::new(2, 1e-3, (-12.0, 12.0), 0.01, 2.0, 4.0);
/// req.gain = Some(25.0);
/// let mut d = design(&req).unwrap();
/// d.k_u *= 50.0;                       // a much stiffer loop than the rules allow
/// check(&mut d, &req).unwrap();
/// let sampled = d.checks().iter().find(|c| c.rule == Rule::SampledLoop).unwrap();
/// assert_eq!(sampled.level, Level::Fail);
/// ```
pub fn check(d: &mut Design, req: &Requirements) -> Result<(), ConfigError> {
    req.validate()?;
    d.n_checks = 0;
    let n = req.order;
    let noise_ratio = d.noise_ratio;
    let n_law = d.law_order;
    let (lo, hi) = req.u_limits;
    let u_far = F::max(lo.abs(), hi.abs());
    let level = |bad: bool| if bad { Level::Fail } else { Level::Ok };
    d.push(
        Rule::HoldInput,
        level(req.hold_input >= u_far),
        req.hold_input,
        u_far,
        f64::NAN,
    );
    if n_law > 1 {
        let need = (F::ln(5.0) + 1.5 * (n_law - 1) as f64) / (req.settle_time - d.settle_time);
        let shortest = 2.0 * (F::ln(5.0) + 1.5 * (n_law - 1) as f64) / d.lambda;
        // The rate rule is an estimate (it ignores the initial state and the
        // reaching phase): a shortfall of up to 2x warns, more fails.
        let lvl = if d.lambda < 0.5 * need {
            Level::Fail
        } else if d.lambda < need {
            Level::Warn
        } else {
            Level::Ok
        };
        d.push(Rule::SettleTime, lvl, d.lambda, need, shortest);
    }
    match req.gain {
        Some(g) => {
            let rho = linear::loop_radius(d, n, req.dt, g)?;
            let lvl = if rho >= 1.0 {
                Level::Fail
            } else if rho >= RADIUS_WARN {
                Level::Warn
            } else {
                Level::Ok
            };
            d.push(Rule::SampledLoop, lvl, rho, 1.0, f64::NAN);
        }
        None => d.push(Rule::GainUnknown, Level::Warn, f64::NAN, f64::NAN, f64::NAN),
    }
    if !d.integral {
        if let Some(g) = req.gain {
            let lam = F::powi(d.lambda, (n_law - 1) as i32);
            let xi = F::tanh(req.hold_input / (2.0 * d.k_u));
            let offset = d.eps_s * xi / lam;
            let smallest = req.hold_input * g / (d.loop_rate * lam);
            d.push(Rule::Accuracy, level(offset > req.eps), offset, req.eps, smallest);
        }
    }
    if n >= ESTIMATE_ORDER {
        match d.estimate_limits {
            Some(l) => d.push(Rule::EstimateLimits, Level::Ok, l[0], f64::NAN, f64::NAN),
            None => d.push(Rule::EstimateLimits, Level::Warn, f64::NAN, f64::NAN, f64::NAN),
        }
    }
    if req.noise_std > 0.0 {
        d.push(
            Rule::Noise,
            level(noise_ratio > 0.15),
            noise_ratio,
            0.15,
            f64::NAN,
        );
    }
    Ok(())
}
