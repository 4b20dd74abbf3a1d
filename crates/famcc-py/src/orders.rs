//! Run-time order to const-generic order: the one list of the orders this
//! binding compiles (famcc-core's `config::MAX_ORDER`), and slices to arrays
//! of that size.

use famcc_core::Real;

/// Evaluates `$body` with the constant `$n` equal to the run-time order
/// `$order` when it is one of `1..=MAX_ORDER`, otherwise `$otherwise`.
macro_rules! with_order {
    ($order:expr, $n:ident => $body:expr, _ => $otherwise:expr) => {
        with_order!(@arms $order, $n, $body, $otherwise, 1 2 3 4 5 6 7 8)
    };
    (@arms $order:expr, $n:ident, $body:expr, $otherwise:expr, $($k:literal)*) => {
        match $order {
            $($k => {
                const $n: usize = $k;
                $body
            })*
            _ => $otherwise,
        }
    };
}
pub(crate) use with_order;

// The arms above are the orders 1..=MAX_ORDER.
const _: () = assert!(famcc_core::config::MAX_ORDER == 8);

/// `v` as an array of `N` values of `T` (`None` for another length).
pub fn to_array<T: Real, const N: usize>(v: &[f64]) -> Option<[T; N]> {
    if v.len() != N {
        return None;
    }
    let mut out = [T::zero(); N];
    out.iter_mut().zip(v).for_each(|(o, x)| *o = T::from_f64(*x));
    Some(out)
}
