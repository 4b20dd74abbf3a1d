//! Conversions between the C types and famcc-core's: configurations (with
//! famcc-core's defaults), enumeration values, diagnostics, errors.

use core::ffi::c_char;
use core::ptr;

use crate::reports::*;
pub(crate) use crate::tables::*;
use crate::types::*;
use famcc_core::config::{DEFAULT_K0, DEFAULT_SETTLE_TIME};
use famcc_core::{
    Config, ConfigBuilder, ConfigError, Constraint, Diagnostics, Direction, DiscreteHgd, Feedback, Gamma,
    HighGain, Latch, Real, Skew, SkewKind, StepError, Transition,
};

pub(crate) fn status_of(e: StepError) -> FamccStatus {
    match e {
        StepError::NonFiniteInput => FamccStatus::NonFiniteInput,
        StepError::NonFiniteApplied => FamccStatus::NonFiniteApplied,
        StepError::InvalidDt => FamccStatus::InvalidDt,
        StepError::NoDifferentiator => FamccStatus::NoDifferentiator,
        StepError::Overflow => FamccStatus::Overflow,
    }
}

fn copy_str(dst: &mut [c_char], s: &str) {
    let n = s.len().min(dst.len().saturating_sub(1));
    for (d, b) in dst.iter_mut().zip(s.as_bytes().iter().take(n)) {
        *d = *b as c_char;
    }
    if let Some(end) = dst.get_mut(n) {
        *end = 0;
    }
}

/// Writes `e` to `out` when `out` is not NULL.
pub(crate) unsafe fn report(out: *mut FamccError, e: &ConfigError) {
    if out.is_null() {
        return;
    }
    let mut r = FamccError {
        stage: e.stage.map_or(-1, |s| s as i32),
        parameter: [0; 32],
        rule: [0; 160],
    };
    copy_str(&mut r.parameter, e.parameter);
    copy_str(&mut r.rule, e.rule);
    ptr::write_unaligned(out, r);
}

fn transition(v: u32, name: &'static str) -> Result<Transition, ConfigError> {
    from_c(&TRANSITIONS, v, name, "must be a FAMCC_TRANSITION_* value")
}

fn feedback<T: Real>(f: &FamccFeedback<T>) -> Result<Feedback<T>, ConfigError> {
    // SAFETY (all arms): every union member is plain floats, so any
    // initialised bytes are a valid value of the member read.
    let p = &f.params;
    Ok(unsafe {
        match f.kind {
            0 => Feedback::Linear { k: p.linear.k },
            1 => Feedback::FiniteTime {
                k: p.finite_time.k,
                p: p.finite_time.p,
            },
            2 => Feedback::FixedTime {
                alpha: p.fixed_time.alpha,
                p: p.fixed_time.p,
                beta: p.fixed_time.beta,
                q: p.fixed_time.q,
            },
            3 => Feedback::VariableExponent {
                k: p.variable_exponent.k,
                r_b: p.variable_exponent.r_b,
                r_1: p.variable_exponent.r_1,
                r_t: p.variable_exponent.r_t,
            },
            4 => Feedback::MoulayDiscontinuous {
                beta: p.moulay.beta,
                lambda: p.moulay.lambda,
                mu: p.moulay.mu,
            },
            _ => {
                return Err(ConfigError::new(
                    "feedback.kind",
                    "must be a FAMCC_FEEDBACK_KIND_* value",
                ))
            }
        }
    })
}

fn skew<T: Real>(s: &FamccSkew<T>) -> Result<Option<Skew<T>>, ConfigError> {
    let kind = match s.kind {
        0 => return Ok(None),
        1 => SkewKind::Smooth,
        2 => SkewKind::Nonsingular { k_pp: s.k_pp },
        _ => return Err(ConfigError::new("skew.kind", "must be a FAMCC_SKEW_KIND_* value")),
    };
    Ok(Some(Skew {
        eps_s: s.eps_s,
        eps_z: s.eps_z,
        kind,
        transition: transition(s.transition, "skew.transition")?,
    }))
}

/// The famcc-core configuration of order `N` described by `c`.
pub(crate) fn to_config<T: Real, const N: usize>(c: &FamccConfig<T>) -> Result<Config<T, N>, ConfigError> {
    to_builder(c)?.build()
}

