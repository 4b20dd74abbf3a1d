//! The design rules proper: [`design`] picks every parameter from the
//! requirements, widening the time-scale ratio until the sampled loop is stable.

use super::coefficients::binomial;
use super::{
    check, linear, Check, Design, Level, Requirements, Rule, ESTIMATE_FACTOR, ESTIMATE_ORDER, MAX_CHECKS,
    MAX_ORDER, MU_PER_SETTLE, NOISE_MU_STEP, NOISE_RATIO, NOISE_SIGMAS, PREFILTER_ORDER, PREFILTER_PER_MU,
    RADIUS_WARN, RATIO_ORDER,
};
use crate::differentiator::auto_discretization_at;
use crate::error::ConfigError;
use num_traits::Float as F;

/// Sets `mu` (raised for noise, with the prefilter), the loop rate, `lambda` and `eps_s` for a
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
        if n <= PREFILTER_ORDER {
            d.prefilter = PREFILTER_PER_MU * d.mu;
        }
        let sigma_s = req.noise_std * linear::noise_gain(d, n, req.dt)?;
        noise_ratio = sigma_s / d.eps_s;
        // The linearized law's input noise, NOISE_SIGMAS deep, within the
        // headroom the hold input leaves on the nearer limit.
        let u_noise = NOISE_SIGMAS * 2.0 * k_u * sigma_s / d.eps_s;
        let headroom = F::max(F::min(-lo, hi) - req.hold_input.abs(), 0.05 * (hi - lo));
        if noise_ratio <= NOISE_RATIO && u_noise <= headroom {
            break;
        }
        if d.mu * NOISE_MU_STEP > MU_PER_SETTLE * req.settle_time {
            break;
        }
        d.mu *= NOISE_MU_STEP;
    }
    Ok(noise_ratio)
}

/// Computes the design (see the module documentation and docs/tuning.md).
pub fn design(req: &Requirements) -> Result<Design, ConfigError> {
    req.validate()?;
    // The sign of G sets the direction; every rule below uses |G|.
    let direction = req.gain.and_then(crate::Direction::of).unwrap_or_default();
    let req = &Requirements {
        gain: req.gain.map(F::abs),
        ..*req
    };
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
    // Exact ZOH up to order 3 while mu >= 10 dt (the paper's ratio), the
    // first-order hold beyond, Tustin from order 4 on (reset whenever mu
    // changes, in `time_scales`).
    let discretization = auto_discretization_at(n, req.dt, req.mu_per_dt * req.dt);
    // The phase model counts n_law - 1 stage lags and n_law differentiator lags;
    // beyond a law of order 3 that overcounts (measured: flexible joint and
    // integrator chains of orders 4-6 settle only with the order-3 ratio, and
    // stay stable with it), so the ratio stops growing at order 3.
    let k_u = super::k_u_to_hold(F::max(req.hold_input, 0.05 * u_scale));
    let mut d = Design {
        law_order: n_law,
        direction,
        integral,
        mu: req.mu_per_dt * req.dt,
        a,
        discretization,
        prefilter: 0.0,
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
