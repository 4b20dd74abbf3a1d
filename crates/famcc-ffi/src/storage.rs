//! Caller-provided storage: the tagged slot a controller lives in, and the
//! checked access every C function goes through.

use core::mem::{align_of, size_of};
use core::ptr;

use crate::convert::{diag_to_c, discretized_to_c, report, status_of, to_config, to_config_discretized};
use crate::reports::*;
use crate::types::*;
use famcc_core::{ConfigError, Controller, Real};

/// What the storage holds: a tag (which controller type, initialised or not)
/// and the controller.
#[repr(C)]
struct Slot<T, const N: usize> {
    magic: u64,
    ctrl: Controller<T, N>,
}

pub(crate) const fn magic(order: u64, bits: u64) -> u64 {
    // "FAMCC" + order + float width.
    0x4641_4d43_4300_0000 | (order << 8) | bits
}

/// Whether storage `S` holds a `Controller<T, N>` and its tag (checked at
/// compile time for every storage type, on every target: `api.rs`).
pub(crate) const fn fits<S, T, const N: usize>() -> bool {
    size_of::<Slot<T, N>>() <= size_of::<S>() && align_of::<Slot<T, N>>() <= align_of::<S>()
}

/// Checks that `storage` is non-NULL, aligned and holds a controller tagged
/// `tag`; returns it as a `Slot` pointer.
unsafe fn checked<S, T, const N: usize>(
    storage: *const S,
    tag: u64,
) -> Result<*const Slot<T, N>, FamccStatus> {
    if storage.is_null() {
        return Err(FamccStatus::NullPointer);
    }
    if (storage as usize) % align_of::<S>() != 0 {
        return Err(FamccStatus::Misaligned);
    }
    let s = storage.cast::<Slot<T, N>>();
    // Another order or float type reads as not initialised (its tag differs).
    if ptr::read(ptr::addr_of!((*s).magic)) != tag {
        return Err(FamccStatus::NotInitialized);
    }
    Ok(s)
}

/// The controller in `storage`, for mutation.
unsafe fn slot_mut<'a, S, T, const N: usize>(
    storage: *mut S,
    tag: u64,
) -> Result<&'a mut Slot<T, N>, FamccStatus> {
    checked::<S, T, N>(storage, tag).map(|s| &mut *s.cast_mut())
}

/// The controller in `storage`, read only.
unsafe fn slot_ref<'a, S, T, const N: usize>(
    storage: *const S,
    tag: u64,
) -> Result<&'a Slot<T, N>, FamccStatus> {
    checked::<S, T, N>(storage, tag).map(|s| &*s)
}

/// Initialises `storage` (of `size` bytes when given, else a whole `S`).
pub(crate) unsafe fn init<S, T: Real, const N: usize>(
    storage: *mut S,
    size: Option<usize>,
    config: *const FamccConfig<T>,
    discretized: Option<*const FamccDiscretized<T>>,
    error: *mut FamccError,
    tag: u64,
) -> FamccStatus {
    if storage.is_null() || config.is_null() || discretized.is_some_and(|d| d.is_null()) {
        return FamccStatus::NullPointer;
    }
    if size.is_some_and(|n| n < size_of::<S>()) {
        return FamccStatus::StorageTooSmall;
    }
    if (storage as usize) % align_of::<S>() != 0 {
        return FamccStatus::Misaligned;
    }
    let s = storage.cast::<Slot<T, N>>();
    // Until a controller is in place the storage reads as uninitialised.
    ptr::write(ptr::addr_of_mut!((*s).magic), 0);
    let c = ptr::read_unaligned(config);
    let built = match discretized {
        Some(d) => to_config_discretized::<T, N>(&c, &ptr::read_unaligned(d)),
        None => to_config::<T, N>(&c),
    };
    match built.map(Controller::new) {
        Ok(ctrl) => {
            ptr::write(s, Slot { magic: tag, ctrl });
            FamccStatus::Ok
        }
        Err(e) => {
            report(error, &e);
            FamccStatus::InvalidConfig
        }
    }
}

/// The differentiator's recursion of a validated configuration (for
/// `*_init_discretized` on a target).
pub(crate) unsafe fn discretize<T: Real, const N: usize>(
    config: *const FamccConfig<T>,
    out: *mut FamccDiscretized<T>,
    error: *mut FamccError,
) -> FamccStatus {
    if config.is_null() || out.is_null() {
        return FamccStatus::NullPointer;
    }
    let result = to_config::<T, N>(&ptr::read_unaligned(config)).and_then(|cfg| {
        cfg.discretized().ok_or(ConfigError::new(
            "differentiator.enabled",
            "must be nonzero: without a differentiator there is no recursion to precompute",
        ))
    });
    match result {
        Ok(d) => {
            ptr::write_unaligned(out, discretized_to_c(&d));
            FamccStatus::Ok
        }
        Err(e) => {
            report(error, &e);
            FamccStatus::InvalidConfig
        }
    }
}

pub(crate) unsafe fn step<S, T: Real, const N: usize>(
    storage: *mut S,
    tag: u64,
    e: T,
    applied: Option<T>,
    v: *mut T,
) -> FamccStatus {
    if v.is_null() {
        return FamccStatus::NullPointer;
    }
    match slot_mut::<S, T, N>(storage, tag) {
        Ok(s) => match s.ctrl.step_applied(e, applied) {
            Ok(out) => {
                ptr::write_unaligned(v, out);
                FamccStatus::Ok
            }
            Err(err) => status_of(err),
        },
        Err(st) => st,
    }
}

pub(crate) unsafe fn reset<S, T: Real, const N: usize>(storage: *mut S, tag: u64) -> FamccStatus {
    match slot_mut::<S, T, N>(storage, tag) {
        Ok(s) => {
            s.ctrl.reset();
            FamccStatus::Ok
        }
        Err(st) => st,
    }
}
/// The configuration of the controller in `storage` (checked as every call).
pub(crate) unsafe fn slot_config<'a, S, T: Real, const N: usize>(
    storage: *const S,
    tag: u64,
) -> Result<&'a famcc_core::Config<T, N>, FamccStatus> {
    slot_ref::<S, T, N>(storage, tag).map(|s| s.ctrl.config())
}

pub(crate) unsafe fn diagnostics<S, T: Real, const N: usize>(
    storage: *const S,
    tag: u64,
    out: *mut FamccDiagnostics<T>,
) -> FamccStatus {
    if out.is_null() {
        return FamccStatus::NullPointer;
    }
    match slot_ref::<S, T, N>(storage, tag) {
        Ok(s) => {
            ptr::write_unaligned(out, diag_to_c(&s.ctrl.diagnostics(), s.ctrl.lumped()));
            FamccStatus::Ok
        }
        Err(st) => st,
    }
}
