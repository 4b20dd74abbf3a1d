//! Everything about the constraint variable `xi` (paper Steps C1-C3 and the
//! flexible boundaries): the constraint type with its final widths
//! ([`Constraint`]), the envelopes and their latch (eqs. (21)-(22), xUxL and
//! yUyL), the offset along the gradient line (eqs. (26)-(27), [`offset`]
//! module), `xi` itself (eq. (28)), the flexible expansion (eqs. (30)-(31),
//! [`expansion`]), the clamp below 1 (docs/design.md §3.6) and the root
//! search behind `h_v` and `x_c` ([`decreasing_root`]).
//!
//! With symmetric bounds (`x_L = -x_U`, `y_L = -y_U`) eq. (28) reduces to
//! `xi = sigma / width`, and `|xi| = d_sc / d_U` where `d_sc` is the distance
//! from the state to `(x_c, y_c)` along the gradient line and
//! `d_U = sqrt(x_U^2 + y_U^2)` its nominal half-width (the quantities of the
//! flexible boundary, eq. (30)):
//!
//! | type | `sigma` | width | `d_U` |
//! |---|---|---|---|
//! | LoMC | `s` | `y_U` | `y_U` |
//! | LaMC | `s_{n-1} - h_v(ds_{n-1})` | `x_U` | `x_U` |
//! | OMC | `s_{n-1} - x_c` | `x_U` | `sqrt(x_U^2 + y_U^2)` |
//!
//! ```
//! use famcc_core::Constraint;
//! let c = Constraint::Oblique { eps_x: 0.1_f64, eps_y: 0.4 };
//! assert_eq!(c.eps(), (0.1, 0.4));
//! // rho_e defaults to min(0.01, smallest final width / 10)
//! assert_eq!(Constraint::Lateral { eps: 0.05_f64 }.default_rho_e(), 0.05 * 0.1);
//! assert_eq!(Constraint::Lateral { eps: 0.5_f64 }.default_rho_e(), 0.01);
//! ```

mod flexible;
pub mod offset;
mod root;

pub use flexible::expansion;
pub use offset::{inverse, Offset};
pub use root::{bracketed_root, decreasing_root, BRACKET_ITERATIONS, ROOT_ITERATIONS};

use crate::error::{positive, ConfigError};
use crate::manifold::Manifold;
use crate::{Envelope, Latch, Real, SkewedLaw, Transition};

/// The constraint type with its final half-widths (paper Step C1, eqs. (21)
/// xUxL and (22) yUyL).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Constraint<T> {
    /// LoMC: final vertical half-width `eps = eps_y` (unit of `s`).
    Longitudinal {
        /// `eps_y > 0`.
        eps: T,
    },
    /// LaMC: final horizontal half-width `eps = eps_x` (unit of `s_{n-1}`);
    /// with the paper's choice `eps_x = eps_z` it is the output accuracy at order 2.
    Lateral {
        /// `eps_x > 0`.
        eps: T,
    },
    /// OMC: both final half-widths.
    Oblique {
        /// `eps_x > 0`.
        eps_x: T,
        /// `eps_y > 0`.
        eps_y: T,
    },
}

/// The two envelopes `x_U(t) = -x_L(t)` and `y_U(t) = -y_L(t)` of eqs. (21)
/// and (22); the one a constraint type does not use stays at its final width.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Envelopes<T> {
    /// Horizontal half-width `x_U` (LaMC, OMC).
    pub x: Envelope<T>,
    /// Vertical half-width `y_U` (LoMC, OMC).
    pub y: Envelope<T>,
}

/// `xi` and what it was made of, at one state (eqs. (28), (30), (31)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Evaluation<T> {
    /// The constraint variable used by the law (flexible `xi~` when the
    /// flexible boundary is on), after the clamp below 1.
    pub xi: T,
    /// The nominal `xi` of eq. (28), before the clamp.
    pub xi_nominal: T,
    /// The flexible expansion factor `x~_U / x_U = y~_U / y_U` (1: nominal).
    pub expansion: T,
    /// The nominal half-widths `(x_U, y_U)` at this time (0 where unused).
    pub nominal: (T, T),
    /// True when `|xi|` had to be clamped below 1.
    pub clamped: bool,
}

impl<T> Constraint<T> {
    /// The same type with its widths converted by `f` (e.g. `f64` to `f32`).
    pub fn map<U>(self, f: impl Fn(T) -> U) -> Constraint<U> {
        match self {
            Constraint::Longitudinal { eps } => Constraint::Longitudinal { eps: f(eps) },
            Constraint::Lateral { eps } => Constraint::Lateral { eps: f(eps) },
            Constraint::Oblique { eps_x, eps_y } => Constraint::Oblique {
                eps_x: f(eps_x),
                eps_y: f(eps_y),
            },
        }
    }
}

