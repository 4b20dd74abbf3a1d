//! The C-facing types: status codes, enumeration values and the
//! configuration structs (what the functions report back is in
//! [`crate::reports`]; the opaque storage of each controller type is
//! generated, in `api.rs`). cbindgen writes `include/famcc.h` from them.

/// The largest system order this ABI supports (arrays below are sized by it).
pub const FAMCC_MAX_ORDER: usize = 6;
/// The largest number of manifold stages (`order - 1`).
pub const FAMCC_MAX_STAGES: usize = FAMCC_MAX_ORDER - 1;

/// Result of every call. `FAMCC_STATUS_OK` is 0; errors are positive.
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FamccStatus {
    /// Success.
    Ok = 0,
    /// A required pointer argument was NULL.
    NullPointer = 1,
    /// The storage is not aligned to `*_align()` bytes.
    Misaligned = 2,
    /// The storage does not hold an initialised controller of this type.
    NotInitialized = 3,
    /// The configuration was rejected (details in `FamccError`); the storage
    /// is left uninitialised.
    InvalidConfig = 4,
    /// The measurement was NaN or infinite; the state is unchanged.
    NonFiniteInput = 5,
    /// The applied input was NaN or infinite; the state is unchanged.
    NonFiniteApplied = 6,
    /// A sample period was not finite and > 0.
    InvalidDt = 7,
    /// `step` at order >= 2 needs a differentiator (`differentiator.enabled`).
    NoDifferentiator = 8,
    /// The sample was finite but could not be used: the law overflowed on
    /// the estimate, or the sample would have taken the estimate out of
    /// range. After the first step the sample is consumed: the clock
    /// advances and the estimate restarts (famcc-core's recovery rule,
    /// docs/design.md §3.7), so the next moderate sample steps again; before
    /// the first step nothing changes. `*v` is not written: hold the previous
    /// output.
    Overflow = 9,
    /// `storage_size` of `*_init_sized` is smaller than the controller's
    /// storage type (`*_size()`); nothing was written.
    StorageTooSmall = 10,
}

/// Feedback law kinds (`FamccFeedback.kind`).
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FamccFeedbackKind {
    /// `h(s) = -k s`; parameters `linear`.
    Linear = 0,
    /// `h(s) = -k |s|^p sign(s)`, `0 < p < 1`; parameters `finite_time`.
    FiniteTime = 1,
    /// `-alpha |s|^p sign(s) - beta |s|^q sign(s)`; parameters `fixed_time`.
    FixedTime = 2,
    /// The paper's variable-exponent law; parameters `variable_exponent`.
    VariableExponent = 3,
    /// Moulay's discontinuous law (comparison only); parameters `moulay`.
    MoulayDiscontinuous = 4,
}

/// Skew kinds (`FamccSkew.kind`).
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FamccSkewKind {
    /// No skew: `h_m = h_p`.
    None = 0,
    /// SSMD (smooth skewed manifold).
    Smooth = 1,
    /// NSMD (nonsingular skewed manifold), uses `k_pp`.
    Nonsingular = 2,
}

/// Constraint kinds (`FamccConstraint.kind`).
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FamccConstraintKind {
    /// LoMC: uses `eps_y`.
    Longitudinal = 0,
    /// LaMC: uses `eps_x`.
    Lateral = 1,
    /// OMC: uses `eps_x` and `eps_y`.
    Oblique = 2,
}

/// The map Gamma of the control law (`FamccConfig.gamma`).
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FamccGamma {
    /// `ln((1 + xi)/(1 - xi))`.
    Log = 0,
    /// `xi / ((1 + xi)(1 - xi))`.
    Rational = 1,
}

/// Double-ended transitions (`FamccConfig.transition`, `FamccSkew.transition`).
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FamccTransition {
    /// The paper's C-infinity transition.
    Exponential = 0,
    /// `3z^2 - 2z^3`.
    Cubic = 1,
    /// `10z^3 - 15z^4 + 6z^5`.
    Quintic = 2,
    /// `sin^2(pi z / 2)`.
    Sine = 3,
}

/// How the envelopes' initial widths are latched (`FamccConfig.latch`).
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FamccLatch {
    /// The paper: `rho0 = k0 max(|s0|, eps)`.
    Paper = 0,
    /// The authors' code: `rho0 = max(k0 |s0|, eps)`.
    Authors = 1,
}

/// Differentiator discretizations (`FamccDifferentiator.discretization`).
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FamccDiscretization {
    /// Zero-order hold (matrix exponential): stable for every dt.
    Exact = 0,
    /// Forward Euler (comparison only).
    Euler = 1,
    /// Tustin (bilinear).
    Tustin = 2,
    /// First-order (triangle) hold: the estimate of a sample uses that
    /// sample; famcc's choice below 500 Hz up to order 3.
    Foh = 3,
}

/// Whether and how the flexible boundaries are on (`FamccConfig.flexible`).
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FamccFlexible {
    /// No flexible boundaries (the controller of eq. (29)).
    Off = 0,
    /// Flexible boundaries with the margin `rho_e`.
    On = 1,
    /// Flexible boundaries with famcc-core's margin, min(0.01, smallest
    /// final width / 10) (the default).
    Auto = 2,
}

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
