//! The sampled closed loop (controller at `dt`, plant by RK4 substeps, input
//! held and clamped to the actuator limits) and its checks.
//!
//! Everything here is f32 and runs identically on the target and the host;
//! the report lines are printed by both and compared verbatim.

use crate::out::Sink;
use crate::Digest;
use famcc_core::{Controller, StepError};
use famcc_paper::plants::{rk4, Clock, Plant};
use libm::{cosf, sinf};

/// The time functions at `t` from two libm calls (the rest by double-angle
/// formulas).
#[inline]
fn clock_at(t: f32) -> Clock<f32> {
    Clock::from_sin_cos(sinf(t), cosf(t))
}

/// The most RK4 substeps per sample [`run`] takes.
pub const MAX_SUBSTEPS: usize = 16;

/// One closed-loop run to make and check.
#[derive(Clone, Copy, Debug)]
pub struct Scenario {
    /// Name used in the report.
    pub name: &'static str,
    /// Sample period, seconds.
    pub dt: f32,
    /// Number of samples (`t = 0, dt, ..., (steps - 1) dt`).
    pub steps: u32,
    /// Actuator limits `(lo, hi)`.
    pub limits: (f32, f32),
    /// RK4 substeps per sample (1 to [`MAX_SUBSTEPS`]).
    pub substeps: u32,
    /// Output accuracy `eps_z` to reach.
    pub eps_z: f32,
    /// Unsaturated: the theoretical settling bound `T_s + T'` (seconds), from
    /// which on `|z1| < eps_z` must hold. Saturated: `T'`, and the bound is
    /// `max(T_e, T_s) + T'` with `T_e` the end of the last saturation.
    pub bound: f32,
    /// The envelopes' settling time `T_s`, seconds.
    pub settle_time: f32,
    /// True when the run must saturate (and expand the flexible bounds).
    pub saturated: bool,
}

impl Scenario {
    fn ms(&self, k: u32) -> u64 {
        // Sample index to integer milliseconds (dt is a whole number of
        // microseconds here), without float formatting.
        let us = (self.dt * 1e6 + 0.5) as u64;
        u64::from(k) * us / 1000
    }
}

/// What a run did (per-sample quantities folded as they come: the target has
/// no room for 10 000-sample traces of everything).
#[derive(Clone, Copy, Debug)]
pub struct Stats {
    /// Samples taken.
    pub steps: u32,
    /// The step error that stopped the run, if any.
    pub error: Option<StepError>,
    /// The plant state became non-finite.
    pub plant_nonfinite: bool,
    /// `max |xi~|` over the run (`diagnostics().xi`).
    pub max_abs_xi: f32,
    /// The controller's clamp counter at the end.
    pub clamp_count: u64,
    /// Range of the applied input `u` (after the limits).
    pub u_min: f32,
    /// See `u_min`.
    pub u_max: f32,
    /// First sample with `|z1| < eps_z`.
    pub first_in_band: Option<u32>,
    /// Last sample with `|z1| >= eps_z`.
    pub last_out_of_band: Option<u32>,
    /// Samples at which `v` was outside the limits.
    pub saturated: u32,
    /// Last such sample.
    pub last_saturated: Option<u32>,
    /// Samples with expanded flexible bounds.
    pub expanded: u32,
    /// Last such sample.
    pub last_expanded: Option<u32>,
    /// Samples whose `expanded` flag disagrees with bounds vs nominal bounds.
    pub expansion_mismatch: u32,
    /// Digest of every sample's `(e, v, xi~)` bit patterns.
    pub digest: Digest,
    /// The last error sample.
    pub last_z1: f32,
}

