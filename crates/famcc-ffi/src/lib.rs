//! C ABI for famcc-core: the FAMCC controller of orders 1 to 6 in `float`
//! (f32) and `double` (f64), for C firmware and other languages.
//!
//! Design:
//! - **No allocation.** The caller provides the storage: `FamccO1F32` to
//!   `FamccO6F64` (order 1 to 6, `float` or `double`) are opaque structs of
//!   fixed size and 8-byte alignment declared in the header (static, stack or
//!   pool objects); `famcc_o2_f32_size()`/`_align()` report the same numbers
//!   at run time. `*_init` writes a controller into the storage; every other call
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
//! cbindgen writes to `include/famcc.h`; see `cbindgen.toml`), [`reports`]
//! (what the functions report back: diagnostics, findings, errors), `convert`
//! (C configuration and diagnostics to and from famcc-core's, with its
//! defaults), `storage` (the tagged slots and checked access), `api` (the
//! storage types and C functions of every order and float type, generated
//! from one template by `src/api_gen.rs`: cbindgen does not expand macros),
//! and here the functions common to all.
#![no_std]
#![allow(clippy::missing_safety_doc)]

#[rustfmt::skip]
mod api;
#[cfg(test)]
mod api_gen;
mod convert;
pub mod enums;
mod lint;
mod observer;
pub mod reports;
mod storage;
mod tables;
pub mod types;

use core::ffi::c_char;
use core::ptr;

pub use api::*;
pub use observer::{famcc_observer_f32_binomial, famcc_observer_f64_binomial};
pub use reports::*;
pub use types::*;
// ---------------------------------------------------------------------------
// The C functions of every controller type are generated in `api.rs`
// (src/api_gen.rs: cbindgen does not expand macros); here the common ones
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

#[cfg(test)]
mod tests_discretized;
#[cfg(test)]
mod tests_foh;
#[cfg(test)]
mod tests_observer;
#[cfg(test)]
mod tests_orders;

#[cfg(test)]
mod tests_variant_build;
#[cfg(test)]
mod tests_variant_cases;

#[cfg(test)]
mod tests_variants;
