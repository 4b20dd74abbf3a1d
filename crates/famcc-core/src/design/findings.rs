//! The findings of a design ([`Check`]: a [`Rule`] at a [`Level`], with its
//! numbers) and [`check`], which makes them against the requirements.

use super::{linear, Design, Requirements, ESTIMATE_ORDER, NOISE_RATIO, RADIUS_WARN};
use crate::error::ConfigError;
use num_traits::Float as F;

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
    /// (`value` its std over `eps_s`, `limit` [`super::NOISE_RATIO`]).
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

/// Recomputes a design's findings against the requirements, e.g. after a
/// parameter was changed by hand (the findings of [`design`](super::design) are replaced).
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
            level(noise_ratio > NOISE_RATIO),
            noise_ratio,
            NOISE_RATIO,
            f64::NAN,
        );
    }
    Ok(())
}
