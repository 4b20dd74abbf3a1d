//! The building blocks in f32 agree with f64 on grids of inputs.
//!
//! Every grid point and parameter is exactly representable in f32, so both
//! precisions evaluate the same mathematical input and the difference is f32's
//! own rounding inside famcc. Tolerance, for an f64 result `y` at input `x`:
//!
//!   |y32 - y| <= 1e-5 |y| + 2 spread + 1e-30,
//!
//! - `1e-5 |y|`: about 80 f32 ulps (eps32 = 1.19e-7), room for the dozens of
//!   roundings in a jet or a skewed law;
//! - `spread = max |f(x +- 4 eps32 scale(x)) - y|` computed in f64, with
//!   `scale(x) = |x|` (for the transitions: the distance to the nearer end,
//!   which they are evaluated on; both ends are exact): where the function
//!   is ill-conditioned (the exp tails of S and T, where `exp(-w)` with `w` up to
//!   ~87 turns a relative error eps32 of `w` into 87 eps32 = 1e-5 of the result;
//!   near the jump of the Moulay law; near zero crossings of skewed laws)
//!   f32's intermediate rounding acts like a few-ulp perturbation of the input,
//!   and no f32 implementation can do better than that;
//! - `1e-30`: f32 has no normal numbers below 1.2e-38 and famcc flushes the
//!   transitions to exactly 0 there (their derivatives, up to ~1e8 times larger
//!   than the value near the cutoff, stay far below 1e-30).
//!
//! Both results must have the same infinities; NaN never passes.

use famcc_core::envelope::rho;
use famcc_core::transition::{self, Transition};
use famcc_core::{bounds, manifold, Feedback, Gamma, Jet, Real, Skew, SkewedLaw};

const REL: f64 = 1e-5;
const FLOOR: f64 = 1e-30;
const EPS32: f64 = f32::EPSILON as f64;

/// Compares `f32` against `f64` over `grid`; returns the number of points.
/// The input perturbation for the spread is `4 eps32 |x|`.
fn agree(name: &str, grid: &[f32], f: impl Fn(f64) -> f64, g: impl Fn(f32) -> f32) -> usize {
    agree_with(name, grid, f, g, |_| 0.0, |x| x.abs())
}

/// As [`agree`], for a result that is a sum of terms of total magnitude
/// `|y| + terms(x)`: the relative part of the tolerance applies to that
/// magnitude (rounding in f32 is relative to the summands, not to a sum that
/// cancels).
fn agree_sum(
    name: &str,
    grid: &[f32],
    f: impl Fn(f64) -> f64,
    g: impl Fn(f32) -> f32,
    terms: impl Fn(f64) -> f64,
) -> usize {
    agree_with(name, grid, f, g, terms, |x| x.abs())
}

/// The general comparison: `terms` as in [`agree_sum`]; `scale(x)` is the size
/// that f32 rounding is relative to at `x` (the spread perturbs `x` by
/// `+-4 eps32 scale(x)`): `|x|` in general, the distance to the nearer end for
/// the transitions (which are evaluated on that distance; both ends are exact).
fn agree_with(
    name: &str,
    grid: &[f32],
    f: impl Fn(f64) -> f64,
    g: impl Fn(f32) -> f32,
    terms: impl Fn(f64) -> f64,
    scale: impl Fn(f64) -> f64,
) -> usize {
    let mut bad = Vec::new();
    for &x32 in grid {
        let x = f64::from(x32);
        let y = f(x);
        let y32 = f64::from(g(x32));
        let ok = if y.is_nan() || y32.is_nan() {
            false
        } else if y.is_infinite() || y32.is_infinite() {
            // Same infinity, or an f64 result beyond f32's range.
            let beyond_f32 = y.abs() > f64::from(f32::MAX);
            y32.is_infinite() && beyond_f32 && y.signum() == y32.signum()
        } else {
            let d = 4.0 * EPS32 * scale(x);
            let spread = [x + d, x - d]
                .iter()
                .map(|xp| (f(*xp) - y).abs())
                .fold(0.0, f64::max);
            let spread = if spread.is_finite() { spread } else { f64::INFINITY };
            (y32 - y).abs() <= REL * (y.abs() + terms(x)) + 2.0 * spread + FLOOR
        };
        if !ok {
            bad.push(format!("x = {x:e}: f64 {y:e}, f32 {y32:e}"));
        }
    }
    assert!(
        bad.is_empty(),
        "{name}: {} of {} points disagree:\n{}",
        bad.len(),
        grid.len(),
        bad.join("\n")
    );
    grid.len()
}

