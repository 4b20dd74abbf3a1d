//! Controller configuration: a validating builder, and the defaults and
//! rules every binding shares.
//!
//! [`Config::builder`] takes the values that have no default (sample period,
//! stage laws, constraint, control gain); everything else starts at the
//! paper's choice and can be changed. [`ConfigBuilder::build`] checks every
//! rule once, discretizes the differentiator for `dt`, and returns a
//! [`Config`] that cannot be changed afterwards, so a [`crate::Controller`]
//! built from it needs no further checks.
//!
//! ```
//! use famcc_core::{Config, Constraint, Feedback, HighGain, Latch};
//! // Example 1 of the paper (LaMC, finite-time law), as the authors ran it.
//! let cfg = Config::<f64, 2>::builder(1e-3, &[(Feedback::FiniteTime { k: 1.0, p: 0.5 }, None)],
//!                                     Constraint::Lateral { eps: 0.1 }, 5.0)
//!     .latch(Latch::Authors)
//!     .differentiator(Some(HighGain::paper()))
//!     .build()
//!     .unwrap();
//! assert_eq!((cfg.k0(), cfg.settle_time(), cfg.rho_e()), (2.0, 1.0, Some(0.01)));
//! let err = Config::<f64, 2>::builder(1e-3, &[(Feedback::Linear { k: 1.0 }, None)],
//!                                     Constraint::Lateral { eps: 0.1 }, 5.0)
//!     .k0(0.5)
//!     .build()
//!     .unwrap_err();
//! assert_eq!(err.to_string(), "k0 must be finite and > 1");
//! ```

mod builder;
mod guarantees;
mod lint;
#[cfg(feature = "observer")]
mod observer;
mod options;
mod precomputed;

pub use builder::ConfigBuilder;
pub use lint::{Finding, Findings, Lint, Suggestion, LINT_COUNT};
#[cfg(feature = "observer")]
pub(crate) use observer::Observed;
#[cfg(feature = "observer")]
pub use observer::DEFAULT_CANCELLATION_SHARE;
pub use options::check_estimate_limits;

use crate::differentiator::{DiscreteHgd, Recursion};
use crate::error::ConfigError;
use crate::{Constraint, Direction, Gamma, HighGain, Latch, Real, SkewedLaw, Transition};

/// Default initial-width factor `k0` (eqs. (21)-(22); every example of the paper).
pub const DEFAULT_K0: f64 = 2.0;
/// Default preset settling time `T_s` of the envelopes, seconds (every
/// example of the paper).
pub const DEFAULT_SETTLE_TIME: f64 = 1.0;

macro_rules! max_order {
    () => {
        8
    };
}

/// The largest system order famcc tests and its run-time-order binding
/// (Python) instantiates. `Controller<T, N>` compiles for any `N >= 1`; the
/// test suite covers `1..=MAX_ORDER`.
pub const MAX_ORDER: usize = max_order!();

/// Checks an order chosen at run time against `1..=MAX_ORDER`.
///
/// ```
/// use famcc_core::config::{check_order, MAX_ORDER};
/// assert!(check_order(MAX_ORDER).is_ok());
/// assert_eq!(check_order(0).unwrap_err().to_string(), "order must be between 1 and 8");
/// ```
pub fn check_order(order: usize) -> Result<(), ConfigError> {
    if (1..=MAX_ORDER).contains(&order) {
        Ok(())
    } else {
        Err(ConfigError::new(
            "order",
            concat!("must be between 1 and ", max_order!()),
        ))
    }
}

/// Everything that defines a FAMCC controller of order `N`, validated.
///
/// Built by [`Config::builder`]; read through its accessors. A `Config` is
/// always valid: the only way to make one is [`ConfigBuilder::build`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Config<T, const N: usize> {
    dt: T,
    /// Stage laws `h_m1..h_m(N-1)`; slot `N-1` is unused.
    laws: [SkewedLaw<T>; N],
    constraint: Constraint<T>,
    settle_time: T,
    k0: T,
    k_u: T,
    gamma: Gamma,
    rho_e: Option<T>,
    transition: Transition,
    latch: Latch,
    direction: Direction,
    differentiator: Option<HighGain<T, N>>,
    /// The differentiator discretized for `dt`, stored by columns.
    hgd: Option<Recursion<T, N>>,
    initial_derivatives: Option<[T; N]>,
    estimate_limits: Option<[T; N]>,
    integral: bool,
    output_limits: Option<(T, T)>,
    rate_limit: Option<T>,
    initial_output: Option<T>,
    /// The observer (replaces the differentiator) and its cancellation's bound.
    #[cfg(feature = "observer")]
    observed: Option<observer::Observed<T, N>>,
}