/// [`to_config`] with the differentiator's recursion precomputed (famcc-core's
/// `ConfigBuilder::build_discretized`: checked, not recomputed).
pub(crate) fn to_config_discretized<T: Real, const N: usize>(
    c: &FamccConfig<T>,
    d: &FamccDiscretized<T>,
) -> Result<Config<T, N>, ConfigError> {
    let (phi, gamma, feedthrough) = resized(&d.phi, &d.gamma, &d.feedthrough);
    let hgd = DiscreteHgd {
        phi,
        gamma,
        prefilter: d.prefilter,
        feedthrough,
    };
    to_builder(c)?.build_discretized(hgd)
}

/// famcc-core's recursion as a C [`FamccDiscretized`] (unused entries zero).
pub(crate) fn discretized_to_c<T: Real, const N: usize>(d: &DiscreteHgd<T, N>) -> FamccDiscretized<T> {
    let (phi, gamma, feedthrough) = resized(&d.phi, &d.gamma, &d.feedthrough);
    FamccDiscretized {
        phi,
        gamma,
        prefilter: d.prefilter,
        feedthrough,
    }
}

/// `Phi`, `Gamma` and the feedthrough copied between sizes: the common
/// leading part, the rest zero.
fn resized<T: Real, const A: usize, const B: usize>(
    phi: &[[T; A]; A],
    gamma: &[T; A],
    feedthrough: &[T; A],
) -> ([[T; B]; B], [T; B], [T; B]) {
    let mut p = [[T::zero(); B]; B];
    for (row, src) in p.iter_mut().zip(phi.iter()) {
        row.iter_mut().zip(src.iter()).for_each(|(x, s)| *x = *s);
    }
    let vector = |v: &[T; A]| {
        let mut out = [T::zero(); B];
        out.iter_mut().zip(v.iter()).for_each(|(x, s)| *x = *s);
        out
    };
    (p, vector(gamma), vector(feedthrough))
}

/// The builder of a C configuration (every value given, nothing checked yet).
fn to_builder<T: Real, const N: usize>(c: &FamccConfig<T>) -> Result<ConfigBuilder<T, N>, ConfigError> {
    let placeholder = (Feedback::Linear { k: T::one() }, None);
    let mut laws = [placeholder; FAMCC_MAX_STAGES];
    for (i, (slot, st)) in laws
        .iter_mut()
        .zip(c.stages.iter())
        .take(N.saturating_sub(1))
        .enumerate()
    {
        *slot = (
            feedback(&st.feedback).map_err(|e| e.at_stage(i))?,
            skew(&st.skew).map_err(|e| e.at_stage(i))?,
        );
    }
    let used = laws.get(..N.saturating_sub(1)).unwrap_or(&[]);
    let constraint = match c.constraint.kind {
        0 => Constraint::Longitudinal {
            eps: c.constraint.eps_y,
        },
        1 => Constraint::Lateral {
            eps: c.constraint.eps_x,
        },
        2 => Constraint::Oblique {
            eps_x: c.constraint.eps_x,
            eps_y: c.constraint.eps_y,
        },
        _ => {
            return Err(ConfigError::new(
                "constraint.kind",
                "must be a FAMCC_CONSTRAINT_KIND_* value",
            ))
        }
    };
    let first_n = |src: &[T; FAMCC_MAX_ORDER]| {
        let mut a = [T::zero(); N];
        a.iter_mut().zip(src.iter()).for_each(|(d, s)| *d = *s);
        a
    };
    let d = &c.differentiator;
    let differentiator = if d.enabled != 0 {
        let disc = from_c(
            &DISCRETIZATIONS,
            d.discretization,
            "discretization",
            "must be a FAMCC_DISCRETIZATION_* value",
        )?;
        Some(HighGain::new(d.mu, first_n(&d.a), disc).with_prefilter(d.prefilter))
    } else {
        None
    };
    let [out_lo, out_hi] = c.output_limits;
    let mut b = Config::<T, N>::builder(c.dt, used, constraint, c.k_u)
        .settle_time(c.settle_time)
        .k0(c.k0)
        .gamma(from_c(
            &GAMMAS,
            c.gamma,
            "gamma",
            "must be a FAMCC_GAMMA_* value",
        )?)
        .transition(transition(c.transition, "transition")?)
        .latch(from_c(
            &LATCHES,
            c.latch,
            "latch",
            "must be a FAMCC_LATCH_* value",
        )?)
        .direction(from_c(
            &DIRECTIONS,
            c.direction,
            "direction",
            "must be a FAMCC_DIRECTION_* value",
        )?)
        .differentiator(differentiator)
        .initial_derivatives((c.has_initial_derivatives != 0).then(|| first_n(&c.initial_derivatives)))
        .estimate_limits((c.has_estimate_limits != 0).then(|| first_n(&c.estimate_limits)))
        .integral(c.integral != 0)
        .output_limits((c.has_output_limits != 0).then_some((out_lo, out_hi)))
        .rate_limit((c.has_rate_limit != 0).then_some(c.rate_limit))
        .initial_output((c.has_initial_output != 0).then_some(c.initial_output))
        .observer(crate::observer::to_core(&c.observer)?)
        .cancellation_limit(
            (c.observer.has_cancellation_limit != 0).then_some(c.observer.cancellation_limit),
        );
    b = match c.flexible {
        x if x == FamccFlexible::Off as u32 => b.rho_e(None),
        x if x == FamccFlexible::On as u32 => b.rho_e(Some(c.rho_e)),
        x if x == FamccFlexible::Auto as u32 => b,
        _ => return Err(ConfigError::new("flexible", "must be a FAMCC_FLEXIBLE_* value")),
    };
    Ok(b)
}