/// Distance from `z` to the nearer end of the transition, 0 or 1 (or -1 for U).
fn to_ends(z: f64) -> f64 {
    z.abs().min((z.abs() - 1.0).abs())
}

/// `lo..=hi` in steps of `step` (all exactly representable for power-of-2 steps).
fn lin(lo: f32, hi: f32, step: f32) -> Vec<f32> {
    let n = ((hi - lo) / step).round() as i32;
    (0..=n).map(|i| lo + step * i as f32).collect()
}

/// `+-2^k` for `k` in `lo..=hi`, and the points just inside 0 and 1.
fn edges(lo: i32, hi: i32) -> Vec<f32> {
    let mut v = Vec::new();
    for k in lo..=hi {
        let p = 2f32.powi(k);
        v.extend([p, -p, 1.0 - p.min(0.5), 1.0 + p]);
    }
    v
}

/// Deterministic pseudo-random f32 values with full mantissas (dyadic grid
/// points alone make the polynomial arithmetic exact and hide cancellation):
/// `n` uniform in `[lo, hi)`, and `z`, `1 - z` for `z = u 2^-k`, `u` in [0.5, 1).
fn scattered(n: usize, lo: f32, hi: f32) -> Vec<f32> {
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut next = move || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        ((state >> 40) as f32) / (1u64 << 24) as f32
    };
    let mut v: Vec<f32> = (0..n).map(|_| lo + (hi - lo) * next()).collect();
    for k in 1..=40 {
        for _ in 0..8 {
            let z = (0.5 + 0.5 * next()) * 2f32.powi(-k);
            v.extend([z, -z, 1.0 - z, 1.0 + z, -1.0 + z]);
        }
    }
    v
}

const ALL_S: [Transition; 4] = [
    Transition::Exponential,
    Transition::Cubic,
    Transition::Quintic,
    Transition::Sine,
];

fn s_rate<T: Real>(tr: Transition, z: T, k: usize) -> T {
    tr.double_ended_jet(Jet::<T, 3>::from_derivatives([z, T::one(), T::zero()]))
        .derivative(k)
}

fn t_rate<T: Real>(z: T) -> T {
    transition::single_ended_jet(Jet::<T, 2>::from_derivatives([z, T::one()])).derivative(1)
}

#[test]
fn transitions_f32_matches_f64() {
    let mut grid = lin(-0.5, 1.5, 1.0 / 512.0);
    grid.extend(edges(-40, -1));
    grid.extend(scattered(2000, -0.25, 1.25));
    let mut n = 0;
    n += agree(
        "T",
        &grid,
        transition::single_ended::<f64>,
        transition::single_ended::<f32>,
    );
    n += agree("T'", &grid, t_rate::<f64>, t_rate::<f32>);
    let none = |_: f64| 0.0;
    for tr in ALL_S {
        n += agree_with(
            &format!("{tr:?} S"),
            &grid,
            |z| tr.double_ended(z),
            |z| tr.double_ended(z),
            none,
            to_ends,
        );
        n += agree_with(
            &format!("{tr:?} U"),
            &grid,
            |z| tr.interval(z),
            |z| tr.interval(z),
            none,
            to_ends,
        );
        n += agree_with(
            &format!("{tr:?} S'"),
            &grid,
            |z| s_rate(tr, z, 1),
            |z| s_rate(tr, z, 1),
            none,
            to_ends,
        );
        n += agree_with(
            &format!("{tr:?} S''"),
            &grid,
            |z| s_rate(tr, z, 2),
            |z| s_rate(tr, z, 2),
            none,
            to_ends,
        );
    }
    assert!(n > 20_000, "{n} points");
}

