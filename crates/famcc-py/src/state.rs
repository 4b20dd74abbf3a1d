//! The state codec: a controller's state as the flat `f64` vector of
//! famcc-core's [`Snapshot`] layout, and back.

use famcc_core::{ConfigError, Controller, Real, Snapshot};

/// The flat state vector of a controller.
pub fn to_vec<T: Real, const N: usize>(c: &Controller<T, N>) -> Vec<f64> {
    let mut v = vec![0.0; Snapshot::<T, N>::LEN];
    match c.snapshot().to_array(&mut v) {
        Ok(()) => v,
        Err(_) => Vec::new(),
    }
}

/// Continues `c` from a flat state vector; on error nothing changes.
pub fn restore<T: Real, const N: usize>(c: &mut Controller<T, N>, v: &[f64]) -> Result<(), ConfigError> {
    c.restore(&Snapshot::from_array(v)?)
}
