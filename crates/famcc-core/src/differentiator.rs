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
//! (docs/design.md §3.3), by one of three [`Discretization`]s. The default,
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
