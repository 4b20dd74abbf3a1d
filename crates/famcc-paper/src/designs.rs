//! The paper's three example controllers (docs/design.md §6.2), their input
//! limits and the settling bounds of their corollaries.
//!
//! | example | constraint | stage laws | eps | k_u |
//! |---|---|---|---|---|
//! | 1 (finite-time, Corollary 1) | LaMC | `FiniteTime(k = 1, p = 0.5)` | 0.1 | 5 |
//! | 2 (variable-exponent, Corollary 2) | LoMC | `VariableExponent(k = 1.5, r_b = 0.5, r_1 = 2, r_t = 3)` with `Smooth(eps_s = 0.15` ("paper") / `0.225` ("code")`, eps_z = 0.1)` | 0.15 | 2 |
//! | 3 (RFC, Corollary 3) | LoMC | `FixedTime(1, 0.5, 0.5, 2)` with `Nonsingular(eps_s = 0.2` / `0.1, eps_z = 0.1, k_pp = 0.1)`; `FixedTime(2, 0.5, 1, 2)` with `Nonsingular(eps_s = eps_y, eps_z = 0.2, k_pp = 1)` | `eps_y` = 5 / 3 | 30 |
//!
//! Everything else is famcc-core's default, which is what the paper's
//! examples use: `k0 = 2`, `T_s = 1` s, `rho_e = 0.01`, log Gamma, the
//! exponential transition, and the paper's differentiator
//! ([`HighGain::paper`]: `mu = 0.01`, `a = (4, 4)` / `(4, 6, 4)`). Variant
//! "code" latches the envelopes as the authors' code does
//! ([`famcc_core::Latch::Authors`]).
//!
//! ```
//! use famcc_paper::designs::{self, Example, Variant};
//! let cfg = designs::example3::<f64>(Variant::Paper, 1e-3)?;
//! assert_eq!(cfg.constraint().eps(), (0.0, 5.0));
//! assert_eq!(designs::corollary_bound::<f64>(Example::Rfc), 6.0);        // T_fr' < 6 s
//! assert_eq!(designs::input_limits::<f64>(Example::FiniteTime, true), (-2.5, 3.0));
//! # Ok::<(), famcc_core::ConfigError>(())
//! ```

use famcc_core::{bounds, Config, ConfigBuilder, ConfigError, Constraint, Feedback, HighGain, Real, Skew};

pub use crate::variant::Variant;

/// The paper's three examples.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Example {
    /// Example 1: LaMC finite-time PPC (Corollary 1), order 2.
    FiniteTime,
    /// Example 2: LoMC + SSMD variable-exponent fixed-time PPC (Corollary
    /// 2), order 2.
    VariableExponent,
    /// Example 3: LoMC + NSMD recursive fixed-time control (Corollary 3),
    /// order 3.
    Rfc,
}

impl Example {
    /// The three examples in the paper's order.
    pub const ALL: [Example; 3] = [Example::FiniteTime, Example::VariableExponent, Example::Rfc];

    /// The example with the paper's number `n` (1, 2 or 3).
    pub fn from_number(n: u32) -> Option<Self> {
        match n {
            1 => Some(Example::FiniteTime),
            2 => Some(Example::VariableExponent),
            3 => Some(Example::Rfc),
            _ => None,
        }
    }

    /// The paper's number of the example.
    pub fn number(self) -> u32 {
        match self {
            Example::FiniteTime => 1,
            Example::VariableExponent => 2,
            Example::Rfc => 3,
        }
    }

    /// The system order (2, or 3 for example 3).
    pub fn order(self) -> usize {
        match self {
            Example::Rfc => 3,
            _ => 2,
        }
    }
}

/// The sample period of the paper's scenarios in famcc (1 kHz), seconds.
pub const SAMPLE_PERIOD: f64 = 1e-3;
/// The output accuracy `eps_z` every example's corollary guarantees.
pub const ACCURACY: f64 = 0.1;
/// The horizon of the paper's simulations, seconds.
pub const HORIZON: f64 = 10.0;
/// The input limits of the runs without saturation (never reached after the
/// start-up).
pub const UNSATURATED_LIMITS: (f64, f64) = (-100.0, 100.0);

