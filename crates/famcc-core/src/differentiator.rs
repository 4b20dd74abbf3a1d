//! The high-gain differentiator (paper eq. HGD), discretized once at
//! construction.
//!
//! The paper estimates the error vector `Z = (z1, z1', ..., z1^(N-1))` from the
//! measured `z1` alone with
//!
//! ```text
//! dZhat/dt = A Zhat + H (z1 - C Zhat) = (A - H C) Zhat + H z1        (eq. HGD)
//! ```
//!
//! where `A` is the shift matrix (ones on the superdiagonal), `C = [1 0 ... 0]`
//! and `H = (a1/mu, a2/mu^2, ..., aN/mu^N)^T`. The small time constant `mu`
//! (seconds) sets the speed, the dimensionless `a_i` make
//! `s^N + a1 s^(N-1) + ... + aN` Hurwitz. Units: `Zhat_i` has the units of
//! `z1` per `s^(i-1)`, `H_i` is in `1/s^i`, the sample period `dt` in seconds.
//!
//! The system is linear and time-invariant, so it is turned into the
//! recursion `Zhat_{k+1} = Phi Zhat_k + Gamma e_k` once, for a fixed `dt`
//! (SPEC section 2), by one of three [`Discretization`]s. The default,
//! [`Discretization::Exact`], is the zero-order-hold solution: stable for
//! every `dt`.
//!
//! ```
//! use famcc_core::{Discretization, HighGain};
//! // order 1: Phi = exp(-a1 dt / mu) = exp(-1), Gamma = 1 - Phi
//! let d = HighGain::new(0.1_f64, [1.0], Discretization::Exact).discretize(0.1).unwrap();
//! assert!((d.phi[0][0] - 0.367_879_441_171_442_3).abs() < 1e-15);
//! assert!((d.gamma[0] - 0.632_120_558_828_557_7).abs() < 1e-15);
//! // one step from 0 towards a constant measurement of 2
//! assert!((d.advance(&[0.0], 2.0)[0] - 1.264_241_117_657_115_4).abs() < 1e-14);
//! ```
//!
//! # Numerics
//!
//! Everything is computed in `f64` whatever `T` is, then rounded once to `T`,
//! so an `f32` user gets `Phi` and `Gamma` correct to `f32` rounding.
//!
//! The matrices are built in balanced coordinates `w_i = mu^(i-1) Zhat_i`,
//! where eq. HGD reads `dw/dsigma = M0 w + a z1` with `sigma = t / mu` and
//! `M0 = A - a C` (all entries `O(a_i)`, independent of `mu`). The recursion
//! for `w` over `tau = dt / mu` is computed and mapped back with
//! `Phi_ij = Phi0_ij mu^(j-i)`, `Gamma_i = Gamma0_i mu^(1-i)`. This diagonal
//! similarity is exact in theory and keeps the non-normality `mu^(1-N)` of
//! `A - H C` out of the matrix exponential, so small entries of `Phi` are
//! accurate relative to their own size, not only to the largest entry.

use crate::error::positive;
use crate::{ConfigError, Real};

/// How eq. HGD is turned into a sampled recursion
/// `Zhat_{k+1} = Phi Zhat_k + Gamma e_k` (with `M = A - H C`, `dt` in seconds).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Discretization {
    /// Zero-order hold on `z1` (the sample `e_k` is held over the period):
    /// `Phi = exp(M dt)`, `Gamma = (integral_0^dt exp(M s) ds) H`. Exact for a
    /// held input and stable for every `dt` (the eigenvalues of `Phi` are
    /// `exp(lambda dt)` with `Re lambda < 0`).
    #[default]
    Exact,
    /// Forward Euler: `Phi = I + M dt`, `Gamma = H dt`. For comparison only:
    /// it is unstable once `dt` exceeds roughly `mu` times a constant that
    /// depends on `a` (e.g. `dt > mu` for order 2 with `a = (4, 4)`). Such a
    /// `dt` is accepted, not rejected; the caller asked for Euler.
    Euler,
    /// Tustin (bilinear, trapezoidal rule) with the input held over the
    /// period: `Phi = (I - M dt/2)^-1 (I + M dt/2)`,
    /// `Gamma = (I - M dt/2)^-1 H dt`. Stable for every `dt`, but it maps very
    /// fast modes to eigenvalues near `-1` (ringing) when `dt >> mu`.
    Tustin,
}

/// The high-gain differentiator's parameters (eq. HGD): time constant `mu`
/// (seconds), coefficients `a = (a1, ..., aN)` (dimensionless) and the
/// discretization method.
///
/// ```
/// use famcc_core::{Discretization, HighGain};
/// // the paper's order-2 choice: s^2 + 4 s + 4 = (s + 2)^2
/// let hg = HighGain::new(0.01_f64, [4.0, 4.0], Discretization::Exact);
/// assert!(hg.validate().is_ok());
/// let bad = HighGain::new(0.01_f64, [1.0, 1.0, 10.0], Discretization::Exact);
/// assert_eq!(bad.validate().unwrap_err().parameter, "a");
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HighGain<T, const N: usize> {
    /// The small positive time constant `mu`, seconds.
    pub mu: T,
    /// The coefficients `a1, ..., aN` of the Hurwitz polynomial
    /// `s^N + a1 s^(N-1) + ... + aN` (dimensionless).
    pub a: [T; N],
    /// How eq. HGD is sampled.
    pub discretization: Discretization,
}

/// The sampled differentiator `Zhat_{k+1} = Phi Zhat_k + Gamma e_k` of
/// eq. HGD for one sample period.
///
/// `phi` is row-major (`phi[row][col]`), `gamma[i]` multiplies the held sample
/// `e_k` of `z1`. Build it with [`HighGain::discretize`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DiscreteHgd<T, const N: usize> {
    /// State transition over one period, row-major.
    pub phi: [[T; N]; N],
    /// Input vector over one period.
    pub gamma: [T; N],
}

impl<T: Real, const N: usize> HighGain<T, N> {
    /// The parameters as given (not validated; see [`HighGain::validate`]).
    pub fn new(mu: T, a: [T; N], discretization: Discretization) -> Self {
        Self {
            mu,
            a,
            discretization,
        }
    }

