//! C ABI for famcc-core: the FAMCC controller of orders 2 and 3 in `float`
//! (f32) and `double` (f64), for C firmware and other languages.
//!
//! Design:
//! - **No allocation.** The caller provides the storage: `FamccO2F32`,
//!   `FamccO2F64`, `FamccO3F32`, `FamccO3F64` are opaque structs of fixed size
//!   and 8-byte alignment declared in the header (static, stack or pool
//!   objects); `famcc_o2_f32_size()`/`_align()` report the same numbers at run
//!   time. `*_init` writes a controller into the storage; every other call
//!   checks that it was initialised (`FAMCC_STATUS_NOT_INITIALIZED`).
//! - **Plain C configuration.** `FamccConfig` mirrors `famcc_core::Config`;
//!   feedback laws are tagged structs ([`FamccFeedback`]: a kind and a union
//!   of parameter structs), enumerations are `uint32_t` fields holding the
//!   `FAMCC_*` constants, so no C value can be an invalid Rust enum.
//!   [`famcc_config_f32_defaults`] fills famcc-core's defaults (the paper's).
//! - **Status codes, never unwinding.** Every function returns a
//!   [`FamccStatus`]; configuration errors can also be described in a
//!   [`FamccError`] (parameter, stage, rule). The crate is `no_std`, built
//!   with `panic = "abort"`, and famcc-core never panics.
//!
//! The crate is split by concern: [`types`] (the C-facing types, which
//! cbindgen writes to `include/famcc.h`; see `cbindgen.toml`), `convert`
//! (C configuration and diagnostics to and from famcc-core's, with its
//! defaults), `storage` (the tagged slots and checked access), and here the
//! C functions themselves.
#![no_std]
#![allow(clippy::missing_safety_doc)]

mod convert;
mod lint;
mod storage;
pub mod types;

use core::ffi::c_char;
use core::mem::{align_of, size_of};
use core::ptr;

use storage::{diagnostics, init, reset, step, MAGIC_O2_F32, MAGIC_O2_F64, MAGIC_O3_F32, MAGIC_O3_F64};
pub use types::*;
// ---------------------------------------------------------------------------
// The C functions (written out: cbindgen does not expand macros)
// ---------------------------------------------------------------------------

/// A static NUL-terminated description of a status code.
#[no_mangle]
pub extern "C" fn famcc_status_str(status: u32) -> *const c_char {
    let s: &'static [u8] = match status {
        0 => b"ok\0",
        1 => b"a required pointer was NULL\0",
        2 => b"storage is misaligned\0",
        3 => b"storage does not hold an initialised controller of this type\0",
        4 => b"invalid configuration\0",
        5 => b"input must be finite (got NaN or infinity); state unchanged\0",
        6 => b"applied input must be finite; state unchanged\0",
        7 => b"dt must be finite and > 0 (and within the scale range); state unchanged\0",
        8 => b"step needs a differentiator at order >= 2\0",
        9 => b"sample unusable (an internal value would overflow): consumed, the estimate restarts; hold the previous output\0",
        10 => b"storage_size is smaller than the controller's storage type\0",
        _ => b"unknown status\0",
    };
    s.as_ptr().cast()
}

/// Writes famcc-core's defaults to `cfg`: k0 = 2, T_s = 1 s, log Gamma,
/// flexible boundaries with the core's margin (`FAMCC_FLEXIBLE_AUTO`:
/// min(0.01, eps/10)), exponential transition, the paper's latch,
/// differentiator off, LoMC. What has no default (`dt`, `k_u`, the
/// constraint's widths, the stage laws: linear with k = 0) is zero and must
/// be set.
#[no_mangle]
pub unsafe extern "C" fn famcc_config_f32_defaults(cfg: *mut FamccConfigF32) -> FamccStatus {
    write_defaults(cfg)
}

