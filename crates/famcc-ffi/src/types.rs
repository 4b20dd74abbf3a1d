//! The C-facing types: the configuration structs (the status codes and
//! enumeration values are in [`crate::enums`], what the functions report
//! back in [`crate::reports`]; the opaque storage of each controller type
//! is generated, in `api.rs`). cbindgen writes `include/famcc.h` from them.

pub use crate::enums::*;

/// The largest system order this ABI supports (arrays below are sized by it).
pub const FAMCC_MAX_ORDER: usize = 6;
/// The largest number of manifold stages (`order - 1`).
pub const FAMCC_MAX_STAGES: usize = FAMCC_MAX_ORDER - 1;
/// The largest number of observer coefficients (`order + 1`).
pub const FAMCC_MAX_OBSERVER_COEFFICIENTS: usize = FAMCC_MAX_ORDER + 1;

/// `FAMCC_FEEDBACK_KIND_LINEAR` parameters.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FamccLinear<T> {
    /// Gain `k > 0`, 1/s.
    pub k: T,
}

/// `FAMCC_FEEDBACK_KIND_FINITE_TIME` parameters.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FamccFiniteTime<T> {
    /// Gain `k > 0`.
    pub k: T,
    /// Exponent `0 < p < 1`.
    pub p: T,
}

/// `FAMCC_FEEDBACK_KIND_FIXED_TIME` parameters.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FamccFixedTime<T> {
    /// Low-power gain `alpha > 0`.
    pub alpha: T,
    /// Low power `0 < p < 1`.
    pub p: T,
    /// High-power gain `beta > 0`.
    pub beta: T,
    /// High power `q > 1`.
    pub q: T,
}

/// `FAMCC_FEEDBACK_KIND_VARIABLE_EXPONENT` parameters.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FamccVariableExponent<T> {
    /// Gain `k > 0`.
    pub k: T,
    /// Exponent at 0, `0 < r_b < 1`.
    pub r_b: T,
    /// Exponent at `|s| = 1`, `r_1 > 1`.
    pub r_1: T,
    /// Exponent at infinity, `r_t > r_1`.
    pub r_t: T,
}

/// `FAMCC_FEEDBACK_KIND_MOULAY_DISCONTINUOUS` parameters.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FamccMoulay<T> {
    /// Gain `beta > 0`.
    pub beta: T,
    /// Exponent numerator coefficient `lambda > 0`.
    pub lambda: T,
    /// Exponent denominator coefficient `mu >= 0`.
    pub mu: T,
}

/// The parameters of a feedback law; the member named by `FamccFeedback.kind`
/// is the one read.
#[repr(C)]
#[derive(Clone, Copy)]
pub union FamccFeedbackParams<T: Copy> {
    /// For `FAMCC_FEEDBACK_KIND_LINEAR`.
    pub linear: FamccLinear<T>,
    /// For `FAMCC_FEEDBACK_KIND_FINITE_TIME`.
    pub finite_time: FamccFiniteTime<T>,
    /// For `FAMCC_FEEDBACK_KIND_FIXED_TIME`.
    pub fixed_time: FamccFixedTime<T>,
    /// For `FAMCC_FEEDBACK_KIND_VARIABLE_EXPONENT`.
    pub variable_exponent: FamccVariableExponent<T>,
    /// For `FAMCC_FEEDBACK_KIND_MOULAY_DISCONTINUOUS`.
    pub moulay: FamccMoulay<T>,
}

/// A feedback law `h_p`: a tagged union (`kind` is a `FamccFeedbackKind`).
#[repr(C)]
#[derive(Clone, Copy)]
pub struct FamccFeedback<T: Copy> {
    /// A `FAMCC_FEEDBACK_KIND_*` value.
    pub kind: u32,
    /// The parameters of that kind.
    pub params: FamccFeedbackParams<T>,
}

/// A skew of a stage's law (`kind` is a `FamccSkewKind`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FamccSkew<T> {
    /// A `FAMCC_SKEW_KIND_*` value (`NONE`: the other fields are ignored).
    pub kind: u32,
    /// Vertical offset `eps_s > 0`.
    pub eps_s: T,
    /// Transition half-width `eps_z > 0`.
    pub eps_z: T,
    /// NSMD slope factor `k_pp > 0` (ignored by SSMD).
    pub k_pp: T,
    /// A `FAMCC_TRANSITION_*` value for `T1`, `T2`.
    pub transition: u32,
}

