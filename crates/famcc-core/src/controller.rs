//! The FAMCC controller: a real-time discrete controller (docs/design.md §3).
//!
//! Each [`Controller::step`] takes one sample of the output error
//! `e = y - y_d` and returns the control `v = -k_u Gamma(xi~)` (eqs. uOF, WuT)
//! to hold until the next sample. Inside a step:
//! 1. on the first step the estimate is `(e0, 0, ..., 0)` (or the configured
//!    derivative estimates) and the envelopes latch their initial widths;
//! 2. the output is computed from the current estimate `Zhat_k` (built from
//!    samples up to `k-1`): manifold (eq. IS), constraint offset (eq. xi),
//!    flexible boundary (eqs. WxyUxyL, Wxi), control (eq. uT);
//! 3. the estimate advances, `Zhat_{k+1} = Phi Zhat_k + Gamma e_k` (eq. HGD
//!    discretized at construction).
//!
//! A step is transactional: on an error the state is unchanged, with one
//! exception: [`StepError::Overflow`] after the first step means the sample
//! was valid but the law overflowed on it (an outlier drove the estimate out
//! of range); the estimate and the clock then advance, so the controller
//! recovers as the estimate decays, and the caller holds its last output.
//! Without flexible boundaries a too slow sample rate can push `|xi|` to 1:
//! `xi` is then clamped to the largest float below 1 (`Gamma` stays finite) and the event
//! counted.
//!
//! ```
//! use famcc_core::{Config, Constraint, Controller, Feedback, HighGain, Discretization};
//! // Example 1 of the paper: LaMC, finite-time law, eps_x = 0.1, k_u = 5.
//! let mut cfg = Config::<f64, 2>::new(
//!     1e-3, &[(Feedback::FiniteTime { k: 1.0, p: 0.5 }, None)],
//!     Constraint::Lateral { eps: 0.1 }, 1.0, 5.0).unwrap();
//! cfg.differentiator = Some(HighGain::new(0.01, [4.0, 4.0], Discretization::Exact));
//! let mut ctrl = Controller::new(cfg).unwrap();
//! let v = ctrl.step(-1.0).unwrap();
//! assert!(v > 0.0);                       // error below the reference: push up
//! assert!(ctrl.diagnostics().xi.abs() < 1.0);
//! ```

use crate::constraint::{offset, ConstraintKind};
use crate::differentiator::DiscreteHgd;
use crate::error::{ConfigError, StepError};
use crate::{flexible, manifold, Config, Envelope, Real};

/// What the controller did at its last step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Diagnostics<T, const N: usize> {
    /// Time of the last step's sample, seconds.
    pub t: T,
    /// The constraint variable used for the output (flexible `xi~` when the
    /// flexible boundary is on), after clamping.
    pub xi: T,
    /// The nominal constraint variable `xi` (eq. xi), before clamping.
    pub xi_nominal: T,
    /// The manifold value `s = s_n`.
    pub s: T,
    /// `s_1..s_n`.
    pub stages: [T; N],
    /// `s_{n-1}`.
    pub s_prev: T,
    /// `d/dt s_{n-1}`.
    pub ds_prev: T,
    /// Flexible upper bounds `(x~_U, y~_U)` (lower ones are their negatives).
    pub bounds: (T, T),
    /// Nominal upper bounds `(x_U, y_U)`.
    pub nominal_bounds: (T, T),
    /// The estimate the output was computed from (after optional saturation).
    pub z_hat: [T; N],
    /// True when the flexible boundary was expanded.
    pub expanded: bool,
    /// The expansion factor `x~_U / x_U = y~_U / y_U >= 1` of the flexible
    /// boundary (eq. WxyUxyL); exactly 1 while the bounds are nominal.
    pub expansion: T,
    /// `v_{k-1} - applied` when the caller passed the applied input.
    pub saturation_gap: Option<T>,
    /// Number of steps at which `|xi|` had to be clamped below 1.
    pub clamp_count: u64,
    /// The output `v`.
    pub v: T,
}

impl<T: Real, const N: usize> Default for Diagnostics<T, N> {
    fn default() -> Self {
        let z = T::zero();
        Self {
            t: z,
            xi: z,
            xi_nominal: z,
            s: z,
            stages: [z; N],
            s_prev: z,
            ds_prev: z,
            bounds: (z, z),
            nominal_bounds: (z, z),
            z_hat: [z; N],
            expanded: false,
            expansion: T::one(),
            saturation_gap: None,
            clamp_count: 0,
            v: z,
        }
    }
}