#[test]
fn transition_between_rate_f32_matches_f64() {
    let mut grid = lin(-1.5, 2.5, 1.0 / 256.0);
    grid.extend(scattered(500, -1.5, 3.5));
    for (x1, x2) in [
        (0.0f32, 1.0f32),
        (-0.125, 0.125),
        (0.0, 0.25),
        (1.0, 0.0),
        (-1.0, 3.0),
    ] {
        for (dx, dx1, dx2) in [
            (1.0f32, 0.0f32, 0.0f32),
            (-2.5, 0.0, 0.0),
            (0.25, 0.125, -0.25),
            (0.0, 1.0, 1.0),
        ] {
            // z = (x - x1)/(x2 - x1) is rounded relative to |x - x1| (for the
            // reversed pair, 1 - x loses x's low bits in f32).
            let ends = |x: f64| (x - f64::from(x1)).abs();
            let none = |_: f64| 0.0;
            for tr in ALL_S {
                agree_with(
                    &format!("{tr:?} between_rate {x1}..{x2} ({dx}, {dx1}, {dx2})"),
                    &grid,
                    |x| {
                        tr.between_rate(
                            [x, f64::from(dx)],
                            [f64::from(x1), f64::from(dx1)],
                            [f64::from(x2), f64::from(dx2)],
                        )
                    },
                    |x| tr.between_rate([x, dx], [x1, dx1], [x2, dx2]),
                    none,
                    ends,
                );
                agree_with(
                    &format!("{tr:?} between {x1}..{x2}"),
                    &grid,
                    |x| tr.between(x, f64::from(x1), f64::from(x2)),
                    |x| tr.between(x, x1, x2),
                    none,
                    ends,
                );
            }
        }
    }
}

#[test]
fn envelope_and_gamma_f32_matches_f64() {
    let t = lin(-0.5, 2.5, 1.0 / 256.0);
    for (rho0, eps, ts) in [
        (2.0f32, 0.125f32, 1.0f32),
        (50.0, 0.25, 3.0),
        (0.5, 0.0078125, 0.25),
    ] {
        agree(
            "rho",
            &t,
            |t| rho(f64::from(rho0), f64::from(eps), f64::from(ts), t),
            |t| rho(rho0, eps, ts, t),
        );
    }
    let edge = 1.0 - 1.0 / 512.0;
    let mut xi = lin(-edge, edge, 1.0 / 1024.0);
    xi.extend(
        scattered(1000, -0.999, 0.999)
            .into_iter()
            .filter(|x| x.abs() < 1.0),
    );
    xi.extend((1..=20).map(|k| 1.0 - 2f32.powi(-k)));
    xi.extend((1..=20).map(|k| -1.0 + 2f32.powi(-k)));
    for g in [Gamma::Log, Gamma::Rational] {
        agree(&format!("{g:?}"), &xi, |x| g.eval(x), |x| g.eval(x));
    }
}

/// The laws with parameters exactly representable in f32.
fn law<T: Real>(i: usize) -> Feedback<T> {
    let c = T::from_f64;
    match i {
        0 => Feedback::Linear { k: c(1.5) },
        1 => Feedback::FiniteTime { k: c(1.0), p: c(0.5) },
        2 => Feedback::FixedTime {
            alpha: c(2.0),
            p: c(0.5),
            beta: c(1.0),
            q: c(2.0),
        },
        3 => Feedback::VariableExponent {
            k: c(1.5),
            r_b: c(0.5),
            r_1: c(2.0),
            r_t: c(3.0),
        },
        4 => Feedback::FiniteTime {
            k: c(3.0),
            p: c(0.75),
        },
        5 => Feedback::FixedTime {
            alpha: c(1.0),
            p: c(0.25),
            beta: c(0.5),
            q: c(2.5),
        },
        _ => Feedback::MoulayDiscontinuous {
            beta: c(1.0),
            lambda: c(2.0),
            mu: c(0.125),
        },
    }
}

fn law_grid() -> Vec<f32> {
    let mut g = lin(-4.0, 4.0, 1.0 / 64.0);
    g.extend(scattered(500, -8.0, 8.0));
    for k in -60..=12 {
        let p = 2f32.powi(k);
        g.extend([p, -p, 1.5 * p, -1.5 * p]);
    }
    g
}

