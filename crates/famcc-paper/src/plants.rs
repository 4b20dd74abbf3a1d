//! The paper's plants (docs/design.md §6.3) in strict-feedback form
//! (eq. (5), SFS):
//!
//! ```text
//! x_i' = g_i(x, t) x_{i+1} + f_i(x, t),  i < n;   x_n' = g_n(x, t) u + f_n(x, t);   y = x_1
//! ```
//!
//! Each plant is written once, as its `g_i` and `f_i` ([`Plant::terms`]),
//! generic over the scalar: plain `f32`/`f64` for the right-hand side, and
//! jets (famcc-core's truncated Taylor arithmetic) for the exact output
//! derivatives `y, ..., y^(n-1)` ([`output_derivatives`]) and the gain and
//! drift of `y^(n) = G_a u + F_a` (eq. (7), FAS; [`gain_and_drift`]). The
//! time enters only through `sin t`, `cos t` and `cos 2t` ([`Clock`]), so a
//! caller can supply them cheaply (the firmware rotates them by angle
//! addition instead of calling `sin` at every RK4 stage).
//!
//! ```
//! use famcc_paper::plants::{self, Clock, Plant, SecondOrder};
//! use famcc_paper::Variant;
//! let p = SecondOrder::new(Variant::Paper);
//! let x = p.x0();
//! let y = plants::output_derivatives(&p, 0.0_f64, &x);
//! assert_eq!(y[0], -1.0);
//! assert!((y[1] - 1.527_015_115_293_406_5).abs() < 1e-15);     // y' = g1 x2 + f1
//! let (g_a, _f_a) = plants::gain_and_drift(&p, 0.0, &x);
//! assert!((g_a - 2.112_398).abs() < 1e-6);
//! assert_eq!(p.rhs(&Clock::at(0.0), &x, 0.0)[0], y[1]);
//! ```

use crate::variant::Variant;
use core::ops::{Add, Mul, Neg, Sub};
use famcc_core::{Jet, Real};
use num_traits::Float;

/// A scalar the plants can be evaluated on: `f32`, `f64` or a jet of them.
pub trait Signal<T: Real>:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Neg<Output = Self>
    + Mul<T, Output = Self>
{
    /// The constant `v`.
    fn constant(v: T) -> Self;
    /// `sin` and `cos`.
    fn sin_cos(self) -> (Self, Self);
    /// `sin`.
    fn sin(self) -> Self {
        self.sin_cos().0
    }
    /// `cos`.
    fn cos(self) -> Self {
        self.sin_cos().1
    }
}

impl<T: Real> Signal<T> for T {
    #[inline(always)]
    fn constant(v: T) -> Self {
        v
    }
    #[inline(always)]
    fn sin_cos(self) -> (Self, Self) {
        (Float::sin(self), Float::cos(self))
    }
    #[inline(always)]
    fn sin(self) -> Self {
        Float::sin(self)
    }
    #[inline(always)]
    fn cos(self) -> Self {
        Float::cos(self)
    }
}

impl<T: Real, const K: usize> Signal<T> for Jet<T, K> {
    #[inline]
    fn constant(v: T) -> Self {
        Jet::constant(v)
    }
    #[inline]
    fn sin_cos(self) -> (Self, Self) {
        Jet::sin_cos(&self)
    }
}

/// The time functions the plants use at one instant: `sin t`, `cos t`,
/// `sin 2t`, `cos 2t`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Clock<S> {
    /// `sin t`.
    pub sin: S,
    /// `cos t`.
    pub cos: S,
    /// `sin 2t`.
    pub sin2: S,
    /// `cos 2t`.
    pub cos2: S,
}

impl<S: Copy> Clock<S> {
    /// The time functions of `t` (seconds, a value or a jet of the time).
    #[inline]
    pub fn at<T: Real>(t: S) -> Self
    where
        S: Signal<T>,
    {
        let (sin, cos) = t.sin_cos();
        let (sin2, cos2) = (t * T::from_f64(2.0)).sin_cos();
        Self { sin, cos, sin2, cos2 }
    }
}

impl<T: Real> Clock<T> {
    /// From `sin t` and `cos t` alone (double-angle formulas, no `sin` call).
    #[inline]
    pub fn from_sin_cos(sin: T, cos: T) -> Self {
        Self {
            sin,
            cos,
            sin2: T::from_f64(2.0) * sin * cos,
            cos2: (cos - sin) * (cos + sin),
        }
    }

    /// The time functions at `t + tau` from those at `t` and at `tau`
    /// (angle addition: a few roundings, no `sin` call).
    #[inline]
    pub fn shifted(&self, tau: &Clock<T>) -> Self {
        Self {
            sin: self.sin * tau.cos + self.cos * tau.sin,
            cos: self.cos * tau.cos - self.sin * tau.sin,
            sin2: self.sin2 * tau.cos2 + self.cos2 * tau.sin2,
            cos2: self.cos2 * tau.cos2 - self.sin2 * tau.sin2,
        }
    }
}

