//! Legal but risky configurations: [`Config::lint`] returns a fixed-size list
//! of [`Finding`]s (no allocation), each naming the parameter, the rule it
//! breaks, the number that breaks it and a suggested value. The bindings
//! emit them as warnings (Python: `famcc.DesignWarning` at construction).
//!
//! The rules (docs/design.md §3.8, measured in §7.2):
//!
//! | lint | rule |
//! |---|---|
//! | [`Lint::CoarseSampling`] | `dt / mu <= 0.2` (the differentiator needs `mu >= 5 dt`; famcc's designs use `10 dt`); with Tustin `dt / mu <= 1` (its poles `(1 - dt/mu) / (1 + dt/mu)` stay >= 0) |
//! | [`Lint::Chatter`] | the last stage's law, if it has an infinite slope at 0 (`p < 1` without NSMD), chatters by less than 1 % of the accuracy of `s_(n-1)` |
//! | [`Lint::WideMargin`] | `rho_e <= 0.1 eps` (smallest final width) |
//! | [`Lint::Peaking`] | estimate limits set when the differentiator's order is `>= 4` |
//! | [`Lint::Aliasing`] | no exact (zero-order-hold) differentiator at order `>= 4` |
//!
//! The chatter rule: a law `h(x) ~ -c |x|^p sign(x)` near 0 (`p < 1`: its
//! slope is infinite there), applied with the loop's delay `tau = dt + mu`,
//! oscillates where its slope exceeds `~2 / tau`: with an amplitude
//! `A = (c tau / 2)^(1/(1-p))` in `s_(n-1)`. That is harmless while `A` is
//! small against the accuracy the constraint presets for `s_(n-1)`: `eps_x`
//! (LaMC, OMC), or `(eps_y / c)^(1/p)` (LoMC: `|h(s_(n-1))| <= eps_y`). The
//! paper's example 1 (`FiniteTime(1, 0.5)`, LaMC, `eps = 0.1`) gives `A /
//! eps = 3e-4` at 1 kHz and does not warn; `FiniteTime(20, 0.5)` under LoMC
//! with `eps = 0.01` does.
//!
//! ```
//! use famcc_core::config::Lint;
//! use famcc_core::{Config, Constraint, Discretization, Feedback, HighGain};
//! let linear = [(Feedback::Linear { k: 2.0 }, None); 3];
//! let cfg = Config::<f64, 4>::builder(5e-3, &linear, Constraint::Longitudinal { eps: 1.0 }, 5.0)
//!     .differentiator(Some(HighGain::paper()))
//!     .rho_e(Some(0.5))
//!     .build()?;
//! let found: Vec<Lint> = cfg.lint().iter().map(|f| f.lint).collect();
//! assert_eq!(found, [Lint::CoarseSampling, Lint::WideMargin, Lint::Peaking, Lint::Aliasing]);
//! assert_eq!(cfg.lint().iter().next().unwrap().to_string(),
//!     "dt: the sample period is coarse for the differentiator's time constant mu (raise mu \
//!      to 10 dt or sample faster) (rule: dt / mu <= 0.2; here 0.5); suggested dt = 0.001");
//! # Ok::<(), famcc_core::ConfigError>(())
//! ```

use core::fmt;

use super::Config;
use crate::{Constraint, Discretization, Feedback, Real, SkewedLaw};

/// The number of lints: the capacity of [`Findings`].
pub const LINT_COUNT: usize = 5;

/// Largest `dt / mu` that does not warn (exact and Euler discretizations).
const MAX_DT_PER_MU: f64 = crate::differentiator::EXACT_DT_PER_MU;
/// Largest `dt / mu` that does not warn with Tustin (its poles stay >= 0).
const MAX_DT_PER_MU_TUSTIN: f64 = 1.0;
/// Largest `dt / mu` that does not warn with the first-order hold: the
/// smallest `mu / dt` famcc's rate rule gives it
/// ([`crate::differentiator::FOH_MIN_MU_PER_DT`]).
const MAX_DT_PER_MU_FOH: f64 = 1.0 / crate::differentiator::FOH_MIN_MU_PER_DT;
/// Largest chatter amplitude, as a fraction of the accuracy of `s_(n-1)`.
const CHATTER_FRACTION: f64 = 0.01;
/// Largest `rho_e / eps` that does not warn.
const MAX_MARGIN: f64 = 0.1;
/// The differentiator order from which peaking and aliasing dominate.
const HIGH_ORDER: usize = 4;

