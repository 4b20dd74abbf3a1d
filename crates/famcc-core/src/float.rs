//! The float trait every famcc-core item is generic over.
//!
//! [`Real`] is implemented for `f32` and `f64`. All transcendental functions
//! go through [`num_traits::Float`], which in `no_std` builds is backed by
//! `libm`, so the same code runs on a host and on a Cortex-M4F.

use core::fmt::Debug;

/// A real scalar: `f32` or `f64`.
///
/// ```
/// use famcc_core::Real;
/// assert_eq!(<f32 as Real>::from_f64(0.5) * 2.0, 1.0);
/// assert_eq!(3.0_f64.pow_nonneg(2.0), 9.0);
/// ```
pub trait Real:
    num_traits::Float + num_traits::FloatConst + Copy + Default + Debug + PartialOrd + 'static
{
    /// Converts an `f64` (a constant or a caller's value): exact for `f64`,
    /// rounded to nearest for `f32`.
    fn from_f64(x: f64) -> Self;
    /// Converts to `f64` (exact).
    fn to_f64_lossless(self) -> f64;
    /// Converts a count, rounded to nearest: the same value as
    /// `from_f64(n as f64)` for every `n < 2^53`, without going through
    /// `f64` (a soft-float conversion on an FPU without double precision).
    fn from_u64(n: u64) -> Self;
    /// Square root. Hook for targets with a hardware square root.
    #[inline(always)]
    fn root(self) -> Self {
        num_traits::Float::sqrt(self)
    }
    /// `self^p` for a non-negative base, with exact fast paths for the
    /// exponents the paper's laws use (`1/2`, `1`, `3/2`, `2`, `3`): a square
    /// root or products instead of a general `pow`.
    #[inline(always)]
    fn pow_nonneg(self, p: Self) -> Self {
        let half = Self::from_f64(0.5);
        let two = Self::from_f64(2.0);
        if p == half {
            self.root()
        } else if p == two {
            self * self
        } else if p == Self::one() {
            self
        } else if p == Self::from_f64(1.5) {
            self * self.root()
        } else if p == Self::from_f64(3.0) {
            self * self * self
        } else {
            num_traits::Float::powf(self, p)
        }
    }
    /// `ln` of the smallest positive normal number: `exp(x)` below this is
    /// subnormal or zero.
    fn ln_min_positive() -> Self;
    /// The estimate's range `2^(MAX_EXP / 2)` (`2^512` in `f64`, `2^64` in
    /// `f32`): the square root of the largest float, so that a product of
    /// two values in range stays finite (docs/design.md §3.7).
    fn estimate_range() -> Self;
    /// The largest scale parameter a configuration accepts, `2^(MAX_EXP /
    /// 4)` (`2^256` in `f64`, `2^32` in `f32`; its inverse is the smallest),
    /// docs/design.md §3.9.
    fn scale_limit() -> Self;

    /// `(sin(x), cos(x))` for `|x| <= pi/4` only (the sine transition's
    /// range): in `f64` the library's `sin_cos`; in `f32` Taylor polynomials
    /// of degree 9 and 10 (truncation below `2e-9`, within 2 ulp of the
    /// correctly rounded values), so that a target with no use for a general
    /// `sin` does not carry its argument reduction (~5 KB of flash).
    fn sin_cos_octant(self) -> (Self, Self);

    /// The sine of [`Real::sin_cos_octant`] alone (`|x| <= pi/4`).
    fn sin_octant(self) -> Self;
}

impl Real for f64 {
    #[inline(always)]
    fn from_f64(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn from_u64(n: u64) -> Self {
        n as f64
    }
    #[inline(always)]
    fn to_f64_lossless(self) -> f64 {
        self
    }
    #[inline(always)]
    fn ln_min_positive() -> Self {
        -708.396_418_532_264_1
    }
    #[inline(always)]
    fn estimate_range() -> Self {
        1.340_780_792_994_259_7e154
    }
    #[inline(always)]
    fn scale_limit() -> Self {
        1.157_920_892_373_162e77
    }
    #[inline]
    fn sin_cos_octant(self) -> (Self, Self) {
        num_traits::Float::sin_cos(self)
    }
    #[inline]
    fn sin_octant(self) -> Self {
        num_traits::Float::sin(self)
    }
}

impl Real for f32 {
    #[inline(always)]
    fn from_f64(x: f64) -> Self {
        x as f32
    }
    #[inline(always)]
    fn from_u64(n: u64) -> Self {
        // Both forms round the exact integer once while n < 2^53, so they give
        // the same value. Direct on Arm, where an FPU without double precision
        // would make the f64 step a soft-float call; through f64 elsewhere,
        // where that is the cheaper instruction sequence.
        #[cfg(target_arch = "arm")]
        {
            n as f32
        }
        #[cfg(not(target_arch = "arm"))]
        {
            (n as f64) as f32
        }
    }
    #[inline(always)]
    fn to_f64_lossless(self) -> f64 {
        f64::from(self)
    }
    #[inline(always)]
    fn ln_min_positive() -> Self {
        -87.336_55
    }
    #[inline(always)]
    fn estimate_range() -> Self {
        18_446_744_073_709_551_616.0
    }
    #[inline(always)]
    fn scale_limit() -> Self {
        4_294_967_296.0
    }
    // Out of line, as the library's `sinf` was: the sine transition's arm
    // stays a call.
    #[inline(never)]
    fn sin_cos_octant(self) -> (Self, Self) {
        // 1/3!, 1/5!, ... and 1/2!, 1/4!, ... with alternating signs.
        const S: [f32; 4] = [-1.0 / 6.0, 1.0 / 120.0, -1.0 / 5_040.0, 1.0 / 362_880.0];
        const C: [f32; 5] = [-0.5, 1.0 / 24.0, -1.0 / 720.0, 1.0 / 40_320.0, -1.0 / 3_628_800.0];
        let x2 = self * self;
        let horner = |c: &[f32]| c.iter().rev().fold(0.0, |acc, k| acc * x2 + k);
        (self + self * x2 * horner(&S), 1.0 + x2 * horner(&C))
    }
    #[inline]
    fn sin_octant(self) -> Self {
        self.sin_cos_octant().0
    }
}
