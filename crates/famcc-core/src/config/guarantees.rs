//! What a configuration guarantees about the output: the accuracy it presets
//! for `|z1|` and the reaching time `T'` of the paper's corollaries. The one
//! home of both rules: the bindings, the campaigns' deadlines and the
//! reports ask these two methods.
//!
//! ```
//! use famcc_core::{Config, Constraint, Feedback};
//! // Example 1 of the paper: LaMC at order 2, the finite-time law k = 1, p = 0.5.
//! let cfg = Config::<f64, 2>::builder(1e-3, &[(Feedback::FiniteTime { k: 1.0, p: 0.5 }, None)],
//!                                     Constraint::Lateral { eps: 0.1 }, 5.0)
//!     .build()
//!     .unwrap();
//! assert_eq!(cfg.output_accuracy(), Some(0.1)); // eps_x = eps_z (Corollary 1)
//! assert_eq!(cfg.corollary_time(-1.0), Some(2.0)); // T_fn' = 2 s, so T_fn < 1 + 2 s
//! ```

use super::Config;
use crate::{bounds, Constraint, Feedback, Real};

impl<T: Real, const N: usize> Config<T, N> {
    /// The output accuracy `eps_z` this configuration presets for `|z1|`,
    /// or `None` when it presets none.
    ///
    /// The constraint's half-width bounds the constrained offset, which is
    /// `z1` itself only at law order 1 (`s = z1`) and for LaMC at law order 2
    /// (`s_1 = z1`, `eps_x = eps_z`: Corollary 1). Otherwise a skewed first
    /// stage (SSMD or NSMD) presets its `eps_z` (Corollaries 2 and 3). With
    /// integral action the law's first coordinate is the integral of the
    /// error, which these bounds then concern: no output accuracy.
    ///
    /// ```
    /// use famcc_core::{Config, Constraint, Feedback, Skew};
    /// let law = Feedback::Linear { k: 1.0 };
    /// let lomc = Config::<f64, 2>::builder(1e-3, &[(law, None)],
    ///                                      Constraint::Longitudinal { eps: 0.1 }, 5.0)
    ///     .build().unwrap();
    /// assert_eq!(lomc.output_accuracy(), None); // |s| < eps bounds no z1 by itself
    /// let skewed = Config::<f64, 2>::builder(1e-3, &[(law, Some(Skew::smooth(0.05, 0.02)))],
    ///                                        Constraint::Longitudinal { eps: 0.1 }, 5.0)
    ///     .build().unwrap();
    /// assert_eq!(skewed.output_accuracy(), Some(0.02)); // the first stage's eps_z
    /// ```
    pub fn output_accuracy(&self) -> Option<T> {
        if self.integral() {
            return None;
        }
        match self.constraint {
            Constraint::Longitudinal { eps } if N == 1 => return Some(eps),
            Constraint::Lateral { eps } if N == 2 => return Some(eps),
            _ => {}
        }
        self.laws()
            .first()
            .and_then(|law| law.skew())
            .map(|skew| skew.eps_z)
    }

    /// The reaching time `T'` of the paper's corollaries (seconds) for the
    /// initial error `z1_0`, or `None` when the stage laws have no such
    /// bound. The whole bound on reaching `|z1| < eps_z` is `T_s + T'`
    /// (after a saturation episode ending at `T_e`, `max(T_e, T_s) + T'`).
    ///
    /// - every stage [`Feedback::FixedTime`]: `T_fr'` of Corollary 3
    ///   ([`bounds::fixed_time`], independent of `z1_0`);
    /// - one stage, [`Feedback::VariableExponent`]: `T_fxe'` of Corollary 2
    ///   ([`bounds::variable_exponent`]);
    /// - one stage, [`Feedback::FiniteTime`]: `T_fn'` of Corollary 1
    ///   ([`bounds::finite_time`], which depends on `|z1_0|`).
    ///
    /// ```
    /// use famcc_core::{Config, Constraint, Feedback};
    /// let linear = Config::<f64, 2>::builder(1e-3, &[(Feedback::Linear { k: 1.0 }, None)],
    ///                                        Constraint::Lateral { eps: 0.1 }, 5.0)
    ///     .build().unwrap();
    /// assert_eq!(linear.corollary_time(1.0), None); // exponential, not finite-time
    /// ```
    pub fn corollary_time(&self, z1_0: T) -> Option<T> {
        let laws = self.laws();
        let mut fixed = T::zero();
        let mut all_fixed = !laws.is_empty();
        for law in laws {
            match *law.feedback() {
                Feedback::FixedTime { alpha, p, beta, q } => {
                    fixed = fixed + bounds::fixed_time_stage(alpha, p, beta, q);
                }
                _ => all_fixed = false,
            }
        }
        if all_fixed {
            return Some(fixed);
        }
        match laws {
            [one] => match *one.feedback() {
                Feedback::VariableExponent { k, r_b, r_1, r_t } => {
                    Some(bounds::variable_exponent(k, r_b, r_1, r_t))
                }
                Feedback::FiniteTime { k, p } => Some(bounds::finite_time(k, p, z1_0)),
                _ => None,
            },
            _ => None,
        }
    }
}
