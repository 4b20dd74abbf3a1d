//! What the C functions report back: a step's diagnostics, a
//! configuration's lint findings and why a configuration was rejected
//! (cbindgen writes them to `include/famcc.h` after [`crate::types`]).

use core::ffi::c_char;

use crate::types::FAMCC_MAX_ORDER;

/// What the last step did (mirrors `famcc_core::Diagnostics`; arrays hold
/// `order` used entries).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FamccDiagnostics<T> {
    /// System order of the controller (1 to 6).
    pub order: u32,
    /// Nonzero when the flexible boundary was expanded.
    pub expanded: u32,
    /// Time of the last step's sample, seconds (`double` for both float
    /// types: exact from an integer sample count, docs/design.md §3.10).
    pub t: f64,
    /// The constraint variable used for the output (after clamping).
    pub xi: T,
    /// The nominal constraint variable, before clamping.
    pub xi_nominal: T,
    /// The flexible boundary's expansion factor (1 while the bounds are nominal).
    pub expansion: T,
    /// The manifold value `s = s_n`.
    pub s: T,
    /// `s_1..s_n`.
    pub stages: [T; FAMCC_MAX_ORDER],
    /// `s_{n-1}`.
    pub s_prev: T,
    /// `d/dt s_{n-1}`.
    pub ds_prev: T,
    /// Flexible upper bounds `(x~_U, y~_U)`.
    pub bounds: [T; 2],
    /// Nominal upper bounds `(x_U, y_U)`.
    pub nominal_bounds: [T; 2],
    /// The estimate the output was computed from.
    pub z_hat: [T; FAMCC_MAX_ORDER],
    /// Nonzero when `saturation_gap` is valid (`*_step_applied` was used).
    pub has_saturation_gap: u32,
    /// `v_{k-1} - applied`.
    pub saturation_gap: T,
    /// Steps at which `|xi|` had to be clamped below 1.
    pub clamp_count: u64,
    /// The output `v` (after the output limits, when configured).
    pub v: T,
    /// The law's output before the output limits.
    pub v_unlimited: T,
    /// Nonzero with integral action (then `integral` is valid).
    pub has_integral: u32,
    /// Nonzero when the last step added its sample to the integral.
    pub integrating: u32,
    /// The integral of the error the output used.
    pub integral: T,
    /// Steps at which the bounds expanded while the actuator was known to
    /// have headroom (output limits set or `*_step_applied` used).
    pub unsaturated_expansions: u64,
    /// The observer's cancellation `clip(Lhat / b0, -delta, delta)` in the
    /// output (0 without an observer).
    pub cancellation: T,
    /// The observer's estimate `Lhat` of the lumped term, output units per
    /// `s^order`, for the next step (0 without an observer).
    pub lumped: T,
}

/// One legal but risky choice of a configuration (famcc-core's
/// `Config::lint`): the parameter and the whole finding in words, naming the
/// rule, the configuration's number and a suggested value (NUL-terminated,
/// truncated if needed).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct FamccFinding {
    /// Zero-based stage for per-stage parameters, -1 otherwise.
    pub stage: i32,
    /// The parameter to change (`dt`, `rho_e`, `k`, `estimate_limits`, ...).
    pub parameter: [c_char; 32],
    /// The finding: the risk, the rule, the number and the suggestion.
    pub message: [c_char; 480],
}

/// The largest number of findings `*_lint` writes (one per kind of risk).
pub const FAMCC_MAX_FINDINGS: usize = 5;

/// Why a configuration was rejected (NUL-terminated, truncated if needed).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct FamccError {
    /// Zero-based stage for per-stage parameters, -1 otherwise.
    pub stage: i32,
    /// The parameter's name (`eps`, `p`, `k_u`, `feedback.kind`, ...).
    pub parameter: [c_char; 32],
    /// The rule it broke, e.g. `must be finite and > 0`.
    pub rule: [c_char; 160],
}

/// `float` diagnostics.
pub type FamccDiagnosticsF32 = FamccDiagnostics<f32>;
/// `double` diagnostics.
pub type FamccDiagnosticsF64 = FamccDiagnostics<f64>;
