//! What the controller did at its last step.

use crate::Real;

/// What the controller did at its last step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Diagnostics<T, const N: usize> {
    /// Time of the last step's sample, seconds (exact: from the integer
    /// sample count, docs/design.md §3.10; 0 before the first step and after
    /// `restore`).
    pub t: f64,
    /// The constraint variable used for the output (flexible `xi~` of
    /// eq. (31) when the flexible boundary is on), after clamping.
    pub xi: T,
    /// The nominal constraint variable `xi` (eq. (28)), before clamping.
    pub xi_nominal: T,
    /// The manifold value `s = s_n`.
    pub s: T,
    /// `s_1..s_n` (eq. (11)).
    pub stages: [T; N],
    /// `s_{n-1}`.
    pub s_prev: T,
    /// `d/dt s_{n-1}`.
    pub ds_prev: T,
    /// Flexible upper bounds `(x~_U, y~_U)` (lower ones are their negatives).
    pub bounds: (T, T),
    /// Nominal upper bounds `(x_U, y_U)`.
    pub nominal_bounds: (T, T),
    /// The vector the output was computed from (the estimate after the
    /// optional saturation), in the law's coordinates: with integral action
    /// `(I, z_hat_1, ..., z_hat_n)`.
    pub z_hat: [T; N],
    /// True when the flexible boundary was expanded.
    pub expanded: bool,
    /// The expansion factor `x~_U / x_U = y~_U / y_U >= 1` of the flexible
    /// boundary (eq. (30)); exactly 1 while the bounds are nominal.
    pub expansion: T,
    /// `v_{k-1} - applied` when the caller passed the applied input.
    pub saturation_gap: Option<T>,
    /// Number of steps at which `|xi|` had to be clamped below 1.
    pub clamp_count: u64,
    /// The output returned (after the output limits, when configured).
    pub v: T,
    /// The law's output `v = -k_u Gamma(xi)` before the output limits
    /// (equal to `v` without them).
    pub v_unlimited: T,
    /// The observer's cancellation `c = clip(Lhat / b0, -delta, delta)` in
    /// the output (config/observer.rs; 0 without an observer): `v_unlimited`
    /// is `-k_u Gamma(xi) - c`.
    #[cfg(feature = "observer")]
    pub cancellation: T,
    /// The integral `I` the output used (integral action), `None` without.
    pub integral: Option<T>,
    /// True when this step integrated its sample into `I` (false while the
    /// integral separation froze it, and without integral action).
    pub integrating: bool,
    /// Steps so far at which the bounds were expanded while the actuator
    /// was known to have headroom (output limits configured, or `applied`
    /// passed, and the law's output within them). Nonzero means the preset
    /// accuracy was given up without saturation: `k_u` too small for the
    /// plant, or `rho_e` too large. Saturating at `u64::MAX`.
    pub unsaturated_expansions: u64,
}

impl<T: Real, const N: usize> Default for Diagnostics<T, N> {
    fn default() -> Self {
        let z = T::zero();
        Self {
            t: 0.0,
            xi: z,
            xi_nominal: z,
            s: z,
            stages: [z; N],
            s_prev: z,
            ds_prev: z,
            bounds: (z, z),
            nominal_bounds: (z, z),
            z_hat: [z; N],
            expanded: false,
            expansion: T::one(),
            saturation_gap: None,
            clamp_count: 0,
            v: z,
            v_unlimited: z,
            #[cfg(feature = "observer")]
            cancellation: z,
            integral: None,
            integrating: false,
            unsaturated_expansions: 0,
        }
    }
}