impl Default for Stats {
    fn default() -> Self {
        Self {
            steps: 0,
            error: None,
            plant_nonfinite: false,
            max_abs_xi: 0.0,
            clamp_count: 0,
            u_min: f32::INFINITY,
            u_max: f32::NEG_INFINITY,
            first_in_band: None,
            last_out_of_band: None,
            saturated: 0,
            last_saturated: None,
            expanded: 0,
            last_expanded: None,
            expansion_mismatch: 0,
            digest: Digest::default(),
            last_z1: 0.0,
        }
    }
}

/// Runs the loop: at sample `k`, `e = x1 - sin t`, `v = ctrl.step(e)`,
/// `u = clamp(v)`, then `substeps` RK4 steps with `u` held. The time
/// functions inside a sample come from angle addition (exact to a few f32
/// roundings), so libm's f32 trigonometry (double-precision kernels: soft
/// float on the Cortex-M4F) runs only for the state-dependent terms. `record(k, e, v)`
/// sees every sample (the firmware keeps `e` for the replay benchmark).
pub fn run<const N: usize, P: Plant<f32, N>>(
    sc: &Scenario,
    plant: &P,
    ctrl: &mut Controller<f32, N>,
    record: &mut dyn FnMut(u32, f32, f32),
) -> Stats {
    let mut st = Stats::default();
    let mut x = plant.x0();
    let sub = sc.substeps.clamp(1, MAX_SUBSTEPS as u32) as usize;
    let h = sc.dt / sub as f32;
    // Time functions at the half-substep offsets j h / 2 (j = 0..=2 sub),
    // computed once; per sample they are rotated by the sample's own.
    let mut offsets = [Clock::from_sin_cos(0.0, 1.0); 2 * MAX_SUBSTEPS + 1];
    for (j, o) in offsets.iter_mut().enumerate().take(2 * sub + 1) {
        *o = clock_at(j as f32 * 0.5 * h);
    }
    let (lo, hi) = sc.limits;
    for k in 0..sc.steps {
        let t = k as f32 * sc.dt;
        let now = clock_at(t);
        let e = x[0] - now.sin;
        let v = match ctrl.step(e) {
            Ok(v) => v,
            Err(err) => {
                st.error = Some(err);
                break;
            }
        };
        let u = v.max(lo).min(hi);
        let d = ctrl.diagnostics();
        let a = d.xi.abs();
        if a.is_nan() || a > st.max_abs_xi {
            st.max_abs_xi = a; // a NaN sticks (and fails the check)
        }
        st.clamp_count = d.clamp_count;
        st.u_min = st.u_min.min(u);
        st.u_max = st.u_max.max(u);
        if e.abs() < sc.eps_z {
            if st.first_in_band.is_none() {
                st.first_in_band = Some(k);
            }
        } else {
            st.last_out_of_band = Some(k);
        }
        if u != v {
            st.saturated += 1;
            st.last_saturated = Some(k);
        }
        let widened = d.bounds.0 > d.nominal_bounds.0 || d.bounds.1 > d.nominal_bounds.1;
        let nominal = d.bounds == d.nominal_bounds;
        if d.expanded {
            st.expanded += 1;
            st.last_expanded = Some(k);
        }
        if (d.expanded && !widened) || (!d.expanded && !nominal) {
            st.expansion_mismatch += 1;
        }
        st.digest.f32(e);
        st.digest.f32(v);
        st.digest.f32(d.xi);
        st.last_z1 = e;
        record(k, e, v);
        st.steps = k + 1;
        for j in 0..sub {
            let c = [
                now.shifted(&offsets[2 * j]),
                now.shifted(&offsets[2 * j + 1]),
                now.shifted(&offsets[2 * j + 2]),
            ];
            x = rk4(plant, &c, &x, u, h);
        }
        if x.iter().any(|v| !v.is_finite()) {
            st.plant_nonfinite = true;
            break;
        }
    }
    st
}

fn fail<S: Sink>(out: &mut S, sc: &Scenario, what: &str) -> u32 {
    out.s("FAIL ").s(sc.name).s(": ").s(what).nl();
    1
}

