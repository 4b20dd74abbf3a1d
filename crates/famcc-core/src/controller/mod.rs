//! The FAMCC controller: a real-time discrete controller (docs/design.md §3).
//!
//! Each [`Controller::step`] takes one sample of the output error
//! `e = y - y_d` and returns the control `v = -k_u Gamma(xi~)` (eqs. (35)
//! uOF, (32) WuT) to hold until the next sample. Inside a step:
//! 1. on the first step the estimate is `(e0, 0, ..., 0)` (or the configured
//!    derivative estimates) and the envelopes latch their initial widths;
//! 2. the output is computed from the current estimate `Zhat_k` (built from
//!    samples up to `k-1`): manifold (eq. (11), IS), constraint variable
//!    (eq. (28), xi), flexible boundary (eqs. (30)-(31)), control (eq. (29));
//! 3. the estimate advances, `Zhat_{k+1} = Phi Zhat_k + Gamma e_k` (eq. (34)
//!    discretized at construction).
//!
//! Options beyond the paper (docs/design.md §3.8), all off by default (then
//! every output is bit-identical to the paper's law): integral action (the
//! law of order `N` on `Z = (I, e, ..., e^(N-2))` with integral separation),
//! magnitude and rate limits of the output, a bumpless start from a given
//! output, and the health count of expansions while the actuator had
//! headroom.
//!
//! The sign convention of every step is `e = y - y_d` (the output minus the
//! reference: the opposite of a PID's `setpoint - y`); [`Controller::step_output`]
//! takes `y` and `y_d` and forms it.
//!
//! A step is transactional: on an error the state is unchanged, with one
//! exception: [`StepError::Overflow`] after the first step means the sample
//! was valid but the law overflowed on it (an outlier drove the estimate out
//! of range); the estimate and the clock then advance, so the controller
//! recovers as the estimate decays, and the caller holds its last output.
//!
//! ```
//! use famcc_core::{Config, Constraint, Controller, Feedback, HighGain};
//! // Example 1 of the paper: LaMC, finite-time law, eps_x = 0.1, k_u = 5.
//! let cfg = Config::<f64, 2>::builder(
//!     1e-3, &[(Feedback::FiniteTime { k: 1.0, p: 0.5 }, None)],
//!     Constraint::Lateral { eps: 0.1 }, 5.0)
//!     .differentiator(Some(HighGain::paper()))
//!     .build()
//!     .unwrap();
//! let mut ctrl = Controller::new(cfg);
//! let v = ctrl.step(-1.0).unwrap();
//! assert!(v > 0.0);                       // error below the reference: push up
//! assert!(ctrl.diagnostics().xi.abs() < 1.0);
//! ```

mod clock;
mod diagnostics;
mod health;
mod output;
mod probe;
mod recover;
mod snapshot;
mod start;
mod steps;

pub use diagnostics::Diagnostics;
pub use health::{Health, HEALTH_FRACTION};
pub(crate) use probe::probe;
pub use probe::{probe_error, probe_errors, PROBE_COUNT, PROBE_LIMIT, PROBE_PER_DECADE};
pub use recover::RECOVERY_SAMPLES;
pub use snapshot::{Snapshot, SNAPSHOT_FIELDS};
pub use start::MAX_WIDENING;

use crate::constraint::Envelopes;
use crate::error::StepError;
use crate::{differentiator, manifold, Config, Real};
use clock::Clock;
use output::Limits;
use recover::{in_range, width_in_range, Cause};

/// The controller's mutable state (everything `reset` clears).
#[derive(Clone, Copy, Debug, PartialEq)]
struct State<T, const N: usize> {
    started: bool,
    /// The clock at the next sample.
    clock: Clock<T>,
    /// The clock at the last successful step's sample (the diagnostics' time).
    sampled: Clock<T>,
    /// The estimate in the law's coordinates (with integral action slot 0
    /// holds the integral `I`).
    zhat: [T; N],
    envelopes: Envelopes<T>,
    diag: Diagnostics<T, N>,
}