impl<T: Real> Constraint<T> {
    /// `(eps_x, eps_y)`, 0 in the direction the type doesn't use.
    pub fn eps(&self) -> (T, T) {
        match *self {
            Constraint::Longitudinal { eps } => (T::zero(), eps),
            Constraint::Lateral { eps } => (eps, T::zero()),
            Constraint::Oblique { eps_x, eps_y } => (eps_x, eps_y),
        }
    }

    /// True for the types that bound the horizontal offset (LaMC, OMC): they
    /// need `s_{n-1}`, i.e. order 2 or more (docs/design.md §4.3).
    pub fn uses_x(&self) -> bool {
        !matches!(self, Constraint::Longitudinal { .. })
    }

    /// True for the types that bound the vertical offset `s` (LoMC, OMC).
    pub fn uses_y(&self) -> bool {
        !matches!(self, Constraint::Lateral { .. })
    }

    /// The default flexible-boundary margin: `0.01`, or a tenth of the
    /// smallest final half-width when that is smaller (the paper asks
    /// `rho_e << sqrt(eps_x^2 + eps_y^2)` after eq. (30)).
    pub fn default_rho_e(&self) -> T {
        let smallest = match *self {
            Constraint::Longitudinal { eps } | Constraint::Lateral { eps } => eps,
            Constraint::Oblique { eps_x, eps_y } => eps_x.min(eps_y),
        };
        T::from_f64(0.01).min(smallest * T::from_f64(0.1))
    }

    /// Checks the final widths and that the type exists at `order`.
    pub(crate) fn validate(&self, order: usize) -> Result<(), ConfigError> {
        crate::compiled::constraint(self)?;
        match *self {
            Constraint::Longitudinal { eps } | Constraint::Lateral { eps } => positive(eps, "eps")?,
            Constraint::Oblique { eps_x, eps_y } => {
                positive(eps_x, "eps_x")?;
                positive(eps_y, "eps_y")?;
            }
        }
        if order < 2 && self.uses_x() {
            return Err(ConfigError::new(
                "constraint",
                "must be longitudinal at order 1 (lateral and oblique need s_(n-1))",
            ));
        }
        Ok(())
    }

    /// Checks a flexible-boundary margin against the final widths (after
    /// eq. (30): `rho_e` small against `sqrt(eps_x^2 + eps_y^2)`).
    pub(crate) fn validate_rho_e(&self, rho_e: T) -> Result<(), ConfigError> {
        positive(rho_e, "rho_e")?;
        let (ex, ey) = self.eps();
        if rho_e * rho_e >= ex * ex + ey * ey {
            return Err(ConfigError::new(
                "rho_e",
                "must be smaller than the final bound width eps",
            ));
        }
        Ok(())
    }

    /// The envelopes before the latch: both at their final widths.
    pub fn envelopes(&self, settle_time: T) -> Envelopes<T> {
        let (ex, ey) = self.eps();
        let env = |eps| Envelope {
            rho0: eps,
            eps,
            settle_time,
        };
        Envelopes {
            x: env(ex),
            y: env(ey),
        }
    }

    /// True when the manifold value `s = s_n` is needed at this step: LoMC
    /// constrains `s` itself; OMC latches its vertical width from `s` at the
    /// first step; LaMC (and OMC later on) needs only `(s_{n-1}, ds_{n-1})`.
    #[inline(always)]
    pub fn needs_s(&self, first_step: bool) -> bool {
        match self {
            Constraint::Longitudinal { .. } => true,
            Constraint::Lateral { .. } => false,
            Constraint::Oblique { .. } => first_step,
        }
    }

    /// `xi` of the state `m` at time `t` (eq. (28); eq. (31) with a flexible
    /// margin `rho_e`), with the envelopes `env` latched from this very state
    /// first when `latch` is given (the first step).
    ///
    /// The latch follows the text after eq. (22): `x_U` starts from
    /// `s_x0 = |h_v(ds_{n-1}) - s_{n-1}|`, the horizontal offset, for both
    /// types that use `x` (LaMC and OMC: the paper defines `s_x0` once, not
    /// per type), and `y_U` from `s_y0 = |h(s_{n-1}) - ds_{n-1}| = |s|`.
    ///
    /// Without the flexible boundary a too slow sample rate can push `|xi|`
    /// to 1; `xi` is then clamped to the largest float below 1 (Gamma stays
    /// finite, docs/design.md §3.6) and `clamped` is set.
    #[inline(always)]
    pub fn evaluate<const N: usize>(
        &self,
        last_law: Option<&SkewedLaw<T>>,
        m: &Manifold<T, N>,
        env: &mut Envelopes<T>,
        latch: Option<(Latch, T)>,
        t: T,
        flexible: Option<(T, Transition)>,
    ) -> Evaluation<T> {
        if let (Some((rule, k0)), true) = (latch, self.uses_y()) {
            env.y.rho0 = rule.rho0(m.s(), k0, env.y.eps);
        }
        match (self, last_law) {
            (Constraint::Longitudinal { .. }, _) | (_, None) => {
                // LoMC (and order 1, which has no last law): sigma = s.
                let y_u = env.y.at(t);
                finish(m.s(), y_u, y_u, (T::zero(), y_u), flexible)
            }
            #[cfg(feature = "lateral")]
            (Constraint::Lateral { .. }, Some(law)) => {
                let sigma = offset::lateral(law, m.s_prev, m.ds_prev).sigma;
                if let Some((rule, k0)) = latch {
                    env.x.rho0 = rule.rho0(sigma, k0, env.x.eps);
                }
                let x_u = env.x.at(t);
                finish(sigma, x_u, x_u, (x_u, T::zero()), flexible)
            }
            #[cfg(feature = "oblique")]
            (Constraint::Oblique { .. }, Some(law)) => {
                if let Some((rule, k0)) = latch {
                    let s_x0 = offset::lateral(law, m.s_prev, m.ds_prev).sigma;
                    env.x.rho0 = rule.rho0(s_x0, k0, env.x.eps);
                }
                let (x_u, y_u) = (env.x.at(t), env.y.at(t));
                let sigma = self.offset(law, m.s_prev, m.ds_prev, x_u, y_u).sigma;
                finish(sigma, x_u, half_width(x_u, y_u), (x_u, y_u), flexible)
            }
            // Compiled out (src/compiled.rs): no configuration holds it.
            #[allow(unreachable_patterns)]
            _ => finish(T::nan(), T::one(), T::one(), (T::zero(), T::zero()), None),
        }
    }
}

