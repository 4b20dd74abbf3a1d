//! The parsed configuration of a Python controller, typed (no strings),
//! in f64: what `repr`, `config()`, pickling and banks are made from, and
//! what famcc-core's builder is fed.

use crate::differentiator::{to_array, HighGain};
use crate::laws::{Law, SkewSpec};
use crate::names::DType;
use famcc_core::{Config, ConfigError, Constraint, Gamma, Latch, Real, Transition};

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
    pub differentiator: Option<HighGain>,
    /// `z2..zn`.
    pub initial_derivatives: Option<Vec<f64>>,
    pub dtype: DType,
}

impl Spec {
    /// famcc-core's validated configuration of order `N` in `T`.
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
            .transition(self.transition);
        if let RhoE::Given(r) = self.rho_e {
            b = b.rho_e(r.map(t));
        }
        if let Some(h) = &self.differentiator {
            let core = h
                .core::<T, N>()
                .ok_or(ConfigError::new("a", "must have one coefficient per order"))?;
            b = b
                .differentiator(Some(core))
                .estimate_limits(h.core_limits::<T, N>());
        }
        if let Some(d) = &self.initial_derivatives {
            let full: Vec<f64> = core::iter::once(0.0).chain(d.iter().copied()).collect();
            b = b.initial_derivatives(to_array::<T, N>(&full));
        }
        b.build()
    }

    /// The spec of a famcc-core configuration.
    pub fn from_config<T: Real, const N: usize>(cfg: &Config<T, N>, dtype: DType) -> Self {
        let f = |x: T| x.to_f64_lossless();
        let initial = cfg
            .initial_derivatives()
            .map(|d| d.iter().skip(1).map(|x| f(*x)).collect());
        Spec {
            order: N,
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
            differentiator: cfg
                .differentiator()
                .map(|h| HighGain::from_core(h, cfg.estimate_limits())),
            initial_derivatives: initial,
            dtype,
        }
    }
}
