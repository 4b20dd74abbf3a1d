//! The `f64` computation behind [`super::HighGain::discretize_order`]: the
//! recursion of eq. (34) in balanced coordinates for one of the three
//! [`Discretization`]s, for a differentiator of run-time order `m <= N`
//! embedded in `N`-sized arrays, and the map back to `Zhat` in `T`.
//!
//! The order-`m` differentiator occupies the last `m` slots (`N - m ..
//! N`); the leading rows and columns of `Phi` and the leading entries of
//! `Gamma` are exactly zero, so `advance` leaves those slots at 0 for the
//! caller to fill (the integral of the error, with integral action). For
//! `m = N` nothing is embedded and the arithmetic is the plain order-`N`
//! one.

use super::expm::expm_zoh;
use super::linalg::{identity, lu_solve, mat_vec, Mat};
use super::{DiscreteHgd, Discretization};
use crate::Real;

/// Why the `f64` computation failed.
pub(super) enum Failure {
    /// A numerically singular system (Pade or Tustin solve).
    Singular,
    /// `Phi` or `Gamma` does not fit `T` (`mu` too small).
    Overflow,
}

/// `Phi0, Gamma0` of `dw/dsigma = M0 w + a e` over `tau = dt / mu` for the
/// order-`m` coefficients `a[..m]`, in the leading `m x m` block (zeros
/// elsewhere), then placed in the last `m` slots and mapped back to `Zhat`.
pub(super) fn discretize<T: Real, const N: usize>(
    a: &[f64; N],
    m: usize,
    tau: f64,
    mu: f64,
    method: Discretization,
) -> Result<DiscreteHgd<T, N>, Failure> {
    let mut a = *a;
    a.iter_mut().skip(m).for_each(|x| *x = 0.0);
    let m0 = balanced_matrix(&a, m);
    let mut feed0 = [0.0; N];
    let (mut phi0, gamma0) = match method {
        Discretization::Exact => expm_zoh(&m0, &a, tau).ok_or(Failure::Singular)?,
        Discretization::Foh => {
            let (phi0, zoh) = expm_zoh(&m0, &a, tau).ok_or(Failure::Singular)?;
            // Gamma stays the held input's: the controller adds the
            // feedthrough to the input's increment (DiscreteHgd::feedthrough).
            feed0 = ramp_response(&m0, &a, &zoh, tau, m).ok_or(Failure::Singular)?;
            (phi0, zoh)
        }
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
            lu_solve(lhs, rhs, g).ok_or(Failure::Singular)?
        }
    };
    if m < N {
        // The unused block came out as the identity (exp(0), I + 0, ...).
        for (i, row) in phi0.iter_mut().enumerate() {
            for (j, p) in row.iter_mut().enumerate() {
                if i >= m || j >= m {
                    *p = 0.0;
                }
            }
        }
    }
    unbalance(&phi0, &gamma0, &feed0, mu, m).ok_or(Failure::Overflow)
}