    /// Checks the parameters of eq. HGD: `mu` (seconds) finite and `> 0`,
    /// order `N >= 1`, every `a_i` finite and `> 0`, and
    /// `s^N + a1 s^(N-1) + ... + aN` Hurwitz (Routh-Hurwitz test, computed in
    /// `f64`; a first-column entry that cancels to within rounding counts as
    /// a root on the imaginary axis, i.e. not Hurwitz).
    ///
    /// ```
    /// use famcc_core::{Discretization, HighGain};
    /// // s^3 + 4 s^2 + 6 s + 4 = (s + 2)(s^2 + 2 s + 2): Hurwitz
    /// assert!(HighGain::new(0.01_f64, [4.0, 6.0, 4.0], Discretization::Exact).validate().is_ok());
    /// // s^2 + s - 1 has a root at 0.618...
    /// assert!(HighGain::new(0.01_f64, [1.0, -1.0], Discretization::Exact).validate().is_err());
    /// ```
    pub fn validate(&self) -> Result<(), ConfigError> {
        positive(self.mu, "mu")?;
        if N == 0 {
            return Err(ConfigError::new(
                "a",
                "must have at least one coefficient (order N >= 1)",
            ));
        }
        if !self.a.iter().all(|&ai| ai.is_finite() && ai > T::zero()) {
            return Err(ConfigError::new("a", "must all be finite and > 0"));
        }
        let mut a = [0.0_f64; N];
        for (d, s) in a.iter_mut().zip(self.a.iter()) {
            *d = s.to_f64_lossless();
        }
        if routh_hurwitz(&a) {
            Ok(())
        } else {
            Err(ConfigError::new(
                "a",
                "must make s^N + a1 s^(N-1) + ... + aN Hurwitz; this polynomial is not Hurwitz",
            ))
        }
    }

    /// Validates, checks the sample period `dt` (seconds; finite and `> 0`,
    /// errors name `"dt"`) and discretizes eq. HGD with
    /// [`HighGain::discretization`].
    ///
    /// [`Discretization::Exact`] computes the exponential of the augmented
    /// matrix `[[M0 tau, a tau], [0, 0]]` (balanced coordinates, see the
    /// module docs; `tau = dt / mu`) by scaling and squaring with the
    /// degree-13 diagonal Pade approximant of Higham (2005): the matrix is
    /// divided by the smallest `2^s` (`s >= 0`) that brings its 1-norm to at
    /// most `theta_13 = 5.371920351148152`, the Pade system is solved by LU
    /// with partial pivoting, and the result is squared `s` times.
    ///
    /// Errors: `"mu"` when `mu` is so small that `Phi` or `Gamma` overflows
    /// `T` (entries scale like `mu^(1-N)`); `"dt"` when `dt / mu` overflows.
    ///
    /// ```
    /// use famcc_core::{Discretization, HighGain};
    /// let hg = HighGain::new(0.01_f64, [4.0, 4.0], Discretization::Exact);
    /// let d = hg.discretize(1e-3).unwrap();
    /// // DC gain: a constant measurement 1.5 is a fixed point at (1.5, 0)
    /// let z = d.advance(&[1.5, 0.0], 1.5);
    /// assert!((z[0] - 1.5).abs() < 1e-12 && z[1].abs() < 1e-9);
    /// // dt = 1 s with mu = 0.01: everything decays within one period
    /// let slow = hg.discretize(1.0).unwrap();
    /// assert!(slow.phi.iter().flatten().all(|p| p.abs() < 1e-60));
    /// assert!(hg.discretize(0.0).is_err());
    /// ```
    pub fn discretize(&self, dt: T) -> Result<DiscreteHgd<T, N>, ConfigError> {
        self.validate()?;
        positive(dt, "dt")?;
        let mu = self.mu.to_f64_lossless();
        let tau = dt.to_f64_lossless() / mu;
        if !tau.is_finite() {
            return Err(ConfigError::new(
                "dt",
                "is too large for this mu (dt / mu overflows)",
            ));
        }
        let mut a = [0.0_f64; N];
        for (d, s) in a.iter_mut().zip(self.a.iter()) {
            *d = s.to_f64_lossless();
        }
        let m0 = balanced_matrix(&a);
        let singular = ConfigError::new("dt", "gives a numerically singular system in the discretization");
        let (phi0, gamma0) = match self.discretization {
            Discretization::Exact => expm_zoh(&m0, &a, tau).ok_or(singular)?,
            Discretization::Euler => {
                let mut phi0 = identity::<N>();
                for (prow, mrow) in phi0.iter_mut().zip(m0.iter()) {
                    for (p, m) in prow.iter_mut().zip(mrow.iter()) {
                        *p += tau * m;
                    }
                }
                let mut g = a;
                for gi in g.iter_mut() {
                    *gi *= tau;
                }
                (phi0, g)
            }
            Discretization::Tustin => {
                let mut lhs = identity::<N>();
                let mut rhs = identity::<N>();
                for ((lrow, rrow), mrow) in lhs.iter_mut().zip(rhs.iter_mut()).zip(m0.iter()) {
                    for ((l, r), m) in lrow.iter_mut().zip(rrow.iter_mut()).zip(mrow.iter()) {
                        *l -= 0.5 * tau * m;
                        *r += 0.5 * tau * m;
                    }
                }
                let mut g = a;
                for gi in g.iter_mut() {
                    *gi *= tau;
                }
                lu_solve(lhs, rhs, g).ok_or(singular)?
            }
        };
        unbalance(&phi0, &gamma0, mu).ok_or(ConfigError::new(
            "mu",
            "is so small that Phi or Gamma overflows this float type",
        ))
    }
}

impl<T: Real, const N: usize> DiscreteHgd<T, N> {
    /// One sample of eq. HGD: `Zhat_{k+1} = Phi Zhat_k + Gamma e`, with `e`
    /// the sample of `z1` (held over the period). Allocation-free.
    ///
    /// ```
    /// use famcc_core::DiscreteHgd;
    /// let d = DiscreteHgd { phi: [[0.5_f64, 0.25], [0.0, 0.25]], gamma: [0.5, 2.0] };
    /// assert_eq!(d.advance(&[1.0, 2.0], 4.0), [3.0, 8.5]);
    /// ```
    #[inline]
    pub fn advance(&self, zhat: &[T; N], e: T) -> [T; N] {
        let mut out = [T::zero(); N];
        for ((o, row), g) in out.iter_mut().zip(self.phi.iter()).zip(self.gamma.iter()) {
            *o = row
                .iter()
                .zip(zhat.iter())
                .fold(*g * e, |acc, (p, z)| acc + *p * *z);
        }
        out
    }
}