/// One manifold stage `h_m(i)`: a law and an optional skew.
#[repr(C)]
#[derive(Clone, Copy)]
pub struct FamccStage<T: Copy> {
    /// The feedback law.
    pub feedback: FamccFeedback<T>,
    /// The skew (`kind = FAMCC_SKEW_KIND_NONE` for none).
    pub skew: FamccSkew<T>,
}

/// The constraint type and its final half-widths.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FamccConstraint<T> {
    /// A `FAMCC_CONSTRAINT_KIND_*` value.
    pub kind: u32,
    /// Final horizontal half-width (LaMC, OMC).
    pub eps_x: T,
    /// Final vertical half-width (LoMC, OMC).
    pub eps_y: T,
}

/// The extended high-gain observer (famcc-core's `ExtendedHighGain`,
/// docs/observer.md; beyond the paper): it replaces the differentiator
/// (`differentiator.enabled` must then be 0, `integral` 0), estimates the
/// lumped term of `y^(n) = L + b0 u` from the error and the applied input,
/// and the law cancels it bounded, `u = v - clip(Lhat / b0, -delta, delta)`.
/// `famcc_observer_f32_binomial` / `_f64_` fill the default coefficients.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FamccObserver<T> {
    /// Nonzero: use it.
    pub enabled: u32,
    /// Time constant `mu > 0`, seconds.
    pub mu: T,
    /// Hurwitz coefficients `a_1..a_(order+1)` of
    /// `s^(order+1) + a_1 s^order + ... + a_(order+1)` (the rest is ignored).
    pub a: [T; FAMCC_MAX_OBSERVER_COEFFICIENTS],
    /// The nominal input gain `b0` (nonzero; its sign is the control direction).
    pub b0: T,
    /// `FAMCC_DISCRETIZATION_EXACT` (the error held) or `_FOH`.
    pub discretization: u32,
    /// Nonzero: bound the cancellation by `cancellation_limit`; zero: by
    /// half the output range (finite output limits are then required).
    pub has_cancellation_limit: u32,
    /// The cancellation's bound `delta > 0`, input units.
    pub cancellation_limit: T,
}

/// `float` observer.
pub type FamccObserverF32 = FamccObserver<f32>;
/// `double` observer.
pub type FamccObserverF64 = FamccObserver<f64>;

/// The high-gain differentiator (output feedback).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FamccDifferentiator<T> {
    /// Nonzero: use it (required by `*_step`).
    pub enabled: u32,
    /// Time constant `mu > 0`, seconds.
    pub mu: T,
    /// Hurwitz coefficients `a_1..a_order` (the rest is ignored).
    pub a: [T; FAMCC_MAX_ORDER],
    /// A `FAMCC_DISCRETIZATION_*` value.
    pub discretization: u32,
    /// Time constant of the low-pass prefilter on the error in front of the
    /// differentiator, seconds (`>= 0`; 0, the default: none, the paper's).
    pub prefilter: T,
}