/// `double` version of `famcc_config_f32_defaults`.
#[no_mangle]
pub unsafe extern "C" fn famcc_config_f64_defaults(cfg: *mut FamccConfigF64) -> FamccStatus {
    write_defaults(cfg)
}

unsafe fn write_defaults<T: famcc_core::Real>(cfg: *mut FamccConfig<T>) -> FamccStatus {
    if cfg.is_null() {
        return FamccStatus::NullPointer;
    }
    ptr::write_unaligned(cfg, convert::defaults());
    FamccStatus::Ok
}

/// `sizeof(FamccO2F32)`.
#[no_mangle]
pub extern "C" fn famcc_o2_f32_size() -> usize {
    size_of::<FamccO2F32>()
}

/// `_Alignof(FamccO2F32)`.
#[no_mangle]
pub extern "C" fn famcc_o2_f32_align() -> usize {
    align_of::<FamccO2F32>()
}

/// Validates `config` (order 2: `stages[0]` used) and writes a controller
/// into `storage`. On `FAMCC_STATUS_INVALID_CONFIG` the reason is written to
/// `error` (may be NULL) and `storage` is left uninitialised.
#[no_mangle]
pub unsafe extern "C" fn famcc_o2_f32_init(
    storage: *mut FamccO2F32,
    config: *const FamccConfigF32,
    error: *mut FamccError,
) -> FamccStatus {
    init::<_, f32, 2>(storage, None, config, error, MAGIC_O2_F32)
}

/// `famcc_o2_f32_init` for storage given as a buffer of `storage_size`
/// bytes (e.g. a pool block): `FAMCC_STATUS_STORAGE_TOO_SMALL` when it is
/// smaller than `famcc_o2_f32_size()`, `FAMCC_STATUS_MISALIGNED` when it is
/// not aligned to `famcc_o2_f32_align()`; nothing is written then.
#[no_mangle]
pub unsafe extern "C" fn famcc_o2_f32_init_sized(
    storage: *mut FamccO2F32,
    storage_size: usize,
    config: *const FamccConfigF32,
    error: *mut FamccError,
) -> FamccStatus {
    init::<_, f32, 2>(storage, Some(storage_size), config, error, MAGIC_O2_F32)
}

/// One output-feedback step: consumes the error sample `e = y - y_d`, writes
/// the control `v` to hold until the next sample. On error `*v` is not
/// written and the state is unchanged, except `FAMCC_STATUS_OVERFLOW` after
/// the first step (the sample is consumed; see that status).
#[no_mangle]
pub unsafe extern "C" fn famcc_o2_f32_step(c: *mut FamccO2F32, e: f32, v: *mut f32) -> FamccStatus {
    step::<_, f32, 2>(c, MAGIC_O2_F32, e, None, v)
}

/// `famcc_o2_f32_step`, telling the controller the input the actuator really
/// applied at the previous sample (diagnostics report the saturation gap).
#[no_mangle]
pub unsafe extern "C" fn famcc_o2_f32_step_applied(
    c: *mut FamccO2F32,
    e: f32,
    applied: f32,
    v: *mut f32,
) -> FamccStatus {
    step::<_, f32, 2>(c, MAGIC_O2_F32, e, Some(applied), v)
}

/// Back to the state before the first step (configuration kept).
#[no_mangle]
pub unsafe extern "C" fn famcc_o2_f32_reset(c: *mut FamccO2F32) -> FamccStatus {
    reset::<_, f32, 2>(c, MAGIC_O2_F32)
}

/// What the last step did.
#[no_mangle]
pub unsafe extern "C" fn famcc_o2_f32_diagnostics(
    c: *const FamccO2F32,
    out: *mut FamccDiagnosticsF32,
) -> FamccStatus {
    diagnostics::<_, f32, 2>(c, MAGIC_O2_F32, out)
}

/// `sizeof(FamccO2F64)`.
#[no_mangle]
pub extern "C" fn famcc_o2_f64_size() -> usize {
    size_of::<FamccO2F64>()
}

