//! Controller configuration and its validation (kept apart from the state).

use crate::constraint::ConstraintKind;
use crate::error::{positive, ConfigError};
use crate::{Feedback, Gamma, HighGain, Latch, Real, Skew, SkewedLaw, Transition};

/// The constraint type with its final half-widths (paper eqs. xUxL, yUyL).
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

impl<T: Real> Constraint<T> {
    /// The constraint type.
    pub fn kind(&self) -> ConstraintKind {
        match self {
            Constraint::Longitudinal { .. } => ConstraintKind::Longitudinal,
            Constraint::Lateral { .. } => ConstraintKind::Lateral,
            Constraint::Oblique { .. } => ConstraintKind::Oblique,
        }
    }

    /// `(eps_x, eps_y)`, 0 in the direction the type doesn't use.
    pub fn eps(&self) -> (T, T) {
        match *self {
            Constraint::Longitudinal { eps } => (T::zero(), eps),
            Constraint::Lateral { eps } => (eps, T::zero()),
            Constraint::Oblique { eps_x, eps_y } => (eps_x, eps_y),
        }
    }

    fn validate(&self) -> Result<(), ConfigError> {
        match *self {
            Constraint::Longitudinal { eps } | Constraint::Lateral { eps } => positive(eps, "eps"),
            Constraint::Oblique { eps_x, eps_y } => {
                positive(eps_x, "eps_x")?;
                positive(eps_y, "eps_y")
            }
        }
    }
}

/// Everything that defines a FAMCC controller of order `N`.
///
/// Build with [`Config::new`] (the required values), then adjust the public
/// fields; [`crate::Controller::new`] validates the whole configuration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Config<T, const N: usize> {
    /// Sample period, seconds.
    pub dt: T,
    /// Stage laws `h_m1..h_m(N-1)`; slot `N-1` is unused.
    laws: [SkewedLaw<T>; N],
    /// Constraint type and final half-widths.
    pub constraint: Constraint<T>,
    /// Preset settling time `T_s` of the envelopes, seconds.
    pub settle_time: T,
    /// Initial-width factor `k0 > 1` (eqs. xUxL, yUyL).
    pub k0: T,
    /// Control gain `k_u > 0` (eq. uT), in input units.
    pub k_u: T,
    /// The map Gamma (eq. uT).
    pub gamma: Gamma,
    /// Flexible-boundary margin `rho_e` (eq. WxyUxyL); `None` disables the
    /// flexible boundaries (the controller of eq. uT).
    pub rho_e: Option<T>,
    /// The transition `S` used by the flexible boundary.
    pub transition: Transition,
    /// How the envelopes' initial widths are latched.
    pub latch: Latch,
    /// The high-gain differentiator (output feedback, eq. HGD); `None` for
    /// state feedback only.
    pub differentiator: Option<HighGain<T, N>>,
    /// Initial derivative estimates `(z2, ..., zn)` in slots `1..N` (slot 0 is
    /// ignored: the first sample is used); `None` means zeros.
    pub initial_derivatives: Option<[T; N]>,
    /// Optional saturation `|z_hat_i| <= limit_i` of the estimates fed to the
    /// law (the usual cure for the differentiator's start-up peaking); off by
    /// default.
    pub estimate_limits: Option<[T; N]>,
}

