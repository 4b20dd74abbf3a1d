//! The linearized sampled loop of a design, for its checks: the
//! differentiator's noise gain and the closed loop's spectral radius.
//!
//! The nominal plant is a chain of `n` integrators with input gain `G`
//! (`y^(n) = G u`), held over each sample; the law is linearized at the
//! manifold, `u = -(2 k_u / eps_s) s` (log Gamma has slope 2 at 0), and uses
//! the estimate built from the samples before the current one, as
//! `Controller::step` does (docs/design.md §3.2), plus the current sample's
//! feedthrough with the first-order hold.

use super::coefficients::manifold;
use super::{Design, MAX_ORDER};
use crate::differentiator::{prefilter_gain, HighGain};
use crate::error::ConfigError;
use num_traits::Float as F;

/// Largest closed-loop dimension: plant, estimate (with the prefilter's
/// state) and integral.
const DIM: usize = 2 * MAX_ORDER + 2;
type Mat = [[f64; DIM]; DIM];

/// The design's differentiator (order `n`) as the loop sees it, zero-padded:
/// the state recursion `X_{k+1} = Phi X_k + Gamma e_k`, the estimate the law
/// uses, `Zhat_k = X_k[..n] + tail X_k[n] + direct e_k`, and the state's
/// dimension `ne`.
///
/// The state is `W_k = Zhat_k - D f_k`: the controller stores
/// `V_k = W_k + D f_(k-1)` (its `DiscreteHgd::current`), an equivalent
/// realization that needs the last input; with the held input's `Gamma`,
/// `Gamma_h = Gamma - D`, the first-order hold is `Zhat_k = W_k + D f_k`,
/// `W_{k+1} = Phi_h Zhat_k + Gamma_h f_k`, so
/// `W_{k+1} = Phi_h W_k + (Phi_h D + Gamma_h) f_k` (`D = 0` for the other
/// discretizations), and with the prefilter also the last input `f_(k-1)`
/// (`ne = n + 1`): `f_k = a f_(k-1) + b e_k` (`b` the prefilter's gain,
/// `a = 1 - b`).
struct Sampled {
    phi: Mat,
    gamma: [f64; DIM],
    tail: [f64; DIM],
    direct: [f64; DIM],
    ne: usize,
}

fn hgd(d: &Design, n: usize, dt: f64) -> Result<Sampled, ConfigError> {
    let (mut phi, held, feed) = plain_hgd(d, n, dt)?;
    // Phi_h D + Gamma_h: the stored estimate's input.
    let mut gamma = held;
    for (g, row) in gamma.iter_mut().zip(phi.iter()).take(n) {
        *g += row
            .iter()
            .zip(feed.iter())
            .take(n)
            .map(|(p, f)| p * f)
            .sum::<f64>();
    }
    let b = prefilter_gain(dt, d.prefilter);
    if b == 1.0 {
        return Ok(Sampled {
            phi,
            gamma,
            tail: [0.0; DIM],
            direct: feed,
            ne: n,
        });
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
    Ok(Sampled {
        phi,
        gamma,
        tail: feed.map(|f| (1.0 - b) * f),
        direct: feed.map(|f| b * f),
        ne: n + 1,
    })
}

/// `Phi`, `Gamma` and the feedthrough `D` of the design's differentiator
/// without its prefilter.
fn plain_hgd(d: &Design, n: usize, dt: f64) -> Result<(Mat, [f64; DIM], [f64; DIM]), ConfigError> {
    fn pad<const M: usize>(d: &Design, dt: f64) -> Result<(Mat, [f64; DIM], [f64; DIM]), ConfigError> {
        let mut a = [0.0; M];
        a.iter_mut().zip(d.a.iter()).for_each(|(x, y)| *x = *y);
        let h = HighGain::<f64, M>::new(d.mu, a, d.discretization).discretize(dt)?;
        let mut phi = [[0.0; DIM]; DIM];
        let mut gamma = [0.0; DIM];
        let mut feed = [0.0; DIM];
        for (row, src) in phi.iter_mut().zip(h.phi.iter()) {
            row.iter_mut().zip(src.iter()).for_each(|(x, y)| *x = *y);
        }
        feed.iter_mut()
            .zip(h.feedthrough.iter())
            .for_each(|(x, y)| *x = *y);
        // The W realization's Gamma (Sampled): the held input's less D.
        gamma
            .iter_mut()
            .zip(h.gamma.iter().zip(feed.iter()))
            .for_each(|(x, (g, d))| *x = g - d);
        Ok((phi, gamma, feed))
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
    let h = hgd(d, n, dt)?;
    let (phi, gamma, tail, direct, ne) = (h.phi, h.gamma, h.tail, h.direct, h.ne);
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
    // Zhat = E X + direct e with E = [I | tail]: Cov = E P E' + direct direct'
    // (X_k holds only the noise before sample k).
    let pij = |i: usize, j: usize| p.get(i).and_then(|r| r.get(j)).copied().unwrap_or(0.0);
    let at = |v: &[f64; DIM], i: usize| v.get(i).copied().unwrap_or(0.0);
    let cov = |i: usize, j: usize| {
        let (ti, tj) = (at(&tail, i), at(&tail, j));
        pij(i, j) + ti * pij(n, j) + tj * pij(i, n) + ti * tj * pij(n, n) + at(&direct, i) * at(&direct, j)
    };
    for i in 0..n {
        for j in 0..n {
            let ci = c.get(i + offset).copied().unwrap_or(0.0);
            let cj = c.get(j + offset).copied().unwrap_or(0.0);
            var += ci * cj * cov(i, j);
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
    let h = if estimated { Some(hgd(d, n, dt)?) } else { None };
    let zero = [0.0; DIM];
    let (phi, gamma, tail, direct, ne) = match &h {
        Some(h) => (h.phi, h.gamma, h.tail, h.direct, h.ne),
        None => ([[0.0; DIM]; DIM], zero, zero, zero, 0),
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
        let cj = -k * at(&c, j + ni);
        add_law(if estimated { xe + j } else { xp + j }, cj);
        if estimated {
            // The first-order hold's feedthrough (and the prefilter's state in it).
            if ne > n {
                add_law(xe + n, cj * at(&tail, j));
            }
            add_law(xp, cj * at(&direct, j));
        }
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