/// Which risk a finding is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lint {
    /// `dt` too coarse for the differentiator's `mu`: `dt / mu > 0.2`.
    CoarseSampling,
    /// The last stage's law has an infinite slope at 0 (a power `p < 1`
    /// without NSMD) and chatters at this rate: its sampled amplitude
    /// `(c (dt + mu) / 2)^(1/(1-p))` exceeds 1 % of the accuracy the
    /// constraint presets for `s_(n-1)`.
    Chatter,
    /// `rho_e > 0.1 eps` (the smallest final width): the bounds expand
    /// although the actuator has headroom.
    WideMargin,
    /// No estimate limits at differentiator order `>= 4` (start-up peaking).
    Peaking,
    /// The exact zero-order hold at differentiator order `>= 4` (aliasing,
    /// docs/design.md §7.2).
    Aliasing,
}

/// A suggested value: a number, or a name or phrase (a discretization, a law).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Suggestion {
    /// A number for the parameter.
    Value(f64),
    /// A choice in words.
    Choice(&'static str),
}

/// One risky choice: the parameter (with the stage for a per-stage one), the
/// risk in words, the rule, the number that breaks it and a suggestion.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Finding {
    /// Which lint.
    pub lint: Lint,
    /// The parameter to change (as in the Python API).
    pub parameter: &'static str,
    /// Zero-based stage of a per-stage parameter.
    pub stage: Option<usize>,
    /// What goes wrong, and the cure, in words.
    pub risk: &'static str,
    /// The rule the configuration breaks.
    pub rule: &'static str,
    /// The configuration's number for the rule.
    pub value: f64,
    /// A suggested value of `parameter`.
    pub suggestion: Suggestion,
}

/// The findings of [`Config::lint`], in the order of [`Lint`] (at most one each).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Findings {
    items: [Option<Finding>; LINT_COUNT],
}

impl Findings {
    /// The findings.
    pub fn iter(&self) -> impl Iterator<Item = &Finding> {
        self.items.iter().flatten()
    }

    /// How many.
    pub fn len(&self) -> usize {
        self.iter().count()
    }

    /// True when the configuration has no risky choice.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The finding of one lint, if present.
    pub fn get(&self, lint: Lint) -> Option<&Finding> {
        self.iter().find(|f| f.lint == lint)
    }

    fn push(&mut self, f: Finding) {
        if let Some(slot) = self.items.iter_mut().find(|s| s.is_none()) {
            *slot = Some(f);
        }
    }
}

/// A number with three significant digits.
struct Sig(f64);

impl fmt::Display for Sig {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let x = self.0;
        let a = x.abs();
        if !x.is_finite() || a == 0.0 {
            return write!(f, "{x}");
        }
        if !(1e-3..1e5).contains(&a) {
            return write!(f, "{x:.2e}");
        }
        let digits = 2 - num_traits::Float::floor(num_traits::Float::log10(a)) as i32;
        let digits = digits.clamp(0, 5) as usize;
        let text = &mut [0u8; 32];
        let mut w = Buf { buf: text, len: 0 };
        fmt::write(&mut w, format_args!("{x:.digits$}"))?;
        // Trailing zeros of the fraction carry no information.
        let mut s = w.as_str();
        if s.contains('.') {
            s = s.trim_end_matches('0').trim_end_matches('.');
        }
        f.write_str(s)
    }
}

/// A small stack buffer for [`Sig`].
struct Buf<'a> {
    buf: &'a mut [u8; 32],
    len: usize,
}

impl Buf<'_> {
    fn as_str(&self) -> &str {
        core::str::from_utf8(self.buf.get(..self.len).unwrap_or(&[])).unwrap_or("")
    }
}

