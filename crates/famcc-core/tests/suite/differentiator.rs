//! The high-gain differentiator (eq. (34) (HGD)): discretizations against closed
//! forms, a fine RK4 reference, the DC gain, stability for every dt, the
//! Hurwitz rule and f32/f64 agreement.
#![allow(clippy::needless_range_loop, clippy::unwrap_used, clippy::indexing_slicing)]
use famcc_core::{Discretization, HighGain};

/// The Hurwitz rule through the public API (all coefficients here are > 0,
/// so `validate` fails only on the Routh-Hurwitz test).
fn routh_hurwitz<const N: usize>(a: &[f64; N]) -> bool {
    HighGain::new(1.0, *a, Discretization::Exact).validate().is_ok()
}

fn mat_mul<const N: usize>(x: &[[f64; N]; N], y: &[[f64; N]; N]) -> [[f64; N]; N] {
    let mut out = [[0.0; N]; N];
    for i in 0..N {
        for j in 0..N {
            out[i][j] = (0..N).map(|k| x[i][k] * y[k][j]).sum();
        }
    }
    out
}

const PAPER2: [f64; 2] = [4.0, 4.0];
const PAPER3: [f64; 3] = [4.0, 6.0, 4.0];

/// Coefficients of (s + 1)^N without s^N.
fn binomial<const N: usize>() -> [f64; N] {
    let mut a = [0.0; N];
    let mut c = 1.0;
    for k in 0..N {
        c = c * (N - k) as f64 / (k + 1) as f64;
        a[k] = c;
    }
    a
}

/// Continuous eq. (34) (HGD) right-hand side.
fn rhs<const N: usize>(mu: f64, a: &[f64; N], z: &[f64; N], e: f64) -> [f64; N] {
    let mut d = [0.0; N];
    let innov = e - z[0];
    for i in 0..N {
        let next = if i + 1 < N { z[i + 1] } else { 0.0 };
        d[i] = next + a[i] / mu.powi(i as i32 + 1) * innov;
    }
    d
}