/// Everything a controller needs to continue bit-identically, as plain
/// values (for checkpoints, pickling and hand-over between processes).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Snapshot<T, const N: usize> {
    /// False before the first step.
    pub started: bool,
    /// Time base of the sample clock, seconds.
    pub t_base: T,
    /// Samples taken since `t_base`.
    pub k: u64,
    /// The estimate the next step uses.
    pub zhat: [T; N],
    /// Latched initial width of the lateral envelope.
    pub rho0_x: T,
    /// Latched initial width of the vertical envelope.
    pub rho0_y: T,
    /// Clamp events so far.
    pub clamp_count: u64,
    /// The last output (for the saturation gap).
    pub last_v: T,
}

/// The controller's mutable state (everything `reset` clears).
#[derive(Clone, Copy, Debug, PartialEq)]
struct State<T, const N: usize> {
    started: bool,
    /// Time of the next sample = `t_base + k * dt`.
    t_base: T,
    k: u64,
    zhat: [T; N],
    env_x: Envelope<T>,
    env_y: Envelope<T>,
    diag: Diagnostics<T, N>,
}

/// The FAMCC controller of order `N` (the system order).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Controller<T, const N: usize> {
    config: Config<T, N>,
    hgd: Option<DiscreteHgd<T, N>>,
    state: State<T, N>,
}

impl<T: Real, const N: usize> Controller<T, N> {
    /// Validates the configuration and discretizes the differentiator.
    pub fn new(config: Config<T, N>) -> Result<Self, ConfigError> {
        config.validate()?;
        let hgd = match &config.differentiator {
            Some(h) => Some(h.discretize(config.dt)?),
            None => None,
        };
        Ok(Self {
            config,
            hgd,
            state: Self::initial_state(&config),
        })
    }

    fn initial_state(config: &Config<T, N>) -> State<T, N> {
        let (ex, ey) = config.constraint.eps();
        let env = |eps| Envelope {
            rho0: eps,
            eps,
            settle_time: config.settle_time,
        };
        State {
            started: false,
            t_base: T::zero(),
            k: 0,
            zhat: [T::zero(); N],
            env_x: env(ex),
            env_y: env(ey),
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
        self.state.t_base + T::c(self.state.k as f64) * self.config.dt
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
            rho0_x: st.env_x.rho0,
            rho0_y: st.env_y.rho0,
            clamp_count: st.diag.clamp_count,
            last_v: st.diag.v,
        }
    }

    /// Continues from a [`Controller::snapshot`]. Rejects non-finite values
    /// and widths below the final ones; on error nothing changes. The
    /// diagnostics keep only the clamp count and the last output.
    pub fn restore(&mut self, snap: &Snapshot<T, N>) -> Result<(), ConfigError> {
        let finite =
            snap.t_base.is_finite() && snap.last_v.is_finite() && snap.zhat.iter().all(|v| v.is_finite());
        if !finite || snap.t_base < T::zero() {
            return Err(ConfigError::new(
                "state",
                "must hold finite values and a time >= 0",
            ));
        }
        let (ex, ey) = self.config.constraint.eps();
        if !(snap.rho0_x >= ex && snap.rho0_y >= ey && snap.rho0_x.is_finite() && snap.rho0_y.is_finite()) {
            return Err(ConfigError::new(
                "state",
                "envelope widths must be finite and >= eps",
            ));
        }
        let mut st = Self::initial_state(&self.config);
        st.started = snap.started;
        st.t_base = snap.t_base;
        st.k = snap.k;
        st.zhat = snap.zhat;
        st.env_x.rho0 = snap.rho0_x;
        st.env_y.rho0 = snap.rho0_y;
        st.diag.clamp_count = snap.clamp_count;
        st.diag.v = snap.last_v;
        self.state = st;
        Ok(())
    }

    /// Back to the state before the first step (configuration kept).
    pub fn reset(&mut self) {
        self.state = Self::initial_state(&self.config);
    }

    /// One output-feedback step at the nominal `dt` (eq. uOF).
    #[inline]
    pub fn step(&mut self, e: T) -> Result<T, StepError> {
        self.step_applied(e, None)
    }

