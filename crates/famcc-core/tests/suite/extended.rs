//! The extended high-gain differentiator (`ExtendedHighGain`, docs/observer.md):
//! its sampled recursion equals a fine RK4 of the continuous observer with the
//! sample and the input held, at every order and for random parameters; it
//! estimates the lumped term of a plant `z1^(n) = L + b0 u` and the error's
//! derivatives; its f32 recursion is the f64 one rounded; bad parameters are
//! named.

use famcc_core::config::MAX_ORDER;
use famcc_core::{Discretization, ExtendedHighGain};
use proptest::prelude::*;

const RK4_STEPS: usize = 2000;

/// The continuous observer's right-hand side on `x = (zhat_1..zhat_n, Lhat)` (length n + 1).
fn rhs(mu: f64, a: &[f64], b0: f64, x: &[f64], e: f64, u: f64) -> Vec<f64> {
    let n = x.len() - 1;
    let eta = e - x[0];
    (0..=n)
        .map(|i| {
            let next = if i < n { x[i + 1] } else { 0.0 };
            let input = if i + 1 == n { b0 * u } else { 0.0 };
            next + input + a[i] / mu.powi(i as i32 + 1) * eta
        })
        .collect()
}

/// Classical RK4 over `dt` in [`RK4_STEPS`] steps with `u` held and the
/// measurement the straight line from `e0` to `e1` (held: `e1 = e0`).
fn rk4(mu: f64, a: &[f64], b0: f64, x0: &[f64], (e0, e1, u): (f64, f64, f64), dt: f64) -> Vec<f64> {
    let steps = RK4_STEPS;
    let h = dt / steps as f64;
    let mut x = x0.to_vec();
    let add = |x: &[f64], k: &[f64], s: f64| x.iter().zip(k).map(|(p, q)| p + s * q).collect::<Vec<_>>();
    let e = |j: f64| e0 + (e1 - e0) * j / steps as f64;
    for j in 0..steps {
        let j = j as f64;
        let k1 = rhs(mu, a, b0, &x, e(j), u);
        let k2 = rhs(mu, a, b0, &add(&x, &k1, h / 2.0), e(j + 0.5), u);
        let k3 = rhs(mu, a, b0, &add(&x, &k2, h / 2.0), e(j + 0.5), u);
        let k4 = rhs(mu, a, b0, &add(&x, &k3, h), e(j + 1.0), u);
        for i in 0..x.len() {
            x[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
    }
    x
}

/// One sample of the order-`N` recursion against RK4 (relative to the state's size).
fn matches_rk4<const N: usize>(mu: f64, r: f64, b0: f64, x0: &[f64], (e, e1, u): (f64, f64, f64), dt: f64) {
    // Hurwitz by construction: the binomial (s + 2)^(N+1) with its poles scaled by `r`.
    let base = ExtendedHighGain::<f64, N>::binomial(mu, b0);
    let mut a: Vec<f64> = base.a.iter().copied().chain([base.a_ext]).collect();
    for (i, ai) in a.iter_mut().enumerate() {
        *ai *= r.powi(i as i32 + 1);
    }
    let mut arr = [0.0; N];
    arr.copy_from_slice(&a[..N]);
    let obs = ExtendedHighGain::<f64, N>::new(mu, arr, a[N], b0);
    let mut z = [0.0; N];
    z.copy_from_slice(&x0[..N]);
    // held: the next estimate from e alone; first-order hold: from the line e -> e1
    let held = obs.discretize(dt).expect("valid observer");
    let foh = obs
        .with_discretization(Discretization::Foh)
        .discretize(dt)
        .expect("valid observer");
    let (zn, ln) = held.advance(&z, x0[N], e, u);
    compare::<N>(
        mu,
        r,
        &[zn.as_slice(), &[ln]].concat(),
        &rk4(mu, &a, b0, &x0[..=N], (e, e, u), dt),
    );
    let (v, vl) = foh.advance(&z, x0[N], e, u);
    let (zn, ln) = foh.current(&v, vl, e1 - e);
    compare::<N>(
        mu,
        r,
        &[zn.as_slice(), &[ln]].concat(),
        &rk4(mu, &a, b0, &x0[..=N], (e, e1, u), dt),
    );
}

/// `got` against `want` in the balanced units `w_i = (mu / r)^i x_i`, relative to the state's size.
fn compare<const N: usize>(mu: f64, r: f64, got: &[f64], want: &[f64]) {
    for (i, (g, w)) in got.iter().zip(want.iter()).enumerate() {
        // Entry i scales like 1/mu^i: compare in the balanced units w_i = mu^i x_i, to
        // 1e-7 of the state (order 8 differs by up to 2e-9: rounding in a non-normal system).
        let s = (mu / r).powi(i as i32);
        let size = want
            .iter()
            .enumerate()
            .map(|(j, x)| (x * (mu / r).powi(j as i32)).abs())
            .fold(1.0, f64::max);
        assert!(
            ((g - w) * s).abs() <= 1e-7 * size,
            "order {N}, entry {i}: {g} vs RK4 {w}"
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn the_recursion_is_the_continuous_observer_sampled(
        mu in 0.002_f64..0.2,
        r in 0.5_f64..2.0,
        b0 in prop_oneof![-50.0_f64..-0.1, 0.1_f64..50.0],
        x0 in prop::collection::vec(-3.0_f64..3.0, MAX_ORDER + 1),
        e in -2.0_f64..2.0,
        e1 in -2.0_f64..2.0,
        u in -10.0_f64..10.0,
        dt_per_mu in 0.01_f64..2.0,
    ) {
        let dt = dt_per_mu * mu;
        matches_rk4::<1>(mu, r, b0, &x0, (e, e1, u), dt);
        matches_rk4::<2>(mu, r, b0, &x0, (e, e1, u), dt);
        matches_rk4::<3>(mu, r, b0, &x0, (e, e1, u), dt);
        matches_rk4::<4>(mu, r, b0, &x0, (e, e1, u), dt);
        matches_rk4::<6>(mu, r, b0, &x0, (e, e1, u), dt);
        matches_rk4::<8>(mu, r, b0, &x0, (e, e1, u), dt);
    }
}

/// The observer at `dt` on a sampled plant `z1^(N) = L + b0_true u` with `u` held and
/// a constant `L`, `z1 = accel t^N / N! + 0.3`: the error of `Lhat` against
/// `L + (b0_true - b0) u` (the part of the input the nominal gain misses is lumped
/// in) and of `zhat_2` (or `zhat_1` at order 1) against the truth, after 1.5 s.
fn lumped_error<const N: usize>(b0: f64, b0_true: f64, dt: f64) -> (f64, f64) {
    let mu = 0.02;
    let d = ExtendedHighGain::<f64, N>::binomial(mu, b0)
        .discretize(dt)
        .unwrap();
    let (l_true, u) = (-1.5, 0.8);
    let accel = l_true + b0_true * u; // z1^(N), constant
    let fact: f64 = (1..=N).map(|k| k as f64).product();
    let deriv = |t: f64, k: usize| -> f64 {
        let f: f64 = (N - k + 1..=N).map(|j| j as f64).product();
        accel * f * t.powi((N - k) as i32) / fact + if k == 0 { 0.3 } else { 0.0 }
    };
    let (mut z, mut l) = ([0.0; N], 0.0);
    z[0] = deriv(0.0, 0);
    let steps = (1.5 / dt).round() as usize;
    for k in 0..steps {
        let (e, next) = (deriv(k as f64 * dt, 0), deriv((k + 1) as f64 * dt, 0));
        let (v, vl) = d.advance(&z, l, e, u);
        (z, l) = d.current(&v, vl, next - e);
    }
    let t = steps as f64 * dt;
    let k = N.min(2) - 1;
    (
        (l - (l_true + (b0_true - b0) * u)).abs(),
        (z[k] - deriv(t, k)).abs(),
    )
}

/// The estimates converge to the truth as the sample period falls, at least as
/// fast as `dt^2` (the held sample of a moving error is a staircase whose
/// ripple the high-gain extended state amplifies, docs/observer.md "Sampling").
fn estimates_the_lumped_term<const N: usize>(b0: f64, b0_true: f64) {
    let errs: Vec<(f64, f64)> = [1e-3, 5e-4, 2.5e-4]
        .iter()
        .map(|&dt| lumped_error::<N>(b0, b0_true, dt))
        .collect();
    let ((l0, _), (l1, _), (l2, z2)) = (errs[0], errs[1], errs[2]);
    assert!(
        l1 <= 0.3 * l0 + 1e-9 && l2 <= 0.3 * l1 + 1e-9,
        "order {N}: Lhat errors {errs:?}"
    );
    // ... and, up to order 2, are small at 0.25 ms against the size of z1^(N) (the
    // ripple grows with it). At order 3 the held sample's bias in Lhat is still 1.5
    // there (23 at 1 ms, mu = 20 ms: docs/observer.md); zhat_2 is accurate.
    let size = 1.0 + (-1.5 + b0_true * 0.8_f64).abs();
    let l_tol = if N <= 2 { 0.01 * size } else { 2.0 * size };
    assert!(
        l2 < l_tol && z2 < 2e-3 * size,
        "order {N}: errors at dt = 0.25 ms {errs:?}"
    );
}

#[test]
fn it_estimates_the_lumped_term_and_the_derivatives() {
    estimates_the_lumped_term::<1>(2.0, 2.0);
    estimates_the_lumped_term::<2>(1.0, 1.0);
    estimates_the_lumped_term::<2>(1.0, 1.4); // a 40 % gain error is lumped into L
    estimates_the_lumped_term::<2>(-3.0, -2.0); // a negative control direction
    estimates_the_lumped_term::<3>(5.0, 5.0);
}

#[test]
fn without_the_input_term_the_estimate_is_wrong() {
    // The same plant seen by an observer whose b0 is (almost) zero against the
    // true 2: Lhat then carries the whole input, not L alone (the test above fails
    // for the wrong b0, so it checks the b0 u term).
    let d = ExtendedHighGain::<f64, 1>::binomial(0.02, 1e-6)
        .discretize(1e-3)
        .unwrap();
    let (mut z, mut l) = ([0.0], 0.0);
    for k in 0..2000 {
        (z, l) = d.advance(&z, l, (3.0 + 2.0 * 0.5) * k as f64 * 1e-3, 0.5);
    }
    assert!((l - 4.0).abs() < 0.05 && (l - 3.0).abs() > 0.5, "Lhat {l}");
}

#[test]
fn the_default_is_the_binomial_of_order_n_plus_1() {
    // (s + 2)^2, (s + 2)^3, (s + 2)^4
    let one = ExtendedHighGain::<f64, 1>::binomial(0.01, 1.0);
    assert_eq!((one.a, one.a_ext), ([4.0], 4.0));
    let two = ExtendedHighGain::<f64, 2>::binomial(0.01, 1.0);
    assert_eq!((two.a, two.a_ext), ([6.0, 12.0], 8.0));
    let three = ExtendedHighGain::<f32, 3>::binomial(0.5, -2.0);
    assert_eq!(
        (three.a, three.a_ext, three.mu, three.b0),
        ([8.0, 24.0, 32.0], 16.0, 0.5, -2.0)
    );
    assert_eq!(three.discretization, Discretization::Exact);
}

#[test]
fn f32_is_the_f64_recursion_rounded() {
    // The f64 observer of the f32 one's numbers (0.01 and 1e-3 are not f32 values).
    let (mu, dt) = (0.01_f32, 1e-3_f32);
    let d64 = ExtendedHighGain::<f64, 3>::binomial(mu as f64, 2.5)
        .discretize(dt as f64)
        .unwrap();
    let d32 = ExtendedHighGain::<f32, 3>::binomial(mu, 2.5)
        .discretize(dt)
        .unwrap();
    for i in 0..3 {
        for j in 0..3 {
            assert_eq!(d32.phi[i][j], d64.phi[i][j] as f32);
        }
        assert_eq!(d32.gamma_e[i], d64.gamma_e[i] as f32);
        assert_eq!(d32.gamma_u[i], d64.gamma_u[i] as f32);
        assert_eq!(d32.phi_zl[i], d64.phi_zl[i] as f32);
        assert_eq!(d32.phi_lz[i], d64.phi_lz[i] as f32);
        assert_eq!(d32.feed_e[i], d64.feed_e[i] as f32);
    }
    assert_eq!(d32.phi_ll, d64.phi_ll as f32);
    assert_eq!(d32.feed_e_l, d64.feed_e_l as f32);
    assert_eq!(
        (d32.gamma_e_l, d32.gamma_u_l),
        (d64.gamma_e_l as f32, d64.gamma_u_l as f32)
    );
}

#[test]
fn a_constant_state_at_rest_stays() {
    // zhat = (c, 0, ..., 0), Lhat = -b0 u, e = c: every derivative is zero and
    // the input is cancelled by Lhat, so nothing moves (a fixed point).
    let (b0, u, c) = (2.0, 0.75, 0.4);
    let d = ExtendedHighGain::<f64, 4>::binomial(0.01, b0)
        .discretize(1e-3)
        .unwrap();
    let (z, l) = d.advance(&[c, 0.0, 0.0, 0.0], -b0 * u, c, u);
    assert!(
        (z[0] - c).abs() < 1e-12 && z[1..].iter().all(|x| x.abs() < 1e-9),
        "{z:?}"
    );
    assert!((l + b0 * u).abs() < 1e-6, "{l}");
}

#[test]
fn bad_parameters_are_named() {
    let ok = ExtendedHighGain::<f64, 2>::binomial(0.01, 1.0);
    assert!(ok.validate().is_ok());
    let name = |o: ExtendedHighGain<f64, 2>| o.discretize(1e-3).unwrap_err().parameter;
    assert_eq!(name(ExtendedHighGain { mu: 0.0, ..ok }), "observer_mu");
    assert_eq!(name(ExtendedHighGain { mu: f64::NAN, ..ok }), "observer_mu");
    assert_eq!(name(ExtendedHighGain { b0: 0.0, ..ok }), "b0");
    assert_eq!(
        name(ExtendedHighGain {
            b0: f64::INFINITY,
            ..ok
        }),
        "b0"
    );
    assert_eq!(name(ExtendedHighGain { a_ext: -1.0, ..ok }), "observer_a");
    assert_eq!(
        name(ExtendedHighGain {
            a: [1.0, 1.0],
            a_ext: 10.0,
            ..ok
        }),
        "observer_a"
    );
    assert_eq!(ok.discretize(0.0).unwrap_err().parameter, "dt");
    for d in [Discretization::Euler, Discretization::Tustin] {
        assert_eq!(name(ok.with_discretization(d)), "observer_discretization");
    }
    // order 8 with mu = dt = 10 us: the entry of zhat_1 into Lhat is about
    // a_9 / mu^8 = 5e42, beyond f32 (fine in f64)
    let tiny = ExtendedHighGain::<f32, 8>::binomial(1e-5, 1.0);
    assert_eq!(tiny.discretize(1e-5).unwrap_err().parameter, "observer_mu");
    assert!(ExtendedHighGain::<f64, 8>::binomial(1e-5, 1.0)
        .discretize(1e-5)
        .is_ok());
    assert_eq!(
        ExtendedHighGain::<f64, 0>::new(0.01, [], 1.0, 1.0)
            .validate()
            .unwrap_err()
            .parameter,
        "order"
    );
}
