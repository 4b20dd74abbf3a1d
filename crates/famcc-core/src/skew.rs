//! Skewed manifolds `h_m` built on a feedback law `h_p` (paper Step B2).
//!
//! - SSMD, eq. (14) (SSMD): `h_m(s) = h_p(s) + T1(s) eps_s`.
//! - NSMD, eq. (15) (NSMD): `h_m(s) = T2(s) (h_p(s) + T1(s) eps_s) - (1 - T2(s)) k_p s`,
//!
//! with `T1(s) = 1 - 2 S((s + eps_z)/(2 eps_z))` (+1 below `-eps_z`, -1 above
//! `eps_z`), `T2(s) = U(s/eps_z)` (0 at 0, 1 outside `±eps_z`) and
//! `k_p = k_pp (eps_s - h_p(eps_z))/eps_z`. Outside `±eps_z` both equal
//! `h_p ± eps_s`; near 0 the NSMD is the line `-k_p s`, so it removes the
//! infinite slope of power laws below 1 (and every derivative of `T2` vanishes
//! at 0, docs/design.md §4.2).
//!
//! ```
//! use famcc_core::{Feedback, Skew, SkewedLaw};
//! let h = SkewedLaw::new(Feedback::Linear { k: 1.0_f64 }, Some(Skew::smooth(0.2, 0.1))).unwrap();
//! assert!((h.eval(-1.0) - 1.2).abs() < 1e-15);
//! assert_eq!(h.eval(0.0), 0.0);
//! ```

use crate::error::{positive, ConfigError};
use crate::transition::Transition;
use crate::{Feedback, Jet, Real};

/// Which skew.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SkewKind<T> {
    /// Smooth skewed manifold design (SSMD).
    Smooth,
    /// Nonsingular skewed manifold design (NSMD) with slope factor `k_pp > 0`.
    Nonsingular {
        /// Adjusts the slope `-k_p` of `h_m` at 0.
        k_pp: T,
    },
}

/// A skew: offsets `eps_s` (rate units) and `eps_z` (signal units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Skew<T> {
    /// Vertical offset `eps_s` of the skewed law outside `±eps_z`.
    pub eps_s: T,
    /// Half-width `eps_z` of the transition zone around 0.
    pub eps_z: T,
    /// SSMD or NSMD.
    pub kind: SkewKind<T>,
    /// The double-ended transition used for `T1` and `T2`.
    pub transition: Transition,
}

impl<T: Real> Skew<T> {
    /// SSMD with the paper's transition.
    pub fn smooth(eps_s: T, eps_z: T) -> Self {
        Self {
            eps_s,
            eps_z,
            kind: SkewKind::Smooth,
            transition: Transition::Exponential,
        }
    }

    /// NSMD with the paper's transition.
    pub fn nonsingular(eps_s: T, eps_z: T, k_pp: T) -> Self {
        Self {
            eps_s,
            eps_z,
            kind: SkewKind::Nonsingular { k_pp },
            transition: Transition::Exponential,
        }
    }

    /// Checks `eps_s > 0`, `eps_z > 0` and (NSMD) `k_pp > 0`, all finite.
    pub fn validate(&self) -> Result<(), ConfigError> {
        positive(self.eps_s, "eps_s")?;
        positive(self.eps_z, "eps_z")?;
        if let SkewKind::Nonsingular { k_pp } = self.kind {
            positive(k_pp, "k_pp")?;
        }
        Ok(())
    }
}

/// A negative feedback function `h_mi` of the manifold: a law with an
/// optional skew, and its constants precomputed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SkewedLaw<T> {
    feedback: Feedback<T>,
    skew: Option<Skew<T>>,
    /// `k_p` of NSMD (0 otherwise).
    k_p: T,
}

