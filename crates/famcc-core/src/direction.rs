//! The control direction (beyond the paper, docs/design.md §3.8): the sign of
//! the input gain `G` of `y^(n) = F + G u`.
//!
//! The paper assumes `G > 0` (Assumption 1): a larger input raises the
//! output's `n`-th derivative, and the law `v = -k_u Gamma(xi)` pushes `e`
//! toward 0. A plant with `G < 0` (a heater that cools, a magnetic
//! levitation whose coil current lowers the gap, an inverted actuator)
//! needs the opposite input. With [`Direction::Negative`] the law is
//!
//! ```text
//! v = +k_u Gamma(xi)        (sign(G) = -1)
//! ```
//!
//! which on the plant is the paper's law on `y^(n) = F + |G| (-u)`: every
//! guarantee carries over with `|G|`. The output limits, the rate limit, the
//! initial output and the applied input stay in the actuator's own units;
//! the integral separation and the bumpless start follow the sign.
//!
//! ```
//! use famcc_core::Direction;
//! assert_eq!(Direction::default(), Direction::Positive);
//! assert_eq!(Direction::Negative.apply(2.0_f64), -2.0);
//! assert_eq!(Direction::of(-1.5_f64), Some(Direction::Negative));
//! assert_eq!(Direction::of(0.0_f64), None);
//! ```

use crate::Real;

/// The sign of the plant's input gain `G` (the paper's `G > 0` is
/// [`Direction::Positive`], the default).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Direction {
    /// `G > 0`: a larger input raises the output (the paper's assumption).
    #[default]
    Positive,
    /// `G < 0`: a larger input lowers the output.
    Negative,
}

impl Direction {
    /// `x` with this direction's sign: `x` or `-x` (exact).
    #[inline(always)]
    pub fn apply<T: Real>(self, x: T) -> T {
        match self {
            Direction::Positive => x,
            Direction::Negative => -x,
        }
    }

    /// The direction of a gain `g`: `None` when `g` is zero or NaN.
    pub fn of<T: Real>(g: T) -> Option<Direction> {
        if g > T::zero() {
            Some(Direction::Positive)
        } else if g < T::zero() {
            Some(Direction::Negative)
        } else {
            None
        }
    }
}