/// Classical RK4 of eq. (34) (HGD) over `dt` with `steps` steps and held `e`.
fn rk4<const N: usize>(mu: f64, a: &[f64; N], z0: [f64; N], e: f64, dt: f64, steps: usize) -> [f64; N] {
    let h = dt / steps as f64;
    let mut z = z0;
    let add = |z: &[f64; N], k: &[f64; N], s: f64| {
        let mut o = *z;
        for i in 0..N {
            o[i] += s * k[i];
        }
        o
    };
    for _ in 0..steps {
        let k1 = rhs(mu, a, &z, e);
        let k2 = rhs(mu, a, &add(&z, &k1, h / 2.0), e);
        let k3 = rhs(mu, a, &add(&z, &k2, h / 2.0), e);
        let k4 = rhs(mu, a, &add(&z, &k3, h), e);
        for i in 0..N {
            z[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
    }
    z
}

fn rel_err(x: f64, y: f64) -> f64 {
    if y == 0.0 {
        x.abs()
    } else {
        ((x - y) / y).abs()
    }
}

/// Relative error; entries below 1e-3 of their natural scale `mu^(j-i)`
/// (e.g. Phi_11 = exp(-1)(1 - 1) = 0 for order 2 at dt = mu / 2, where
/// RK4's own rounding is ~2e-15) are compared against that floor.
fn rel_err_floor(x: f64, y: f64, scale: f64) -> f64 {
    (x - y).abs() / y.abs().max(1e-3 * scale)
}

fn norm_inf<const N: usize>(m: &[[f64; N]; N]) -> f64 {
    m.iter()
        .map(|r| r.iter().map(|x| x.abs()).sum::<f64>())
        .fold(0.0, f64::max)
}

fn square<const N: usize>(m: &[[f64; N]; N]) -> [[f64; N]; N] {
    mat_mul(m, m)
}

#[test]
fn order1_matches_closed_form() {
    for &mu in &[1e-3_f64, 0.01, 0.3] {
        for &a1 in &[0.5, 1.0, 7.0] {
            for &dt in &[1e-7, 1e-4, 1e-3, 0.05, 1.0] {
                let d = HighGain::new(mu, [a1], Discretization::Exact)
                    .discretize(dt)
                    .unwrap();
                let x = -a1 * dt / mu;
                let phi = x.exp();
                let gamma = -x.exp_m1(); // 1 - Phi without cancellation
                                         // absolute 1e-14 (Phi, Gamma are in [0, 1]) ...
                assert!((d.phi[0][0] - phi).abs() < 1e-14, "mu {mu} a1 {a1} dt {dt}");
                assert!(
                    (d.gamma[0] - (1.0 - phi)).abs() < 1e-14,
                    "mu {mu} a1 {a1} dt {dt}"
                );
                // ... and relative: 1e-14 for a small dt / mu; squaring
                // grows the relative error of exp(x) like |x| eps
                let rel = 1e-14 * (1.0 + x.abs());
                assert!(rel_err(d.phi[0][0], phi) < rel, "mu {mu} a1 {a1} dt {dt}");
                assert!(rel_err(d.gamma[0], gamma) < 1e-14, "mu {mu} a1 {a1} dt {dt}");
            }
        }
    }
}

fn check_against_rk4<const N: usize>(a: [f64; N]) {
    let mu = 0.01;
    for &dt in &[1e-3, 5e-3] {
        let d = HighGain::new(mu, a, Discretization::Exact)
            .discretize(dt)
            .unwrap();
        let mut worst = 0.0_f64;
        for j in 0..N {
            let mut z0 = [0.0; N];
            z0[j] = 1.0;
            let col = rk4(mu, &a, z0, 0.0, dt, 20_000);
            for i in 0..N {
                worst = worst.max(rel_err_floor(d.phi[i][j], col[i], mu.powi(j as i32 - i as i32)));
            }
        }
        let g = rk4(mu, &a, [0.0; N], 1.0, dt, 20_000);
        for i in 0..N {
            worst = worst.max(rel_err_floor(d.gamma[i], g[i], mu.powi(-(i as i32))));
        }
        assert!(worst < 1e-10, "order {N} dt {dt}: worst relative error {worst:e}");
    }
}

#[test]
fn exact_matches_fine_rk4_order2_and_order3() {
    check_against_rk4(PAPER2);
    check_against_rk4(PAPER3);
}

fn check_dc_gain<const N: usize>(a: [f64; N]) {
    let mu = 0.01;
    for &dt in &[1e-3, 5e-3] {
        let d = HighGain::new(mu, a, Discretization::Exact)
            .discretize(dt)
            .unwrap();
        let e = 2.5;
        // (I - Phi) x = Gamma e at x = (e, 0, ..., 0)
        for i in 0..N {
            let lhs = if i == 0 { e } else { 0.0 } - d.phi[i][0] * e;
            let scale = d.gamma[i].abs() * e + 1e-300;
            assert!((lhs - d.gamma[i] * e).abs() <= 1e-10 * scale, "row {i}");
        }
        // and the recursion converges there from rest
        let mut z = [0.0; N];
        for _ in 0..5_000 {
            z = d.advance(&z, e);
        }
        assert!((z[0] - e).abs() < 1e-12 * e);
        for i in 1..N {
            assert!(z[i].abs() < 1e-9 * e / mu.powi(i as i32), "z[{i}] = {}", z[i]);
        }
    }
}

#[test]
fn constant_input_gives_dc_gain_unit_zero() {
    check_dc_gain(PAPER2);
    check_dc_gain(PAPER3);
}

/// Ramp z1 = slope * t, sampled and held: after the transient Zhat_2
/// tracks the slope. The relative residual at the sample instants comes
/// from the held staircase (a sawtooth of height slope * dt that the fast
/// differentiator partly follows) and scales like (dt / mu)^2: measured
/// 0.33 (dt/mu)^2 for order 2 and 0.48 (dt/mu)^2 for order 3.
fn check_ramp<const N: usize>(a: [f64; N]) {
    let mu = 0.01;
    let slope = 3.0;
    for &dt in &[1e-3, 5e-3] {
        let d = HighGain::new(mu, a, Discretization::Exact)
            .discretize(dt)
            .unwrap();
        let mut z = [0.0; N];
        let steps = (2.0 / dt) as usize;
        for k in 0..steps {
            z = d.advance(&z, slope * k as f64 * dt);
        }
        let err = (z[1] - slope).abs() / slope;
        let tol = 0.6 * (dt / mu) * (dt / mu);
        assert!(err < tol, "order {N} dt {dt}: Zhat_2 = {} (slope {slope})", z[1]);
        // increments settle to (slope dt, 0, ...)
        let z_next = d.advance(&z, slope * steps as f64 * dt);
        assert!(((z_next[0] - z[0]) - slope * dt).abs() < 1e-9);
        for i in 1..N {
            assert!((z_next[i] - z[i]).abs() < 1e-7 / mu.powi(i as i32));
        }
    }
}

#[test]
fn ramp_input_gives_slope() {
    check_ramp(PAPER2);
    check_ramp(PAPER3);
}

fn check_contractive<const N: usize>(a: [f64; N], mu: f64) {
    let mut dt = 1e-6;
    while dt <= 10.0 * (1.0 + 1e-9) {
        for method in [Discretization::Exact, Discretization::Tustin] {
            let d = HighGain::new(mu, a, method).discretize(dt).unwrap();
            assert!(d
                .phi
                .iter()
                .flatten()
                .chain(d.gamma.iter())
                .all(|x| x.is_finite()));
            // Phi^(2^60) -> 0 iff the spectral radius is < 1
            let mut p = d.phi;
            for _ in 0..60 {
                p = square(&p);
                assert!(
                    p.iter().flatten().all(|x| x.is_finite()),
                    "order {N} dt {dt} {method:?}"
                );
            }
            assert!(
                norm_inf(&p) < 1e-30,
                "order {N} dt {dt} {method:?}: {:e}",
                norm_inf(&p)
            );
        }
        dt *= 10.0_f64.sqrt();
    }
}

#[test]
fn exact_and_tustin_are_contractive_for_all_dt() {
    check_contractive([3.0], 0.01);
    check_contractive(PAPER2, 0.01);
    check_contractive(PAPER3, 0.01);
    check_contractive(binomial::<4>(), 0.01);
    check_contractive(binomial::<5>(), 0.05);
    check_contractive(binomial::<6>(), 0.01);
    check_contractive(binomial::<7>(), 0.1);
    check_contractive(binomial::<8>(), 0.01);
}

/// Exact is a semigroup: Phi(2h) = Phi(h)^2, Gamma(2h) = Phi(h) Gamma(h) + Gamma(h).
fn check_semigroup<const N: usize>(a: [f64; N], mu: f64) {
    for &h in &[1e-5, 1e-3, 0.02, 0.3] {
        let one = HighGain::new(mu, a, Discretization::Exact).discretize(h).unwrap();
        let two = HighGain::new(mu, a, Discretization::Exact)
            .discretize(2.0 * h)
            .unwrap();
        let sq = square(&one.phi);
        let g2 = one.advance(&one.gamma, 1.0);
        let mut worst = 0.0_f64;
        for i in 0..N {
            for j in 0..N {
                let scale = mu.powi(j as i32 - i as i32);
                worst = worst.max((sq[i][j] - two.phi[i][j]).abs() / scale);
            }
            worst = worst.max((g2[i] - two.gamma[i]).abs() * mu.powi(i as i32));
        }
        assert!(worst < 1e-12, "order {N} mu {mu} h {h}: {worst:e}");
    }
}

#[test]
fn exact_is_a_semigroup_for_orders_1_to_8() {
    check_semigroup([2.0], 0.01);
    check_semigroup(PAPER2, 0.01);
    check_semigroup(PAPER3, 0.01);
    check_semigroup(binomial::<4>(), 0.01);
    check_semigroup(binomial::<5>(), 0.02);
    check_semigroup(binomial::<6>(), 0.05);
    check_semigroup(binomial::<7>(), 0.1);
    check_semigroup(binomial::<8>(), 0.1);
}

#[test]
fn exact_with_huge_dt_is_zero_not_nan() {
    let d = HighGain::new(0.01, PAPER3, Discretization::Exact)
        .discretize(1.0)
        .unwrap();
    // slowest mode exp(-dt / mu) = exp(-100) ~ 4e-44, times mu^(-2) = 1e4
    assert!(d.phi.iter().flatten().all(|x| x.is_finite() && x.abs() < 1e-38));
    // Gamma -> the DC solution: (1, 0, 0)
    assert!((d.gamma[0] - 1.0).abs() < 1e-12);
    assert!(d.gamma[1].abs() < 1e-9 && d.gamma[2].abs() < 1e-6);
    let d = HighGain::new(1e-4, binomial::<8>(), Discretization::Exact)
        .discretize(10.0)
        .unwrap();
    assert!(d
        .phi
        .iter()
        .flatten()
        .chain(d.gamma.iter())
        .all(|x| x.is_finite()));
}

#[test]
fn euler_with_large_dt_is_unstable_but_accepted() {
    let d = HighGain::new(0.01, PAPER2, Discretization::Euler)
        .discretize(0.05)
        .unwrap();
    // Phi = I + M dt exactly
    assert_eq!(d.phi[0][0], 1.0 - 4.0 / 0.01 * 0.05);
    assert_eq!(d.phi[0][1], 0.05);
    let mut p = d.phi;
    for _ in 0..6 {
        p = square(&p);
    }
    assert!(norm_inf(&p) > 1e30, "Euler should blow up at dt = 5 mu");
    // while small dt agrees with Exact to first order
    let dt = 1e-5;
    let eu = HighGain::new(0.01, PAPER2, Discretization::Euler)
        .discretize(dt)
        .unwrap();
    let ex = HighGain::new(0.01, PAPER2, Discretization::Exact)
        .discretize(dt)
        .unwrap();
    for i in 0..2 {
        for j in 0..2 {
            assert!((eu.phi[i][j] - ex.phi[i][j]).abs() < 1e-2 * 0.01f64.powi(j as i32 - i as i32));
        }
    }
}

#[test]
fn tustin_is_second_order_close_to_exact() {
    let a = PAPER3;
    let mu = 0.01;
    let err = |dt: f64| {
        let tu = HighGain::new(mu, a, Discretization::Tustin)
            .discretize(dt)
            .unwrap();
        let ex = HighGain::new(mu, a, Discretization::Exact)
            .discretize(dt)
            .unwrap();
        let mut w = 0.0_f64;
        for i in 0..3 {
            for j in 0..3 {
                w = w.max((tu.phi[i][j] - ex.phi[i][j]).abs() * mu.powi(i as i32 - j as i32));
            }
        }
        w
    };
    let (e1, e2) = (err(1e-4), err(5e-5));
    // halving dt divides the one-step error by ~8 (local error O(dt^3))
    assert!(e1 / e2 > 7.0 && e1 / e2 < 9.0, "{e1:e} {e2:e}");
}

#[test]
fn advance_is_phi_times_zhat_plus_gamma_e() {
    let d = HighGain::new(0.02, PAPER3, Discretization::Exact)
        .discretize(1e-3)
        .unwrap();
    let z = [0.3, -2.0, 40.0];
    let out = d.advance(&z, 1.7);
    for i in 0..3 {
        let want: f64 = (0..3).map(|j| d.phi[i][j] * z[j]).sum::<f64>() + d.gamma[i] * 1.7;
        assert!((out[i] - want).abs() <= 1e-13 * want.abs().max(1.0));
    }
}

#[test]
fn non_hurwitz_coefficients_are_rejected() {
    let e = HighGain::new(0.01, [1.0, -1.0], Discretization::Exact)
        .validate()
        .unwrap_err();
    assert_eq!(e.parameter, "a");
    // s^3 + s^2 + s + 10: a1 a2 = 1 < a3 = 10
    let e = HighGain::new(0.01, [1.0, 1.0, 10.0], Discretization::Exact)
        .validate()
        .unwrap_err();
    assert_eq!(e.parameter, "a");
    assert!(e.rule.contains("not Hurwitz"), "{}", e.rule);
    // boundary: s^3 + s^2 + s + 1 = (s + 1)(s^2 + 1) has roots on the axis
    assert!(HighGain::new(0.01, [1.0, 1.0, 1.0], Discretization::Exact)
        .validate()
        .is_err());
    // s^4 + s^3 + 3 s^2 + s + 1 ... Routh: (1,3,1),(1,1),(2,1),(0.5),(1) -> Hurwitz
    assert!(HighGain::new(0.01, [1.0, 3.0, 1.0, 1.0], Discretization::Exact)
        .validate()
        .is_ok());
    // s^4 + s^3 + s^2 + s + 1 (roots on the unit circle's right half): not Hurwitz
    assert!(HighGain::new(0.01, [1.0, 1.0, 1.0, 1.0], Discretization::Exact)
        .validate()
        .is_err());
    // discretize validates first
    let e = HighGain::new(0.01, [1.0, 1.0, 10.0], Discretization::Exact)
        .discretize(1e-3)
        .unwrap_err();
    assert_eq!(e.parameter, "a");
    // zero, NaN and infinite coefficients
    for bad in [0.0, -2.0, f64::NAN, f64::INFINITY] {
        let e = HighGain::new(0.01, [4.0, bad], Discretization::Exact)
            .validate()
            .unwrap_err();
        assert_eq!(e.parameter, "a");
    }
}

#[test]
fn hurwitz_test_agrees_with_known_polynomials() {
    // Hurwitz: binomial (s+1)^N for N = 1..=8, and the paper's choices
    assert!(routh_hurwitz(&binomial::<1>()));
    assert!(routh_hurwitz(&binomial::<2>()));
    assert!(routh_hurwitz(&binomial::<3>()));
    assert!(routh_hurwitz(&binomial::<4>()));
    assert!(routh_hurwitz(&binomial::<5>()));
    assert!(routh_hurwitz(&binomial::<6>()));
    assert!(routh_hurwitz(&binomial::<7>()));
    assert!(routh_hurwitz(&binomial::<8>()));
    assert!(routh_hurwitz(&binomial::<12>()));
    assert!(routh_hurwitz(&PAPER2) && routh_hurwitz(&PAPER3));
    // order 3: Hurwitz iff a1 a2 > a3
    assert!(routh_hurwitz(&[2.0, 3.0, 5.9]));
    assert!(!routh_hurwitz(&[2.0, 3.0, 6.1]));
    // (s-1)(s+2)(s+3) = s^3 + 4 s^2 + s - 6 has a negative coefficient;
    // (s^2 - 0.1 s + 1)(s + 1)^2 = s^4 + 1.9 s^3 + 1.8 s^2 + 1.9 s + 1 has
    // positive coefficients but two right-half-plane roots
    assert!(!routh_hurwitz(&[1.9, 1.8, 1.9, 1.0]));
    // (s^2 + 0.1 s + 1)(s + 1)^2 = s^4 + 2.1 s^3 + 2.2 s^2 + 2.1 s + 1: Hurwitz
    assert!(routh_hurwitz(&[2.1, 2.2, 2.1, 1.0]));
}

#[test]
fn bad_mu_and_dt_are_rejected_with_their_names() {
    for mu in [0.0, -0.01, f64::NAN, f64::INFINITY] {
        let hg = HighGain::new(mu, PAPER2, Discretization::Exact);
        assert_eq!(hg.validate().unwrap_err().parameter, "mu");
        assert_eq!(hg.discretize(1e-3).unwrap_err().parameter, "mu");
    }
    let hg = HighGain::new(0.01, PAPER2, Discretization::Exact);
    for dt in [0.0, -1e-3, f64::NAN, f64::INFINITY] {
        assert_eq!(hg.discretize(dt).unwrap_err().parameter, "dt");
    }
    // dt / mu would overflow: mu (and dt) are outside the scale range
    // [2^-256, 2^256] (docs/design.md §3.9), and mu is checked first
    let hg = HighGain::new(1e-300, [1.0], Discretization::Exact);
    assert_eq!(hg.discretize(1e100).unwrap_err().parameter, "mu");
    // order 8 with mu = 1e-6 overflows f32 (H_8 = 1e48)
    let hg = HighGain::new(1e-6_f32, [1.0; 8], Discretization::Euler);
    let hg = HighGain {
        a: binomial::<8>().map(|x| x as f32),
        ..hg
    };
    assert_eq!(hg.discretize(1e-3).unwrap_err().parameter, "mu");
    // order 0 is rejected
    let e = HighGain::<f64, 0>::new(0.01, [], Discretization::Exact)
        .validate()
        .unwrap_err();
    assert_eq!(e.parameter, "a");
}

#[test]
fn f32_and_f64_agree() {
    for method in [
        Discretization::Exact,
        Discretization::Euler,
        Discretization::Tustin,
    ] {
        for &dt in &[1e-4_f32, 1e-3, 5e-3, 0.1] {
            let mu = 0.01_f32;
            let a = [4.0_f32, 6.0, 4.0];
            let d32 = HighGain::new(mu, a, method).discretize(dt).unwrap();
            // the same (f32-representable) parameters in f64: f32 is
            // exactly the f64 result rounded, i.e. within half an f32 ulp
            let d64 = HighGain::new(f64::from(mu), a.map(f64::from), method)
                .discretize(f64::from(dt))
                .unwrap();
            for i in 0..3 {
                for j in 0..3 {
                    let (x, y) = (f64::from(d32.phi[i][j]), d64.phi[i][j]);
                    assert!((x - y).abs() <= 6e-8 * y.abs(), "{method:?} {dt} phi[{i}][{j}]");
                }
                let (x, y) = (f64::from(d32.gamma[i]), d64.gamma[i]);
                assert!((x - y).abs() <= 6e-8 * y.abs(), "{method:?} {dt} gamma[{i}]");
            }
            // and with the decimal parameters in f64 (mu = 0.01 is not an
            // f32 number): relative 1e-6 of each entry's natural scale
            let d64 = HighGain::new(0.01_f64, [4.0, 6.0, 4.0], method)
                .discretize(f64::from(dt))
                .unwrap();
            for i in 0..3 {
                for j in 0..3 {
                    let scale = 0.01_f64.powi(j as i32 - i as i32);
                    let (x, y) = (f64::from(d32.phi[i][j]), d64.phi[i][j]);
                    assert!(
                        (x - y).abs() <= 1e-6 * y.abs().max(scale),
                        "{method:?} {dt} phi[{i}][{j}]"
                    );
                }
                let scale = 0.01_f64.powi(-(i as i32));
                let y = d64.gamma[i];
                assert!((f64::from(d32.gamma[i]) - y).abs() <= 1e-6 * y.abs().max(scale));
            }
        }
    }
}

#[test]
fn f32_advance_tracks_f64() {
    let d32 = HighGain::new(0.01_f32, [4.0, 4.0], Discretization::Exact)
        .discretize(1e-3)
        .unwrap();
    let d64 = HighGain::new(f64::from(0.01_f32), [4.0, 4.0], Discretization::Exact)
        .discretize(1e-3)
        .unwrap();
    let (mut z32, mut z64) = ([0.0_f32; 2], [0.0_f64; 2]);
    for k in 0..2000 {
        let t = k as f64 * 1e-3;
        let e = (3.0 * t).sin();
        z32 = d32.advance(&z32, e as f32);
        z64 = d64.advance(&z64, e);
    }
    assert!((f64::from(z32[0]) - z64[0]).abs() < 1e-5);
    assert!((f64::from(z32[1]) - z64[1]).abs() < 1e-3);
    // Zhat_2 estimates 3 cos(3 t) up to the filter lag
    let t = 1999.0_f64 * 1e-3;
    assert!((z64[1] - 3.0 * (3.0 * t).cos()).abs() < 0.1);
}
