//! The high-gain differentiator (paper eq. (34), HGD), discretized once at
//! construction, and the paper's choice of its parameters
//! ([`HighGain::paper`]: `mu = 0.01`, `a = (4, 4)` at order 2 and `(4, 6, 4)`
//! at order 3 as in the paper's examples, binomial `(s + 2)^n` otherwise).
//!
//! The paper estimates the error vector `Z = (z1, z1', ..., z1^(N-1))` from the
//! measured `z1` alone with
//!
//! ```text
//! dZhat/dt = A Zhat + H (z1 - C Zhat) = (A - H C) Zhat + H z1        (eq. (34))
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
//! (docs/design.md §3.3), by one of four [`Discretization`]s. The default,
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
//! where eq. (34) reads `dw/dsigma = M0 w + a z1` with `sigma = t / mu` and
//! `M0 = A - a C` (all entries `O(a_i)`, independent of `mu`). The recursion
//! for `w` over `tau = dt / mu` is computed and mapped back with
//! `Phi_ij = Phi0_ij mu^(j-i)`, `Gamma_i = Gamma0_i mu^(1-i)`. This diagonal
//! similarity is exact in theory and keeps the non-normality `mu^(1-N)` of
//! `A - H C` out of the matrix exponential, so small entries of `Phi` are
//! accurate relative to their own size, not only to the largest entry.

mod defaults;
mod discretize;
mod expm;
#[cfg(feature = "observer")]
mod extended;
mod high_gain;
mod linalg;
mod recursion;

pub use defaults::{
    auto_discretization, auto_discretization_at, auto_mu, paper_coefficients, EXACT_DT_PER_MU,
    FOH_MIN_MU_PER_DT, FOH_SAMPLE_DELAY, PAPER_MU, PAPER_MU_PER_DT, SAMPLE_DELAY,
};
#[cfg(feature = "observer")]
pub use extended::{DiscreteExtended, ExtendedHighGain};
pub(crate) use high_gain::prefilter_gain;
pub use high_gain::{Discretization, HighGain};
pub use linalg::spectral_radius;
pub use recursion::DiscreteHgd;
pub(crate) use recursion::Recursion;

/// True when output feedback at `order` needs a differentiator: at order 1
/// the measured error is the whole error vector `Z = (e)` (docs/design.md
/// §3.5), so `step(e)` works without one.
pub const fn needed_at(order: usize) -> bool {
    order > 1
}