// ---------------------------------------------------------------------------
// f64 linear algebra (allocation-free, no indexing)
// ---------------------------------------------------------------------------

type Mat<const N: usize> = [[f64; N]; N];

fn identity<const N: usize>() -> Mat<N> {
    let mut m = [[0.0; N]; N];
    for (i, row) in m.iter_mut().enumerate() {
        if let Some(d) = row.get_mut(i) {
            *d = 1.0;
        }
    }
    m
}

/// `M0 = A - a C`: the matrix of eq. HGD in balanced coordinates.
fn balanced_matrix<const N: usize>(a: &[f64; N]) -> Mat<N> {
    let mut m = [[0.0; N]; N];
    for (i, (row, ai)) in m.iter_mut().zip(a.iter()).enumerate() {
        if let Some(first) = row.first_mut() {
            *first = -ai;
        }
        if let Some(sup) = row.get_mut(i + 1) {
            *sup += 1.0;
        }
    }
    m
}

fn mat_mul<const N: usize>(x: &Mat<N>, y: &Mat<N>) -> Mat<N> {
    let mut out = [[0.0; N]; N];
    for (orow, xrow) in out.iter_mut().zip(x.iter()) {
        for (xik, yrow) in xrow.iter().zip(y.iter()) {
            for (o, ykj) in orow.iter_mut().zip(yrow.iter()) {
                *o += xik * ykj;
            }
        }
    }
    out
}

fn mat_vec<const N: usize>(x: &Mat<N>, v: &[f64; N]) -> [f64; N] {
    let mut out = [0.0; N];
    for (o, row) in out.iter_mut().zip(x.iter()) {
        *o = row.iter().zip(v.iter()).map(|(p, q)| p * q).sum();
    }
    out
}

fn swap<R: Copy, const N: usize>(m: &mut [R; N], i: usize, j: usize) -> Option<()> {
    let ri = *m.get(i)?;
    let rj = *m.get(j)?;
    *m.get_mut(i)? = rj;
    *m.get_mut(j)? = ri;
    Some(())
}

/// Solves `a X = b` and `a y = v` by LU with partial pivoting. `None` if `a`
/// is singular (a zero or non-finite pivot).
fn lu_solve<const N: usize>(mut a: Mat<N>, mut b: Mat<N>, mut v: [f64; N]) -> Option<(Mat<N>, [f64; N])> {
    for k in 0..N {
        let mut p = k;
        let mut best = 0.0_f64;
        for (i, row) in a.iter().enumerate().skip(k) {
            let x = row.get(k)?.abs();
            if x > best {
                best = x;
                p = i;
            }
        }
        if !(best > 0.0 && best.is_finite()) {
            return None;
        }
        if p != k {
            swap(&mut a, k, p)?;
            swap(&mut b, k, p)?;
            swap(&mut v, k, p)?;
        }
        let ak = *a.get(k)?;
        let bk = *b.get(k)?;
        let vk = *v.get(k)?;
        let pivot = *ak.get(k)?;
        for ((arow, brow), vi) in a.iter_mut().zip(b.iter_mut()).zip(v.iter_mut()).skip(k + 1) {
            let l = *arow.get(k)? / pivot;
            if l != 0.0 {
                for (x, y) in arow.iter_mut().zip(ak.iter()).skip(k) {
                    *x -= l * y;
                }
                for (x, y) in brow.iter_mut().zip(bk.iter()) {
                    *x -= l * y;
                }
                *vi -= l * vk;
            }
        }
    }
    for i in (0..N).rev() {
        let arow = *a.get(i)?;
        let pivot = *arow.get(i)?;
        let mut brow = *b.get(i)?;
        let mut vi = *v.get(i)?;
        for (j, aij) in arow.iter().enumerate().skip(i + 1) {
            let xrow = b.get(j)?;
            for (x, y) in brow.iter_mut().zip(xrow.iter()) {
                *x -= aij * y;
            }
            vi -= aij * v.get(j)?;
        }
        for x in brow.iter_mut() {
            *x /= pivot;
        }
        *b.get_mut(i)? = brow;
        *v.get_mut(i)? = vi / pivot;
    }
    Some((b, v))
}

// Why a block type instead of an (N+1)x(N+1) matrix: stable Rust cannot write
// `[[f64; N + 1]; N + 1]` for a const generic N, and the zero-order-hold
// exponential only ever needs matrices of the form [[m, v], [0, c]] (the
// augmented matrix, its powers, their linear combinations, the Pade solve and
// the squarings all stay in this set). Storing m (N x N), v (N) and c keeps
// everything on the stack with fixed sizes and also skips the zero row.

/// The `(N+1) x (N+1)` block matrix `[[m, v], [0, c]]`.
#[derive(Clone, Copy)]
struct Aug<const N: usize> {
    m: Mat<N>,
    v: [f64; N],
    c: f64,
}

impl<const N: usize> Aug<N> {
    fn identity() -> Self {
        Self {
            m: identity::<N>(),
            v: [0.0; N],
            c: 1.0,
        }
    }

    /// `[[m1, v1], [0, c1]] [[m2, v2], [0, c2]] = [[m1 m2, m1 v2 + v1 c2], [0, c1 c2]]`.
    fn mul(&self, o: &Self) -> Self {
        let mut v = mat_vec(&self.m, &o.v);
        for (x, y) in v.iter_mut().zip(self.v.iter()) {
            *x += y * o.c;
        }
        Self {
            m: mat_mul(&self.m, &o.m),
            v,
            c: self.c * o.c,
        }
    }

    /// `sum_k coef_k X_k`.
    fn combine(terms: &[(f64, &Self)]) -> Self {
        let mut out = Self {
            m: [[0.0; N]; N],
            v: [0.0; N],
            c: 0.0,
        };
        for &(k, x) in terms {
            for (orow, xrow) in out.m.iter_mut().zip(x.m.iter()) {
                for (o, y) in orow.iter_mut().zip(xrow.iter()) {
                    *o += k * y;
                }
            }
            for (o, y) in out.v.iter_mut().zip(x.v.iter()) {
                *o += k * y;
            }
            out.c += k * x.c;
        }
        out
    }

