//! [`ConfigBuilder`]: the values of a configuration under construction,
//! and the one place where they are checked.

use super::options::check_options;
use super::{Config, DEFAULT_K0, DEFAULT_SETTLE_TIME};
use crate::error::{positive, scale, ConfigError};
use crate::{
    Constraint, Direction, DiscreteHgd, Feedback, Gamma, HighGain, Latch, Real, Skew, SkewedLaw, Transition,
};

/// The flexible-boundary margin a builder was given.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Margin<T> {
    /// [`Constraint::default_rho_e`].
    Default,
    /// An explicit `rho_e`, or `None`: no flexible boundary.
    Given(Option<T>),
}

/// A [`Config`] under construction; [`ConfigBuilder::build`] validates it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConfigBuilder<T, const N: usize> {
    pub(super) dt: T,
    laws: [(Feedback<T>, Option<Skew<T>>); N],
    n_laws: usize,
    constraint: Constraint<T>,
    settle_time: T,
    k0: T,
    k_u: T,
    gamma: Gamma,
    rho_e: Margin<T>,
    transition: Transition,
    latch: Latch,
    pub(super) direction: Direction,
    pub(super) differentiator: Option<HighGain<T, N>>,
    initial_derivatives: Option<[T; N]>,
    estimate_limits: Option<[T; N]>,
    pub(super) integral: bool,
    pub(super) output_limits: Option<(T, T)>,
    rate_limit: Option<T>,
    initial_output: Option<T>,
    #[cfg(feature = "observer")]
    pub(super) observer: Option<crate::ExtendedHighGain<T, N>>,
    #[cfg(feature = "observer")]
    pub(super) cancellation_limit: Option<T>,
}

impl<T: Real, const N: usize> Config<T, N> {
    /// A builder with the required values: sample period `dt` (seconds), one
    /// `(h_p, skew)` per stage (exactly `N - 1`), the constraint with its
    /// final widths, and the control gain `k_u` (eq. (29), input units).
    /// Everything else starts at the paper's choice: `k0 = 2`, `T_s = 1` s,
    /// log Gamma, `rho_e` = [`Constraint::default_rho_e`], the exponential
    /// transition, the paper's latch, no differentiator (state feedback),
    /// zero initial derivatives, no estimate limits, no integral action, no
    /// output limits, no bumpless start.
    pub fn builder(
        dt: T,
        laws: &[(Feedback<T>, Option<Skew<T>>)],
        constraint: Constraint<T>,
        k_u: T,
    ) -> ConfigBuilder<T, N> {
        let mut slots = [(Feedback::Linear { k: T::one() }, None); N];
        slots.iter_mut().zip(laws.iter()).for_each(|(s, l)| *s = *l);
        ConfigBuilder {
            dt,
            laws: slots,
            n_laws: laws.len(),
            constraint,
            settle_time: T::from_f64(DEFAULT_SETTLE_TIME),
            k0: T::from_f64(DEFAULT_K0),
            k_u,
            gamma: Gamma::default(),
            rho_e: Margin::Default,
            transition: Transition::default(),
            latch: Latch::default(),
            direction: Direction::Positive,
            differentiator: None,
            initial_derivatives: None,
            estimate_limits: None,
            integral: false,
            output_limits: None,
            rate_limit: None,
            initial_output: None,
            #[cfg(feature = "observer")]
            observer: None,
            #[cfg(feature = "observer")]
            cancellation_limit: None,
        }
    }

    /// A builder holding this configuration, to derive a changed one.
    pub fn to_builder(&self) -> ConfigBuilder<T, N> {
        let mut laws = [(Feedback::Linear { k: T::one() }, None); N];
        laws.iter_mut()
            .zip(self.laws().iter())
            .for_each(|(s, l)| *s = (*l.feedback(), l.skew().copied()));
        ConfigBuilder {
            dt: self.dt,
            laws,
            n_laws: N.saturating_sub(1),
            constraint: self.constraint,
            settle_time: self.settle_time,
            k0: self.k0,
            k_u: self.k_u,
            gamma: self.gamma,
            rho_e: Margin::Given(self.rho_e),
            transition: self.transition,
            latch: self.latch,
            direction: self.direction,
            differentiator: self.differentiator,
            initial_derivatives: self.initial_derivatives,
            estimate_limits: self.estimate_limits,
            integral: self.integral,
            output_limits: self.output_limits,
            rate_limit: self.rate_limit,
            initial_output: self.initial_output,
            #[cfg(feature = "observer")]
            observer: self.observer().copied(),
            #[cfg(feature = "observer")]
            cancellation_limit: self.cancellation_limit(),
        }
    }
}