/// `_Alignof(FamccO2F64)`.
#[no_mangle]
pub extern "C" fn famcc_o2_f64_align() -> usize {
    align_of::<FamccO2F64>()
}

/// See `famcc_o2_f32_init`.
#[no_mangle]
pub unsafe extern "C" fn famcc_o2_f64_init(
    storage: *mut FamccO2F64,
    config: *const FamccConfigF64,
    error: *mut FamccError,
) -> FamccStatus {
    init::<_, f64, 2>(storage, None, config, error, MAGIC_O2_F64)
}

/// `famcc_o2_f64_init` for storage given as a buffer of `storage_size`
/// bytes (e.g. a pool block): `FAMCC_STATUS_STORAGE_TOO_SMALL` when it is
/// smaller than `famcc_o2_f64_size()`, `FAMCC_STATUS_MISALIGNED` when it is
/// not aligned to `famcc_o2_f64_align()`; nothing is written then.
#[no_mangle]
pub unsafe extern "C" fn famcc_o2_f64_init_sized(
    storage: *mut FamccO2F64,
    storage_size: usize,
    config: *const FamccConfigF64,
    error: *mut FamccError,
) -> FamccStatus {
    init::<_, f64, 2>(storage, Some(storage_size), config, error, MAGIC_O2_F64)
}

/// See `famcc_o2_f32_step`.
#[no_mangle]
pub unsafe extern "C" fn famcc_o2_f64_step(c: *mut FamccO2F64, e: f64, v: *mut f64) -> FamccStatus {
    step::<_, f64, 2>(c, MAGIC_O2_F64, e, None, v)
}

/// See `famcc_o2_f32_step_applied`.
#[no_mangle]
pub unsafe extern "C" fn famcc_o2_f64_step_applied(
    c: *mut FamccO2F64,
    e: f64,
    applied: f64,
    v: *mut f64,
) -> FamccStatus {
    step::<_, f64, 2>(c, MAGIC_O2_F64, e, Some(applied), v)
}

/// See `famcc_o2_f32_reset`.
#[no_mangle]
pub unsafe extern "C" fn famcc_o2_f64_reset(c: *mut FamccO2F64) -> FamccStatus {
    reset::<_, f64, 2>(c, MAGIC_O2_F64)
}

/// See `famcc_o2_f32_diagnostics`.
#[no_mangle]
pub unsafe extern "C" fn famcc_o2_f64_diagnostics(
    c: *const FamccO2F64,
    out: *mut FamccDiagnosticsF64,
) -> FamccStatus {
    diagnostics::<_, f64, 2>(c, MAGIC_O2_F64, out)
}

/// `sizeof(FamccO3F32)`.
#[no_mangle]
pub extern "C" fn famcc_o3_f32_size() -> usize {
    size_of::<FamccO3F32>()
}

/// `_Alignof(FamccO3F32)`.
#[no_mangle]
pub extern "C" fn famcc_o3_f32_align() -> usize {
    align_of::<FamccO3F32>()
}

/// See `famcc_o2_f32_init` (order 3: `stages[0..2]` used).
#[no_mangle]
pub unsafe extern "C" fn famcc_o3_f32_init(
    storage: *mut FamccO3F32,
    config: *const FamccConfigF32,
    error: *mut FamccError,
) -> FamccStatus {
    init::<_, f32, 3>(storage, None, config, error, MAGIC_O3_F32)
}

/// `famcc_o3_f32_init` for storage given as a buffer of `storage_size`
/// bytes (e.g. a pool block): `FAMCC_STATUS_STORAGE_TOO_SMALL` when it is
/// smaller than `famcc_o3_f32_size()`, `FAMCC_STATUS_MISALIGNED` when it is
/// not aligned to `famcc_o3_f32_align()`; nothing is written then.
#[no_mangle]
pub unsafe extern "C" fn famcc_o3_f32_init_sized(
    storage: *mut FamccO3F32,
    storage_size: usize,
    config: *const FamccConfigF32,
    error: *mut FamccError,
) -> FamccStatus {
    init::<_, f32, 3>(storage, Some(storage_size), config, error, MAGIC_O3_F32)
}