    /// [`Controller::step`], telling the controller the input the actuator
    /// really applied at the previous sample (diagnostics report the gap).
    #[inline]
    pub fn step_applied(&mut self, e: T, applied: Option<T>) -> Result<T, StepError> {
        if !e.is_finite() {
            return Err(StepError::NonFiniteInput);
        }
        let (zhat, next) = match &self.hgd {
            Some(h) => {
                let z = self.current_estimate(e);
                (z, h.advance(&z, e))
            }
            // Order 1 needs no differentiator: Z = (e) is measured.
            None if N == 1 => ([e; N], [e; N]),
            None => return Err(StepError::NoDifferentiator),
        };
        self.finish(zhat, next, self.config.dt, applied)
    }

    /// One step with a one-off sample period `dt` (the differentiator is
    /// rediscretized for it; the nominal discretization is kept).
    pub fn step_dt(&mut self, e: T, dt: T, applied: Option<T>) -> Result<T, StepError> {
        if !e.is_finite() {
            return Err(StepError::NonFiniteInput);
        }
        if !(dt.is_finite() && dt > T::zero()) {
            return Err(StepError::InvalidDt);
        }
        let (zhat, next) = match &self.config.differentiator {
            Some(h) => {
                let z = self.current_estimate(e);
                (
                    z,
                    h.discretize(dt).map_err(|_| StepError::InvalidDt)?.advance(&z, e),
                )
            }
            None if N == 1 => ([e; N], [e; N]),
            None => return Err(StepError::NoDifferentiator),
        };
        self.finish(zhat, next, dt, applied)
    }

    /// One state-feedback step with a measured error vector `Z = (z1..zn)`
    /// (paper Theorems 1-2). A configured differentiator keeps tracking `z1`.
    pub fn step_state(&mut self, z: [T; N]) -> Result<T, StepError> {
        self.step_state_applied(z, None)
    }

    /// [`Controller::step_state`] with the applied input of the previous sample.
    pub fn step_state_applied(&mut self, z: [T; N], applied: Option<T>) -> Result<T, StepError> {
        if z.iter().any(|v| !v.is_finite()) {
            return Err(StepError::NonFiniteInput);
        }
        let e = z.first().copied().unwrap_or_else(T::zero);
        let zhat = if self.state.started { self.state.zhat } else { z };
        let next = match &self.hgd {
            Some(h) => h.advance(&zhat, e),
            None => z,
        };
        self.finish_with(z, next, self.config.dt, applied)
    }

    /// The estimate for this step: the stored one, or the initial one.
    #[inline]
    fn current_estimate(&self, e: T) -> [T; N] {
        if self.state.started {
            return self.state.zhat;
        }
        let mut z = self.config.initial_derivatives.unwrap_or([T::zero(); N]);
        if let Some(z1) = z.first_mut() {
            *z1 = e;
        }
        z
    }

    #[inline]
    fn finish(&mut self, zhat: [T; N], next: [T; N], dt: T, applied: Option<T>) -> Result<T, StepError> {
        let mut used = zhat;
        if let Some(limits) = &self.config.estimate_limits {
            used.iter_mut()
                .zip(limits.iter())
                .for_each(|(z, l)| *z = z.max(-*l).min(*l));
        }
        self.finish_with(used, next, dt, applied)
    }

    /// Computes the output from `z`, then commits the state (or nothing).
    #[inline]
    fn finish_with(&mut self, z: [T; N], next: [T; N], dt: T, applied: Option<T>) -> Result<T, StepError> {
        if let Some(a) = applied {
            if !a.is_finite() {
                return Err(StepError::NonFiniteApplied);
            }
        }
        if next.iter().any(|v| !v.is_finite()) {
            return Err(StepError::Overflow);
        }
        let t = self.time();
        let t_next = t + dt;
        if !t_next.is_finite() {
            return Err(StepError::InvalidDt);
        }
        let (env_x, env_y) = if self.state.started {
            (self.state.env_x, self.state.env_y)
        } else {
            let (ex, ey) = self.latch(&z);
            if !(ex.rho0.is_finite() && ey.rho0.is_finite()) {
                return Err(StepError::Overflow);
            }
            (ex, ey)
        };
        let mut diag = self.law(&z, t, &env_x, &env_y);
        if !(diag.v.is_finite() && diag.xi.is_finite()) {
            if self.state.started {
                // The sample is valid: let the estimate and the clock move on
                // so that the controller recovers once the estimate is back
                // in range (one outlier must not stop it for good).
                self.state.zhat = next;
                self.advance_clock(t_next, dt);
            }
            return Err(StepError::Overflow);
        }
        diag.saturation_gap = applied.map(|a| self.state.diag.v - a);
        diag.clamp_count += self.state.diag.clamp_count;
        let v = diag.v;
        let st = &mut self.state;
        st.started = true;
        st.env_x = env_x;
        st.env_y = env_y;
        st.zhat = next;
        st.diag = diag;
        self.advance_clock(t_next, dt);
        Ok(v)
    }