/// `xi` from the signed offset `sigma`, its half-width `width` and the
/// ratio `d_u` (eq. (28)), expanded by the flexible boundary (eqs. (30)-(31))
/// and clamped below 1.
#[inline(always)]
fn finish<T: Real>(
    sigma: T,
    width: T,
    d_u: T,
    nominal: (T, T),
    flexible: Option<(T, Transition)>,
) -> Evaluation<T> {
    let xi_nominal = sigma / width;
    let factor = match flexible {
        Some((rho_e, transition)) => expansion(transition, xi_nominal.abs() * d_u, d_u, rho_e),
        None => T::one(),
    };
    // A finite offset so far out that the expansion overflowed: |xi~| =
    // d_sc / (d_sc + rho_e) is 1 to the float's precision (then clamped below
    // 1). An infinite offset stays an overflow (NaN).
    let (xi, factor) = if factor.is_finite() || !xi_nominal.is_finite() {
        (xi_nominal / factor, factor)
    } else {
        (xi_nominal.signum(), T::max_value())
    };
    let (xi, clamped) = clamp_below_one(xi);
    Evaluation {
        xi,
        xi_nominal,
        expansion: factor,
        nominal,
        clamped,
    }
}

/// `d_U = sqrt(x_U^2 + y_U^2)`, scaled when the squares would overflow
/// (latched widths far out of the usual range).
#[cfg_attr(not(feature = "oblique"), allow(dead_code))]
#[inline(always)]
fn half_width<T: Real>(x_u: T, y_u: T) -> T {
    let d = (x_u * x_u + y_u * y_u).root();
    if d.is_finite() {
        return d;
    }
    let m = x_u.max(y_u);
    let (a, b) = (x_u / m, y_u / m);
    m * (a * a + b * b).root()
}

/// `xi` clamped to the largest float below 1 in magnitude (docs/design.md
/// §3.6), and whether it had to be.
#[inline(always)]
fn clamp_below_one<T: Real>(xi: T) -> (T, bool) {
    let limit = T::one() - T::epsilon() * T::from_f64(0.5);
    if xi.abs() > limit {
        (if xi > T::zero() { limit } else { -limit }, true)
    } else {
        (xi, false)
    }
}

#[cfg(test)]
mod tests {
    use super::{clamp_below_one, half_width};

    #[test]
    fn the_half_width_is_the_hypotenuse_even_where_the_squares_overflow() {
        assert_eq!(half_width(3.0_f64, 4.0), 5.0);
        // The wider x_U too (x^2 - y^2 would be finite there, and wrong).
        assert_eq!(half_width(4.0_f64, 3.0), 5.0);
        // 3e200 and 4e200: the squares overflow, the scaled form does not.
        let d = half_width(3e200_f64, 4e200);
        assert!((d / 5e200 - 1.0).abs() < 1e-15, "{d}");
        let d32 = half_width(3e30_f32, 4e30);
        assert!((d32 / 5e30 - 1.0).abs() < 1e-6, "{d32}");
    }

    #[test]
    fn the_largest_float_below_one_is_not_clamped() {
        let limit = 1.0 - f64::EPSILON * 0.5;
        assert_eq!(clamp_below_one(limit), (limit, false));
        assert_eq!(clamp_below_one(-limit), (-limit, false));
        assert_eq!(clamp_below_one(1.0), (limit, true));
        assert_eq!(clamp_below_one(-3.0), (-limit, true));
        let limit32 = 1.0 - f32::EPSILON * 0.5;
        assert_eq!(clamp_below_one(limit32), (limit32, false));
        assert_eq!(clamp_below_one(f32::INFINITY), (limit32, true));
    }
}