impl<T: Real, const N: usize> State<T, N> {
    /// A failed step on a finite sample (the recovery rule, recover.rs):
    /// before the first step nothing changes; after it the sample is
    /// consumed, the estimate restarts and the clock advances.
    #[cold]
    fn consume(
        &mut self,
        c: &Config<T, N>,
        measured: &Measured<T, N>,
        hgd: Option<&differentiator::DiscreteHgd<T, N>>,
        clock_next: Clock<T>,
        cause: Cause,
    ) -> StepError {
        if self.started {
            self.zhat = recover::restarted(c, measured, hgd, cause);
            self.clock = clock_next;
        }
        StepError::Overflow
    }
}

/// What a step measured: the output error (output feedback, eq. (35)) or
/// the whole error vector (state feedback, eq. (32)).
#[derive(Clone, Copy)]
enum Measured<T, const N: usize> {
    Error(T),
    State([T; N]),
}

/// The FAMCC controller of order `N` (the system order).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Controller<T, const N: usize> {
    config: Config<T, N>,
    state: State<T, N>,
}

impl<T: Real, const N: usize> Controller<T, N> {
    /// A controller in its state before the first step. The configuration is
    /// valid by construction ([`crate::ConfigBuilder::build`]).
    pub fn new(config: Config<T, N>) -> Self {
        Self {
            state: Self::initial_state(&config),
            config,
        }
    }

    fn initial_state(config: &Config<T, N>) -> State<T, N> {
        State {
            started: false,
            clock: Clock::start(config.dt()),
            sampled: Clock::start(config.dt()),
            zhat: [T::zero(); N],
            envelopes: config.constraint().envelopes(config.settle_time()),
            diag: Diagnostics::default(),
        }
    }

    /// The configuration.
    pub fn config(&self) -> &Config<T, N> {
        &self.config
    }

    /// What the last step did. The manifold values (`s`, `stages`,
    /// `s_prev`, `ds_prev`) are evaluated here from the estimate the step
    /// used, so `step()` does not pay for values only a reader needs.
    pub fn diagnostics(&self) -> Diagnostics<T, N> {
        let mut d = self.state.diag;
        d.t = self.state.sampled.time();
        if self.state.started {
            let m = manifold::evaluate(&d.z_hat, self.config.laws());
            d.s = m.s();
            d.stages = m.stages;
            d.s_prev = m.s_prev;
            d.ds_prev = m.ds_prev;
        }
        d
    }

    /// The time of the next sample, seconds (exact: an integer sample count
    /// and an `f64` base, docs/design.md §3.10).
    pub fn time(&self) -> f64 {
        self.state.clock.time()
    }

    /// The number of samples of the current run at one period (all the
    /// samples so far when only the nominal `dt` was used), saturating at
    /// `u64::MAX`.
    pub fn samples(&self) -> u64 {
        self.state.clock.k
    }

    /// The current estimate `Zhat` (the one the next step will use).
    pub fn estimate(&self) -> &[T; N] {
        &self.state.zhat
    }

    /// Back to the state before the first step (configuration kept).
    pub fn reset(&mut self) {
        self.state = Self::initial_state(&self.config);
    }