impl<T: Real, const N: usize> Config<T, N> {
    /// Sample period, seconds.
    pub fn dt(&self) -> T {
        self.dt
    }

    /// The stage laws `h_m1..h_m(N-1)`.
    pub fn laws(&self) -> &[SkewedLaw<T>] {
        self.laws.get(..N.saturating_sub(1)).unwrap_or(&[])
    }

    /// The last stage's law `h_m(n-1)` (None at order 1).
    pub fn last_law(&self) -> Option<&SkewedLaw<T>> {
        self.laws().last()
    }

    /// Constraint type and final half-widths.
    pub fn constraint(&self) -> &Constraint<T> {
        &self.constraint
    }

    /// Preset settling time `T_s` of the envelopes, seconds.
    pub fn settle_time(&self) -> T {
        self.settle_time
    }

    /// Initial-width factor `k0 > 1` (eqs. (21)-(22)).
    pub fn k0(&self) -> T {
        self.k0
    }

    /// Control gain `k_u > 0` (eq. (29)), in input units.
    pub fn k_u(&self) -> T {
        self.k_u
    }

    /// The map Gamma of eq. (29).
    pub fn gamma(&self) -> Gamma {
        self.gamma
    }

    /// Flexible-boundary margin `rho_e` (eq. (30)); `None`: no flexible
    /// boundary (the controller of eq. (29)).
    pub fn rho_e(&self) -> Option<T> {
        self.rho_e
    }

    /// The transition `S` of the flexible boundary.
    pub fn transition(&self) -> Transition {
        self.transition
    }

    /// How the envelopes' initial widths are latched.
    pub fn latch(&self) -> Latch {
        self.latch
    }

    /// The control direction, the sign of the plant's input gain (default
    /// [`Direction::Positive`], the paper's).
    pub fn direction(&self) -> Direction {
        self.direction
    }

    /// The high-gain differentiator (output feedback, eq. (34)); `None` for
    /// state feedback only.
    pub fn differentiator(&self) -> Option<&HighGain<T, N>> {
        self.differentiator.as_ref()
    }

    /// The differentiator discretized for [`Config::dt`].
    pub fn discretized(&self) -> Option<DiscreteHgd<T, N>> {
        self.hgd.as_ref().map(Recursion::hgd)
    }

    /// [`Config::discretized`] as the step runs it.
    #[inline(always)]
    pub(crate) fn recursion(&self) -> Option<&Recursion<T, N>> {
        self.hgd.as_ref()
    }

    /// Initial derivative estimates `(z2, ..., zn)` in slots `offset + 1..N`
    /// ([`Config::estimate_offset`]; the slots before are ignored: the first
    /// sample and, with integral action, the integral); `None` means zeros.
    pub fn initial_derivatives(&self) -> Option<&[T; N]> {
        self.initial_derivatives.as_ref()
    }

    /// The saturation `|z_hat_i| <= limit_i` of the estimates fed to the law
    /// (docs/design.md §3.8), if any. With integral action slot 0 (the
    /// integral) is not limited.
    pub fn estimate_limits(&self) -> Option<&[T; N]> {
        self.estimate_limits.as_ref()
    }

    /// Integral action (docs/design.md §3.8): the law of order `N` acts on
    /// `Z = (I, e, e', ..., e^(N-2))`, `I` the integral of the measured error,
    /// for a plant of order `N - 1`.
    pub fn integral(&self) -> bool {
        // Compiled out (src/compiled.rs): never on, and its code is dead.
        self.integral && cfg!(feature = "integral")
    }

    /// The plant's order: `N`, or `N - 1` with integral action.
    pub fn plant_order(&self) -> usize {
        N - self.estimate_offset()
    }

