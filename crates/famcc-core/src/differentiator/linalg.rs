//! Allocation-free `f64` linear algebra for the differentiator's
//! discretization (no indexing: every access is checked): small dense
//! matrices, LU with partial pivoting, the Routh-Hurwitz test, and the
//! spectral radius (without an eigen-solver; in any [`Real`], so that a
//! recursion precomputed on a host is checked on a microcontroller in its
//! own float type).

use crate::Real;

/// A dense `N x N` matrix, row-major.
pub(super) type Mat<const N: usize> = [[f64; N]; N];

pub(super) fn identity<const N: usize>() -> Mat<N> {
    let mut m = [[0.0; N]; N];
    for (i, row) in m.iter_mut().enumerate() {
        if let Some(d) = row.get_mut(i) {
            *d = 1.0;
        }
    }
    m
}

pub(super) fn mat_mul<R: Real, const N: usize>(x: &[[R; N]; N], y: &[[R; N]; N]) -> [[R; N]; N] {
    let mut out = [[R::zero(); N]; N];
    for (orow, xrow) in out.iter_mut().zip(x.iter()) {
        for (xik, yrow) in xrow.iter().zip(y.iter()) {
            for (o, ykj) in orow.iter_mut().zip(yrow.iter()) {
                *o = *o + *xik * *ykj;
            }
        }
    }
    out
}

pub(super) fn mat_vec<const N: usize>(x: &Mat<N>, v: &[f64; N]) -> [f64; N] {
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
pub(super) fn lu_solve<const N: usize>(
    mut a: Mat<N>,
    mut b: Mat<N>,
    mut v: [f64; N],
) -> Option<(Mat<N>, [f64; N])> {
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

/// Routh-Hurwitz test for the monic `s^m + a1 s^(m-1) + ... + am`, `m =
/// a.len() <= N` (all `a_i > 0` already checked). Rows of the Routh array
/// have at most `ceil((m+1)/2) <= N` entries, so two `[f64; N]` rows
/// suffice; missing entries are zero. Hurwitz iff every first-column entry is
/// `> 0`; an entry that cancels to within rounding (`<= 16 eps` times the
/// terms it was made from) is treated as zero, i.e. a root on or near the
/// imaginary axis.
pub(super) fn routh_hurwitz<const N: usize>(a: &[f64]) -> bool {
    let m = a.len().min(N);
    // row0 = (1, a2, a4, ...), row1 = (a1, a3, a5, ...)
    let mut r0 = [0.0_f64; N];
    let mut r1 = [0.0_f64; N];
    let coeffs = || core::iter::once(1.0).chain(a.iter().take(m).copied());
    for (d, c) in r0.iter_mut().zip(coeffs().step_by(2)) {
        *d = c;
    }
    for (d, c) in r1.iter_mut().zip(coeffs().skip(1).step_by(2)) {
        *d = c;
    }
    // rows 2..=m
    for _ in 1..m {
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

/// Squarings of [`spectral_radius`]: `||M^m||^(1/m)` with `m = 2^40`.
const SQUARINGS: u32 = 40;

/// The spectral radius `max |lambda_i|` of a square matrix, without an
/// eigen-solver: `||M^m||^(1/m)` (Gelfand's formula) with `m = 2^40`, by
/// repeated squaring, each square rescaled to norm 1 and the scales summed
/// as logarithms (so neither overflow nor underflow can occur).
///
/// Accuracy: a Jordan block of size `k` adds a factor `(C m^(k-1))^(1/m)`,
/// that is `1 + O(k 28 / 2^40)`, about `1 + 3e-11 k`, so a marginal
/// eigenvalue (`|lambda| = 1`, Euler at `dt = mu` for order 2) reads as
/// `>= 1`, and a decaying one reads as `< 1` whenever it is at least
/// ~`1e-10` inside the unit circle. (A defective eigenvalue of multiplicity
/// `k` of the rounded matrix itself moves by ~`rounding^(1/k)`.) Returns 0
/// for a nilpotent (or zero) matrix and infinity if an entry is not finite.
/// Computed in the matrix's float type: in `f32` a radius within ~`1e-7` of 1
/// reads as 1 (a precomputed recursion is checked this way by
/// [`crate::ConfigBuilder::build_discretized`]).
///
/// ```
/// use famcc_core::differentiator::spectral_radius;
/// // eigenvalues 0.5 and -0.9 (upper triangular): radius 0.9
/// let r = spectral_radius(&[[0.5_f64, 7.0], [0.0, -0.9]]);
/// assert!((r - 0.9).abs() < 1e-9);
/// // the same in f32
/// assert!((spectral_radius(&[[0.5_f32, 7.0], [0.0, -0.9]]) - 0.9).abs() < 1e-6);
/// // a Jordan block at -1 (Euler, order 2, dt = mu): marginal, reads >= 1
/// assert!(spectral_radius(&[[-3.0_f64, 1.0], [-4.0, 1.0]]) >= 1.0);
/// assert_eq!(spectral_radius(&[[0.0_f64, 1.0], [0.0, 0.0]]), 0.0);
/// ```
pub fn spectral_radius<R: Real, const N: usize>(m: &[[R; N]; N]) -> R {
    let norm = |x: &[[R; N]; N]| {
        x.iter()
            .map(|row| row.iter().fold(R::zero(), |acc, v| acc + v.abs()))
            .fold(R::zero(), R::max)
    };
    let two = R::from_f64(2.0);
    let mut a = *m;
    // a holds M^(2^k) / exp(log_norm)
    let mut log_norm = R::zero();
    for k in 0..=SQUARINGS {
        let nm = norm(&a);
        if !nm.is_finite() {
            return R::infinity();
        }
        if nm == R::zero() {
            return R::zero();
        }
        a.iter_mut().flatten().for_each(|v| *v = *v / nm);
        log_norm = log_norm + nm.ln();
        if k == SQUARINGS {
            break;
        }
        a = mat_mul(&a, &a);
        log_norm = log_norm * two;
    }
    (log_norm / two.powi(SQUARINGS as i32)).exp()
}