/// See `famcc_o2_f32_step`.
#[no_mangle]
pub unsafe extern "C" fn famcc_o3_f32_step(c: *mut FamccO3F32, e: f32, v: *mut f32) -> FamccStatus {
    step::<_, f32, 3>(c, MAGIC_O3_F32, e, None, v)
}

/// See `famcc_o2_f32_step_applied`.
#[no_mangle]
pub unsafe extern "C" fn famcc_o3_f32_step_applied(
    c: *mut FamccO3F32,
    e: f32,
    applied: f32,
    v: *mut f32,
) -> FamccStatus {
    step::<_, f32, 3>(c, MAGIC_O3_F32, e, Some(applied), v)
}

/// See `famcc_o2_f32_reset`.
#[no_mangle]
pub unsafe extern "C" fn famcc_o3_f32_reset(c: *mut FamccO3F32) -> FamccStatus {
    reset::<_, f32, 3>(c, MAGIC_O3_F32)
}

/// See `famcc_o2_f32_diagnostics`.
#[no_mangle]
pub unsafe extern "C" fn famcc_o3_f32_diagnostics(
    c: *const FamccO3F32,
    out: *mut FamccDiagnosticsF32,
) -> FamccStatus {
    diagnostics::<_, f32, 3>(c, MAGIC_O3_F32, out)
}

/// `sizeof(FamccO3F64)`.
#[no_mangle]
pub extern "C" fn famcc_o3_f64_size() -> usize {
    size_of::<FamccO3F64>()
}

/// `_Alignof(FamccO3F64)`.
#[no_mangle]
pub extern "C" fn famcc_o3_f64_align() -> usize {
    align_of::<FamccO3F64>()
}

/// See `famcc_o3_f32_init`.
#[no_mangle]
pub unsafe extern "C" fn famcc_o3_f64_init(
    storage: *mut FamccO3F64,
    config: *const FamccConfigF64,
    error: *mut FamccError,
) -> FamccStatus {
    init::<_, f64, 3>(storage, None, config, error, MAGIC_O3_F64)
}

/// `famcc_o3_f64_init` for storage given as a buffer of `storage_size`
/// bytes (e.g. a pool block): `FAMCC_STATUS_STORAGE_TOO_SMALL` when it is
/// smaller than `famcc_o3_f64_size()`, `FAMCC_STATUS_MISALIGNED` when it is
/// not aligned to `famcc_o3_f64_align()`; nothing is written then.
#[no_mangle]
pub unsafe extern "C" fn famcc_o3_f64_init_sized(
    storage: *mut FamccO3F64,
    storage_size: usize,
    config: *const FamccConfigF64,
    error: *mut FamccError,
) -> FamccStatus {
    init::<_, f64, 3>(storage, Some(storage_size), config, error, MAGIC_O3_F64)
}

/// See `famcc_o2_f32_step`.
#[no_mangle]
pub unsafe extern "C" fn famcc_o3_f64_step(c: *mut FamccO3F64, e: f64, v: *mut f64) -> FamccStatus {
    step::<_, f64, 3>(c, MAGIC_O3_F64, e, None, v)
}

/// See `famcc_o2_f32_step_applied`.
#[no_mangle]
pub unsafe extern "C" fn famcc_o3_f64_step_applied(
    c: *mut FamccO3F64,
    e: f64,
    applied: f64,
    v: *mut f64,
) -> FamccStatus {
    step::<_, f64, 3>(c, MAGIC_O3_F64, e, Some(applied), v)
}