// Example 1 (eq. (37), fn): h_p1(z1) = -k_c |z1|^p sign(z1).
const EX1_K: f64 = 1.0;
const EX1_P: f64 = 0.5;
// Example 2 (eq. (45), fxe).
const EX2_LAW: [f64; 4] = [1.5, 0.5, 2.0, 3.0]; // k, r_b, r_1, r_t
                                                // Example 3 (eq. (61), RFCs): (alpha_i, p_i, beta_i, q_i) per stage.
const EX3_STAGES: [(f64, f64, f64, f64); 2] = [(1.0, 0.5, 0.5, 2.0), (2.0, 0.5, 1.0, 2.0)];

type Stage<T> = (Feedback<T>, Option<Skew<T>>);

fn lit<T: Real>(x: f64) -> T {
    T::from_f64(x)
}

fn fixed_time<T: Real>((alpha, p, beta, q): (f64, f64, f64, f64)) -> Feedback<T> {
    Feedback::FixedTime {
        alpha: lit(alpha),
        p: lit(p),
        beta: lit(beta),
        q: lit(q),
    }
}

/// Example 1: LaMC, `FiniteTime(k = 1, p = 0.5)`, `eps_x = 0.1`, `k_u = 5`.
pub fn example1<T: Real>(variant: Variant, dt: T) -> Result<Config<T, 2>, ConfigError> {
    example1_builder(variant, dt).build()
}

/// [`example1`] before [`ConfigBuilder::build`] (e.g. for
/// [`ConfigBuilder::build_discretized`] with a recursion precomputed on a host).
pub fn example1_builder<T: Real>(variant: Variant, dt: T) -> ConfigBuilder<T, 2> {
    let law = Feedback::FiniteTime {
        k: lit(EX1_K),
        p: lit(EX1_P),
    };
    finish(
        Config::builder(
            dt,
            &[(law, None)],
            Constraint::Lateral { eps: lit(0.1) },
            lit(5.0),
        ),
        variant,
    )
}

/// Example 2: LoMC, the variable-exponent law with SSMD (`eps_s` = 0.15 in
/// the paper, 0.225 in the authors' code), `eps_y = 0.15`, `k_u = 2`.
pub fn example2<T: Real>(variant: Variant, dt: T) -> Result<Config<T, 2>, ConfigError> {
    example2_builder(variant, dt).build()
}

/// [`example2`] before [`ConfigBuilder::build`] (e.g. for
/// [`ConfigBuilder::build_discretized`] with a recursion precomputed on a host).
pub fn example2_builder<T: Real>(variant: Variant, dt: T) -> ConfigBuilder<T, 2> {
    let [k, r_b, r_1, r_t] = EX2_LAW.map(lit::<T>);
    let eps_s = match variant {
        Variant::Paper => 0.15,
        Variant::Code => 0.225,
    };
    let stage: Stage<T> = (
        Feedback::VariableExponent { k, r_b, r_1, r_t },
        Some(Skew::smooth(lit(eps_s), lit(0.1))),
    );
    finish(
        Config::builder(
            dt,
            &[stage],
            Constraint::Longitudinal { eps: lit(0.15) },
            lit(2.0),
        ),
        variant,
    )
}

/// Example 3 (RFC): LoMC, two fixed-time stages with NSMD, `k_u = 30`.
/// Variant "paper": `eps_s1 = 0.2`, `eps_y = 5`; "code": `eps_s1 = 0.1`,
/// `eps_y = 3`.
pub fn example3<T: Real>(variant: Variant, dt: T) -> Result<Config<T, 3>, ConfigError> {
    example3_builder(variant, dt).build()
}

/// [`example3`] before [`ConfigBuilder::build`] (e.g. for
/// [`ConfigBuilder::build_discretized`] with a recursion precomputed on a host).
pub fn example3_builder<T: Real>(variant: Variant, dt: T) -> ConfigBuilder<T, 3> {
    let (eps_s1, eps_y) = match variant {
        Variant::Paper => (0.2, 5.0),
        Variant::Code => (0.1, 3.0),
    };
    let [first, second] = EX3_STAGES;
    let stages: [Stage<T>; 2] = [
        (
            fixed_time(first),
            Some(Skew::nonsingular(lit(eps_s1), lit(0.1), lit(0.1))),
        ),
        (
            fixed_time(second),
            Some(Skew::nonsingular(lit(eps_y), lit(0.2), lit(1.0))),
        ),
    ];
    finish(
        Config::builder(
            dt,
            &stages,
            Constraint::Longitudinal { eps: lit(eps_y) },
            lit(30.0),
        ),
        variant,
    )
}