impl<T: Real, const N: usize> Config<T, N> {
    /// A configuration with the required values and the paper's defaults
    /// (`k0 = 2`, log Gamma, `rho_e = 0.01` — or a tenth of the smallest final
    /// width when that is below 0.1 —, the paper's latch, no differentiator). `laws` holds one `(h_p, skew)` per stage: exactly
    /// `N - 1` of them.
    pub fn new(
        dt: T,
        laws: &[(Feedback<T>, Option<Skew<T>>)],
        constraint: Constraint<T>,
        settle_time: T,
        k_u: T,
    ) -> Result<Self, ConfigError> {
        if N == 0 {
            return Err(ConfigError::new("order", "must be >= 1"));
        }
        if laws.len() != N - 1 {
            return Err(ConfigError::new(
                "feedback",
                "must have exactly order - 1 entries (one per stage)",
            ));
        }
        let filler = SkewedLaw::new(Feedback::Linear { k: T::one() }, None)?;
        let mut prepared = [filler; N];
        for (i, (slot, (h, skew))) in prepared.iter_mut().zip(laws.iter()).enumerate() {
            *slot = SkewedLaw::new(*h, *skew).map_err(|e| e.at_stage(i))?;
        }
        let cfg = Self {
            dt,
            laws: prepared,
            constraint,
            settle_time,
            k0: T::c(2.0),
            k_u,
            gamma: Gamma::Log,
            rho_e: Some(Self::default_rho_e(&constraint)),
            transition: Transition::Exponential,
            latch: Latch::Paper,
            differentiator: None,
            initial_derivatives: None,
            estimate_limits: None,
        };
        cfg.validate()?;
        Ok(cfg)
    }

    /// `0.01`, or a tenth of the smallest final half-width when that is
    /// smaller (the paper asks `rho_e << sqrt(eps_x^2 + eps_y^2)`).
    fn default_rho_e(constraint: &Constraint<T>) -> T {
        let (ex, ey) = constraint.eps();
        let smallest = match constraint.kind() {
            ConstraintKind::Oblique => ex.min(ey),
            ConstraintKind::Lateral => ex,
            ConstraintKind::Longitudinal => ey,
        };
        T::c(0.01).min(smallest * T::c(0.1))
    }

    /// The stage laws `h_m1..h_m(N-1)`.
    pub fn laws(&self) -> &[SkewedLaw<T>] {
        self.laws.get(..N.saturating_sub(1)).unwrap_or(&[])
    }

    /// The last stage's law `h_m(n-1)` (None at order 1).
    pub(crate) fn last_law(&self) -> Option<&SkewedLaw<T>> {
        self.laws().last()
    }

    /// Checks every rule; the error names the parameter and the rule.
    pub fn validate(&self) -> Result<(), ConfigError> {
        if N == 0 {
            return Err(ConfigError::new("order", "must be >= 1"));
        }
        positive(self.dt, "dt")?;
        positive(self.settle_time, "settle_time")?;
        positive(self.k_u, "k_u")?;
        if !(self.k0 > T::one() && self.k0.is_finite()) {
            return Err(ConfigError::new("k0", "must be finite and > 1"));
        }
        self.constraint.validate()?;
        if N < 2 && self.constraint.kind() != ConstraintKind::Longitudinal {
            return Err(ConfigError::new(
                "constraint",
                "must be longitudinal at order 1 (lateral and oblique need s_(n-1))",
            ));
        }
        if let Some(rho_e) = self.rho_e {
            positive(rho_e, "rho_e")?;
            let (ex, ey) = self.constraint.eps();
            if rho_e * rho_e >= ex * ex + ey * ey {
                return Err(ConfigError::new(
                    "rho_e",
                    "must be smaller than the final bound width eps",
                ));
            }
        }
        let needs_derivatives = N.saturating_sub(2);
        for (i, law) in self.laws().iter().enumerate() {
            if i < needs_derivatives && law.is_singular_at_zero() {
                return Err(ConfigError::new(
                    "skew",
                    "must be Nonsingular (NSMD): a power law below 1 without NSMD has unbounded \
                     derivatives at 0, and this stage's derivatives are needed (order >= 3)",
                )
                .at_stage(i));
            }
        }
        if let Some(h) = &self.differentiator {
            h.validate()?;
        }
        if let Some(d) = &self.initial_derivatives {
            if d.iter().any(|v| !v.is_finite()) {
                return Err(ConfigError::new("initial_derivatives", "must be finite"));
            }
        }
        if let Some(l) = &self.estimate_limits {
            if l.iter().any(|v| v.is_nan() || *v <= T::zero()) {
                return Err(ConfigError::new(
                    "estimate_limits",
                    "must all be > 0 (inf allowed)",
                ));
            }
        }
        Ok(())
    }
}
