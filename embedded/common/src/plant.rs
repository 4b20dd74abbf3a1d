//! The paper's plants (docs/design.md §6.3) in f32, integrated by classical RK4
//! with the input held between samples. Same equations as
//! `crates/famcc-core/tests/common/mod.rs` (there in f64).

use libm::{cosf, sinf};

/// Which printed numbers a plant uses (docs/design.md §6.2).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Variant {
    /// As printed in the paper (disturbance amplitude 1 etc.).
    Paper,
    /// The authors' MATLAB code (disturbance amplitude 3, x(0) = (1, 0.5, 4)).
    Code,
}

/// The time functions a right-hand side needs at one instant.
#[derive(Clone, Copy, Debug)]
pub struct Clock {
    /// `sin t`.
    pub sin: f32,
    /// `cos t`.
    pub cos: f32,
    /// `sin 2t`.
    pub sin2: f32,
    /// `cos 2t`.
    pub cos2: f32,
}

impl Clock {
    /// Evaluates the time functions at `t` seconds (two libm calls).
    #[inline]
    pub fn at(t: f32) -> Self {
        Self::from_sin_cos(sinf(t), cosf(t))
    }

    /// From `sin t`, `cos t`.
    #[inline]
    pub fn from_sin_cos(sin: f32, cos: f32) -> Self {
        Self {
            sin,
            cos,
            sin2: 2.0 * sin * cos,
            cos2: (cos - sin) * (cos + sin),
        }
    }

    /// The time functions at `t + tau` from those at `t` and at `tau`
    /// (angle addition: a few roundings, no libm call).
    #[inline]
    pub fn shifted(&self, tau: &Clock) -> Self {
        Self {
            sin: self.sin * tau.cos + self.cos * tau.sin,
            cos: self.cos * tau.cos - self.sin * tau.sin,
            sin2: self.sin2 * tau.cos2 + self.cos2 * tau.sin2,
            cos2: self.cos2 * tau.cos2 - self.sin2 * tau.sin2,
        }
    }
}

/// A strict-feedback plant `x' = f(t, x, u)` with output `y = x1`.
pub trait Plant<const N: usize> {
    /// The initial state.
    fn x0(&self) -> [f32; N];
    /// The right-hand side.
    fn rhs(&self, c: &Clock, x: &[f32; N], u: f32) -> [f32; N];
}

/// Examples 1/2 (eq. System_sim); variant "code" has disturbance amplitude 3.
#[derive(Clone, Copy, Debug)]
pub struct Second(pub Variant);

impl Plant<2> for Second {
    fn x0(&self) -> [f32; 2] {
        [-1.0, 0.5]
    }

    #[inline]
    fn rhs(&self, c: &Clock, x: &[f32; 2], u: f32) -> [f32; 2] {
        let amp = if self.0 == Variant::Code { 3.0 } else { 1.0 };
        let (x1, x2) = (x[0], x[1]);
        [
            (1.0 + 0.1 * cosf(x1) + 0.1 * c.sin) * x2 - x1 + c.sin,
            (2.0 + 0.2 * sinf(x1 * x2) + 0.1 * c.cos) * u - (x1 * x1 - 1.0) * x2 + amp * (c.sin + c.cos2),
        ]
    }
}

/// Example 3 (eq. System_sim3) with the factor `x2` restored in `x1'`.
#[derive(Clone, Copy, Debug)]
pub struct Third(pub Variant);

impl Plant<3> for Third {
    fn x0(&self) -> [f32; 3] {
        match self.0 {
            Variant::Paper => [1.0, -0.2, 0.4],
            Variant::Code => [1.0, 0.5, 4.0],
        }
    }

    #[inline]
    fn rhs(&self, c: &Clock, x: &[f32; 3], u: f32) -> [f32; 3] {
        let (x1, x2, x3) = (x[0], x[1], x[2]);
        [
            (1.0 + 0.1 * sinf(x1) + 0.1 * c.cos) * x2 - x1 + c.cos,
            (1.0 + 0.1 * cosf(x1 * x2) + 0.1 * c.sin) * x3 - (x1 * x1 - 1.0) * x2 + c.sin,
            (2.0 + 0.2 * sinf(x1 * x2 * x3) + 0.1 * c.cos) * u - (x1 * x1 + x2) * x3
                + 10.0 * c.sin
                + 10.0 * c.cos2,
        ]
    }
}

#[inline]
fn axpy<const N: usize>(x: &[f32; N], a: f32, k: &[f32; N]) -> [f32; N] {
    let mut out = *x;
    for (o, ki) in out.iter_mut().zip(k) {
        *o += a * *ki;
    }
    out
}

/// Classical RK4 over `[t, t + h]` with the input `u` held; `c` holds the
/// time functions at `t`, `t + h/2` and `t + h`.
pub fn rk4<const N: usize, P: Plant<N>>(p: &P, c: &[Clock; 3], x: &[f32; N], u: f32, h: f32) -> [f32; N] {
    let k1 = p.rhs(&c[0], x, u);
    let k2 = p.rhs(&c[1], &axpy(x, 0.5 * h, &k1), u);
    let k3 = p.rhs(&c[1], &axpy(x, 0.5 * h, &k2), u);
    let k4 = p.rhs(&c[2], &axpy(x, h, &k3), u);
    let mut out = *x;
    for i in 0..N {
        out[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
    }
    out
}
