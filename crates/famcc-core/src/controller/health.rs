//! The run-time health rule (docs/design.md §3.8): the bounds expanded
//! while the actuator had headroom, for long enough to be a persistent loss
//! of the preset accuracy rather than a start-up transient or the flexible
//! boundary's recovery after a saturation. The cure it suggests is the
//! design's own hold rule, [`crate::design::k_u_to_hold`].
//!
//! ```
//! use famcc_core::{Config, Constraint, Controller, Feedback, HighGain};
//! // x'' = u - 2 under k_u = 0.3: the law cannot hold the load with xi < 1.
//! let cfg = Config::<f64, 2>::builder(1e-3, &[(Feedback::Linear { k: 2.0 }, None)],
//!     Constraint::Lateral { eps: 2.0 }, 0.3)
//!     .differentiator(Some(HighGain::paper())).settle_time(0.2).rho_e(Some(0.1)).output_limits(Some((-100.0, 100.0)))
//!     .build()?;
//! let mut ctrl = Controller::new(cfg);
//! assert_eq!(ctrl.persistent_expansions(), 100);      // 0.5 T_s / dt
//! let (mut x, mut v, mut u) = (0.5, 0.0, 0.0);
//! for _ in 0..3000 {
//!     u = ctrl.step_applied(x, Some(u)).unwrap_or(u).clamp(-100.0, 100.0);
//!     for _ in 0..10 { v += 1e-4 * (u - 2.0); x += 1e-4 * v; }
//! }
//! let h = ctrl.health().expect("k_u too small");
//! assert!(h.suggested_k_u > 0.3);
//! assert!(h.to_string().starts_with("k_u too small for this plant"));
//! # Ok::<(), famcc_core::ConfigError>(())
//! ```

use core::fmt;

use super::Controller;
use crate::Real;

/// The health rule fires once the bounds were expanded with headroom for
/// this fraction of the envelope's settling time `T_s` (counted in samples).
pub const HEALTH_FRACTION: f64 = 0.5;

/// A persistent expansion with headroom: `k_u` too small for the plant (or
/// `rho_e` too large). [`fmt::Display`] gives the message with the cure.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Health {
    /// Steps at which the bounds expanded while the actuator had headroom.
    pub expansions: u64,
    /// `|v|` of the last step: about the input that holds the error still.
    pub hold: f64,
    /// The gain to try: the larger of `2 k_u` and the hold rule's `k_u`.
    pub suggested_k_u: f64,
}

impl fmt::Display for Health {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "k_u too small for this plant: the bounds expanded {} times while the actuator had \
             headroom; raise k_u to {:.3} (k_u >= |u_hold| / (2 atanh 0.5), u_hold the input that \
             holds the error still, about |v| = {:.3} here) or lower rho_e",
            self.expansions, self.suggested_k_u, self.hold
        )
    }
}

impl<T: Real, const N: usize> Controller<T, N> {
    /// The count of [`Controller::unsaturated_expansions`] from which the
    /// loss counts as persistent: `ceil(HEALTH_FRACTION T_s / dt)`, at least 1.
    pub fn persistent_expansions(&self) -> u64 {
        let cfg = self.config();
        let samples = HEALTH_FRACTION * cfg.settle_time().to_f64_lossless() / cfg.dt().to_f64_lossless();
        // `as` saturates (and maps NaN to 0): never a panic.
        num_traits::Float::max(num_traits::Float::ceil(samples), 1.0) as u64
    }

    /// The health finding, when the bounds have expanded with headroom for
    /// [`Controller::persistent_expansions`] steps (only counted when the
    /// applied input is known: `applied` passed, or output limits set).
    /// Cheap while the count is 0.
    #[inline]
    pub fn health(&self) -> Option<Health> {
        let expansions = self.unsaturated_expansions();
        if expansions == 0 || expansions < self.persistent_expansions() {
            return None;
        }
        let hold = num_traits::Float::abs(self.diagnostics().v_unlimited.to_f64_lossless());
        let k_u = self.config().k_u().to_f64_lossless();
        Some(Health {
            expansions,
            hold,
            suggested_k_u: num_traits::Float::max(2.0 * k_u, crate::design::k_u_to_hold(hold)),
        })
    }
}
