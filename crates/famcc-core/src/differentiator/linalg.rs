//! Allocation-free `f64` linear algebra for the differentiator's
//! discretization (no indexing: every access is checked): small dense
//! matrices, LU with partial pivoting, and the Routh-Hurwitz test.

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

pub(super) fn mat_mul<const N: usize>(x: &Mat<N>, y: &Mat<N>) -> Mat<N> {
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

/// Routh-Hurwitz test for the monic `s^N + a1 s^(N-1) + ... + aN` (all
/// `a_i > 0` already checked). Rows of the Routh array have at most
/// `ceil((N+1)/2) <= N` entries, so two `[f64; N]` rows suffice; missing
/// entries are zero. Hurwitz iff every first-column entry is `> 0`; an entry
/// that cancels to within rounding (`<= 16 eps` times the terms it was made
/// from) is treated as zero, i.e. a root on or near the imaginary axis.
pub(super) fn routh_hurwitz<const N: usize>(a: &[f64; N]) -> bool {
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
