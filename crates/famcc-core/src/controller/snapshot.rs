//! The controller's state as plain values, and its flat layout: the one
//! definition of the vector every binding exchanges (Python `state()` /
//! `set_state()`, pickling).
//!
//! ```
//! use famcc_core::{Snapshot, SNAPSHOT_FIELDS};
//! assert_eq!(SNAPSHOT_FIELDS[0], "started");
//! assert_eq!(Snapshot::<f64, 3>::LEN, SNAPSHOT_FIELDS.len() + 3);
//! let s = Snapshot::<f32, 2> { started: true, t_base: 0.0, k: 5, zhat: [0.5, -1.0],
//!                              rho0_x: 0.2, rho0_y: 0.0, clamp_count: 0, last_v: 1.5 };
//! let mut flat = [0.0; Snapshot::<f32, 2>::LEN];
//! s.to_array(&mut flat).unwrap();
//! assert_eq!(flat, [1.0, 0.0, 5.0, 0.2_f32 as f64, 0.0, 0.0, 1.5, 0.5, -1.0]);
//! assert_eq!(Snapshot::<f32, 2>::from_array(&flat), Ok(s));
//! ```

use crate::{ConfigError, Real};

/// The names of the leading entries of the flat layout, in order; the
/// estimate `z_hat[0..N]` ([`Snapshot::ESTIMATE`]) follows them.
pub const SNAPSHOT_FIELDS: [&str; 7] = [
    "started",
    "t_base",
    "k",
    "rho0_x",
    "rho0_y",
    "clamp_count",
    "last_v",
];

/// Everything a controller needs to continue bit-identically, as plain
/// values (for checkpoints, pickling and hand-over between processes).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Snapshot<T, const N: usize> {
    /// False before the first step.
    pub started: bool,
    /// Time base of the sample clock, seconds.
    pub t_base: T,
    /// Samples taken since `t_base`.
    pub k: u64,
    /// The estimate the next step uses.
    pub zhat: [T; N],
    /// Latched initial width of the lateral envelope.
    pub rho0_x: T,
    /// Latched initial width of the vertical envelope.
    pub rho0_y: T,
    /// Clamp events so far.
    pub clamp_count: u64,
    /// The last output (for the saturation gap).
    pub last_v: T,
}

const _: () = assert!(SNAPSHOT_FIELDS.len() == 7, "update split() and length_error()");

/// The largest integer every `f64` below it represents exactly (`2^53`).
const EXACT_INTEGERS: f64 = 9_007_199_254_740_992.0;

fn count(x: f64, name: &'static str) -> Result<u64, ConfigError> {
    if x.is_finite() && x >= 0.0 && num_traits::Float::fract(x) == 0.0 && x <= EXACT_INTEGERS {
        Ok(x as u64)
    } else {
        Err(ConfigError::new(name, "must be a non-negative integer"))
    }
}

impl<T: Real, const N: usize> Snapshot<T, N> {
    /// [`SNAPSHOT_FIELDS`].
    pub const FIELDS: [&'static str; 7] = SNAPSHOT_FIELDS;
    /// The name of the trailing estimate entries (`z_hat[0]`, `z_hat[1]`, ...).
    pub const ESTIMATE: &'static str = "z_hat";
    /// Length of the flat layout: the fields, then the estimate.
    pub const LEN: usize = SNAPSHOT_FIELDS.len() + N;

    /// Writes the flat layout `[started, t_base, k, rho0_x, rho0_y,
    /// clamp_count, last_v, z_hat...]` into `out` (exactly [`Self::LEN`]
    /// entries; `started` as 1 or 0, the counts as exact integers).
    pub fn to_array(&self, out: &mut [f64]) -> Result<(), ConfigError> {
        if out.len() != Self::LEN {
            return Err(length_error());
        }
        let f = |x: T| x.to_f64_lossless();
        let head = [
            if self.started { 1.0 } else { 0.0 },
            f(self.t_base),
            self.k as f64,
            f(self.rho0_x),
            f(self.rho0_y),
            self.clamp_count as f64,
            f(self.last_v),
        ];
        let estimate = self.zhat.iter().map(|z| f(*z));
        out.iter_mut()
            .zip(head.into_iter().chain(estimate))
            .for_each(|(o, x)| *o = x);
        Ok(())
    }

    /// Reads the flat layout of [`Snapshot::to_array`]. Rejects a wrong
    /// length and counts that are not exact non-negative integers; the
    /// values themselves are checked by [`crate::Controller::restore`].
    pub fn from_array(v: &[f64]) -> Result<Self, ConfigError> {
        let ([started, t_base, k, rho0_x, rho0_y, clamp_count, last_v], estimate) = split::<N>(v)?;
        let mut zhat = [T::zero(); N];
        zhat.iter_mut()
            .zip(estimate.iter())
            .for_each(|(z, x)| *z = T::from_f64(*x));
        Ok(Self {
            started: *started != 0.0,
            t_base: T::from_f64(*t_base),
            k: count(*k, "state.k")?,
            zhat,
            rho0_x: T::from_f64(*rho0_x),
            rho0_y: T::from_f64(*rho0_y),
            clamp_count: count(*clamp_count, "state.clamp_count")?,
            last_v: T::from_f64(*last_v),
        })
    }

    /// Checks the values: finite, a time `>= 0`, envelope widths finite and
    /// at least the final ones `eps`.
    pub(crate) fn check(&self, eps: (T, T)) -> Result<(), ConfigError> {
        let finite =
            self.t_base.is_finite() && self.last_v.is_finite() && self.zhat.iter().all(|v| v.is_finite());
        if !finite || self.t_base < T::zero() {
            return Err(ConfigError::new(
                "state",
                "must hold finite values and a time >= 0",
            ));
        }
        let (ex, ey) = eps;
        let widths = self.rho0_x >= ex && self.rho0_y >= ey;
        if !(widths && self.rho0_x.is_finite() && self.rho0_y.is_finite()) {
            return Err(ConfigError::new(
                "state",
                "envelope widths must be finite and >= eps",
            ));
        }
        Ok(())
    }
}

fn length_error() -> ConfigError {
    ConfigError::new(
        "state",
        "must be a float vector of length 7 + order (the fields, then z_hat)",
    )
}

/// The fields and the estimate of a flat vector of the right length.
#[allow(clippy::type_complexity)]
fn split<const N: usize>(v: &[f64]) -> Result<(&[f64; 7], &[f64]), ConfigError> {
    match v.split_first_chunk::<7>() {
        Some((head, estimate)) if estimate.len() == N => Ok((head, estimate)),
        _ => Err(length_error()),
    }
}