    /// `d^-1 n` for block matrices: `r_c = n_c / d_c`, `d_m r_m = n_m`,
    /// `d_m r_v = n_v - d_v r_c`.
    fn solve(d: &Self, n: &Self) -> Option<Self> {
        if d.c == 0.0 {
            return None;
        }
        let c = n.c / d.c;
        let mut rhs = n.v;
        for (x, y) in rhs.iter_mut().zip(d.v.iter()) {
            *x -= y * c;
        }
        let (m, v) = lu_solve(d.m, n.m, rhs)?;
        Some(Self { m, v, c })
    }
}

/// `theta_13` of Higham (2005), Table 2.3: the 1-norm up to which the
/// degree-13 Pade approximant of `exp` is accurate to double precision.
const THETA_13: f64 = 5.371_920_351_148_152;

/// Coefficients `b_0..b_13` of the degree-13 Pade approximant (Higham 2005).
const PADE_13: [f64; 14] = [
    64_764_752_532_480_000.0,
    32_382_376_266_240_000.0,
    7_771_770_303_897_600.0,
    1_187_353_796_428_800.0,
    129_060_195_264_000.0,
    10_559_470_521_600.0,
    670_442_572_800.0,
    33_522_128_640.0,
    1_323_241_920.0,
    40_840_800.0,
    960_960.0,
    16_380.0,
    182.0,
    1.0,
];

/// `r_13(x) = (V - U)^-1 (V + U)`, `U` odd and `V` even in `x`.
fn pade13<const N: usize>(x: &Aug<N>) -> Option<Aug<N>> {
    let [b0, b1, b2, b3, b4, b5, b6, b7, b8, b9, b10, b11, b12, b13] = PADE_13;
    let id = Aug::<N>::identity();
    let x2 = x.mul(x);
    let x4 = x2.mul(&x2);
    let x6 = x4.mul(&x2);
    let u_inner = x6.mul(&Aug::combine(&[(b13, &x6), (b11, &x4), (b9, &x2)]));
    let u = x.mul(&Aug::combine(&[
        (1.0, &u_inner),
        (b7, &x6),
        (b5, &x4),
        (b3, &x2),
        (b1, &id),
    ]));
    let v_inner = x6.mul(&Aug::combine(&[(b12, &x6), (b10, &x4), (b8, &x2)]));
    let v = Aug::combine(&[(1.0, &v_inner), (b6, &x6), (b4, &x4), (b2, &x2), (b0, &id)]);
    Aug::solve(
        &Aug::combine(&[(1.0, &v), (-1.0, &u)]),
        &Aug::combine(&[(1.0, &v), (1.0, &u)]),
    )
}

/// Zero-order-hold discretization of `dw/dsigma = m0 w + a e` over `tau`:
/// `exp([[m0, a], [0, 0]] tau) = [[Phi0, Gamma0], [0, 1]]`.
fn expm_zoh<const N: usize>(m0: &Mat<N>, a: &[f64; N], tau: f64) -> Option<(Mat<N>, [f64; N])> {
    // 1-norm (largest column sum) of the augmented matrix [[m0, a], [0, 0]].
    let mut norm = a.iter().map(|x| x.abs()).sum::<f64>();
    for j in 0..N {
        let col: f64 = m0.iter().map(|row| row.get(j).map_or(0.0, |x| x.abs())).sum();
        norm = norm.max(col);
    }
    // Halving is exact; for a finite tau and norm this ends after at most
    // ~2100 halvings (tau * norm <= f64::MAX * f64::MAX is then below theta).
    let mut scaled = tau;
    let mut squarings = 0_u32;
    while scaled * norm > THETA_13 {
        scaled *= 0.5;
        squarings += 1;
    }
    let mut x = Aug::<N> {
        m: *m0,
        v: *a,
        c: 0.0,
    };
    for row in x.m.iter_mut() {
        for e in row.iter_mut() {
            *e *= scaled;
        }
    }
    for e in x.v.iter_mut() {
        *e *= scaled;
    }
    let mut r = pade13(&x)?;
    for _ in 0..squarings {
        // [[E, G], [0, 1]]^2 = [[E^2, E G + G], [0, 1]]
        r = r.mul(&r);
    }
    Some((r.m, r.v))
}

/// Maps the balanced-coordinate recursion back to `Zhat`:
/// `Phi_ij = Phi0_ij mu^(j-i)`, `Gamma_i = Gamma0_i mu^(-i)` (0-based), then
/// rounds to `T`. `None` if anything is not finite in `T`.
fn unbalance<T: Real, const N: usize>(
    phi0: &Mat<N>,
    gamma0: &[f64; N],
    mu: f64,
) -> Option<DiscreteHgd<T, N>> {
    let mut phi = [[T::zero(); N]; N];
    let mut gamma = [T::zero(); N];
    let pow = |k: i64| -> f64 {
        // k is within +-(N-1); clamp keeps the cast lossless for any N.
        let k = k.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32;
        num_traits::Float::powi(mu, k)
    };
    for (i, ((prow, p0row), (g, g0))) in phi
        .iter_mut()
        .zip(phi0.iter())
        .zip(gamma.iter_mut().zip(gamma0.iter()))
        .enumerate()
    {
        let i = i as i64;
        for (j, (p, p0)) in prow.iter_mut().zip(p0row.iter()).enumerate() {
            let x = if *p0 == 0.0 { 0.0 } else { p0 * pow(j as i64 - i) };
            *p = T::c(x);
            if !p.is_finite() {
                return None;
            }
        }
        let x = if *g0 == 0.0 { 0.0 } else { g0 * pow(-i) };
        *g = T::c(x);
        if !g.is_finite() {
            return None;
        }
    }
    Some(DiscreteHgd { phi, gamma })
}

