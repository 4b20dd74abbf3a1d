//! The default (`auto`) differentiator closes the loop at plant orders 4, 5
//! and 6 at 1 kHz (issue 13), with and without integral action, on a chain of
//! integrators of the paper's class: nonlinear `F`, time-varying `G`,
//!
//! `x_i' = (1 + 0.1 sin(t + i)) x_{i+1} + 0.2 sin(x_1) - 0.1 x_i`, `x_{n+1} = u`,
//!
//! tracking `y_d = 0.5 sin t` from `x0 = (0.5, 0, ...)`. The stage laws are
//! `Linear(lambda)`, slow enough for the differentiator (the phase budget of
//! docs/design.md §3.8): `loop_rate = (2 / mu) / q`, `lambda = loop_rate / r`,
//! `q = r = (2 N - 1) / 0.8` for the law order `N`, `k_u = 2.28`, and the
//! longitudinal width `eps = 2 k_u 1.1 / loop_rate`.
//!
//! Run with `--nocapture` to see the figures.
#![allow(clippy::unwrap_used, clippy::indexing_slicing)]

use famcc_core::differentiator::PAPER_MU;
use famcc_core::{Config, Constraint, Controller, Discretization, Feedback, HighGain};

const DT: f64 = 1e-3;
const T_END: f64 = 30.0;
const K_U: f64 = 2.28;

/// `dx/dt` of the plant of order `n` (the first `n` entries of `x`).
fn rhs<const M: usize>(n: usize, t: f64, x: &[f64; M], u: f64) -> [f64; M] {
    let mut d = [0.0; M];
    for i in 0..n {
        let next = if i + 1 < n { x[i + 1] } else { u };
        let g = 1.0 + 0.1 * (t + (i + 1) as f64).sin();
        d[i] = g * next + 0.2 * x[0].sin() - 0.1 * x[i];
    }
    d
}

fn rk4<const M: usize>(n: usize, t: f64, x: &[f64; M], u: f64, h: f64) -> [f64; M] {
    let add = |a: &[f64; M], b: &[f64; M], s: f64| {
        let mut o = *a;
        o.iter_mut().zip(b).for_each(|(o, b)| *o += s * b);
        o
    };
    let k1 = rhs(n, t, x, u);
    let k2 = rhs(n, t + h / 2.0, &add(x, &k1, h / 2.0), u);
    let k3 = rhs(n, t + h / 2.0, &add(x, &k2, h / 2.0), u);
    let k4 = rhs(n, t + h, &add(x, &k3, h), u);
    let mut o = *x;
    for i in 0..M {
        o[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
    }
    o
}

/// The configuration of law order `N` for plant order `n = N - integral`.
fn config<const N: usize>(integral: bool) -> Config<f64, N> {
    let q = (2.0 * N as f64 - 1.0) / 0.8;
    let loop_rate = 2.0 / PAPER_MU / q;
    let lambda = loop_rate / q;
    let eps = 2.0 * K_U * 1.1 / loop_rate;
    let laws = [(Feedback::Linear { k: lambda }, None); 8];
    let plant = N - usize::from(integral);
    let cfg = Config::<f64, N>::builder(DT, &laws[..N - 1], Constraint::Longitudinal { eps }, K_U)
        .settle_time(5.0)
        .differentiator(Some(HighGain::auto_for(plant)))
        .integral(integral)
        .build()
        .unwrap();
    let h = cfg.differentiator().unwrap();
    assert_eq!((h.mu, h.discretization), (PAPER_MU, Discretization::Tustin));
    cfg
}

struct Outcome {
    /// max |e| over the last 5 s.
    tail_error: f64,
    /// max |u| over the run.
    peak_u: f64,
    /// expanded at any step of the last 5 s.
    expanded_late: bool,
}

fn run<const N: usize>(integral: bool) -> Outcome {
    let n = N - usize::from(integral);
    let mut c = Controller::new(config::<N>(integral));
    let mut x = [0.0; 8];
    x[0] = 0.5;
    let steps = (T_END / DT) as usize;
    let mut out = Outcome {
        tail_error: 0.0,
        peak_u: 0.0,
        expanded_late: false,
    };
    let mut u_prev = None;
    for k in 0..steps {
        let t = k as f64 * DT;
        let e = x[0] - 0.5 * t.sin();
        let u = c.step_applied(e, u_prev).unwrap();
        assert!(
            u.is_finite() && x.iter().all(|v| v.is_finite() && v.abs() < 1e3),
            "diverged at t = {t}"
        );
        out.peak_u = out.peak_u.max(u.abs());
        if t > T_END - 5.0 {
            out.tail_error = out.tail_error.max(e.abs());
            out.expanded_late |= c.diagnostics().expanded;
        }
        x = rk4(n, t, &x, u, DT);
        u_prev = Some(u);
    }
    println!(
        "n = {n}, law order {N}, integral {integral}: max|e| over the last 5 s {:.2e}, max|u| {:.3}, \
         expanded late {}",
        out.tail_error, out.peak_u, out.expanded_late
    );
    out
}

fn check(o: &Outcome, bound: f64) {
    assert!(o.tail_error < bound, "tail error {} >= {bound}", o.tail_error);
    assert!(!o.expanded_late, "bounds still expanded after settling");
}

#[test]
fn auto_closes_the_loop_at_order_4() {
    check(&run::<4>(false), 0.05);
}

#[test]
fn auto_closes_the_loop_at_order_5() {
    check(&run::<5>(false), 0.05);
}

#[test]
fn auto_closes_the_loop_at_order_6() {
    check(&run::<6>(false), 0.05);
}

#[test]
fn auto_with_integral_action_closes_the_loop_at_orders_4_to_6() {
    check(&run::<5>(true), 0.02);
    check(&run::<6>(true), 0.02);
    check(&run::<7>(true), 0.02);
}