impl fmt::Write for Buf<'_> {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        let end = self.len + s.len();
        let dst = self.buf.get_mut(self.len..end).ok_or(fmt::Error)?;
        dst.copy_from_slice(s.as_bytes());
        self.len = end;
        Ok(())
    }
}

impl fmt::Display for Finding {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(i) = self.stage {
            write!(f, "stage {}: ", i + 1)?;
        }
        write!(
            f,
            "{}: {} (rule: {}; here {}); suggested {} = ",
            self.parameter,
            self.risk,
            self.rule,
            Sig(self.value),
            self.parameter
        )?;
        match self.suggestion {
            Suggestion::Value(x) => write!(f, "{}", Sig(x)),
            Suggestion::Choice(s) => f.write_str(s),
        }
    }
}

/// The gain parameter's name, the gain `c` and the power `p` of a law that
/// behaves like `-c |x|^p sign(x)` near 0 with `p < 1` (`None`: finite slope
/// at 0, or a Nonsingular skew removes the singularity).
fn singular_power<T: Real>(law: &SkewedLaw<T>) -> Option<(&'static str, f64, f64)> {
    if !law.is_singular_at_zero() {
        return None;
    }
    let f = |x: T| x.to_f64_lossless();
    match *law.feedback() {
        Feedback::Linear { .. } => None,
        Feedback::FiniteTime { k, p } => Some(("k", f(k), f(p))),
        Feedback::FixedTime { alpha, p, .. } => Some(("alpha", f(alpha), f(p))),
        Feedback::VariableExponent { k, r_b, .. } => Some(("k", f(k), f(r_b))),
        Feedback::MoulayDiscontinuous { beta, .. } => Some(("beta", f(beta), 0.0)),
    }
}

impl<T: Real, const N: usize> Config<T, N> {
    /// The legal but risky choices of this configuration: at most one
    /// finding per [`Lint`] (each variant states its rule; the derivation is
    /// in docs/design.md §3.8), in a fixed-size list, without allocation.
    /// Each finding's `Display` names the parameter, the rule, the number
    /// that breaks it and a suggested value.
    pub fn lint(&self) -> Findings {
        let mut out = Findings::default();
        let dt = self.dt().to_f64_lossless();
        let order = self.plant_order();
        let hgd = self.differentiator();
        let mu = hgd.map(|h| h.mu.to_f64_lossless());
        if let (Some(mu), Some(h)) = (mu, hgd) {
            // Tustin maps the poles -2/mu to (1 - dt/mu) / (1 + dt/mu): it
            // rings only once dt > mu. The first-order hold never rings;
            // famcc's rate rule gives it mu >= dt / 2 (from dt / mu > 0.2 on,
            // differentiator::auto_discretization_at).
            let (limit, rule) = match h.discretization {
                Discretization::Tustin => (MAX_DT_PER_MU_TUSTIN, "dt / mu <= 1 (Tustin)"),
                Discretization::Foh => (MAX_DT_PER_MU_FOH, "dt / mu <= 2 (first-order hold)"),
                _ => (MAX_DT_PER_MU, "dt / mu <= 0.2"),
            };
            if dt / mu > limit {
                out.push(Finding {
                    lint: Lint::CoarseSampling,
                    parameter: "dt",
                    stage: None,
                    risk: "the sample period is coarse for the differentiator's time constant mu \
                           (raise mu to 10 dt or sample faster)",
                    rule,
                    value: dt / mu,
                    suggestion: Suggestion::Value(mu / 10.0),
                });
            }
        }
        // The loop's delay: a period of sampling and the differentiator's
        // mu, less the period the first-order hold's estimate saves
        // (differentiator::SAMPLE_DELAY - FOH_SAMPLE_DELAY).
        let foh = hgd.is_some_and(|h| h.discretization == Discretization::Foh);
        let saved = crate::differentiator::SAMPLE_DELAY - crate::differentiator::FOH_SAMPLE_DELAY;
        let sampling = if foh { dt - saved * dt } else { dt };
        if let Some(f) = self.chatter(sampling + mu.unwrap_or(0.0)) {
            out.push(f);
        }
        let (ex, ey) = self.constraint().eps();
        let (ex, ey) = (ex.to_f64_lossless(), ey.to_f64_lossless());
        let eps = match self.constraint() {
            Constraint::Longitudinal { .. } => ey,
            Constraint::Lateral { .. } => ex,
            Constraint::Oblique { .. } => ex.min(ey),
        };
        if let Some(rho_e) = self.rho_e().map(|r| r.to_f64_lossless()) {
            if rho_e > MAX_MARGIN * eps {
                out.push(Finding {
                    lint: Lint::WideMargin,
                    parameter: "rho_e",
                    stage: None,
                    risk: "the flexible bounds open once the state comes within rho_e of the nominal \
                           ones, so a wide margin gives the preset accuracy up although the actuator \
                           has headroom",
                    rule: "rho_e <= 0.1 eps",
                    value: rho_e / eps,
                    suggestion: Suggestion::Value(0.01 * eps),
                });
            }
        }
        if let Some(h) = hgd.filter(|_| order >= HIGH_ORDER) {
            if self.estimate_limits().is_none() {
                out.push(Finding {
                    lint: Lint::Peaking,
                    parameter: "estimate_limits",
                    stage: None,
                    risk: "the differentiator's start-up peaking (its k-th estimate grows like \
                           mu^(1-k)) drives the law far outside its bounds, where the flexible law \
                           is weak, and high orders diverge",
                    rule: "estimate limits set at differentiator order >= 4",
                    value: order as f64,
                    suggestion: Suggestion::Choice("a few times the largest expected |z_i|, one per entry"),
                });
            }
            if h.discretization == Discretization::Exact {
                out.push(Finding {
                    lint: Lint::Aliasing,
                    parameter: "discretization",
                    stage: None,
                    risk: "the exact zero-order hold treats the held samples as a staircase, and from \
                           order 4 on that aliasing dominates the estimates (docs/design.md 7.2)",
                    rule: "no exact differentiator at order >= 4",
                    value: order as f64,
                    suggestion: Suggestion::Choice("tustin"),
                });
            }
        }
        out
    }

