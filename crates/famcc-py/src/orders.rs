//! Run-time order to const-generic order: the one list of the orders this
//! binding compiles (famcc-core's `config::MAX_ORDER`).

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