/// The drift `f_i` of one row of eq. (5), as up to three terms: the
/// right-hand side adds them in this order after `g_i x_{i+1}`, so that it
/// rounds as the equation is written (unused terms are zero).
pub type Drift<S> = [S; 3];

/// A strict-feedback plant of order `N` with output `y = x_1` (eq. (5)).
pub trait Plant<T: Real, const N: usize> {
    /// The initial state.
    fn x0(&self) -> [T; N];

    /// `(g_i, f_i)` of eq. (5) for every row, at the state `x` and the time
    /// functions `c`.
    fn terms<S: Signal<T>>(&self, c: &Clock<S>, x: &[S; N]) -> [(S, Drift<S>); N];

    /// The right-hand side `x_i' = g_i x_{i+1} + f_i` (`x_{n+1} = u`).
    #[inline]
    fn rhs<S: Signal<T>>(&self, c: &Clock<S>, x: &[S; N], u: S) -> [S; N] {
        let rows = self.terms(c, x);
        let mut out = x.map(|_| S::constant(T::zero()));
        for (i, (o, (g, f))) in out.iter_mut().zip(rows.iter()).enumerate() {
            let next = x.get(i + 1).copied().unwrap_or(u);
            *o = f.iter().fold(*g * next, |acc, term| acc + *term);
        }
        out
    }
}

/// The initial state of the second-order plant (both variants).
pub const SECOND_ORDER_X0: [f64; 2] = [-1.0, 0.5];

/// The plant of examples 1 and 2 (eq. (44), System_sim):
/// `x1' = (1 + 0.1 cos x1 + 0.1 sin t) x2 - x1 + sin t`,
/// `x2' = b (2 + 0.2 sin(x1 x2) + 0.1 cos t) u - (x1^2 - 1) x2 + a (sin t + cos 2t)`,
/// `a = 1` as printed ([`Variant::Paper`]), `a = 3` in the authors' code;
/// `x(0) = (-1, 0.5)`. The input-gain factor `b` (1 in the paper), the
/// amplitude `a` and `x(0)` can be dispersed (robustness campaigns); with the
/// defaults of [`SecondOrder::new`] the arithmetic is the paper's, bit for bit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SecondOrder {
    /// Which printed numbers.
    pub variant: Variant,
    /// Input-gain factor `b` (1 in the paper).
    pub gain: f64,
    /// Disturbance amplitude `a`.
    pub amp: f64,
    /// Initial state.
    pub x0: [f64; 2],
}

impl SecondOrder {
    /// The paper's plant in `variant`.
    pub const fn new(variant: Variant) -> Self {
        let amp = match variant {
            Variant::Paper => 1.0,
            Variant::Code => 3.0,
        };
        Self {
            variant,
            gain: 1.0,
            amp,
            x0: SECOND_ORDER_X0,
        }
    }
}

impl<T: Real> Plant<T, 2> for SecondOrder {
    fn x0(&self) -> [T; 2] {
        self.x0.map(T::from_f64)
    }

    #[inline]
    fn terms<S: Signal<T>>(&self, c: &Clock<S>, x: &[S; 2]) -> [(S, Drift<S>); 2] {
        let k = |v: f64| T::from_f64(v);
        let amp = k(self.amp);
        let [x1, x2] = *x;
        let (one, zero) = (S::constant(k(1.0)), S::constant(k(0.0)));
        let g1 = one + x1.cos() * k(0.1) + c.sin * k(0.1);
        let g2 = (S::constant(k(2.0)) + (x1 * x2).sin() * k(0.2) + c.cos * k(0.1)) * k(self.gain);
        let f2 = -(x1 * x1 - one) * x2 + (c.sin + c.cos2) * amp;
        [(g1, [-x1, c.sin, zero]), (g2, [f2, zero, zero])]
    }
}

/// The plant of example 3 (eq. (68), System_sim3) with the factor `x2`
/// restored in `x1'` (without it the plant cannot be controlled;
/// docs/errata.md): `x1' = (1 + 0.1 sin x1 + 0.1 cos t) x2 - x1 + cos t`,
/// `x2' = (1 + 0.1 cos(x1 x2) + 0.1 sin t) x3 - (x1^2 - 1) x2 + sin t`,
/// `x3' = b (2 + 0.2 sin(x1 x2 x3) + 0.1 cos t) u - (x1^2 + x2) x3 + a sin t + a cos 2t`
/// with `a = 10`, `b = 1`; `x(0) = (1, -0.2, 0.4)` as printed, `(1, 0.5, 4)`
/// in the authors' code. `b`, `a` and `x(0)` can be dispersed; the defaults of
/// [`ThirdOrder::new`] give the paper's arithmetic bit for bit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ThirdOrder {
    /// Which printed numbers.
    pub variant: Variant,
    /// Input-gain factor `b` (1 in the paper).
    pub gain: f64,
    /// Disturbance amplitude `a` (10 in the paper).
    pub amp: f64,
    /// Initial state.
    pub x0: [f64; 3],
}