    /// Every step: computes the control from the current estimate (or the
    /// measured state), then advances the estimate and the clock by `dt`
    /// (`None`: the nominal period) and commits, or changes nothing on an
    /// error (except a law overflow after the first step, see the module docs).
    #[inline(always)]
    fn control_then_advance(
        &mut self,
        measured: Measured<T, N>,
        one_off_dt: Option<T>,
        applied: Option<T>,
    ) -> Result<T, StepError> {
        let c = &self.config;
        let off = c.estimate_offset();
        let finite = match &measured {
            Measured::Error(e) => e.is_finite(),
            Measured::State(z) => z.iter().skip(off).all(|v| v.is_finite()),
        };
        if !finite {
            return Err(StepError::NonFiniteInput);
        }
        let dt = match one_off_dt {
            Some(dt) if !(dt.is_finite() && dt > T::zero()) => return Err(StepError::InvalidDt),
            Some(dt) => dt,
            None => c.dt(),
        };
        let first = !self.state.started;
        let settle_time = c.settle_time();
        // This step's discretization (a one-off period is rediscretized).
        let one_off;
        let hgd = match one_off_dt.and_then(|dt| c.discretize_at(dt)) {
            Some(d) => {
                one_off = d.map_err(|_| StepError::InvalidDt)?;
                Some(&one_off)
            }
            None => c.discretized(),
        };
        // The measured sample, the vector the law uses, and the estimate the
        // next step will use (all in the law's coordinates).
        // Without a differentiator the next step measures its own vector.
        let carried = hgd.is_some();
        let (e, mut z, mut next) = match measured {
            Measured::Error(e) => match hgd {
                Some(d) => {
                    let z = self.current_estimate(e);
                    (e, self.limited(z), d.advance(&z, e))
                }
                // Order 1 needs no differentiator: Z = (e) (or (I, e)) is measured.
                None if !differentiator::needed_at(c.plant_order()) => {
                    let mut z = [e; N];
                    if let (1, Some(i)) = (off, z.first_mut()) {
                        *i = self.state.zhat.first().copied().unwrap_or_else(T::zero);
                    }
                    (e, z, z)
                }
                None => return Err(StepError::NoDifferentiator),
            },
            Measured::State(mut z) => {
                let e = z.get(off).copied().unwrap_or_else(T::zero);
                if let (1, Some(i)) = (off, z.first_mut()) {
                    *i = self.state.zhat.first().copied().unwrap_or_else(T::zero);
                }
                let zhat = if self.state.started { self.state.zhat } else { z };
                let next = match c.discretized() {
                    Some(d) => d.advance(&zhat, e),
                    None => z,
                };
                (e, z, next)
            }
        };
        if applied.is_some_and(|a| !a.is_finite()) {
            return Err(StepError::NonFiniteApplied);
        }
        // A one-off period within the scale range of §3.9 (the clock then
        // stays finite for any number of samples).
        let in_scale = one_off_dt.is_none() || crate::error::scale(dt, "dt").is_ok();
        let Some(clock_next) = self.state.clock.advanced(dt, settle_time).filter(|_| in_scale) else {
            return Err(StepError::InvalidDt);
        };
        // Beyond this point a failure after the first step consumes the
        // sample and restarts the estimate (the recovery rule, recover.rs).
        if carried && !in_range(&next) {
            return Err(self.state.consume(c, &measured, hgd, clock_next, Cause::Update));
        }
        let t = self.state.clock.law_time(settle_time);
        // Bumpless start with integral action: the I_0 whose output is u0.
        if let (true, 1, Some(u0)) = (first, off, c.initial_output()) {
            let i0 = self.initial_integral(&z, u0, t);
            if let Some(z0) = z.first_mut() {
                *z0 = i0;
            }
        }

        // The law (eqs. (11), (28)-(32)), with the envelopes latched from
        // this very state at the first step.
        let c = &self.config;
        let constraint = c.constraint();
        let m = if constraint.needs_s(first) {
            manifold::evaluate(&z, c.laws())
        } else {
            manifold::evaluate_prev(&z, c.laws())
        };
        // A failed first step leaves the envelopes as they were.
        let unlatched = if first { Some(self.state.envelopes) } else { None };
        let flexible = c.rho_e().map(|rho_e| (rho_e, c.transition()));
        let mut eval = constraint.evaluate(
            c.last_law(),
            &m,
            &mut self.state.envelopes,
            first.then(|| (c.latch(), c.k0())),
            t,
            flexible,
        );
        // Bumpless start without integral action: the latch for u0.
        if let (true, 0, Some(u0)) = (first, off, c.initial_output()) {
            let env = self.bumpless_envelopes(&z, self.state.envelopes, u0, t);
            self.state.envelopes = env;
            eval = constraint.evaluate(c.last_law(), &m, &mut self.state.envelopes, None, t, flexible);
        }
        let v = -c.k_u() * c.gamma().eval(eval.xi);
        let env = &self.state.envelopes;
        let latched = !first || (width_in_range(env.x.rho0) && width_in_range(env.y.rho0));
        if !(latched && v.is_finite() && eval.xi.is_finite()) {
            if let Some(envelopes) = unlatched {
                self.state.envelopes = envelopes;
            }
            return Err(self.state.consume(c, &measured, hgd, clock_next, Cause::Law));
        }

        // The output limits, what is known of the actuator, the integral
        // separation and the health count (docs/design.md §3.8).
        let previous = if first {
            c.initial_output()
        } else {
            Some(self.state.diag.v)
        };
        let limited = Limits {
            magnitude: c.output_limits(),
            rate: c.rate_limit().map(|r| (r, dt)),
            previous,
            applied: if first { None } else { applied },
            k_u: c.k_u(),
        }
        .apply(v);
        let integral = z.first().copied().filter(|_| off == 1);
        let mut integrating = false;
        if let (Some(i), Some(n0)) = (integral, next.first_mut()) {
            let (width, eps) = match constraint {
                crate::Constraint::Longitudinal { eps } => (eval.nominal.1, *eps),
                crate::Constraint::Lateral { eps } => (eval.nominal.0, *eps),
                crate::Constraint::Oblique { eps_x, .. } => (eval.nominal.0, *eps_x),
            };
            integrating = limited.integrates(e, eval.xi_nominal.abs() * width <= eps);
            let i_next = if integrating { i + dt * e } else { i };
            if !in_range(&[i_next]) {
                if let Some(envelopes) = unlatched {
                    self.state.envelopes = envelopes;
                }
                return Err(self.state.consume(c, &measured, hgd, clock_next, Cause::Update));
            }
            *n0 = i_next;
        }

        let (x_u, y_u) = eval.nominal;
        let factor = eval.expansion;
        let expanded = factor > T::one();
        let st = &mut self.state;
        let (previous_v, previous_clamps) = (st.diag.v, st.diag.clamp_count);
        let unsaturated = st.diag.unsaturated_expansions;
        st.diag = Diagnostics {
            // The time is read from `sampled` by `diagnostics()`.
            t: 0.0,
            xi: eval.xi,
            xi_nominal: eval.xi_nominal,
            bounds: (
                (factor * x_u).min(T::max_value()),
                (factor * y_u).min(T::max_value()),
            ),
            nominal_bounds: (x_u, y_u),
            z_hat: z,
            expanded,
            expansion: factor,
            saturation_gap: applied.map(|a| previous_v - a),
            clamp_count: previous_clamps.saturating_add(u64::from(eval.clamped)),
            v: limited.u,
            v_unlimited: v,
            integral,
            integrating,
            unsaturated_expansions: unsaturated.saturating_add(u64::from(expanded && limited.headroom())),
            // The manifold values are filled in by `diagnostics()`.
            ..Diagnostics::default()
        };
        st.started = true;
        st.zhat = next;
        st.sampled = st.clock;
        st.clock = clock_next;
        Ok(limited.u)
    }

    /// The estimate for this step: the stored one, or the initial one.
    #[inline]
    fn current_estimate(&self, e: T) -> [T; N] {
        if self.state.started {
            return self.state.zhat;
        }
        recover::initial_estimate(&self.config, e)
    }

    /// The estimate after the optional saturation `|z_hat_i| <= limit_i`
    /// (the integral, slot 0 with integral action, is not limited).
    #[inline]
    fn limited(&self, mut z: [T; N]) -> [T; N] {
        if let Some(limits) = self.config.estimate_limits() {
            z.iter_mut()
                .zip(limits.iter())
                .skip(self.config.estimate_offset())
                .for_each(|(z, l)| *z = z.max(-*l).min(*l));
        }
        z
    }
}
