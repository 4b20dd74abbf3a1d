//! The prescribed performance function (paper eq. (4) (rho)).
//!
//! `rho(t) = (rho0 - eps) T((T_rho - t)/T_rho) + eps`: it starts at `rho0`,
//! shrinks smoothly, and equals `eps` exactly from `t = T_rho` on. Units are
//! those of the bounded quantity (`rho0`, `eps`), and seconds (`t`, `T_rho`).
//!
//! ```
//! use famcc_core::envelope::rho;
//! assert_eq!(rho(2.0_f64, 0.1, 1.0, 0.0), 2.0);
//! assert_eq!(rho(2.0_f64, 0.1, 1.0, 1.5), 0.1);
//! assert!((rho(2.0_f64, 0.1, 1.0, 0.5) - (0.1 + 1.9 * (-1.0_f64).exp())).abs() < 1e-15);
//! ```

use crate::error::{positive, ConfigError};
use crate::{transition, Real};

/// `rho(rho0, eps, T_rho)` at time `t` (eq. (4) (rho)).
#[inline]
pub fn rho<T: Real>(rho0: T, eps: T, settle_time: T, t: T) -> T {
    if t >= settle_time {
        return eps;
    }
    (rho0 - eps) * transition::single_ended((settle_time - t) / settle_time) + eps
}

/// A latched envelope: `rho(rho0, eps, T_s)` with `rho0` fixed at the first
/// sample (see [`Latch`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Envelope<T> {
    /// Initial width.
    pub rho0: T,
    /// Final width (the prescribed accuracy of the bounded quantity).
    pub eps: T,
    /// Settling time `T_s` in seconds.
    pub settle_time: T,
}

impl<T: Real> Envelope<T> {
    /// A checked envelope: `eps` finite and `> 0`, `rho0` finite and at
    /// least `eps`, `settle_time` finite and `> 0` (the controller's own
    /// envelopes follow from a validated configuration).
    ///
    /// ```
    /// use famcc_core::Envelope;
    /// assert!(Envelope::new(2.0_f64, 0.1, 1.0).is_ok());
    /// assert_eq!(Envelope::new(0.05_f64, 0.1, 1.0).unwrap_err().parameter, "rho0");
    /// ```
    pub fn new(rho0: T, eps: T, settle_time: T) -> Result<Self, ConfigError> {
        positive(eps, "eps")?;
        if !(rho0 >= eps && rho0.is_finite()) {
            return Err(ConfigError::new("rho0", "must be finite and >= eps"));
        }
        positive(settle_time, "settle_time")?;
        Ok(Self {
            rho0,
            eps,
            settle_time,
        })
    }

    /// The width at time `t` seconds.
    #[inline]
    pub fn at(&self, t: T) -> T {
        rho(self.rho0, self.eps, self.settle_time, t)
    }
}

/// How the initial width is latched from the first sample's offset `s0`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Latch {
    /// The paper (text after eq. (22) (yUyL)): `rho0 = k0 * max(|s0|, eps)`.
    #[default]
    Paper,
    /// The authors' code: `rho0 = max(k0 * |s0|, eps)`.
    Authors,
}

impl Latch {
    /// The initial width for offset `s0`, gain `k0 > 1` and final width `eps`.
    ///
    /// ```
    /// use famcc_core::envelope::Latch;
    /// assert_eq!(Latch::Paper.rho0(0.01_f64, 2.0, 0.1), 0.2);
    /// assert_eq!(Latch::Authors.rho0(0.01_f64, 2.0, 0.1), 0.1);
    /// ```
    /// A width that would overflow is the largest float instead (a state
    /// at the edge of the range latches the widest envelope, docs/design.md
    /// §3.7); NaN stays NaN.
    #[inline]
    pub fn rho0<T: Real>(self, s0: T, k0: T, eps: T) -> T {
        let w = match self {
            Latch::Paper => k0 * s0.abs().max(eps),
            Latch::Authors => (k0 * s0.abs()).max(eps),
        };
        if w > T::max_value() {
            T::max_value()
        } else {
            w
        }
    }
}