    #[inline]
    fn advance_clock(&mut self, t_next: T, dt: T) {
        let st = &mut self.state;
        if dt == self.config.dt {
            st.k += 1;
        } else {
            st.t_base = t_next;
            st.k = 0;
        }
    }

    /// The envelopes latched at the first sample (text after eq. yUyL):
    /// `s_x0 = |h_v(ds_{n-1}) - s_{n-1}|`, `s_y0 = |s|`.
    fn latch(&self, z: &[T; N]) -> (Envelope<T>, Envelope<T>) {
        let c = &self.config;
        let m = manifold::evaluate(z, c.laws());
        let (ex, ey) = c.constraint.eps();
        let mut env_x = self.state.env_x;
        let mut env_y = self.state.env_y;
        let kind = c.constraint.kind();
        if kind != ConstraintKind::Longitudinal {
            if let Some(law) = c.last_law() {
                let o = offset(
                    ConstraintKind::Lateral,
                    law,
                    m.s_prev,
                    m.ds_prev,
                    T::one(),
                    T::one(),
                );
                env_x.rho0 = c.latch.rho0(o.sigma, c.k0, ex);
            }
        }
        if kind != ConstraintKind::Lateral {
            env_y.rho0 = c.latch.rho0(m.s(), c.k0, ey);
        }
        (env_x, env_y)
    }

    /// The control law on an error vector at time `t` (pure).
    #[inline]
    fn law(&self, z: &[T; N], t: T, env_x: &Envelope<T>, env_y: &Envelope<T>) -> Diagnostics<T, N> {
        let c = &self.config;
        let kind = c.constraint.kind();
        // LoMC needs s; LaMC and OMC only (s_{n-1}, ds_{n-1}).
        let m = if kind == ConstraintKind::Longitudinal {
            manifold::evaluate(z, c.laws())
        } else {
            manifold::evaluate_prev(z, c.laws())
        };
        let x_u = if kind == ConstraintKind::Longitudinal {
            T::zero()
        } else {
            env_x.at(t)
        };
        let y_u = if kind == ConstraintKind::Lateral {
            T::zero()
        } else {
            env_y.at(t)
        };
        // Signed offset sigma along the gradient line, half-width in that
        // direction, and the ratio d_U / width that converts |sigma| to d_sc.
        let (sigma, width, d_u) = match (kind, c.last_law()) {
            (ConstraintKind::Longitudinal, _) | (_, None) => (m.s(), y_u, y_u),
            (ConstraintKind::Lateral, Some(law)) => {
                (offset(kind, law, m.s_prev, m.ds_prev, x_u, y_u).sigma, x_u, x_u)
            }
            (ConstraintKind::Oblique, Some(law)) => {
                let d_u = (x_u * x_u + y_u * y_u).root();
                (offset(kind, law, m.s_prev, m.ds_prev, x_u, y_u).sigma, x_u, d_u)
            }
        };
        let xi_nominal = sigma / width;
        let factor = match c.rho_e {
            Some(rho_e) => flexible::expansion(c.transition, xi_nominal.abs() * d_u, d_u, rho_e),
            None => T::one(),
        };
        let mut xi = xi_nominal / factor;
        let mut clamps = 0;
        // The largest float below 1 (docs/design.md §3.6): Gamma stays finite.
        let limit = T::one() - T::epsilon() * T::c(0.5);
        if xi.abs() > limit {
            xi = if xi > T::zero() { limit } else { -limit };
            clamps = 1;
        }
        let v = -c.k_u * c.gamma.eval(xi);
        Diagnostics {
            t,
            xi,
            xi_nominal,
            // Filled in by `diagnostics()`.
            s: T::zero(),
            stages: [T::zero(); N],
            s_prev: T::zero(),
            ds_prev: T::zero(),
            bounds: (factor * x_u, factor * y_u),
            nominal_bounds: (x_u, y_u),
            z_hat: *z,
            expanded: factor > T::one(),
            expansion: factor,
            saturation_gap: None,
            clamp_count: clamps,
            v,
        }
    }
}
