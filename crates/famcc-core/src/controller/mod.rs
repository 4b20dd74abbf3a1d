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

mod advance;
mod clock;
mod diagnostics;
mod health;
mod observe;
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
use recover::Cause;

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
    /// The differentiator's last input: the prefiltered error (the error
    /// itself without a prefilter).
    filtered: T,
    /// The observer's estimate of the lumped term, `Lhat` (observe.rs).
    #[cfg(feature = "observer")]
    lhat: T,
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
        hgd: Option<&differentiator::Recursion<T, N>>,
        clock_next: Clock<T>,
        cause: Cause,
    ) -> StepError {
        if self.started {
            (self.zhat, self.filtered) = recover::restarted(c, measured, hgd, cause);
            #[cfg(feature = "observer")]
            {
                self.lhat = T::zero();
            }
            self.clock = clock_next;
            if hgd.is_some_and(differentiator::Recursion::has_feedthrough) {
                // The first-order hold: the next sample starts a run (count
                // 0, which no sample after the first has otherwise), and
                // `held` adds no increment to the restarted estimate then.
                self.clock = Clock::at(clock_next.time(), 0, clock_next.period, c.settle_time());
            }
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
            filtered: T::zero(),
            #[cfg(feature = "observer")]
            lhat: T::zero(),
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
    /// used, and the flexible bounds from the nominal ones and the
    /// expansion factor, so `step()` does not pay for values only a reader
    /// needs.
    pub fn diagnostics(&self) -> Diagnostics<T, N> {
        let mut d = self.state.diag;
        d.t = self.state.sampled.time();
        // `min(T::MAX)` without its NaN handling (a NaN product gives MAX either way).
        let capped = |w: T| if w < T::max_value() { w } else { T::max_value() };
        let (x_u, y_u) = d.nominal_bounds;
        d.bounds = (capped(d.expansion * x_u), capped(d.expansion * y_u));
        d.expanded = d.expansion > T::one();
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
    /// samples so far when only the nominal `dt` was used, and, with the
    /// first-order hold, no step overflowed: its restart starts a run),
    /// saturating at `u64::MAX`.
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
}