/// See `famcc_o2_f32_reset`.
#[no_mangle]
pub unsafe extern "C" fn famcc_o3_f64_reset(c: *mut FamccO3F64) -> FamccStatus {
    reset::<_, f64, 3>(c, MAGIC_O3_F64)
}

/// See `famcc_o2_f32_diagnostics`.
#[no_mangle]
pub unsafe extern "C" fn famcc_o3_f64_diagnostics(
    c: *const FamccO3F64,
    out: *mut FamccDiagnosticsF64,
) -> FamccStatus {
    diagnostics::<_, f64, 3>(c, MAGIC_O3_F64, out)
}

// ---------------------------------------------------------------------------
// Panic handler (no_std builds; never reached: famcc-core does not panic)
// ---------------------------------------------------------------------------

#[cfg(all(feature = "panic-handler", not(test), target_os = "none"))]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    // A permanently undefined instruction: HardFault on a Cortex-M.
    #[cfg(target_arch = "arm")]
    // SAFETY: traps; never returns.
    unsafe {
        core::arch::asm!("udf #0xfe", options(noreturn))
    }
    #[cfg(not(target_arch = "arm"))]
    loop {}
}

#[cfg(all(feature = "panic-handler", not(test), not(target_os = "none")))]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    extern "C" {
        fn abort() -> !;
    }
    // SAFETY: the C library's abort(); hosted targets always have one.
    unsafe { abort() }
}

/// The legal but risky choices of the controller's configuration
/// (famcc-core's `Config::lint`: dt too coarse for mu, a last-stage law that
/// chatters, rho_e too large for eps, no estimate limits or the exact ZOH
/// at order >= 4). Writes at most `capacity` findings to `out` (may be NULL
/// when `capacity` is 0) and their number to `*count`; at most
/// `FAMCC_MAX_FINDINGS`.
#[no_mangle]
pub unsafe extern "C" fn famcc_o2_f32_lint(
    c: *const FamccO2F32,
    out: *mut FamccFinding,
    capacity: usize,
    count: *mut usize,
) -> FamccStatus {
    lint::lint::<_, f32, 2>(c, MAGIC_O2_F32, out, capacity, count)
}

/// `famcc_o2_f32_lint` for `FamccO2F64`.
#[no_mangle]
pub unsafe extern "C" fn famcc_o2_f64_lint(
    c: *const FamccO2F64,
    out: *mut FamccFinding,
    capacity: usize,
    count: *mut usize,
) -> FamccStatus {
    lint::lint::<_, f64, 2>(c, MAGIC_O2_F64, out, capacity, count)
}

/// `famcc_o2_f32_lint` for `FamccO3F32`.
#[no_mangle]
pub unsafe extern "C" fn famcc_o3_f32_lint(
    c: *const FamccO3F32,
    out: *mut FamccFinding,
    capacity: usize,
    count: *mut usize,
) -> FamccStatus {
    lint::lint::<_, f32, 3>(c, MAGIC_O3_F32, out, capacity, count)
}

/// `famcc_o2_f32_lint` for `FamccO3F64`.
#[no_mangle]
pub unsafe extern "C" fn famcc_o3_f64_lint(
    c: *const FamccO3F64,
    out: *mut FamccFinding,
    capacity: usize,
    count: *mut usize,
) -> FamccStatus {
    lint::lint::<_, f64, 3>(c, MAGIC_O3_F64, out, capacity, count)
}

/// The prebuilt `core` of hosted targets is compiled with unwinding and
/// references this personality routine; this crate is `panic = "abort"` and
/// never unwinds, so it is never called (bare-metal builds rebuild `core`
/// with `-Zbuild-std` and do not need it).
#[cfg(all(feature = "panic-handler", not(test), not(target_os = "none")))]
#[no_mangle]
pub extern "C" fn rust_eh_personality() {}

#[cfg(test)]
mod tests;

#[cfg(test)]
mod tests_options;