/// famcc-core's defaults as a C configuration: `k0`, `T_s`, Gamma, the
/// transition and the latch are the core's; flexible boundaries with the
/// core's margin (`FAMCC_FLEXIBLE_AUTO`); no differentiator. What has no
/// default (`dt`, `k_u`, the constraint's widths, the stage laws) is zero,
/// which the validation rejects until it is set.
pub(crate) fn defaults<T: Real>() -> FamccConfig<T> {
    let z = T::zero();
    let stage = FamccStage {
        feedback: FamccFeedback {
            kind: FamccFeedbackKind::Linear as u32,
            params: FamccFeedbackParams {
                fixed_time: FamccFixedTime::default(),
            },
        },
        skew: FamccSkew::default(),
    };
    FamccConfig {
        dt: z,
        settle_time: T::from_f64(DEFAULT_SETTLE_TIME),
        k0: T::from_f64(DEFAULT_K0),
        k_u: z,
        constraint: FamccConstraint::default(),
        gamma: to_c(&GAMMAS, Gamma::default()),
        flexible: FamccFlexible::Auto as u32,
        rho_e: z,
        transition: to_c(&TRANSITIONS, Transition::default()),
        latch: to_c(&LATCHES, Latch::default()),
        stages: [stage; FAMCC_MAX_STAGES],
        differentiator: FamccDifferentiator::default(),
        has_initial_derivatives: 0,
        initial_derivatives: [z; FAMCC_MAX_ORDER],
        has_estimate_limits: 0,
        estimate_limits: [z; FAMCC_MAX_ORDER],
        integral: 0,
        has_output_limits: 0,
        output_limits: [z; 2],
        has_rate_limit: 0,
        rate_limit: z,
        has_initial_output: 0,
        initial_output: z,
        observer: FamccObserver::default(),
        direction: to_c(&DIRECTIONS, Direction::default()),
    }
}

/// `d` as C diagnostics, with the observer's estimate `lumped`.
pub(crate) fn diag_to_c<T: Real, const N: usize>(d: &Diagnostics<T, N>, lumped: T) -> FamccDiagnostics<T> {
    let pad = |src: &[T; N]| {
        let mut a = [T::zero(); FAMCC_MAX_ORDER];
        a.iter_mut().zip(src.iter()).for_each(|(d, s)| *d = *s);
        a
    };
    FamccDiagnostics {
        order: N as u32,
        expanded: u32::from(d.expanded),
        t: d.t,
        xi: d.xi,
        xi_nominal: d.xi_nominal,
        expansion: d.expansion,
        s: d.s,
        stages: pad(&d.stages),
        s_prev: d.s_prev,
        ds_prev: d.ds_prev,
        bounds: [d.bounds.0, d.bounds.1],
        nominal_bounds: [d.nominal_bounds.0, d.nominal_bounds.1],
        z_hat: pad(&d.z_hat),
        has_saturation_gap: u32::from(d.saturation_gap.is_some()),
        saturation_gap: d.saturation_gap.unwrap_or_else(T::zero),
        clamp_count: d.clamp_count,
        v: d.v,
        v_unlimited: d.v_unlimited,
        has_integral: u32::from(d.integral.is_some()),
        integrating: u32::from(d.integrating),
        integral: d.integral.unwrap_or_else(T::zero),
        unsaturated_expansions: d.unsaturated_expansions,
        cancellation: d.cancellation,
        lumped,
    }
}