/// Routh-Hurwitz test for the monic `s^N + a1 s^(N-1) + ... + aN` (all
/// `a_i > 0` already checked). Rows of the Routh array have at most
/// `ceil((N+1)/2) <= N` entries, so two `[f64; N]` rows suffice; missing
/// entries are zero. Hurwitz iff every first-column entry is `> 0`; an entry
/// that cancels to within rounding (`<= 16 eps` times the terms it was made
/// from) is treated as zero, i.e. a root on or near the imaginary axis.
fn routh_hurwitz<const N: usize>(a: &[f64; N]) -> bool {
    // row0 = (1, a2, a4, ...), row1 = (a1, a3, a5, ...)
    let mut r0 = [0.0_f64; N];
    let mut r1 = [0.0_f64; N];
    let coeffs = || core::iter::once(1.0).chain(a.iter().copied());
    for (d, c) in r0.iter_mut().zip(coeffs().step_by(2)) {
        *d = c;
    }
    for (d, c) in r1.iter_mut().zip(coeffs().skip(1).step_by(2)) {
        *d = c;
    }
    // rows 2..=N
    for _ in 1..N {
        let p0 = r0.first().copied().unwrap_or(0.0);
        let p1 = r1.first().copied().unwrap_or(0.0);
        if !(p1 > 0.0 && p1.is_finite()) {
            return false;
        }
        let mut next = [0.0_f64; N];
        for (k, (n, (x0, x1))) in next
            .iter_mut()
            .zip(r0.iter().skip(1).zip(r1.iter().skip(1)))
            .enumerate()
        {
            let num = p1 * x0 - p0 * x1;
            if k == 0 {
                let scale = (p1 * x0).abs() + (p0 * x1).abs();
                if !(num > 16.0 * f64::EPSILON * scale && num.is_finite()) {
                    return false;
                }
            }
            *n = num / p1;
        }
        r0 = r1;
        r1 = next;
    }
    r1.first().is_some_and(|&p| p > 0.0 && p.is_finite())
}

#[cfg(test)]
#[allow(clippy::needless_range_loop)]
mod tests {
    use super::*;

    const PAPER2: [f64; 2] = [4.0, 4.0];
    const PAPER3: [f64; 3] = [4.0, 6.0, 4.0];

    /// Coefficients of (s + 1)^N without s^N.
    fn binomial<const N: usize>() -> [f64; N] {
        let mut a = [0.0; N];
        let mut c = 1.0;
        for k in 0..N {
            c = c * (N - k) as f64 / (k + 1) as f64;
            a[k] = c;
        }
        a
    }

    /// Continuous eq. HGD right-hand side.
    fn rhs<const N: usize>(mu: f64, a: &[f64; N], z: &[f64; N], e: f64) -> [f64; N] {
        let mut d = [0.0; N];
        let innov = e - z[0];
        for i in 0..N {
            let next = if i + 1 < N { z[i + 1] } else { 0.0 };
            d[i] = next + a[i] / mu.powi(i as i32 + 1) * innov;
        }
        d
    }