/// Everything that defines a controller (mirrors `famcc_core::Config`).
/// Fill it with `famcc_config_f32_defaults` / `_f64_defaults`, then set the
/// required values.
#[repr(C)]
#[derive(Clone, Copy)]
pub struct FamccConfig<T: Copy> {
    /// Sample period, seconds (> 0).
    pub dt: T,
    /// Envelope settling time `T_s`, seconds (> 0; default famcc-core's, 1 s).
    pub settle_time: T,
    /// Initial-width factor `k0 > 1` (default famcc-core's, 2).
    pub k0: T,
    /// Control gain `k_u > 0`.
    pub k_u: T,
    /// Constraint type and final half-widths.
    pub constraint: FamccConstraint<T>,
    /// A `FAMCC_GAMMA_*` value (default log).
    pub gamma: u32,
    /// A `FAMCC_FLEXIBLE_*` value (default `AUTO`).
    pub flexible: u32,
    /// Flexible-boundary margin `rho_e > 0`, read with `FAMCC_FLEXIBLE_ON`.
    pub rho_e: T,
    /// A `FAMCC_TRANSITION_*` value for the flexible boundary (default exponential).
    pub transition: u32,
    /// A `FAMCC_LATCH_*` value (default paper).
    pub latch: u32,
    /// Stages `h_m1..h_m(order-1)`; the rest is ignored.
    pub stages: [FamccStage<T>; FAMCC_MAX_STAGES],
    /// The differentiator.
    pub differentiator: FamccDifferentiator<T>,
    /// Nonzero: use `initial_derivatives[1..order]` as the first estimate.
    pub has_initial_derivatives: u32,
    /// Initial derivative estimates (slot 0 ignored).
    pub initial_derivatives: [T; FAMCC_MAX_ORDER],
    /// Nonzero: clamp `|z_hat_i| <= estimate_limits[i]` before the law.
    pub has_estimate_limits: u32,
    /// Estimate limits (> 0, infinity allowed).
    pub estimate_limits: [T; FAMCC_MAX_ORDER],
    /// Nonzero: integral action (docs/design.md §3.8). The controller's
    /// order is then the law's, the plant's + 1: an order-3 controller for
    /// an order-2 plant, with `stages[0..2]`, the differentiator of the
    /// plant's order in `a[0..order-1]`, and the arrays above in the law's
    /// coordinates (slot 0 the integral: `initial_derivatives[2..order]` are
    /// the plant's `z2..zn`, `estimate_limits[0]` is ignored).
    pub integral: u32,
    /// Nonzero: limit the output to `[output_limits[0], output_limits[1]]`.
    pub has_output_limits: u32,
    /// Output magnitude limits `lo < hi` (infinite ends allowed).
    pub output_limits: [T; 2],
    /// Nonzero: limit the output's rate to `rate_limit` units per second.
    pub has_rate_limit: u32,
    /// Output rate limit (> 0), units per second.
    pub rate_limit: T,
    /// Nonzero: bumpless start, the first output is `initial_output` when feasible.
    pub has_initial_output: u32,
    /// The output the first step starts from.
    pub initial_output: T,
    /// The extended observer and its bounded cancellation (beyond the paper;
    /// off by default).
    pub observer: FamccObserver<T>,
    /// The control direction, a `FAMCC_DIRECTION_*` value (default
    /// `POSITIVE`, the paper's `G > 0`); an observer's `b0` must have its
    /// sign. The last member, so the members before it keep their offsets.
    pub direction: u32,
}

/// `float` configuration.
pub type FamccConfigF32 = FamccConfig<f32>;
/// `double` configuration.
pub type FamccConfigF64 = FamccConfig<f64>;

/// A differentiator's recursion `V_{k+1} = Phi Zhat_k + Gamma f_k`, with the
/// estimate `Zhat_k = V_k + D (f_k - f_{k-1})` (`D` the feedthrough of the
/// input's increment, zero but for `FAMCC_DISCRETIZATION_FOH`, whose `Phi`
/// and `Gamma` are the exact hold's), for one sample period (famcc-core's
/// `DiscreteHgd`): computed on a host by `*_discretize` and passed to
/// `*_init_discretized` on a target, which then runs no matrix exponential
/// (and links none). `feedthrough` is the last member, so the members
/// before it keep their offsets.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FamccDiscretized<T> {
    /// `Phi`, row-major: entry `(i, j)` is `phi[i][j]`; the first `order`
    /// rows and columns are used.
    pub phi: [[T; FAMCC_MAX_ORDER]; FAMCC_MAX_ORDER],
    /// `Gamma`; the first `order` entries are used.
    pub gamma: [T; FAMCC_MAX_ORDER],
    /// The prefilter's gain per period, in `(0, 1]`; exactly 1 without a
    /// prefilter.
    pub prefilter: T,
    /// The direct feedthrough `D` of the first-order hold
    /// (`FAMCC_DISCRETIZATION_FOH`); zeros for the other discretizations.
    /// The first `order` entries are used.
    pub feedthrough: [T; FAMCC_MAX_ORDER],
}

/// `float` precomputed recursion.
pub type FamccDiscretizedF32 = FamccDiscretized<f32>;
/// `double` precomputed recursion.
pub type FamccDiscretizedF64 = FamccDiscretized<f64>;
