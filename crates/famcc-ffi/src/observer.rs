//! The observer through the C ABI (famcc-core's feature `observer`, beyond
//! the paper; docs/observer.md): the conversion of a [`FamccObserver`] to
//! famcc-core's `ExtendedHighGain`, and the C functions that fill the
//! default coefficients.

use core::ptr;

use crate::tables::{from_c, DISCRETIZATIONS};
use crate::types::*;
use famcc_core::{ConfigError, ExtendedHighGain, Real};

/// famcc-core's observer of order `N` described by `o` (`None` when it is
/// off): `a[0..N]` are `a_1..a_N`, `a[N]` is `a_(N+1)`.
pub(crate) fn to_core<T: Real, const N: usize>(
    o: &FamccObserver<T>,
) -> Result<Option<ExtendedHighGain<T, N>>, ConfigError> {
    if o.enabled == 0 {
        return Ok(None);
    }
    let mut a = [T::zero(); N];
    a.iter_mut().zip(o.a.iter()).for_each(|(d, s)| *d = *s);
    let a_ext = o.a.get(N).copied().unwrap_or_else(T::zero);
    let disc = from_c(
        &DISCRETIZATIONS,
        o.discretization,
        "observer.discretization",
        "must be FAMCC_DISCRETIZATION_EXACT or FAMCC_DISCRETIZATION_FOH",
    )?;
    Ok(Some(
        ExtendedHighGain::new(o.mu, a, a_ext, o.b0).with_discretization(disc),
    ))
}

/// The C observer of famcc-core's `o` (the coefficients past `a_(N+1)`
/// zero, no cancellation limit).
pub(crate) fn to_c<T: Real, const N: usize>(o: &ExtendedHighGain<T, N>) -> FamccObserver<T> {
    let mut a = [T::zero(); FAMCC_MAX_OBSERVER_COEFFICIENTS];
    a.iter_mut().zip(o.a.iter()).for_each(|(d, s)| *d = *s);
    if let Some(slot) = a.get_mut(N) {
        *slot = o.a_ext;
    }
    FamccObserver {
        enabled: 1,
        mu: o.mu,
        a,
        b0: o.b0,
        discretization: crate::tables::to_c(&DISCRETIZATIONS, o.discretization),
        has_cancellation_limit: 0,
        cancellation_limit: T::zero(),
    }
}

/// The binomial observer of `order` (famcc-core's
/// `ExtendedHighGain::binomial`), or `None` for an order out of range.
fn binomial<T: Real>(order: u32, mu: T, b0: T) -> Option<FamccObserver<T>> {
    fn of<T: Real, const N: usize>(mu: T, b0: T) -> FamccObserver<T> {
        to_c(&ExtendedHighGain::<T, N>::binomial(mu, b0))
    }
    Some(match order {
        1 => of::<T, 1>(mu, b0),
        2 => of::<T, 2>(mu, b0),
        3 => of::<T, 3>(mu, b0),
        4 => of::<T, 4>(mu, b0),
        5 => of::<T, 5>(mu, b0),
        6 => of::<T, 6>(mu, b0),
        _ => return None,
    })
}

unsafe fn write_binomial<T: Real>(order: u32, mu: T, b0: T, out: *mut FamccObserver<T>) -> FamccStatus {
    if out.is_null() {
        return FamccStatus::NullPointer;
    }
    match binomial(order, mu, b0) {
        Some(o) => {
            ptr::write_unaligned(out, o);
            FamccStatus::Ok
        }
        None => FamccStatus::InvalidConfig,
    }
}

/// Writes the observer of a controller of `order` (1 to 6; the plant's
/// order) with time constant `mu` and nominal input gain `b0` to `out`,
/// enabled, with famcc-core's default coefficients: every pole of the
/// estimation error at `-2 / mu`, `(s + 2)^(order+1)`; the error held
/// (`FAMCC_DISCRETIZATION_EXACT`); the cancellation bounded by half the
/// output range. `mu` and `b0` are checked by `*_init`.
/// `FAMCC_STATUS_INVALID_CONFIG` for an order out of range.
#[no_mangle]
pub unsafe extern "C" fn famcc_observer_f32_binomial(
    order: u32,
    mu: f32,
    b0: f32,
    out: *mut FamccObserverF32,
) -> FamccStatus {
    write_binomial(order, mu, b0, out)
}

/// `double` version of `famcc_observer_f32_binomial`.
#[no_mangle]
pub unsafe extern "C" fn famcc_observer_f64_binomial(
    order: u32,
    mu: f64,
    b0: f64,
    out: *mut FamccObserverF64,
) -> FamccStatus {
    write_binomial(order, mu, b0, out)
}