#[test]
fn feedback_laws_f32_matches_f64() {
    let grid = law_grid();
    for i in 0..7 {
        let name = format!("{:?}", law::<f64>(i));
        agree(
            &format!("{name} eval"),
            &grid,
            |s| law::<f64>(i).eval(s),
            |s| law::<f32>(i).eval(s),
        );
        let nonzero: Vec<f32> = grid.iter().copied().filter(|s| *s != 0.0).collect();
        agree(
            &format!("{name} slope"),
            &nonzero,
            |s| law::<f64>(i).slope(s),
            |s| law::<f32>(i).slope(s),
        );
    }
}

fn skewed<T: Real>(i: usize, nsmd: bool) -> SkewedLaw<T> {
    let skew = if nsmd {
        Skew::nonsingular(T::from_f64(0.25), T::from_f64(0.125), T::from_f64(0.125))
    } else {
        Skew::smooth(T::from_f64(0.15625), T::from_f64(0.125))
    };
    SkewedLaw::new(law(i), Some(skew)).unwrap_or_else(|e| panic!("{e}"))
}

fn skewed_rate<T: Real>(i: usize, nsmd: bool, s: T, ds: T) -> T {
    skewed::<T>(i, nsmd)
        .eval_jet(Jet::<T, 2>::from_derivatives([s, ds]))
        .derivative(1)
}

fn skewed_second<T: Real>(i: usize, s: T) -> T {
    // d^2/dt^2 h_m(s(t)) for s' = 1, s'' = -0.5 (NSMD only: SSMD is singular at 0).
    skewed::<T>(i, true)
        .eval_jet(Jet::<T, 3>::from_derivatives([s, T::one(), T::from_f64(-0.5)]))
        .derivative(2)
}

#[test]
fn skewed_laws_f32_matches_f64() {
    // Skewed laws add the offset T1(s) eps_s (and NSMD the line -k_p s) to
    // h_p(s); T1 is computed from (s + eps_z)/(2 eps_z), which absorbs a tiny s
    // in f32. So the relative tolerance applies to the summands' magnitude:
    // |h_p(s)| + eps_s (+ k_p |s|) for values, |h_p'(s) s'| + |T1'| eps_s |s'|
    // (+ k_p |s'|) for rates.
    let mut grid = lin(-1.0, 1.0, 1.0 / 512.0);
    for k in -60..=-1 {
        let p = 2f32.powi(k);
        grid.extend([p, -p]);
    }
    grid.extend(scattered(500, -1.0, 1.0));
    let eps_s = 0.25; // the larger of the two offsets
    let t1_slope = 2.0 * 2.0 / (2.0 * 0.125); // max |T1'| = 2 max S' / (2 eps_z)
    for i in [1usize, 2, 3] {
        let hp = law::<f64>(i);
        for nsmd in [false, true] {
            let name = format!("{hp:?} nsmd={nsmd}");
            let kp = skewed::<f64>(i, nsmd).k_p();
            agree_sum(
                &format!("{name} eval"),
                &grid,
                |s| skewed::<f64>(i, nsmd).eval(s),
                |s| skewed::<f32>(i, nsmd).eval(s),
                |s| hp.eval(s).abs() + eps_s + kp * s.abs(),
            );
            let pts: Vec<f32> = grid.iter().copied().filter(|s| nsmd || *s != 0.0).collect();
            let ds = 0.75;
            agree_sum(
                &format!("{name} rate"),
                &pts,
                |s| skewed_rate(i, nsmd, s, ds),
                |s| skewed_rate(i, nsmd, s, ds as f32),
                |s| {
                    let slope = if s == 0.0 { 0.0 } else { hp.slope(s).abs() };
                    (slope + t1_slope * eps_s + kp) * ds
                },
            );
        }
        agree_sum(
            &format!("{hp:?} NSMD second derivative"),
            &grid,
            |s| skewed_second(i, s),
            |s| skewed_second(i, s),
            |s| {
                // Summands of h_m'': (h_p(s(t)))'', (T1(s(t)))'' eps_s, k_p s''.
                let st = Jet::<f64, 3>::from_derivatives([s, 1.0, -0.5]);
                // h_p enters weighted by T2 = U(s/eps_z) (0 near s = 0).
                let t2 = Transition::Exponential.interval(s / 0.125);
                let hp2 = if t2 == 0.0 {
                    0.0
                } else {
                    t2 * hp.eval_jet(st).derivative(2).abs()
                };
                let t1 = Transition::Exponential
                    .double_ended_jet((st + 0.125) / 0.25)
                    .derivative(2)
                    .abs()
                    * 2.0;
                hp2 + t1 * eps_s + skewed::<f64>(i, true).k_p() * 0.5
            },
        );
    }
}