impl<T: Real, const N: usize> ConfigBuilder<T, N> {
    /// Sample period `dt`, seconds.
    pub fn dt(mut self, dt: T) -> Self {
        self.dt = dt;
        self
    }

    /// Control gain `k_u > 0` (eq. (29)).
    pub fn k_u(mut self, k_u: T) -> Self {
        self.k_u = k_u;
        self
    }

    /// Constraint type and final half-widths.
    pub fn constraint(mut self, constraint: Constraint<T>) -> Self {
        self.constraint = constraint;
        self
    }

    /// Preset settling time `T_s` of the envelopes, seconds (default 1 s).
    pub fn settle_time(mut self, settle_time: T) -> Self {
        self.settle_time = settle_time;
        self
    }

    /// Initial-width factor `k0 > 1` (default 2).
    pub fn k0(mut self, k0: T) -> Self {
        self.k0 = k0;
        self
    }

    /// The map Gamma (default log).
    pub fn gamma(mut self, gamma: Gamma) -> Self {
        self.gamma = gamma;
        self
    }

    /// The flexible-boundary margin `rho_e`, or `None` for no flexible
    /// boundary. Not calling this keeps [`Constraint::default_rho_e`].
    pub fn rho_e(mut self, rho_e: Option<T>) -> Self {
        self.rho_e = Margin::Given(rho_e);
        self
    }

    /// The transition `S` of the flexible boundary (default exponential).
    pub fn transition(mut self, transition: Transition) -> Self {
        self.transition = transition;
        self
    }

    /// The latch of the envelopes' initial widths (default the paper's).
    pub fn latch(mut self, latch: Latch) -> Self {
        self.latch = latch;
        self
    }

    /// The control direction, the sign of the plant's input gain `G`
    /// (default [`Direction::Positive`], the paper's `G > 0`; src/direction.rs).
    pub fn direction(mut self, direction: Direction) -> Self {
        self.direction = direction;
        self
    }

    /// The high-gain differentiator, or `None` for state feedback only
    /// (default). [`HighGain::paper`] is the paper's.
    pub fn differentiator(mut self, differentiator: Option<HighGain<T, N>>) -> Self {
        self.differentiator = differentiator;
        self
    }

    /// Initial derivative estimates `(z2, ..., zn)` in slots `1..N`.
    pub fn initial_derivatives(mut self, d: Option<[T; N]>) -> Self {
        self.initial_derivatives = d;
        self
    }

    /// Estimate limits `|z_hat_i| <= limit_i` (default none).
    pub fn estimate_limits(mut self, limits: Option<[T; N]>) -> Self {
        self.estimate_limits = limits;
        self
    }

    /// Integral action (default off; docs/design.md §3.8): the law of order
    /// `N` acts on `(I, e, e', ..., e^(N-2))` for a plant of order `N - 1`,
    /// `I` the integral of the measured error (with integral separation).
    /// The stage laws are the `N - 1` of the order-`N` law; the
    /// differentiator runs at order `N - 1` on `e` (its leading `N - 1`
    /// coefficients are used).
    pub fn integral(mut self, on: bool) -> Self {
        self.integral = on;
        self
    }

    /// Magnitude limits `(lo, hi)` of the output, `lo < hi` (infinite ends
    /// allowed); `step` returns the limited output (default none).
    pub fn output_limits(mut self, limits: Option<(T, T)>) -> Self {
        self.output_limits = limits;
        self
    }

    /// Rate limit of the output, output units per second, `> 0` (default none).
    pub fn rate_limit(mut self, rate: Option<T>) -> Self {
        self.rate_limit = rate;
        self
    }

    /// The output the first step starts from (bumpless start; default none).
    pub fn initial_output(mut self, u0: Option<T>) -> Self {
        self.initial_output = u0;
        self
    }

    /// Checks every rule (the error names the parameter and the rule, and
    /// the stage for per-stage values), discretizes the differentiator, and
    /// checks that the first steps succeed for moderate inputs (the probe of
    /// docs/design.md §3.9).
    pub fn build(&self) -> Result<Config<T, N>, ConfigError> {
        let config = self.build_unprobed()?;
        crate::controller::probe(&config)?;
        Ok(config)
    }

