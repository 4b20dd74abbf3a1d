//! Smooth transition functions (paper Definitions 1-3), named as the paper
//! names them.
//!
//! - [`single_ended`] is the single-ended `T(z)` of eq. (1) (trnsT): 0 for
//!   `z <= 0`, `exp((z-1)/z)` for `z > 0`, so `T(1) = 1`.
//! - [`Transition::double_ended`] is a double-ended `S(z)`: 0 for `z <= 0`, 1
//!   for `z >= 1`, nondecreasing. [`Transition::Exponential`] is the paper's
//!   C-infinity eq. (2) (trnsS); `Cubic` (C1), `Quintic` (C2) and `Sine` (C1)
//!   are cheaper alternatives (the authors' code offers the same four).
//! - [`Transition::interval`] is the interval transition `U(z) = S(|z|)` of
//!   eq. (3) (trnsU).
//!
//! All functions are dimensionless and return finite values for every finite
//! input: where `exp` would underflow (the function is below the smallest
//! normal float there) the flat value is returned exactly.
//!
//! ```
//! use famcc_core::transition::{self, Transition};
//! assert_eq!(transition::single_ended(1.0_f64), 1.0);
//! assert!((Transition::Exponential.double_ended(0.5_f64) - 0.5).abs() < 1e-15);
//! assert!((Transition::Cubic.double_ended(0.25_f64) - 0.15625).abs() < 1e-15);
//! ```

use crate::{Jet, Real};

/// Which double-ended smooth transition `S(z)` to use.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Transition {
    /// The paper's eq. (2) (trnsS): `1 / (exp((1-2z)/(z(1-z))) + 1)`, C-infinity.
    #[default]
    Exponential,
    /// `3z^2 - 2z^3`: continuous first derivative.
    Cubic,
    /// `10z^3 - 15z^4 + 6z^5`: continuous second derivative.
    Quintic,
    /// `(1 - cos(pi z)) / 2`, evaluated as `sin^2(pi z / 2)`: continuous first
    /// derivative.
    Sine,
}

/// The single-ended transition `T(z)` of eq. (1) (trnsT, Definition 1),
/// extended by the same formula for `z > 1` (it keeps increasing towards `e`).
///
/// ```
/// use famcc_core::transition::single_ended;
/// assert_eq!(single_ended(-3.0_f64), 0.0);
/// assert!((single_ended(0.5_f64) - (-1.0_f64).exp()).abs() < 1e-15);
/// ```
#[inline]
pub fn single_ended<T: Real>(z: T) -> T {
    if z <= T::zero() {
        return T::zero();
    }
    let w = (z - T::one()) / z;
    if w < T::ln_min_positive() {
        T::zero()
    } else {
        w.exp()
    }
}

/// [`single_ended`] on a jet: `T(z(t))` with its time derivatives.
#[inline]
pub fn single_ended_jet<T: Real, const K: usize>(z: Jet<T, K>) -> Jet<T, K> {
    let z0 = z.value();
    if z0 <= T::zero() {
        return Jet::constant(T::zero());
    }
    // Flat only far below the underflow threshold (see `double_ended_jet`): the
    // derivatives can be normal numbers where `T` itself is subnormal.
    if (z0 - T::one()) / z0 < T::from_f64(2.0) * T::ln_min_positive() {
        return Jet::constant(T::zero());
    }
    ((z - T::one()) / z).exp()
}

impl Transition {
    /// The double-ended transition `S(z)` (Definition 2, eq. (2) for
    /// [`Transition::Exponential`]).
    ///
    /// For `z > 1/2` it is evaluated as `1 - S(1 - z)` (exact symmetry of all
    /// four transitions; `1 - z` is exact there), which keeps `S <= 1` (the
    /// quintic's direct form exceeds 1 just below `z = 1`) and makes
    /// `S(z) + S(1 - z) = 1` hold to rounding.
    #[inline]
    pub fn double_ended<T: Real>(self, z: T) -> T {
        self.double_ended_inline(z)
    }

    /// [`Transition::double_ended`], always inlined: for the skew's hot
    /// call, where the call's overhead exceeds the transition's.
    #[cfg_attr(not(feature = "skew"), allow(dead_code))]
    #[inline(always)]
    pub(crate) fn double_ended_inline<T: Real>(self, z: T) -> T {
        if z <= T::zero() {
            return T::zero();
        }
        if z >= T::one() {
            return T::one();
        }
        if z > T::from_f64(0.5) {
            return T::one() - self.rising(T::one() - z);
        }
        self.rising(z)
    }