impl ThirdOrder {
    /// The paper's plant in `variant`.
    pub const fn new(variant: Variant) -> Self {
        let x0 = match variant {
            Variant::Paper => [1.0, -0.2, 0.4],
            Variant::Code => [1.0, 0.5, 4.0],
        };
        Self {
            variant,
            gain: 1.0,
            amp: 10.0,
            x0,
        }
    }
}

impl<T: Real> Plant<T, 3> for ThirdOrder {
    fn x0(&self) -> [T; 3] {
        self.x0.map(T::from_f64)
    }

    #[inline]
    fn terms<S: Signal<T>>(&self, c: &Clock<S>, x: &[S; 3]) -> [(S, Drift<S>); 3] {
        let k = |v: f64| T::from_f64(v);
        let [x1, x2, x3] = *x;
        let (one, zero) = (S::constant(k(1.0)), S::constant(k(0.0)));
        let g1 = one + x1.sin() * k(0.1) + c.cos * k(0.1);
        let g2 = one + (x1 * x2).cos() * k(0.1) + c.sin * k(0.1);
        let g3 = (S::constant(k(2.0)) + (x1 * x2 * x3).sin() * k(0.2) + c.cos * k(0.1)) * k(self.gain);
        [
            (g1, [-x1, c.cos, zero]),
            (g2, [-((x1 * x1 - one) * x2), c.sin, zero]),
            (
                g3,
                [-((x1 * x1 + x2) * x3), c.sin * k(self.amp), c.cos2 * k(self.amp)],
            ),
        ]
    }
}

/// Length of the jets behind [`output_derivatives`] and [`gain_and_drift`]:
/// enough for plants up to order 3 (`y^(3)` needs 4 Taylor coefficients).
const JET: usize = 4;

/// Taylor coefficients `x_i^(k) / k!`, `k < JET`, of the solution through
/// `x` at time `t` with the input `u` held (the Taylor method: coefficient
/// `k` of the right-hand side needs only the state's coefficients up to `k`).
fn taylor<T: Real, const N: usize, P: Plant<T, N>>(plant: &P, t: T, x: &[T; N], u: T) -> [Jet<T, JET>; N] {
    let mut time = [T::zero(); JET];
    time.iter_mut().zip([t, T::one()]).for_each(|(c, v)| *c = v);
    let clock = Clock::at(Jet::from_taylor(time));
    let mut coeffs = x.map(Jet::<T, JET>::constant);
    for k in 0..N.min(JET - 1) {
        let rates = plant.rhs(&clock, &coeffs, Jet::constant(u));
        for (state, rate) in coeffs.iter_mut().zip(rates.iter()) {
            let mut c = state.taylor();
            if let (Some(next), Some(r)) = (c.get_mut(k + 1), rate.taylor().get(k)) {
                *next = *r / T::from_f64((k + 1) as f64);
            }
            *state = Jet::from_taylor(c);
        }
    }
    coeffs
}

/// `(y, y', ..., y^(n-1))` at time `t` (seconds) and state `x`, exactly
/// (for a strict-feedback plant they do not depend on the input), for
/// plants up to order 3 (NaN above).
pub fn output_derivatives<T: Real, const N: usize, P: Plant<T, N>>(plant: &P, t: T, x: &[T; N]) -> [T; N] {
    let mut out = [T::nan(); N];
    if N < JET {
        if let Some(y) = taylor(plant, t, x, T::zero()).first() {
            out.iter_mut().zip(y.derivatives()).for_each(|(o, d)| *o = d);
        }
    }
    out
}

/// `(G_a, F_a)` with `y^(n) = G_a u + F_a` (eq. (7), FAS) at time `t` and
/// state `x`: `G_a = g_1 ... g_n`, and `F_a = y^(n)` with `u = 0` (so
/// `-F_a/G_a` is the input that holds `y^(n) = 0`), for plants up to order 3
/// (NaN above).
pub fn gain_and_drift<T: Real, const N: usize, P: Plant<T, N>>(plant: &P, t: T, x: &[T; N]) -> (T, T) {
    if N >= JET {
        return (T::nan(), T::nan());
    }
    let gain = plant
        .terms(&Clock::at(t), x)
        .iter()
        .fold(T::one(), |acc, (g, _)| acc * *g);
    let drift = taylor(plant, t, x, T::zero())
        .first()
        .map_or(T::nan(), |y| y.derivative(N));
    (gain, drift)
}

pub use crate::rk4::{rk4_with, Instant};

/// Classical RK4 over `[t, t + h]` with the input `u` held; `c` holds the
/// time functions at `t`, `t + h/2` and `t + h`.
pub fn rk4<T: Real, const N: usize, P: Plant<T, N>>(
    p: &P,
    c: &[Clock<T>; 3],
    x: &[T; N],
    u: T,
    h: T,
) -> [T; N] {
    let [start, middle, end] = c;
    let clock = |i: Instant| match i {
        Instant::Start => start,
        Instant::Middle => middle,
        Instant::End => end,
    };
    rk4_with(|i, x| p.rhs(clock(i), x, u), x, h)
}
