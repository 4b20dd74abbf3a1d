//! The matrix exponential behind the exact (zero-order-hold) discretization:
//! scaling and squaring with the degree-13 diagonal Pade approximant of
//! Higham (2005), on bordered matrices `[[m, v], [0, c]]`.

use super::linalg::{identity, lu_solve, mat_mul, mat_vec, Mat};

// Why a block type instead of an (N+1)x(N+1) matrix: stable Rust cannot write
// `[[f64; N + 1]; N + 1]` for a const generic N, and the zero-order-hold
// exponential only ever needs matrices of the form [[m, v], [0, c]] (the
// augmented matrix, its powers, their linear combinations, the Pade solve and
// the squarings all stay in this set). Storing m (N x N), v (N) and c keeps
// everything on the stack with fixed sizes and also skips the zero row.

/// The `(N+1) x (N+1)` block matrix `[[m, v], [0, c]]`.
#[derive(Clone, Copy)]
struct Bordered<const N: usize> {
    m: Mat<N>,
    v: [f64; N],
    c: f64,
}

impl<const N: usize> Bordered<N> {
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
fn pade13<const N: usize>(x: &Bordered<N>) -> Option<Bordered<N>> {
    let [b0, b1, b2, b3, b4, b5, b6, b7, b8, b9, b10, b11, b12, b13] = PADE_13;
    let id = Bordered::<N>::identity();
    let x2 = x.mul(x);
    let x4 = x2.mul(&x2);
    let x6 = x4.mul(&x2);
    let u_inner = x6.mul(&Bordered::combine(&[(b13, &x6), (b11, &x4), (b9, &x2)]));
    let u = x.mul(&Bordered::combine(&[
        (1.0, &u_inner),
        (b7, &x6),
        (b5, &x4),
        (b3, &x2),
        (b1, &id),
    ]));
    let v_inner = x6.mul(&Bordered::combine(&[(b12, &x6), (b10, &x4), (b8, &x2)]));
    let v = Bordered::combine(&[(1.0, &v_inner), (b6, &x6), (b4, &x4), (b2, &x2), (b0, &id)]);
    Bordered::solve(
        &Bordered::combine(&[(1.0, &v), (-1.0, &u)]),
        &Bordered::combine(&[(1.0, &v), (1.0, &u)]),
    )
}

/// Zero-order-hold discretization of `dw/dsigma = m0 w + a e` over `tau`:
/// `exp([[m0, a], [0, 0]] tau) = [[Phi0, Gamma0], [0, 1]]`.
pub(super) fn expm_zoh<const N: usize>(m0: &Mat<N>, a: &[f64; N], tau: f64) -> Option<(Mat<N>, [f64; N])> {
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
    let mut x = Bordered::<N> {
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