    /// The chatter finding of the last stage's law, with loop delay `tau`.
    fn chatter(&self, tau: f64) -> Option<Finding> {
        let stage = self.laws().len().checked_sub(1)?;
        let (name, c, p) = singular_power(self.last_law()?)?;
        let (ex, ey) = self.constraint().eps();
        let (ex, ey) = (ex.to_f64_lossless(), ey.to_f64_lossless());
        let pw = num_traits::Float::powf;
        let ln = num_traits::Float::ln;
        let amplitude = pw(c * tau / 2.0, 1.0 / (1.0 - p));
        let lateral = !matches!(self.constraint(), Constraint::Longitudinal { .. });
        // The accuracy the constraint presets for s_(n-1).
        let band = if lateral { ex } else { pw(ey / c, 1.0 / p) };
        let ratio = amplitude / band;
        if ratio.partial_cmp(&CHATTER_FRACTION) != Some(core::cmp::Ordering::Greater) {
            return None;
        }
        // The gain at which the ratio is CHATTER_FRACTION.
        let suggested = if p <= 0.0 {
            None
        } else if lateral {
            Some(2.0 * pw(CHATTER_FRACTION * ex, 1.0 - p) / tau)
        } else {
            let q = 1.0 / (1.0 - p) + 1.0 / p;
            let rhs = ln(CHATTER_FRACTION) - ln(tau / 2.0) / (1.0 - p) + ln(ey) / p;
            Some(num_traits::Float::exp(rhs / q))
        };
        Some(Finding {
            lint: Lint::Chatter,
            parameter: name,
            stage: Some(stage),
            risk: "the last stage's law has an infinite slope at 0 (a power below 1 without a \
                   Nonsingular skew), so the sampled loop chatters around s_(n-1) = 0; use Linear \
                   or a Nonsingular skew, or a smaller gain",
            rule: "amplitude (c (dt + mu) / 2)^(1/(1-p)) <= 1 % of the accuracy of s_(n-1)",
            value: ratio,
            suggestion: match suggested {
                Some(x) if x.is_finite() => Suggestion::Value(x),
                _ => Suggestion::Choice("Linear, or a Nonsingular skew"),
            },
        })
    }
}