    /// The slot of `e` in the law's vector `Z`: 0, or 1 with integral action
    /// (slot 0 then holds the integral). Every `N`-sized array about the
    /// plant (estimate, initial derivatives, estimate limits, the state of
    /// `step_state`) is laid out in the law's coordinates: the plant's
    /// `(z1, ..., zn)` in slots `offset..N`.
    pub fn estimate_offset(&self) -> usize {
        usize::from(self.integral())
    }

    /// The first step's estimate `(e0, d2, ..., dn)` in slots `offset..N`
    /// (docs/design.md §3.4; the integral starts at 0): what the first step,
    /// the validation probe and the recovery rule's restart start from.
    #[inline]
    pub(crate) fn initial_estimate(&self, e: T) -> [T; N] {
        let mut z = self.initial_derivatives().copied().unwrap_or([T::zero(); N]);
        let off = self.estimate_offset();
        z.iter_mut().take(off).for_each(|i| *i = T::zero());
        if let Some(z1) = z.get_mut(off) {
            *z1 = e;
        }
        z
    }

    /// The magnitude limits `(lo, hi)` of the output (`step` returns the
    /// limited output), if any.
    pub fn output_limits(&self) -> Option<(T, T)> {
        self.output_limits
    }

    /// The rate limit of the output, output units per second, if any.
    pub fn rate_limit(&self) -> Option<T> {
        self.rate_limit
    }

    /// The output the first step starts from (bumpless start), if any.
    pub fn initial_output(&self) -> Option<T> {
        // Compiled out (src/compiled.rs): never set, and its code is dead.
        self.initial_output.filter(|_| cfg!(feature = "bumpless"))
    }

    /// True without output limits, a rate limit and integral action: the
    /// step's limits, integral separation and health count then do nothing
    /// (unless the caller tells the applied input).
    #[inline(always)]
    pub fn unlimited(&self) -> bool {
        self.output_limits.is_none() && self.rate_limit.is_none() && !self.integral()
    }

    /// [`Config::unlimited`], and a differentiator without the first-order
    /// hold's feedthrough: the steady step that needs neither is compiled
    /// apart (controller/advance.rs).
    #[inline(always)]
    pub(crate) fn steady_fast(&self) -> bool {
        self.unlimited() && !self.hgd.as_ref().is_some_and(Recursion::has_feedthrough)
    }

    /// True with an observer (feature `observer`).
    #[inline(always)]
    pub(crate) fn observing(&self) -> bool {
        #[cfg(feature = "observer")]
        return self.observed.is_some();
        #[cfg(not(feature = "observer"))]
        false
    }

    /// A 52-bit fingerprint of the configuration's values (FNV-1a over
    /// their `Debug` text), exact in an `f64`. Snapshots carry it, so that a
    /// state is never restored into a controller with another configuration.
    pub fn fingerprint(&self) -> u64 {
        let mut h = Fnv(0xcbf2_9ce4_8422_2325);
        // Writing into `Fnv` cannot fail.
        let _ = core::fmt::write(&mut h, format_args!("{:?}", self.to_builder()));
        h.0 & ((1 << 52) - 1)
    }

    /// This configuration with zero initial derivatives (the probe's
    /// diagnosis; every other value stays valid).
    pub(crate) fn without_initial_derivatives(&self) -> Self {
        Self {
            initial_derivatives: None,
            ..*self
        }
    }

    /// The differentiator of [`Config::differentiator`] discretized for a
    /// one-off period `dt` (order [`Config::plant_order`]).
    pub fn discretize_at(&self, dt: T) -> Option<Result<DiscreteHgd<T, N>, ConfigError>> {
        self.differentiator
            .as_ref()
            .map(|h| h.discretize_order(dt, self.plant_order()))
    }

    /// [`Config::discretize_at`] as the step runs it.
    pub(crate) fn recursion_at(&self, dt: T) -> Option<Result<Recursion<T, N>, ConfigError>> {
        self.discretize_at(dt).map(|d| d.map(|d| Recursion::new(&d)))
    }
}

/// The FNV-1a hash of the text written into it.
struct Fnv(u64);

impl core::fmt::Write for Fnv {
    fn write_str(&mut self, s: &str) -> core::fmt::Result {
        for b in s.bytes() {
            self.0 = (self.0 ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3);
        }
        Ok(())
    }
}
