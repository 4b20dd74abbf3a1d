//! `adversarial2` / `adversarial3` (issue 15): the worst single step over
//! adversarial inputs, next to the median step, for the paper's controller of
//! the order and for one that runs a root search at every step (LaMC over a
//! skewed fixed-time law at order 2, OMC over example 3's laws at order 3).
//!
//! The recorded closed-loop error is replayed with every 37th sample replaced
//! by an adversarial one (`±f32::MAX`, `1e19`, `1e30`, subnormal, NaN, inf,
//! ...), so the steps include outliers, consumed samples, restarts of the
//! estimate (famcc-core's recovery rule) and root searches from far-off
//! states. Each step is timed by SysTick (under `-icount shift=0` one tick is
//! 40 instructions); the median comes from a histogram of the tick counts.

use core::hint::black_box;
use famcc_core::{Config, Constraint, Controller, Feedback, HighGain, Skew};
use famcc_fw::{systick_now, systick_start, ticks, Out};
use famcc_fw_common::out::Sink;

/// The samples injected into the recorded error, in turn.
const PALETTE: [f32; 12] = [
    f32::MAX,
    -1e19,
    3.4e38,
    -f32::MAX,
    1e30,
    -1e10,
    1e-40,
    f32::NAN,
    f32::INFINITY,
    1e6,
    -3e18,
    1e15,
];
/// One sample in `EVERY` is adversarial.
const EVERY: usize = 37;
/// Tick counts above this share the histogram's last bin (the median only).
const BINS: usize = 2048;

/// The largest and the median SysTick ticks per step, and the sample of the
/// largest.
fn measure<const M: usize>(c: &mut Controller<f32, M>, e: &[f32]) -> (u32, u32, usize) {
    let mut hist = [0u32; BINS];
    systick_start();
    let (mut max, mut at) = (0u32, 0usize);
    for (k, &x) in e.iter().enumerate() {
        let x = if k % EVERY == EVERY - 1 {
            PALETTE.get((k / EVERY) % PALETTE.len()).copied().unwrap_or(x)
        } else {
            x
        };
        let t0 = systick_now();
        black_box(c.step(black_box(x)).unwrap_or(f32::NAN));
        let d = ticks(t0, systick_now());
        if let Some(h) = hist.get_mut((d as usize).min(BINS - 1)) {
            *h += 1;
        }
        if d > max {
            max = d;
            at = k;
        }
    }
    let half = (e.len() as u32).div_ceil(2);
    let (mut seen, mut median) = (0u32, 0u32);
    for (t, n) in hist.iter().enumerate() {
        seen += n;
        if seen >= half {
            median = t as u32;
            break;
        }
    }
    (max, median, at)
}

/// Order 2, LaMC over a skewed fixed-time law: `h_v` by root search every step.
fn rooted2() -> Option<Controller<f32, 2>> {
    let law = Feedback::FixedTime {
        alpha: 1.0,
        p: 0.5,
        beta: 0.5,
        q: 2.0,
    };
    Config::<f32, 2>::builder(
        1e-3,
        &[(law, Some(Skew::nonsingular(0.2, 0.1, 0.1)))],
        Constraint::Lateral { eps: 0.1 },
        5.0,
    )
    .differentiator(Some(HighGain::paper()))
    .build()
    .ok()
    .map(Controller::new)
}

/// Order 3, OMC over example 3's laws: `x_c` by root search every step.
fn rooted3() -> Option<Controller<f32, 3>> {
    let s1 = (
        Feedback::FixedTime {
            alpha: 1.0,
            p: 0.5,
            beta: 0.5,
            q: 2.0,
        },
        Some(Skew::nonsingular(0.1, 0.1, 0.1)),
    );
    let s2 = (
        Feedback::FixedTime {
            alpha: 2.0,
            p: 0.5,
            beta: 1.0,
            q: 2.0,
        },
        Some(Skew::nonsingular(3.0, 0.2, 1.0)),
    );
    Config::<f32, 3>::builder(
        1e-3,
        &[s1, s2],
        Constraint::Oblique {
            eps_x: 0.1,
            eps_y: 3.0,
        },
        30.0,
    )
    .differentiator(Some(HighGain::paper()))
    .build()
    .ok()
    .map(Controller::new)
}

fn report(out: &mut Out, order: &str, name: &str, r: Option<(u32, u32, usize)>, steps: usize) {
    out.s("adversarial ").s(order).s(" ").s(name);
    match r {
        Some((max, median, at)) => out
            .s(" steps=")
            .u(steps as u64)
            .s(" max_ticks=")
            .u(u64::from(max))
            .s(" median_ticks=")
            .u(u64::from(median))
            .s(" at_k=")
            .u(at as u64)
            .nl(),
        None => out.s(" config rejected").nl(),
    };
}

/// Runs the order-2 measurements on the recorded error `e`.
pub fn order2(out: &mut Out, paper: &mut Controller<f32, 2>, e: &[f32]) {
    report(out, "o2", "paper", Some(measure(paper, e)), e.len());
    report(
        out,
        "o2",
        "root-search",
        rooted2().map(|mut c| measure(&mut c, e)),
        e.len(),
    );
}

/// Runs the order-3 measurements on the recorded error `e`.
pub fn order3(out: &mut Out, paper: &mut Controller<f32, 3>, e: &[f32]) {
    report(out, "o3", "paper", Some(measure(paper, e)), e.len());
    report(
        out,
        "o3",
        "root-search",
        rooted3().map(|mut c| measure(&mut c, e)),
        e.len(),
    );
}