/// The first-order hold's feedthrough in balanced coordinates,
/// `D0 = (1/tau) integral_0^tau exp(M0 s) (tau - s) ds a`, from the held
/// input's `zoh = integral_0^tau exp(M0 s) ds a`.
///
/// `M0 D0 = (zoh - tau a) / tau` (integrate `exp(M0 s)` by parts), solved
/// by LU where `tau ||M0||_1 > 1`; below that the difference cancels, and the
/// series `D0 = sum_k tau^(k+1) M0^k a / (k+2)!` (its terms fall by at least
/// `1/(k+3)` each) is summed until a term no longer changes the sum. The
/// unused block (`m < N`) is the identity in the solve, with a zero right side.
pub(super) fn ramp_response<const N: usize>(
    m0: &Mat<N>,
    a: &[f64; N],
    zoh: &[f64; N],
    tau: f64,
    m: usize,
) -> Option<[f64; N]> {
    let norm = (0..N)
        .map(|j| {
            m0.iter()
                .map(|row| row.get(j).map_or(0.0, |x| x.abs()))
                .sum::<f64>()
        })
        .fold(0.0, f64::max);
    if tau * norm > 1.0 {
        let mut lhs = *m0;
        for (i, row) in lhs.iter_mut().enumerate().skip(m) {
            if let Some(d) = row.get_mut(i) {
                *d = 1.0;
            }
        }
        let mut rhs = [0.0; N];
        for ((r, z), ai) in rhs.iter_mut().zip(zoh.iter()).zip(a.iter()) {
            *r = (z - tau * ai) / tau;
        }
        return lu_solve(lhs, [[0.0; N]; N], rhs).map(|(_, d)| d);
    }
    // term_k = tau^(k+1) M0^k a / (k+2)!
    let mut term = a.map(|x| x * tau / 2.0);
    let mut sum = term;
    for k in 1..64 {
        let next = mat_vec(m0, &term);
        let scale = tau / (k + 2) as f64;
        term = next.map(|x| x * scale);
        let before = sum;
        sum.iter_mut().zip(term.iter()).for_each(|(s, t)| *s += t);
        if sum == before {
            break;
        }
    }
    Some(sum)
}

/// `M0 = A - a C` of order `m` (the leading block): the matrix of eq. (34)
/// in balanced coordinates.
pub(super) fn balanced_matrix<const N: usize>(a: &[f64; N], m: usize) -> Mat<N> {
    let mut out = [[0.0; N]; N];
    for (i, (row, ai)) in out.iter_mut().zip(a.iter()).take(m).enumerate() {
        if let Some(first) = row.first_mut() {
            *first = -ai;
        }
        if i + 1 < m {
            if let Some(sup) = row.get_mut(i + 1) {
                *sup += 1.0;
            }
        }
    }
    out
}

/// Maps the balanced-coordinate recursion (leading `m x m` block) back to
/// `Zhat` in the last `m` slots: `Phi_ij = Phi0_ij mu^(j-i)`, `Gamma_i =
/// Gamma0_i mu^(-i)` (0-based within the block), then rounds to `T`. `None`
/// if anything is not finite in `T`.
fn unbalance<T: Real, const N: usize>(
    phi0: &Mat<N>,
    gamma0: &[f64; N],
    feed0: &[f64; N],
    mu: f64,
    m: usize,
) -> Option<DiscreteHgd<T, N>> {
    let offset = N.saturating_sub(m);
    let mut phi = [[T::zero(); N]; N];
    let mut gamma = [T::zero(); N];
    let mut feedthrough = [T::zero(); N];
    let pow = |k: i64| -> f64 {
        // k is within +-(N-1); clamp keeps the cast lossless for any N.
        let k = k.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32;
        num_traits::Float::powi(mu, k)
    };
    for (i, (((prow, p0row), (g, g0)), (d, d0))) in phi
        .iter_mut()
        .skip(offset)
        .zip(phi0.iter())
        .zip(gamma.iter_mut().skip(offset).zip(gamma0.iter()))
        .zip(feedthrough.iter_mut().skip(offset).zip(feed0.iter()))
        .enumerate()
    {
        let i = i as i64;
        for (j, (p, p0)) in prow.iter_mut().skip(offset).zip(p0row.iter()).enumerate() {
            let x = if *p0 == 0.0 { 0.0 } else { p0 * pow(j as i64 - i) };
            *p = T::from_f64(x);
            if !p.is_finite() {
                return None;
            }
        }
        for (out, v0) in [(g, g0), (d, d0)] {
            *out = T::from_f64(if *v0 == 0.0 { 0.0 } else { v0 * pow(-i) });
            if !out.is_finite() {
                return None;
            }
        }
    }
    Some(DiscreteHgd {
        phi,
        gamma,
        prefilter: T::one(),
        feedthrough,
    })
}
