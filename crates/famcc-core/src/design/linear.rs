//! The linearized sampled loop of a design, for its checks: the
//! differentiator's noise gain and the closed loop's spectral radius.
//!
//! The nominal plant is a chain of `n` integrators with input gain `G`
//! (`y^(n) = G u`), held over each sample; the law is linearized at the
//! manifold, `u = -(2 k_u / eps_s) s` (log Gamma has slope 2 at 0), and uses
//! the estimate built from the samples before the current one, as
//! `Controller::step` does (docs/design.md §3.2).

use super::rules::manifold;
use super::{Design, MAX_ORDER};
use crate::differentiator::{prefilter_gain, HighGain};
use crate::error::ConfigError;
use num_traits::Float as F;

/// Largest closed-loop dimension: plant, estimate (with the prefilter's
/// state) and integral.
const DIM: usize = 2 * MAX_ORDER + 2;
type Mat = [[f64; DIM]; DIM];

/// `Phi`, `Gamma` of the design's differentiator (order `n`), zero-padded,
/// and its dimension: `n`, or `n + 1` with the prefilter, whose state is the
/// last input `f_(k-1)`: with `f_k = a f_(k-1) + b e_k` (`b` the prefilter's
/// gain, `a = 1 - b`), `Zhat_{k+1} = Phi Zhat_k + a Gamma f_(k-1) + b Gamma e_k`.
fn hgd(d: &Design, n: usize, dt: f64) -> Result<(Mat, [f64; DIM], usize), ConfigError> {
    let (mut phi, mut gamma) = plain_hgd(d, n, dt)?;
    let b = prefilter_gain(dt, d.prefilter);
    if b == 1.0 {
        return Ok((phi, gamma, n));
    }
    for (i, row) in phi.iter_mut().enumerate().take(n) {
        if let Some(x) = row.get_mut(n) {
            *x = (1.0 - b) * gamma.get(i).copied().unwrap_or(0.0);
        }
    }
    if let Some(x) = phi.get_mut(n).and_then(|r| r.get_mut(n)) {
        *x = 1.0 - b;
    }
    gamma.iter_mut().take(n).for_each(|g| *g *= b);
    if let Some(g) = gamma.get_mut(n) {
        *g = b;
    }
    Ok((phi, gamma, n + 1))
}

/// `Phi`, `Gamma` of the design's differentiator without its prefilter.
fn plain_hgd(d: &Design, n: usize, dt: f64) -> Result<(Mat, [f64; DIM]), ConfigError> {
    fn pad<const M: usize>(d: &Design, dt: f64) -> Result<(Mat, [f64; DIM]), ConfigError> {
        let mut a = [0.0; M];
        a.iter_mut().zip(d.a.iter()).for_each(|(x, y)| *x = *y);
        let h = HighGain::<f64, M>::new(d.mu, a, d.discretization).discretize(dt)?;
        let mut phi = [[0.0; DIM]; DIM];
        let mut gamma = [0.0; DIM];
        for (row, src) in phi.iter_mut().zip(h.phi.iter()) {
            row.iter_mut().zip(src.iter()).for_each(|(x, y)| *x = *y);
        }
        gamma.iter_mut().zip(h.gamma.iter()).for_each(|(x, y)| *x = *y);
        Ok((phi, gamma))
    }
    match n {
        1 => pad::<1>(d, dt),
        2 => pad::<2>(d, dt),
        3 => pad::<3>(d, dt),
        4 => pad::<4>(d, dt),
        5 => pad::<5>(d, dt),
        6 => pad::<6>(d, dt),
        7 => pad::<7>(d, dt),
        _ => pad::<8>(d, dt),
    }
}

fn mul(a: &Mat, b: &Mat, dim: usize) -> Mat {
    let mut c = [[0.0; DIM]; DIM];
    for (crow, arow) in c.iter_mut().zip(a.iter()).take(dim) {
        for (k, aik) in arow.iter().enumerate().take(dim) {
            if *aik != 0.0 {
                if let Some(brow) = b.get(k) {
                    for (cij, bkj) in crow.iter_mut().zip(brow.iter()).take(dim) {
                        *cij += aik * bkj;
                    }
                }
            }
        }
    }
    c
}

fn transpose(a: &Mat) -> Mat {
    let mut t = [[0.0; DIM]; DIM];
    for (i, row) in a.iter().enumerate() {
        for (j, v) in row.iter().enumerate() {
            if let Some(x) = t.get_mut(j).and_then(|r| r.get_mut(i)) {
                *x = *v;
            }
        }
    }
    t
}

fn norm(a: &Mat) -> f64 {
    a.iter().flatten().fold(0.0, |m: f64, v| m.max(v.abs()))
}