    /// Classical RK4 of eq. HGD over `dt` with `steps` steps and held `e`.
    fn rk4<const N: usize>(mu: f64, a: &[f64; N], z0: [f64; N], e: f64, dt: f64, steps: usize) -> [f64; N] {
        let h = dt / steps as f64;
        let mut z = z0;
        let add = |z: &[f64; N], k: &[f64; N], s: f64| {
            let mut o = *z;
            for i in 0..N {
                o[i] += s * k[i];
            }
            o
        };
        for _ in 0..steps {
            let k1 = rhs(mu, a, &z, e);
            let k2 = rhs(mu, a, &add(&z, &k1, h / 2.0), e);
            let k3 = rhs(mu, a, &add(&z, &k2, h / 2.0), e);
            let k4 = rhs(mu, a, &add(&z, &k3, h), e);
            for i in 0..N {
                z[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
            }
        }
        z
    }

    fn rel_err(x: f64, y: f64) -> f64 {
        if y == 0.0 {
            x.abs()
        } else {
            ((x - y) / y).abs()
        }
    }

    /// Relative error; entries below 1e-3 of their natural scale `mu^(j-i)`
    /// (e.g. Phi_11 = exp(-1)(1 - 1) = 0 for order 2 at dt = mu / 2, where
    /// RK4's own rounding is ~2e-15) are compared against that floor.
    fn rel_err_floor(x: f64, y: f64, scale: f64) -> f64 {
        (x - y).abs() / y.abs().max(1e-3 * scale)
    }

    fn norm_inf<const N: usize>(m: &[[f64; N]; N]) -> f64 {
        m.iter()
            .map(|r| r.iter().map(|x| x.abs()).sum::<f64>())
            .fold(0.0, f64::max)
    }

    fn square<const N: usize>(m: &[[f64; N]; N]) -> [[f64; N]; N] {
        mat_mul(m, m)
    }

    #[test]
    fn order1_matches_closed_form() {
        for &mu in &[1e-3_f64, 0.01, 0.3] {
            for &a1 in &[0.5, 1.0, 7.0] {
                for &dt in &[1e-7, 1e-4, 1e-3, 0.05, 1.0] {
                    let d = HighGain::new(mu, [a1], Discretization::Exact)
                        .discretize(dt)
                        .unwrap();
                    let x = -a1 * dt / mu;
                    let phi = x.exp();
                    let gamma = -x.exp_m1(); // 1 - Phi without cancellation
                                             // absolute 1e-14 (Phi, Gamma are in [0, 1]) ...
                    assert!((d.phi[0][0] - phi).abs() < 1e-14, "mu {mu} a1 {a1} dt {dt}");
                    assert!(
                        (d.gamma[0] - (1.0 - phi)).abs() < 1e-14,
                        "mu {mu} a1 {a1} dt {dt}"
                    );
                    // ... and relative: 1e-14 for a small dt / mu; squaring
                    // grows the relative error of exp(x) like |x| eps
                    let rel = 1e-14 * (1.0 + x.abs());
                    assert!(rel_err(d.phi[0][0], phi) < rel, "mu {mu} a1 {a1} dt {dt}");
                    assert!(rel_err(d.gamma[0], gamma) < 1e-14, "mu {mu} a1 {a1} dt {dt}");
                }
            }
        }
    }

    fn check_against_rk4<const N: usize>(a: [f64; N]) {
        let mu = 0.01;
        for &dt in &[1e-3, 5e-3] {
            let d = HighGain::new(mu, a, Discretization::Exact)
                .discretize(dt)
                .unwrap();
            let mut worst = 0.0_f64;
            for j in 0..N {
                let mut z0 = [0.0; N];
                z0[j] = 1.0;
                let col = rk4(mu, &a, z0, 0.0, dt, 20_000);
                for i in 0..N {
                    worst = worst.max(rel_err_floor(d.phi[i][j], col[i], mu.powi(j as i32 - i as i32)));
                }
            }
            let g = rk4(mu, &a, [0.0; N], 1.0, dt, 20_000);
            for i in 0..N {
                worst = worst.max(rel_err_floor(d.gamma[i], g[i], mu.powi(-(i as i32))));
            }
            assert!(worst < 1e-10, "order {N} dt {dt}: worst relative error {worst:e}");
        }
    }

    #[test]
    fn exact_matches_fine_rk4_order2_and_order3() {
        check_against_rk4(PAPER2);
        check_against_rk4(PAPER3);
    }

    fn check_dc_gain<const N: usize>(a: [f64; N]) {
        let mu = 0.01;
        for &dt in &[1e-3, 5e-3] {
            let d = HighGain::new(mu, a, Discretization::Exact)
                .discretize(dt)
                .unwrap();
            let e = 2.5;
            // (I - Phi) x = Gamma e at x = (e, 0, ..., 0)
            for i in 0..N {
                let lhs = if i == 0 { e } else { 0.0 } - d.phi[i][0] * e;
                let scale = d.gamma[i].abs() * e + 1e-300;
                assert!((lhs - d.gamma[i] * e).abs() <= 1e-10 * scale, "row {i}");
            }
            // and the recursion converges there from rest
            let mut z = [0.0; N];
            for _ in 0..5_000 {
                z = d.advance(&z, e);
            }
            assert!((z[0] - e).abs() < 1e-12 * e);
            for i in 1..N {
                assert!(z[i].abs() < 1e-9 * e / mu.powi(i as i32), "z[{i}] = {}", z[i]);
            }
        }
    }

    #[test]
    fn constant_input_gives_dc_gain_unit_zero() {
        check_dc_gain(PAPER2);
        check_dc_gain(PAPER3);
    }

    /// Ramp z1 = slope * t, sampled and held: after the transient Zhat_2
    /// tracks the slope. The relative residual at the sample instants comes
    /// from the held staircase (a sawtooth of height slope * dt that the fast
    /// differentiator partly follows) and scales like (dt / mu)^2: measured
    /// 0.33 (dt/mu)^2 for order 2 and 0.48 (dt/mu)^2 for order 3.
    fn check_ramp<const N: usize>(a: [f64; N]) {
        let mu = 0.01;
        let slope = 3.0;
        for &dt in &[1e-3, 5e-3] {
            let d = HighGain::new(mu, a, Discretization::Exact)
                .discretize(dt)
                .unwrap();
            let mut z = [0.0; N];
            let steps = (2.0 / dt) as usize;
            for k in 0..steps {
                z = d.advance(&z, slope * k as f64 * dt);
            }
            let err = (z[1] - slope).abs() / slope;
            let tol = 0.6 * (dt / mu) * (dt / mu);
            assert!(err < tol, "order {N} dt {dt}: Zhat_2 = {} (slope {slope})", z[1]);
            // increments settle to (slope dt, 0, ...)
            let z_next = d.advance(&z, slope * steps as f64 * dt);
            assert!(((z_next[0] - z[0]) - slope * dt).abs() < 1e-9);
            for i in 1..N {
                assert!((z_next[i] - z[i]).abs() < 1e-7 / mu.powi(i as i32));
            }
        }
    }

    #[test]
    fn ramp_input_gives_slope() {
        check_ramp(PAPER2);
        check_ramp(PAPER3);
    }

    fn check_contractive<const N: usize>(a: [f64; N], mu: f64) {
        let mut dt = 1e-6;
        while dt <= 10.0 * (1.0 + 1e-9) {
            for method in [Discretization::Exact, Discretization::Tustin] {
                let d = HighGain::new(mu, a, method).discretize(dt).unwrap();
                assert!(d
                    .phi
                    .iter()
                    .flatten()
                    .chain(d.gamma.iter())
                    .all(|x| x.is_finite()));
                // Phi^(2^60) -> 0 iff the spectral radius is < 1
                let mut p = d.phi;
                for _ in 0..60 {
                    p = square(&p);
                    assert!(
                        p.iter().flatten().all(|x| x.is_finite()),
                        "order {N} dt {dt} {method:?}"
                    );
                }
                assert!(
                    norm_inf(&p) < 1e-30,
                    "order {N} dt {dt} {method:?}: {:e}",
                    norm_inf(&p)
                );
            }
            dt *= 10.0_f64.sqrt();
        }
    }

    #[test]
    fn exact_and_tustin_are_contractive_for_all_dt() {
        check_contractive([3.0], 0.01);
        check_contractive(PAPER2, 0.01);
        check_contractive(PAPER3, 0.01);
        check_contractive(binomial::<4>(), 0.01);
        check_contractive(binomial::<5>(), 0.05);
        check_contractive(binomial::<6>(), 0.01);
        check_contractive(binomial::<7>(), 0.1);
        check_contractive(binomial::<8>(), 0.01);
    }

    /// Exact is a semigroup: Phi(2h) = Phi(h)^2, Gamma(2h) = Phi(h) Gamma(h) + Gamma(h).
    fn check_semigroup<const N: usize>(a: [f64; N], mu: f64) {
        for &h in &[1e-5, 1e-3, 0.02, 0.3] {
            let one = HighGain::new(mu, a, Discretization::Exact).discretize(h).unwrap();
            let two = HighGain::new(mu, a, Discretization::Exact)
                .discretize(2.0 * h)
                .unwrap();
            let sq = square(&one.phi);
            let g2 = one.advance(&one.gamma, 1.0);
            let mut worst = 0.0_f64;
            for i in 0..N {
                for j in 0..N {
                    let scale = mu.powi(j as i32 - i as i32);
                    worst = worst.max((sq[i][j] - two.phi[i][j]).abs() / scale);
                }
                worst = worst.max((g2[i] - two.gamma[i]).abs() * mu.powi(i as i32));
            }
            assert!(worst < 1e-12, "order {N} mu {mu} h {h}: {worst:e}");
        }
    }

    #[test]
    fn exact_is_a_semigroup_for_orders_1_to_8() {
        check_semigroup([2.0], 0.01);
        check_semigroup(PAPER2, 0.01);
        check_semigroup(PAPER3, 0.01);
        check_semigroup(binomial::<4>(), 0.01);
        check_semigroup(binomial::<5>(), 0.02);
        check_semigroup(binomial::<6>(), 0.05);
        check_semigroup(binomial::<7>(), 0.1);
        check_semigroup(binomial::<8>(), 0.1);
    }

    #[test]
    fn exact_with_huge_dt_is_zero_not_nan() {
        let d = HighGain::new(0.01, PAPER3, Discretization::Exact)
            .discretize(1.0)
            .unwrap();
        // slowest mode exp(-dt / mu) = exp(-100) ~ 4e-44, times mu^(-2) = 1e4
        assert!(d.phi.iter().flatten().all(|x| x.is_finite() && x.abs() < 1e-38));
        // Gamma -> the DC solution: (1, 0, 0)
        assert!((d.gamma[0] - 1.0).abs() < 1e-12);
        assert!(d.gamma[1].abs() < 1e-9 && d.gamma[2].abs() < 1e-6);
        let d = HighGain::new(1e-4, binomial::<8>(), Discretization::Exact)
            .discretize(10.0)
            .unwrap();
        assert!(d
            .phi
            .iter()
            .flatten()
            .chain(d.gamma.iter())
            .all(|x| x.is_finite()));
    }

    #[test]
    fn euler_with_large_dt_is_unstable_but_accepted() {
        let d = HighGain::new(0.01, PAPER2, Discretization::Euler)
            .discretize(0.05)
            .unwrap();
        // Phi = I + M dt exactly
        assert_eq!(d.phi[0][0], 1.0 - 4.0 / 0.01 * 0.05);
        assert_eq!(d.phi[0][1], 0.05);
        let mut p = d.phi;
        for _ in 0..6 {
            p = square(&p);
        }
        assert!(norm_inf(&p) > 1e30, "Euler should blow up at dt = 5 mu");
        // while small dt agrees with Exact to first order
        let dt = 1e-5;
        let eu = HighGain::new(0.01, PAPER2, Discretization::Euler)
            .discretize(dt)
            .unwrap();
        let ex = HighGain::new(0.01, PAPER2, Discretization::Exact)
            .discretize(dt)
            .unwrap();
        for i in 0..2 {
            for j in 0..2 {
                assert!((eu.phi[i][j] - ex.phi[i][j]).abs() < 1e-2 * 0.01f64.powi(j as i32 - i as i32));
            }
        }
    }

    #[test]
    fn tustin_is_second_order_close_to_exact() {
        let a = PAPER3;
        let mu = 0.01;
        let err = |dt: f64| {
            let tu = HighGain::new(mu, a, Discretization::Tustin)
                .discretize(dt)
                .unwrap();
            let ex = HighGain::new(mu, a, Discretization::Exact)
                .discretize(dt)
                .unwrap();
            let mut w = 0.0_f64;
            for i in 0..3 {
                for j in 0..3 {
                    w = w.max((tu.phi[i][j] - ex.phi[i][j]).abs() * mu.powi(i as i32 - j as i32));
                }
            }
            w
        };
        let (e1, e2) = (err(1e-4), err(5e-5));
        // halving dt divides the one-step error by ~8 (local error O(dt^3))
        assert!(e1 / e2 > 7.0 && e1 / e2 < 9.0, "{e1:e} {e2:e}");
    }

    #[test]
    fn advance_is_phi_times_zhat_plus_gamma_e() {
        let d = HighGain::new(0.02, PAPER3, Discretization::Exact)
            .discretize(1e-3)
            .unwrap();
        let z = [0.3, -2.0, 40.0];
        let out = d.advance(&z, 1.7);
        for i in 0..3 {
            let want: f64 = (0..3).map(|j| d.phi[i][j] * z[j]).sum::<f64>() + d.gamma[i] * 1.7;
            assert!((out[i] - want).abs() <= 1e-13 * want.abs().max(1.0));
        }
    }

    #[test]
    fn non_hurwitz_coefficients_are_rejected() {
        let e = HighGain::new(0.01, [1.0, -1.0], Discretization::Exact)
            .validate()
            .unwrap_err();
        assert_eq!(e.parameter, "a");
        // s^3 + s^2 + s + 10: a1 a2 = 1 < a3 = 10
        let e = HighGain::new(0.01, [1.0, 1.0, 10.0], Discretization::Exact)
            .validate()
            .unwrap_err();
        assert_eq!(e.parameter, "a");
        assert!(e.rule.contains("not Hurwitz"), "{}", e.rule);
        // boundary: s^3 + s^2 + s + 1 = (s + 1)(s^2 + 1) has roots on the axis
        assert!(HighGain::new(0.01, [1.0, 1.0, 1.0], Discretization::Exact)
            .validate()
            .is_err());
        // s^4 + s^3 + 3 s^2 + s + 1 ... Routh: (1,3,1),(1,1),(2,1),(0.5),(1) -> Hurwitz
        assert!(HighGain::new(0.01, [1.0, 3.0, 1.0, 1.0], Discretization::Exact)
            .validate()
            .is_ok());
        // s^4 + s^3 + s^2 + s + 1 (roots on the unit circle's right half): not Hurwitz
        assert!(HighGain::new(0.01, [1.0, 1.0, 1.0, 1.0], Discretization::Exact)
            .validate()
            .is_err());
        // discretize validates first
        let e = HighGain::new(0.01, [1.0, 1.0, 10.0], Discretization::Exact)
            .discretize(1e-3)
            .unwrap_err();
        assert_eq!(e.parameter, "a");
        // zero, NaN and infinite coefficients
        for bad in [0.0, -2.0, f64::NAN, f64::INFINITY] {
            let e = HighGain::new(0.01, [4.0, bad], Discretization::Exact)
                .validate()
                .unwrap_err();
            assert_eq!(e.parameter, "a");
        }
    }

    #[test]
    fn hurwitz_test_agrees_with_known_polynomials() {
        // Hurwitz: binomial (s+1)^N for N = 1..=8, and the paper's choices
        assert!(routh_hurwitz(&binomial::<1>()));
        assert!(routh_hurwitz(&binomial::<2>()));
        assert!(routh_hurwitz(&binomial::<3>()));
        assert!(routh_hurwitz(&binomial::<4>()));
        assert!(routh_hurwitz(&binomial::<5>()));
        assert!(routh_hurwitz(&binomial::<6>()));
        assert!(routh_hurwitz(&binomial::<7>()));
        assert!(routh_hurwitz(&binomial::<8>()));
        assert!(routh_hurwitz(&binomial::<12>()));
        assert!(routh_hurwitz(&PAPER2) && routh_hurwitz(&PAPER3));
        // order 3: Hurwitz iff a1 a2 > a3
        assert!(routh_hurwitz(&[2.0, 3.0, 5.9]));
        assert!(!routh_hurwitz(&[2.0, 3.0, 6.1]));
        // (s-1)(s+2)(s+3) = s^3 + 4 s^2 + s - 6 has a negative coefficient;
        // (s^2 - 0.1 s + 1)(s + 1)^2 = s^4 + 1.9 s^3 + 1.8 s^2 + 1.9 s + 1 has
        // positive coefficients but two right-half-plane roots
        assert!(!routh_hurwitz(&[1.9, 1.8, 1.9, 1.0]));
        // (s^2 + 0.1 s + 1)(s + 1)^2 = s^4 + 2.1 s^3 + 2.2 s^2 + 2.1 s + 1: Hurwitz
        assert!(routh_hurwitz(&[2.1, 2.2, 2.1, 1.0]));
    }

    #[test]
    fn bad_mu_and_dt_are_rejected_with_their_names() {
        for mu in [0.0, -0.01, f64::NAN, f64::INFINITY] {
            let hg = HighGain::new(mu, PAPER2, Discretization::Exact);
            assert_eq!(hg.validate().unwrap_err().parameter, "mu");
            assert_eq!(hg.discretize(1e-3).unwrap_err().parameter, "mu");
        }
        let hg = HighGain::new(0.01, PAPER2, Discretization::Exact);
        for dt in [0.0, -1e-3, f64::NAN, f64::INFINITY] {
            assert_eq!(hg.discretize(dt).unwrap_err().parameter, "dt");
        }
        // dt / mu overflows
        let hg = HighGain::new(1e-300, [1.0], Discretization::Exact);
        assert_eq!(hg.discretize(1e100).unwrap_err().parameter, "dt");
        // order 8 with mu = 1e-6 overflows f32 (H_8 = 1e48)
        let hg = HighGain::new(1e-6_f32, [1.0; 8], Discretization::Euler);
        let hg = HighGain {
            a: binomial::<8>().map(|x| x as f32),
            ..hg
        };
        assert_eq!(hg.discretize(1e-3).unwrap_err().parameter, "mu");
        // order 0 is rejected
        let e = HighGain::<f64, 0>::new(0.01, [], Discretization::Exact)
            .validate()
            .unwrap_err();
        assert_eq!(e.parameter, "a");
    }

    #[test]
    fn f32_and_f64_agree() {
        for method in [
            Discretization::Exact,
            Discretization::Euler,
            Discretization::Tustin,
        ] {
            for &dt in &[1e-4_f32, 1e-3, 5e-3, 0.1] {
                let mu = 0.01_f32;
                let a = [4.0_f32, 6.0, 4.0];
                let d32 = HighGain::new(mu, a, method).discretize(dt).unwrap();
                // the same (f32-representable) parameters in f64: f32 is
                // exactly the f64 result rounded, i.e. within half an f32 ulp
                let d64 = HighGain::new(f64::from(mu), a.map(f64::from), method)
                    .discretize(f64::from(dt))
                    .unwrap();
                for i in 0..3 {
                    for j in 0..3 {
                        let (x, y) = (f64::from(d32.phi[i][j]), d64.phi[i][j]);
                        assert!((x - y).abs() <= 6e-8 * y.abs(), "{method:?} {dt} phi[{i}][{j}]");
                    }
                    let (x, y) = (f64::from(d32.gamma[i]), d64.gamma[i]);
                    assert!((x - y).abs() <= 6e-8 * y.abs(), "{method:?} {dt} gamma[{i}]");
                }
                // and with the decimal parameters in f64 (mu = 0.01 is not an
                // f32 number): relative 1e-6 of each entry's natural scale
                let d64 = HighGain::new(0.01_f64, [4.0, 6.0, 4.0], method)
                    .discretize(f64::from(dt))
                    .unwrap();
                for i in 0..3 {
                    for j in 0..3 {
                        let scale = 0.01_f64.powi(j as i32 - i as i32);
                        let (x, y) = (f64::from(d32.phi[i][j]), d64.phi[i][j]);
                        assert!(
                            (x - y).abs() <= 1e-6 * y.abs().max(scale),
                            "{method:?} {dt} phi[{i}][{j}]"
                        );
                    }
                    let scale = 0.01_f64.powi(-(i as i32));
                    let y = d64.gamma[i];
                    assert!((f64::from(d32.gamma[i]) - y).abs() <= 1e-6 * y.abs().max(scale));
                }
            }
        }
    }

    #[test]
    fn f32_advance_tracks_f64() {
        let d32 = HighGain::new(0.01_f32, [4.0, 4.0], Discretization::Exact)
            .discretize(1e-3)
            .unwrap();
        let d64 = HighGain::new(f64::from(0.01_f32), [4.0, 4.0], Discretization::Exact)
            .discretize(1e-3)
            .unwrap();
        let (mut z32, mut z64) = ([0.0_f32; 2], [0.0_f64; 2]);
        for k in 0..2000 {
            let t = k as f64 * 1e-3;
            let e = (3.0 * t).sin();
            z32 = d32.advance(&z32, e as f32);
            z64 = d64.advance(&z64, e);
        }
        assert!((f64::from(z32[0]) - z64[0]).abs() < 1e-5);
        assert!((f64::from(z32[1]) - z64[1]).abs() < 1e-3);
        // Zhat_2 estimates 3 cos(3 t) up to the filter lag
        let t = 1999.0_f64 * 1e-3;
        assert!((z64[1] - 3.0 * (3.0 * t).cos()).abs() < 0.1);
    }
}