fn stages<T: Real>() -> [SkewedLaw<T>; 2] {
    let c = T::from_f64;
    [
        SkewedLaw::new(
            Feedback::FixedTime {
                alpha: c(1.0),
                p: c(0.5),
                beta: c(0.5),
                q: c(2.0),
            },
            Some(Skew::nonsingular(c(0.125), c(0.125), c(0.125))),
        )
        .unwrap_or_else(|e| panic!("{e}")),
        SkewedLaw::new(
            Feedback::FixedTime {
                alpha: c(2.0),
                p: c(0.5),
                beta: c(1.0),
                q: c(2.0),
            },
            Some(Skew::nonsingular(c(3.0), c(0.25), c(1.0))),
        )
        .unwrap_or_else(|e| panic!("{e}")),
    ]
}

fn manifold_s<T: Real>(z1: T, z2: T, z3: T) -> T {
    manifold::evaluate(&[z1, z2, z3], &stages::<T>()).s()
}

#[test]
fn manifold_f32_matches_f64() {
    // Third-order nonlinear manifold (example 3's structure), varying z1 on a
    // grid for a spread of (z2, z3).
    let mut grid = lin(-2.0, 2.0, 1.0 / 128.0);
    for k in -40..=-1 {
        grid.extend([2f32.powi(k), -(2f32.powi(k))]);
    }
    grid.extend(scattered(300, -2.0, 2.0));
    let mut n = 0;
    for (z2, z3) in [(0.0f32, 0.0f32), (0.5, -1.0), (-3.0, 2.5), (0.0625, 8.0)] {
        n += agree(
            &format!("manifold s (z2 = {z2}, z3 = {z3})"),
            &grid,
            |z1| manifold_s(z1, f64::from(z2), f64::from(z3)),
            |z1| manifold_s(z1, z2, z3),
        );
    }
    // Linear third-order manifold: s = z3 + 5 z2 + 6 z1.
    let lin_stages = |k1: f64, k2: f64| {
        [
            SkewedLaw::new(Feedback::Linear { k: k1 }, None).unwrap_or_else(|e| panic!("{e}")),
            SkewedLaw::new(Feedback::Linear { k: k2 }, None).unwrap_or_else(|e| panic!("{e}")),
        ]
    };
    let lin32 = [
        SkewedLaw::new(Feedback::Linear { k: 2.0f32 }, None).unwrap_or_else(|e| panic!("{e}")),
        SkewedLaw::new(Feedback::Linear { k: 3.0f32 }, None).unwrap_or_else(|e| panic!("{e}")),
    ];
    n += agree(
        "linear manifold",
        &grid,
        |z1| manifold::evaluate(&[z1, 0.5, -1.0], &lin_stages(2.0, 3.0)).s(),
        |z1| manifold::evaluate(&[z1, 0.5f32, -1.0], &lin32).s(),
    );
    assert!(n > 2000);
}

#[test]
fn bounds_f32_matches_f64() {
    let z = lin(-4.0, 4.0, 1.0 / 16.0);
    agree(
        "finite_time",
        &z,
        |z| bounds::finite_time(1.0, 0.5, z),
        |z| bounds::finite_time(1.0f32, 0.5, z),
    );
    let k = lin(0.25, 4.0, 1.0 / 16.0);
    agree(
        "variable_exponent",
        &k,
        |k| bounds::variable_exponent(k, 0.5, 2.0, 3.0),
        |k| bounds::variable_exponent(k, 0.5f32, 2.0, 3.0),
    );
    agree(
        "fixed_time",
        &k,
        |a| bounds::fixed_time(&[(a, 0.5, 0.5, 2.0), (2.0, 0.5, 1.0, 2.0)]),
        |a| bounds::fixed_time(&[(a, 0.5f32, 0.5, 2.0), (2.0, 0.5, 1.0, 2.0)]),
    );
}
