//! The C-facing enumerations: status codes and the `FAMCC_*` values of
//! the configuration's `uint32_t` fields (re-exported by [`crate::types`]).

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

/// The control direction, the sign of the plant's input gain `G`
/// (`FamccConfig.direction`; famcc-core's `Direction`).
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FamccDirection {
    /// `G > 0`, the paper's: a larger input raises the output.
    Positive = 0,
    /// `G < 0`: the law's sign is reversed (`v = +k_u Gamma(xi)`); the
    /// limits and inputs stay in the actuator's units.
    Negative = 1,
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