    /// [`ConfigBuilder::build`] without the probe.
    pub(crate) fn build_unprobed(&self) -> Result<Config<T, N>, ConfigError> {
        let (laws, rho_e, plant_order) = self.checked(true)?;
        let hgd = match &self.differentiator {
            Some(h) => Some(h.discretize_order(self.dt, plant_order)?),
            None => None,
        };
        if hgd
            .as_ref()
            .is_some_and(|d| d.spectral_radius().partial_cmp(&1.0) != Some(core::cmp::Ordering::Less))
        {
            return Err(ConfigError::new(
                "dt",
                "gives an unstable discretized differentiator (spectral radius of Phi >= 1): lower dt, \
                 raise mu or use discretization exact or tustin",
            ));
        }
        self.assemble(laws, rho_e, hgd)
    }

    /// Every rule but the differentiator's discretization (with the Hurwitz
    /// test of its coefficients when `hurwitz`): the validated stage laws,
    /// `rho_e` and the plant order.
    #[allow(clippy::type_complexity)]
    pub(super) fn checked(
        &self,
        hurwitz: bool,
    ) -> Result<([SkewedLaw<T>; N], Option<T>, usize), ConfigError> {
        if N == 0 {
            return Err(ConfigError::new("order", "must be >= 1"));
        }
        if self.n_laws != N - 1 {
            return Err(ConfigError::new(
                "feedback",
                "must have exactly order - 1 entries (one per stage)",
            ));
        }
        let filler = SkewedLaw::new(Feedback::Linear { k: T::one() }, None)?;
        let mut laws = [filler; N];
        for (i, (slot, (h, skew))) in laws.iter_mut().zip(self.laws.iter()).take(N - 1).enumerate() {
            *slot = SkewedLaw::new(*h, *skew).map_err(|e| e.at_stage(i))?;
        }
        positive(self.dt, "dt")?;
        positive(self.settle_time, "settle_time")?;
        positive(self.k_u, "k_u")?;
        if !(self.k0 > T::one() && self.k0.is_finite()) {
            return Err(ConfigError::new("k0", "must be finite and > 1"));
        }
        scale(self.k0, "k0")?;
        self.constraint.validate(N)?;
        crate::compiled::transition(self.transition)?;
        let rho_e = match self.rho_e {
            Margin::Default => Some(self.constraint.default_rho_e()),
            Margin::Given(r) => r,
        };
        if let Some(r) = rho_e {
            self.constraint.validate_rho_e(r)?;
        }
        // Stage i's derivatives are needed up to order N - 2 - i (eq. (12)).
        for (i, law) in laws.iter().take(N - 1).enumerate() {
            if i + 2 < N && law.is_singular_at_zero() {
                return Err(ConfigError::new(
                    "skew",
                    "must be Nonsingular (NSMD): a power law below 1 without NSMD has unbounded \
                     derivatives at 0, and this stage's derivatives are needed (order >= 3)",
                )
                .at_stage(i));
            }
        }
        crate::compiled::options(self.initial_output.is_some(), self.integral)?;
        if self.integral && N < 2 {
            return Err(ConfigError::new(
                "integral",
                "needs a law of order N >= 2 (N = the plant's order + 1)",
            ));
        }
        let plant_order = N - usize::from(self.integral);
        if let Some(h) = &self.differentiator {
            crate::compiled::discretization(h.discretization)?;
            if hurwitz {
                h.validate_order(plant_order)?;
            } else {
                h.validate_values(plant_order)?;
            }
        }
        check_options(
            self.initial_derivatives.as_ref(),
            self.estimate_limits.as_ref(),
            self.output_limits,
            self.rate_limit,
            self.initial_output,
        )?;
        Ok((laws, rho_e, plant_order))
    }

    /// The configuration of these checked values.
    pub(super) fn assemble(
        &self,
        laws: [SkewedLaw<T>; N],
        rho_e: Option<T>,
        hgd: Option<DiscreteHgd<T, N>>,
    ) -> Result<Config<T, N>, ConfigError> {
        #[cfg(feature = "observer")]
        let observed = self.observed()?;
        Ok(Config {
            dt: self.dt,
            laws,
            constraint: self.constraint,
            settle_time: self.settle_time,
            k0: self.k0,
            k_u: self.k_u,
            gamma: self.gamma,
            rho_e,
            transition: self.transition,
            latch: self.latch,
            direction: self.direction,
            differentiator: self.differentiator,
            hgd: hgd.map(Into::into),
            initial_derivatives: self.initial_derivatives,
            estimate_limits: self.estimate_limits,
            integral: self.integral,
            output_limits: self.output_limits,
            rate_limit: self.rate_limit,
            initial_output: self.initial_output,
            #[cfg(feature = "observer")]
            observed,
        })
    }
}