/// Prints the run's report line and checks it; returns the number of failed
/// checks (each printed as a `FAIL` line).
///
/// Checks: the run completed with finite values; `|xi~| < 1` at every sample
/// with no clamping; `u` within the limits. Unsaturated: `|z1| < eps_z` from
/// the theoretical bound on. Saturated: the run saturated, the flexible
/// bounds expanded (and exactly when flagged) and were nominal again at the
/// end, and `|z1| < eps_z` from `max(T_e, T_s) + T'` on.
pub fn check<S: Sink>(sc: &Scenario, st: &Stats, out: &mut S) -> u32 {
    let opt_ms = |o: Option<u32>| o.map(|k| sc.ms(k) as i64).unwrap_or(-1);
    let settle = st.last_out_of_band.map(|k| k + 1).unwrap_or(0);
    out.s("loop ")
        .s(sc.name)
        .s(" steps=")
        .u(u64::from(st.steps))
        .s(" digest=")
        .x64(st.digest.0)
        .s(" max|xi~|=")
        .fx(st.max_abs_xi, 6)
        .s(" clamps=")
        .u(st.clamp_count)
        .s(" u=[")
        .fx(st.u_min, 3)
        .s(",")
        .fx(st.u_max, 3)
        .s("] first_in_band_ms=")
        .i(opt_ms(st.first_in_band))
        .s(" settled_ms=")
        .u(sc.ms(settle))
        .s(" saturated=")
        .u(u64::from(st.saturated))
        .s(" last_sat_ms=")
        .i(opt_ms(st.last_saturated))
        .s(" expanded=")
        .u(u64::from(st.expanded))
        .s(" last_exp_ms=")
        .i(opt_ms(st.last_expanded))
        .nl();

    let mut f = 0;
    if let Some(e) = st.error {
        f += fail(
            out,
            sc,
            match e {
                StepError::NonFiniteInput => "step error NonFiniteInput",
                StepError::NonFiniteApplied => "step error NonFiniteApplied",
                StepError::InvalidDt => "step error InvalidDt",
                StepError::NoDifferentiator => "step error NoDifferentiator",
                StepError::Overflow => "step error Overflow",
            },
        );
    }
    if st.plant_nonfinite {
        f += fail(out, sc, "plant state became non-finite");
    }
    if st.steps != sc.steps {
        f += fail(out, sc, "run stopped early");
    }
    if st.max_abs_xi.is_nan() || st.max_abs_xi >= 1.0 {
        f += fail(out, sc, "|xi~| reached 1");
    }
    if st.clamp_count != 0 {
        f += fail(out, sc, "xi~ was clamped");
    }
    if !(st.u_min >= sc.limits.0 && st.u_max <= sc.limits.1) {
        f += fail(out, sc, "u left the limits");
    }
    let bound_s = if sc.saturated {
        let t_e = st.last_saturated.map(|k| (k + 1) as f32 * sc.dt).unwrap_or(0.0);
        t_e.max(sc.settle_time) + sc.bound
    } else {
        sc.bound
    };
    let bound_k = (bound_s / sc.dt + 0.5) as u32;
    if settle > bound_k {
        f += fail(out, sc, "|z1| >= eps_z after the settling bound");
    }
    if sc.saturated {
        if st.saturated == 0 {
            f += fail(out, sc, "never saturated");
        }
        if st.expanded == 0 {
            f += fail(out, sc, "flexible bounds never expanded");
        }
        if st.last_expanded.is_some_and(|k| k + 1 >= st.steps) {
            f += fail(out, sc, "bounds still expanded at the end");
        }
    }
    if st.expansion_mismatch != 0 {
        f += fail(out, sc, "expanded flag disagrees with the bounds");
    }
    out.s("check ")
        .s(sc.name)
        .s(" bound_ms=")
        .u(sc.ms(bound_k))
        .s(if f == 0 { " ok" } else { " FAILED" })
        .nl();
    f
}
