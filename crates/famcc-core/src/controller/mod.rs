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

mod diagnostics;
mod output;
mod snapshot;
mod start;
mod steps;

pub use diagnostics::Diagnostics;
pub use snapshot::{Snapshot, SNAPSHOT_FIELDS};
pub use start::MAX_WIDENING;

use crate::constraint::Envelopes;
use crate::error::{ConfigError, StepError};
use crate::{differentiator, manifold, Config, Real};
use output::Limits;

/// The controller's mutable state (everything `reset` clears).
#[derive(Clone, Copy, Debug, PartialEq)]
struct State<T, const N: usize> {
    started: bool,
    /// Time of the next sample = `t_base + k * dt`.
    t_base: T,
    k: u64,
    /// The estimate in the law's coordinates (with integral action slot 0
    /// holds the integral `I`).
    zhat: [T; N],
    envelopes: Envelopes<T>,
    diag: Diagnostics<T, N>,
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
            t_base: T::zero(),
            k: 0,
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
        if self.state.started {
            let m = manifold::evaluate(&d.z_hat, self.config.laws());
            d.s = m.s();
            d.stages = m.stages;
            d.s_prev = m.s_prev;
            d.ds_prev = m.ds_prev;
        }
        d
    }

    /// The time of the next sample, seconds.
    pub fn time(&self) -> T {
        self.state.t_base + T::from_u64(self.state.k) * self.config.dt()
    }

    /// The current estimate `Zhat` (the one the next step will use).
    pub fn estimate(&self) -> &[T; N] {
        &self.state.zhat
    }

    /// The state as plain values; [`Controller::restore`] continues from it.
    pub fn snapshot(&self) -> Snapshot<T, N> {
        let st = &self.state;
        Snapshot {
            started: st.started,
            t_base: st.t_base,
            k: st.k,
            zhat: st.zhat,
            rho0_x: st.envelopes.x.rho0,
            rho0_y: st.envelopes.y.rho0,
            clamp_count: st.diag.clamp_count,
            last_v: st.diag.v,
        }
    }

    /// Continues from a [`Controller::snapshot`]. Rejects non-finite values,
    /// a negative time and widths below the final ones; on error nothing
    /// changes. The diagnostics keep only the clamp count and the last output
    /// (the count of expansions with headroom restarts at 0). The estimate
    /// carries the integral (slot 0) with integral action.
    pub fn restore(&mut self, snap: &Snapshot<T, N>) -> Result<(), ConfigError> {
        snap.check(self.config.constraint().eps())?;
        let mut st = Self::initial_state(&self.config);
        st.started = snap.started;
        st.t_base = snap.t_base;
        st.k = snap.k;
        st.zhat = snap.zhat;
        st.envelopes.x.rho0 = snap.rho0_x;
        st.envelopes.y.rho0 = snap.rho0_y;
        st.diag.clamp_count = snap.clamp_count;
        st.diag.v = snap.last_v;
        self.state = st;
        Ok(())
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
        // The measured sample, the vector the law uses, and the estimate the
        // next step will use (all in the law's coordinates).
        let (e, mut z, mut next) = match measured {
            Measured::Error(e) => {
                let one_off;
                let hgd = match one_off_dt.and_then(|dt| c.discretize_at(dt)) {
                    Some(d) => {
                        one_off = d.map_err(|_| StepError::InvalidDt)?;
                        Some(&one_off)
                    }
                    None => c.discretized(),
                };
                match hgd {
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
                }
            }
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
        if next.iter().any(|v| !v.is_finite()) {
            return Err(StepError::Overflow);
        }
        let t = self.time();
        let t_next = t + dt;
        if !t_next.is_finite() {
            return Err(StepError::InvalidDt);
        }
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
        let latched = !first || (env.x.rho0.is_finite() && env.y.rho0.is_finite());
        if !(latched && v.is_finite() && eval.xi.is_finite()) {
            match unlatched {
                Some(envelopes) => self.state.envelopes = envelopes,
                None => {
                    // The sample is valid: let the estimate and the clock move
                    // on so that the controller recovers once the estimate is
                    // back in range (one outlier must not stop it for good).
                    if let (1, Some(n0), Some(z0)) = (off, next.first_mut(), z.first()) {
                        *n0 = *z0;
                    }
                    self.state.zhat = next;
                    self.advance_clock(t_next, dt);
                }
            }
            return Err(StepError::Overflow);
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
            if !i_next.is_finite() {
                if let Some(envelopes) = unlatched {
                    self.state.envelopes = envelopes;
                }
                return Err(StepError::Overflow);
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
            t,
            xi: eval.xi,
            xi_nominal: eval.xi_nominal,
            bounds: (factor * x_u, factor * y_u),
            nominal_bounds: (x_u, y_u),
            z_hat: z,
            expanded,
            expansion: factor,
            saturation_gap: applied.map(|a| previous_v - a),
            clamp_count: previous_clamps + u64::from(eval.clamped),
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
        self.advance_clock(t_next, dt);
        Ok(limited.u)
    }

    /// The estimate for this step: the stored one, or the initial one
    /// (`(e0, d2, ..., dn)` in slots `offset..N`; the integral starts at 0).
    #[inline]
    fn current_estimate(&self, e: T) -> [T; N] {
        if self.state.started {
            return self.state.zhat;
        }
        let mut z = self
            .config
            .initial_derivatives()
            .copied()
            .unwrap_or([T::zero(); N]);
        let off = self.config.estimate_offset();
        z.iter_mut().take(off).for_each(|i| *i = T::zero());
        if let Some(z1) = z.get_mut(off) {
            *z1 = e;
        }
        z
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

    #[inline]
    fn advance_clock(&mut self, t_next: T, dt: T) {
        let st = &mut self.state;
        if dt == self.config.dt() {
            st.k += 1;
        } else {
            st.t_base = t_next;
            st.k = 0;
        }
    }
}
