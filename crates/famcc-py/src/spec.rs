//! The parsed configuration of a Python controller, typed (no strings),
//! in f64: what `repr`, `config()`, pickling and banks are made from, and
//! what famcc-core's builder is fed.

use crate::differentiator::HighGain;
use crate::laws::Law;
use crate::names::DType;
use crate::observer::Observer;
use crate::orders::to_array;
use crate::skews::SkewSpec;
use famcc_core::{Config, ConfigError, Constraint, Direction, Gamma, Latch, Real, Transition};
use pyo3::prelude::*;

/// The flexible-boundary margin as given.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RhoE {
    /// famcc-core's default (`Constraint::default_rho_e`).
    Default,
    /// An explicit margin, or `None`: no flexible boundary.
    Given(Option<f64>),
}

/// A controller's configuration.
#[derive(Clone, Debug)]
pub struct Spec {
    pub order: usize,
    pub dt: f64,
    /// One `(h_p, skew)` per stage (`order - 1`).
    pub stages: Vec<(Law, Option<SkewSpec>)>,
    pub constraint: Constraint<f64>,
    pub settle_time: f64,
    pub k0: f64,
    pub k_u: f64,
    pub gamma: Gamma,
    pub rho_e: RhoE,
    pub latch: Latch,
    pub transition: Transition,
    /// The control direction, the sign of the plant's input gain.
    pub direction: Direction,
    pub differentiator: Option<HighGain>,
    /// `z2..zn`.
    pub initial_derivatives: Option<Vec<f64>>,
    pub dtype: DType,
    /// Integral action: the core's law has order `order + 1`.
    pub integral: bool,
    pub output_limits: Option<(f64, f64)>,
    pub rate_limit: Option<f64>,
    pub initial_output: Option<f64>,
    /// The extended observer (replaces the differentiator; docs/observer.md).
    pub observer: Option<Observer>,
    /// The cancellation's bound `delta` (None: famcc-core's default).
    pub cancellation_limit: Option<f64>,
}

impl Spec {
    /// The order of the core's law: the plant's `order`, plus 1 with
    /// integral action.
    pub fn law_order(&self) -> usize {
        self.order + usize::from(self.integral)
    }

    /// famcc-core's validated configuration of law order `N` in `T`
    /// ([`Spec::law_order`]; with integral action the plant's arrays are
    /// laid out in the law's coordinates: the differentiator's coefficients
    /// padded with a trailing 0, the estimate limits and the initial
    /// derivatives shifted by the integral's slot).
    pub fn config<T: Real, const N: usize>(&self) -> Result<Config<T, N>, ConfigError> {
        let t = |x: f64| T::from_f64(x);
        let stages: Vec<_> = self
            .stages
            .iter()
            .map(|(l, s)| (l.feedback::<T>(), s.map(|s| s.skew::<T>())))
            .collect();
        let mut b = Config::<T, N>::builder(t(self.dt), &stages, self.constraint.map(t), t(self.k_u))
            .settle_time(t(self.settle_time))
            .k0(t(self.k0))
            .gamma(self.gamma)
            .latch(self.latch)
            .direction(self.direction)
            .transition(self.transition);
        if let RhoE::Given(r) = self.rho_e {
            b = b.rho_e(r.map(t));
        }
        let off = usize::from(self.integral);
        if let Some(h) = &self.differentiator {
            let core = h
                .core_padded::<T, N>(off)
                .ok_or(ConfigError::new("a", "must have one coefficient per order"))?;
            b = b
                .differentiator(Some(core))
                .estimate_limits(h.core_limits_shifted::<T, N>(off));
        }
        if let Some(d) = &self.initial_derivatives {
            let full: Vec<f64> = core::iter::repeat_n(0.0, 1 + off)
                .chain(d.iter().copied())
                .collect();
            b = b.initial_derivatives(to_array::<T, N>(&full));
        }
        if let Some(o) = &self.observer {
            let core = o.core::<T, N>().ok_or(ConfigError::new(
                "observer_a",
                "must have order + 1 coefficients (or None: the binomial default)",
            ))?;
            b = b.observer(Some(core));
        }
        b.cancellation_limit(self.cancellation_limit.map(t))
            .integral(self.integral)
            .output_limits(self.output_limits.map(|(lo, hi)| (t(lo), t(hi))))
            .rate_limit(self.rate_limit.map(t))
            .initial_output(self.initial_output.map(t))
            .build()
    }

    /// The spec of a famcc-core configuration.
    pub fn from_config<T: Real, const N: usize>(cfg: &Config<T, N>, dtype: DType) -> Self {
        let f = |x: T| x.to_f64_lossless();
        let off = cfg.estimate_offset();
        let initial = cfg
            .initial_derivatives()
            .map(|d| d.iter().skip(1 + off).map(|x| f(*x)).collect());
        Spec {
            order: cfg.plant_order(),
            dt: f(cfg.dt()),
            stages: cfg
                .laws()
                .iter()
                .map(|l| {
                    (
                        Law::from_feedback(l.feedback()),
                        l.skew().map(SkewSpec::from_skew),
                    )
                })
                .collect(),
            constraint: cfg.constraint().map(f),
            settle_time: f(cfg.settle_time()),
            k0: f(cfg.k0()),
            k_u: f(cfg.k_u()),
            gamma: cfg.gamma(),
            rho_e: RhoE::Given(cfg.rho_e().map(f)),
            latch: cfg.latch(),
            transition: cfg.transition(),
            direction: cfg.direction(),
            differentiator: cfg
                .differentiator()
                .map(|h| HighGain::from_core(h, cfg.estimate_limits(), off)),
            initial_derivatives: initial,
            dtype,
            integral: cfg.integral(),
            output_limits: cfg.output_limits().map(|(lo, hi)| (f(lo), f(hi))),
            rate_limit: cfg.rate_limit().map(f),
            initial_output: cfg.initial_output().map(f),
            observer: cfg.observer().map(Observer::from_core),
            cancellation_limit: cfg.cancellation_limit().map(f),
        }
    }
}

/// A controller's configuration, parsed and typed; :meth:`build` makes the
/// controller.
///
/// Returned by :func:`famcc.design` (``Design.spec``): the design's
/// configuration, built into a :class:`Controller` without keyword
/// arguments or text. Frozen and picklable. Its values are checked when a
/// controller is built (by famcc-core, as in the :class:`Controller`
/// constructor).
///
/// Examples
/// --------
/// >>> import famcc
/// >>> d = famcc.design(2, 1e-3, u_limits=(-12, 12), eps=0.01, settle_time=2.0,
/// ...                  hold_input=4.0, gain=25.0)
/// >>> spec = d.spec
/// >>> spec.order, spec.dt
/// (2, 0.001)
/// >>> spec.build().config() == d.controller().config()
/// True
/// >>> spec.replace(k_u=10.0).config()["k_u"]
/// 10.0
#[pyclass(frozen, module = "famcc._core", name = "ControllerSpec")]
#[derive(Clone)]
pub struct ControllerSpec {
    pub spec: Spec,
}