    /// `S(z)` for `0 < z <= 1/2`.
    #[inline]
    fn rising<T: Real>(self, z: T) -> T {
        let one = T::one();
        let two = T::from_f64(2.0);
        match self {
            Transition::Exponential => {
                // w >= 0: S = q / (1 + q) with q = exp(-w) <= 1.
                let w = (one - two * z) / (z * (one - z));
                if -w < T::ln_min_positive() {
                    return T::zero();
                }
                let q = (-w).exp();
                q / (one + q)
            }
            Transition::Cubic => z * z * (T::from_f64(3.0) - two * z),
            Transition::Quintic => {
                z * z * z * (z * (z * T::from_f64(6.0) - T::from_f64(15.0)) + T::from_f64(10.0))
            }
            #[cfg(feature = "sine")]
            Transition::Sine => {
                let s = (T::FRAC_PI_2() * z).sin_octant();
                s * s
            }
            // Compiled out (src/compiled.rs): no configuration holds it.
            #[cfg(not(feature = "sine"))]
            Transition::Sine => T::nan(),
        }
    }

    /// [`Transition::double_ended`] on a jet: `S(z(t))` with its time derivatives.
    ///
    /// For `z > 1/2` it uses the symmetry `S(z) = 1 - S(1 - z)` (exact for all
    /// four transitions), so the derivatives keep their relative accuracy as
    /// `z -> 1` (the polynomial forms would otherwise cancel catastrophically
    /// there). The exponential form returns the flat jet only where `S` is
    /// below `exp(2 ln(min_positive))` (about `1e-616` in `f64`), far enough
    /// down that the derivatives have underflowed too; above that the
    /// derivatives are computed even where `S` itself is subnormal.
    #[inline]
    pub fn double_ended_jet<T: Real, const K: usize>(self, z: Jet<T, K>) -> Jet<T, K> {
        let z0 = z.value();
        if z0 <= T::zero() {
            return Jet::constant(T::zero());
        }
        if z0 >= T::one() {
            return Jet::constant(T::one());
        }
        if z0 > T::from_f64(0.5) {
            // 1 - z0 is exact here (Sterbenz).
            return -self.rising_jet(-z + T::one()) + T::one();
        }
        self.rising_jet(z)
    }

    /// `S(z(t))` for `0 < z0 <= 1/2`.
    #[inline]
    fn rising_jet<T: Real, const K: usize>(self, z: Jet<T, K>) -> Jet<T, K> {
        let one = T::one();
        let two = T::from_f64(2.0);
        match self {
            Transition::Exponential => {
                let z0 = z.value();
                let w0 = (one - two * z0) / (z0 * (one - z0));
                if -w0 < two * T::ln_min_positive() {
                    return Jet::constant(T::zero());
                }
                let w = (-(z * two) + one) / (z * (-z + one));
                // S = 1/(1 + e^w) = logistic(-w) <= 1/2 here.
                (-w).logistic()
            }
            Transition::Cubic => z * z * (z * (-two) + T::from_f64(3.0)),
            Transition::Quintic => {
                z * z * z * (z * (z * T::from_f64(6.0) - T::from_f64(15.0)) + T::from_f64(10.0))
            }
            #[cfg(feature = "sine")]
            Transition::Sine => {
                let (s, _) = (z * T::FRAC_PI_2()).sin_cos_octant();
                s * s
            }
            #[cfg(not(feature = "sine"))]
            Transition::Sine => Jet::constant(T::nan()),
        }
    }

    /// The interval transition `U(z) = S(|z|)` (Definition 3, eq. (3)).
    ///
    /// ```
    /// use famcc_core::transition::Transition;
    /// let u = Transition::Exponential;
    /// assert_eq!(u.interval(0.0_f64), 0.0);
    /// assert_eq!(u.interval(-2.0_f64), 1.0);
    /// ```
    #[inline]
    pub fn interval<T: Real>(self, z: T) -> T {
        self.double_ended(z.abs())
    }

    /// [`Transition::interval`] on a jet.
    #[inline]
    pub fn interval_jet<T: Real, const K: usize>(self, z: Jet<T, K>) -> Jet<T, K> {
        self.double_ended_jet(z.abs())
    }

    /// The authors' parametrised form `trns(x, x1, x2)`: `S((x - x1)/(x2 - x1))`,
    /// a transition from 0 at `x1` to 1 at `x2` (`x1 > x2` reverses it).
    #[inline]
    pub fn between<T: Real>(self, x: T, x1: T, x2: T) -> T {
        self.double_ended((x - x1) / (x2 - x1))
    }

    /// The time derivative of [`Transition::between`] for moving end points:
    /// `d/dt S((x - x1)/(x2 - x1))` given `dx`, `dx1`, `dx2`.
    #[inline]
    pub fn between_rate<T: Real>(self, x: [T; 2], x1: [T; 2], x2: [T; 2]) -> T {
        let x = Jet::<T, 2>::from_derivatives(x);
        let x1 = Jet::<T, 2>::from_derivatives(x1);
        let x2 = Jet::<T, 2>::from_derivatives(x2);
        self.double_ended_jet((x - x1) / (x2 - x1)).derivative(1)
    }
}