impl<T: Real> SkewedLaw<T> {
    /// Validates and prepares `h_m` from a law and an optional skew.
    pub fn new(feedback: Feedback<T>, skew: Option<Skew<T>>) -> Result<Self, ConfigError> {
        feedback.validate()?;
        let mut k_p = T::zero();
        if let Some(sk) = skew {
            crate::compiled::skew(&sk.kind)?;
            crate::compiled::transition(sk.transition)?;
            sk.validate()?;
            if let SkewKind::Nonsingular { k_pp } = sk.kind {
                k_p = k_pp * (sk.eps_s - feedback.eval(sk.eps_z)) / sk.eps_z;
            }
        }
        Ok(Self { feedback, skew, k_p })
    }

    /// The feedback law `h_p`.
    pub fn feedback(&self) -> &Feedback<T> {
        &self.feedback
    }

    /// The skew, if any.
    pub fn skew(&self) -> Option<&Skew<T>> {
        self.skew.as_ref()
    }

    /// The NSMD slope `k_p` (0 for other designs).
    pub fn k_p(&self) -> T {
        self.k_p
    }

    /// True when `h_m` has unbounded derivatives at 0 (an unskewed or SSMD
    /// power law below 1): the manifold cannot use its time derivatives.
    pub fn is_singular_at_zero(&self) -> bool {
        let nonsingular = matches!(
            self.skew,
            Some(Skew {
                kind: SkewKind::Nonsingular { .. },
                ..
            })
        );
        !nonsingular && self.feedback.is_singular_at_zero()
    }

    /// `h_m(s)`.
    #[inline]
    pub fn eval(&self, s: T) -> T {
        #[cfg(feature = "skew")]
        if let Some(sk) = self.skew {
            return self.eval_skewed(sk, s);
        }
        self.feedback.eval(s)
    }

    /// [`SkewedLaw::eval`] with the skew `sk`: out of line, with its
    /// transition inlined (measured: cheaper than the call inside, and the
    /// unskewed law does not carry the larger body).
    #[cfg(feature = "skew")]
    #[inline(never)]
    fn eval_skewed(&self, sk: Skew<T>, s: T) -> T {
        let two = T::from_f64(2.0);
        let t1 = T::one()
            - two
                * sk.transition
                    .double_ended_inline((s + sk.eps_z) / (two * sk.eps_z));
        match sk.kind {
            SkewKind::Smooth => self.feedback.eval(s) + t1 * sk.eps_s,
            SkewKind::Nonsingular { .. } => {
                let t2 = sk.transition.interval(s / sk.eps_z);
                let lin = -(T::one() - t2) * self.k_p * s;
                if t2 == T::zero() {
                    lin
                } else {
                    t2 * (self.feedback.eval(s) + t1 * sk.eps_s) + lin
                }
            }
        }
    }

    /// `h_m(s(t))` with its time derivatives.
    #[inline]
    pub fn eval_jet<const K: usize>(&self, s: Jet<T, K>) -> Jet<T, K> {
        // Compiled out (src/compiled.rs): no law holds a skew.
        let (true, Some(sk)) = (cfg!(feature = "skew"), self.skew) else {
            return self.feedback.eval_jet(s);
        };
        let two = T::from_f64(2.0);
        let t1 = -sk.transition.double_ended_jet((s + sk.eps_z) / (two * sk.eps_z)) * two + T::one();
        match sk.kind {
            SkewKind::Smooth => self.feedback.eval_jet(s) + t1 * sk.eps_s,
            SkewKind::Nonsingular { .. } => {
                let t2 = sk.transition.interval_jet(s / sk.eps_z);
                if t2 == Jet::constant(T::one()) {
                    // Outside +-eps_z: exactly h_p + T1 eps_s. Skipping the
                    // products avoids 0 * inf where h_p overflows (|s| ~ 1e200).
                    return self.feedback.eval_jet(s) + t1 * sk.eps_s;
                }
                let lin = (-t2 + T::one()) * s * (-self.k_p);
                if t2.is_zero() {
                    // Every derivative of T2 vanishes: skip the singular branch
                    // (it would give 0 * inf).
                    lin
                } else {
                    t2 * (self.feedback.eval_jet(s) + t1 * sk.eps_s) + lin
                }
            }
        }
    }
}