/// The standard deviation of `s` (the estimated part of the manifold) per
/// unit standard deviation of white measurement noise on `y`: `sqrt(c' P c)`
/// with `P = Phi P Phi' + Gamma Gamma'` the estimate's steady covariance
/// (doubling: `P <- P + A P A'`, `A <- A^2`).
pub(super) fn noise_gain(d: &Design, n: usize, dt: f64) -> Result<f64, ConfigError> {
    let (phi, gamma, ne) = hgd(d, n, dt)?;
    let mut p = [[0.0; DIM]; DIM];
    for (i, row) in p.iter_mut().enumerate().take(ne) {
        for (j, v) in row.iter_mut().enumerate().take(ne) {
            *v = gamma.get(i).copied().unwrap_or(0.0) * gamma.get(j).copied().unwrap_or(0.0);
        }
    }
    let mut a = phi;
    for _ in 0..48 {
        let apa = mul(&mul(&a, &p, ne), &transpose(&a), ne);
        p.iter_mut()
            .flatten()
            .zip(apa.iter().flatten())
            .for_each(|(x, y)| *x += *y);
        a = mul(&a, &a, ne);
        if norm(&a) < 1e-18 {
            break;
        }
    }
    let c = manifold(d.law_order, d.lambda);
    let offset = usize::from(d.integral);
    let mut var = 0.0;
    for i in 0..n {
        for j in 0..n {
            let ci = c.get(i + offset).copied().unwrap_or(0.0);
            let cj = c.get(j + offset).copied().unwrap_or(0.0);
            var += ci * cj * p.get(i).and_then(|r| r.get(j)).copied().unwrap_or(0.0);
        }
    }
    if var.is_finite() && var >= 0.0 {
        Ok(F::sqrt(var))
    } else {
        Err(ConfigError::new(
            "noise_std",
            "gives a non-finite noise estimate for this design",
        ))
    }
}

/// The spectral radius of the linearized closed loop (plant, estimate and
/// integral), from `||M^m||^(1/m)` with `m = 2^40` by repeated squaring.
pub(super) fn loop_radius(d: &Design, n: usize, dt: f64, gain: f64) -> Result<f64, ConfigError> {
    let estimated = n > 1;
    let (phi, gamma, ne) = if estimated {
        hgd(d, n, dt)?
    } else {
        ([[0.0; DIM]; DIM], [0.0; DIM], 0)
    };
    let ni = usize::from(d.integral);
    let dim = n + ne + ni;
    let (xp, xe, xi) = (0, n, n + ne);
    let c = manifold(d.law_order, d.lambda);
    let k = 2.0 * d.k_u / d.eps_s;
    let at = |v: &[f64], i: usize| v.get(i).copied().unwrap_or(0.0);
    let fact = |j: usize| (1..=j).fold(1.0, |acc, i| acc * i as f64);
    let mut m = [[0.0; DIM]; DIM];
    let mut set = |i: usize, j: usize, v: f64| {
        if let Some(x) = m.get_mut(i).and_then(|r| r.get_mut(j)) {
            *x += v;
        }
    };
    // u = -k (c_I I + sum c_j z_j), z from the estimate (or measured at order 1)
    let mut law = [0.0; DIM];
    let mut add_law = |col: usize, v: f64| {
        if let Some(l) = law.get_mut(col) {
            *l += v;
        }
    };
    if d.integral {
        add_law(xi, -k * at(&c, 0));
    }
    for j in 0..n {
        add_law(if estimated { xe + j } else { xp + j }, -k * at(&c, j + ni));
    }
    for i in 0..n {
        for j in i..n {
            set(xp + i, xp + j, F::powi(dt, (j - i) as i32) / fact(j - i));
        }
        let b = gain * F::powi(dt, (n - i) as i32) / fact(n - i);
        for (col, l) in law.iter().enumerate().take(dim) {
            set(xp + i, col, b * l);
        }
    }
    for (i, row) in phi.iter().enumerate().take(ne) {
        for (j, v) in row.iter().enumerate().take(ne) {
            set(xe + i, xe + j, *v);
        }
        set(xe + i, xp, at(&gamma, i));
    }
    if d.integral {
        set(xi, xi, 1.0);
        set(xi, xp, dt);
    }
    let mut log_norm = 0.0;
    let mut a = m;
    for step in 0..40 {
        let nm = norm(&a);
        if !(nm.is_finite()) || nm == 0.0 {
            return if nm == 0.0 {
                Ok(0.0)
            } else {
                Err(ConfigError::new("dt", "gives a non-finite closed-loop matrix"))
            };
        }
        // a holds M^(2^step) / exp(log_norm)
        a.iter_mut().flatten().for_each(|v| *v /= nm);
        log_norm += F::ln(nm);
        if step == 39 {
            break;
        }
        a = mul(&a, &a, dim);
        log_norm *= 2.0;
    }
    Ok(F::exp(log_norm / F::powf(2.0, 39.0)))
}