/// What every example shares: the variant's latch, the paper's
/// differentiator, the core's defaults for the rest.
fn finish<T: Real, const N: usize>(design: ConfigBuilder<T, N>, variant: Variant) -> ConfigBuilder<T, N> {
    design
        .latch(variant.latch())
        .differentiator(Some(HighGain::paper()))
}

/// A design of a run-time-chosen example.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Design<T> {
    /// Examples 1 and 2.
    Order2(Config<T, 2>),
    /// Example 3.
    Order3(Config<T, 3>),
}

/// The design of `example` in `variant` at sample period `dt` (seconds).
pub fn design<T: Real>(example: Example, variant: Variant, dt: T) -> Result<Design<T>, ConfigError> {
    Ok(match example {
        Example::FiniteTime => Design::Order2(example1(variant, dt)?),
        Example::VariableExponent => Design::Order2(example2(variant, dt)?),
        Example::Rfc => Design::Order3(example3(variant, dt)?),
    })
}

/// The settling bound `T'` of the example's corollary, seconds: the output
/// reaches `|z1| < ACCURACY` by `T_s + T'` without saturation. Corollary 1
/// (eq. (42), fnT) from the plants' initial error `z1(0) = x1(0) - sin 0 = -1`:
/// `T_fn' = 2`; Corollary 2 (eq. (53), fxeT): `T_fxe' = 3.32`; Corollary 3
/// (eq. (63), fxTho): `T_fr' = 6`. The same in both variants.
pub fn corollary_bound<T: Real>(example: Example) -> T {
    match example {
        Example::FiniteTime => {
            let z1_0 = crate::plants::SECOND_ORDER_X0[0];
            bounds::finite_time(lit(EX1_K), lit(EX1_P), lit(z1_0))
        }
        Example::VariableExponent => {
            let [k, r_b, r_1, r_t] = EX2_LAW.map(lit::<T>);
            bounds::variable_exponent(k, r_b, r_1, r_t)
        }
        Example::Rfc => {
            let stages = EX3_STAGES.map(|(a, p, b, q)| (lit(a), lit(p), lit(b), lit(q)));
            bounds::fixed_time(&stages)
        }
    }
}

/// The plant's nominal input gain `G0 = 2` of every example: the product of
/// the constant terms of the chain's gains (eq. (44): `g1 = 1 + ...`,
/// `g2 = 2 + ...`; eq. (68): `g1 = g2 = 1 + ...`, `g3 = 2 + ...`). The true
/// `G` varies about it (1.9-2.5 along example 1's run, 1.7-2.9 along
/// example 3's); it is the observer's `b0` (docs/observer.md).
///
/// ```
/// use famcc_paper::designs::{nominal_gain, Example};
/// assert_eq!(nominal_gain::<f64>(Example::Rfc), 2.0);
/// ```
pub fn nominal_gain<T: Real>(example: Example) -> T {
    match example {
        Example::FiniteTime | Example::VariableExponent | Example::Rfc => lit(2.0),
    }
}

/// The actuator limits `(lo, hi)` of the example's scenario: saturated
/// `[-2.5, 3]`, `[-2, 3]`, `[-7, 9]` (examples 1-3), otherwise
/// [`UNSATURATED_LIMITS`].
pub fn input_limits<T: Real>(example: Example, saturated: bool) -> (T, T) {
    let (lo, hi) = match (example, saturated) {
        (_, false) => UNSATURATED_LIMITS,
        (Example::FiniteTime, true) => (-2.5, 3.0),
        (Example::VariableExponent, true) => (-2.0, 3.0),
        (Example::Rfc, true) => (-7.0, 9.0),
    };
    (lit(lo), lit(hi))
}
