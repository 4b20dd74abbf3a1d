//! Building a configuration from a differentiator recursion precomputed
//! elsewhere (on a host), so that a microcontroller links no matrix
//! exponential.

use super::builder::ConfigBuilder;
use crate::error::ConfigError;
use crate::{Config, DiscreteHgd, Real};

impl<T: Real, const N: usize> ConfigBuilder<T, N> {
    /// [`ConfigBuilder::build`] with the differentiator's recursion `hgd`
    /// precomputed for `dt`, e.g. on a host by
    /// [`crate::HighGain::discretize_order`]`(dt, plant order)` (the plant order is
    /// `N`, or `N - 1` with integral action): nothing is discretized here, so
    /// a microcontroller that builds its configuration this way links
    /// neither the `f64` matrix exponential nor soft-float `f64`.
    ///
    /// The differentiator must still be given ([`ConfigBuilder::differentiator`]):
    /// it names the recursion in diagnostics and snapshots, and
    /// [`crate::Controller::step_dt`] rediscretizes it for a one-off period.
    /// Its values are checked as in `build`, but instead of the Hurwitz test
    /// of its coefficients the recursion itself is checked, in `T`: every
    /// entry finite, the prefilter gain in `(0, 1]`, the slots below the plant
    /// order (the integral's) exactly zero, and the spectral radius of `Phi`
    /// below 1. Whether `hgd` is this differentiator's discretization is the
    /// caller's to ensure: build it with the same code on the host.
    ///
    /// ```
    /// use famcc_core::{Config, Constraint, Feedback, HighGain};
    /// let b = Config::<f32, 2>::builder(1e-3, &[(Feedback::Linear { k: 1.0 }, None)],
    ///                                   Constraint::Lateral { eps: 0.1 }, 5.0)
    ///     .differentiator(Some(HighGain::paper()));
    /// // on the host:
    /// let hgd = HighGain::<f32, 2>::paper().discretize(1e-3).unwrap();
    /// // on the target, from the host's values:
    /// assert_eq!(b.build_discretized(hgd), b.build());
    /// let mut unstable = hgd;
    /// unstable.phi[1][1] = 1.5;
    /// assert_eq!(b.build_discretized(unstable).unwrap_err().parameter, "discretized");
    /// ```
    pub fn build_discretized(&self, hgd: DiscreteHgd<T, N>) -> Result<Config<T, N>, ConfigError> {
        let (laws, rho_e, plant_order) = self.checked(false)?;
        if self.differentiator.is_none() {
            return Err(ConfigError::new(
                "differentiator",
                "must be given with a precomputed recursion (e.g. HighGain::paper())",
            ));
        }
        hgd.check_precomputed(N - plant_order)?;
        let config = self.assemble(laws, rho_e, Some(hgd))?;
        crate::controller::probe(&config)?;
        Ok(config)
    }
}
