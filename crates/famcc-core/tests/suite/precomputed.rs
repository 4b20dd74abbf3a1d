//! A configuration from a differentiator recursion precomputed elsewhere
//! (`ConfigBuilder::build_discretized`, for a microcontroller that must not
//! run the matrix exponential): equal to `build`'s wherever `build` accepts,
//! and each check of the recursion rejecting what it is there for. Also the
//! two pieces in `T` it relies on: the spectral radius and the sine
//! transition's `sin`/`cos` in `f32`.
#![allow(clippy::unwrap_used, clippy::indexing_slicing, clippy::float_cmp)]

use famcc_core::differentiator::spectral_radius;
use famcc_core::{Config, ConfigBuilder, Constraint, DiscreteHgd, Discretization, Feedback, HighGain, Real};
use proptest::prelude::*;

const DISCRETIZATIONS: [Discretization; 3] = [
    Discretization::Exact,
    Discretization::Tustin,
    Discretization::Euler,
];

fn builder<T: Real>(dt: f64, h: HighGain<T, 3>, integral: bool) -> ConfigBuilder<T, 3> {
    let laws = [(Feedback::Linear { k: T::from_f64(2.0) }, None); 2];
    Config::<T, 3>::builder(
        T::from_f64(dt),
        &laws,
        Constraint::Longitudinal {
            eps: T::from_f64(0.5),
        },
        T::from_f64(3.0),
    )
    .differentiator(Some(h))
    .integral(integral)
}

fn high_gain<T: Real>(mu: f64, d: Discretization, tau: f64, integral: bool) -> HighGain<T, 3> {
    let a = if integral {
        [4.0, 4.0, 0.0]
    } else {
        [4.0, 6.0, 4.0]
    };
    HighGain::new(T::from_f64(mu), a.map(T::from_f64), d).with_prefilter(T::from_f64(tau))
}

/// The property in one float type: the precomputed recursion gives `build`'s
/// configuration, or, where `build` rejects the sampled differentiator as
/// unstable, the precomputed (unstable) recursion is rejected too.
fn agrees<T: Real>(
    mu: f64,
    dt: f64,
    d: Discretization,
    tau: f64,
    integral: bool,
) -> Result<(), TestCaseError> {
    let h = high_gain::<T>(mu, d, tau, integral);
    let b = builder(dt, h, integral);
    let Ok(recursion) = h.discretize_order(T::from_f64(dt), 3 - usize::from(integral)) else {
        return Ok(());
    };
    match b.build() {
        Ok(c) => prop_assert_eq!(b.build_discretized(recursion), Ok(c)),
        Err(e) if e.parameter == "dt" => {
            prop_assert_eq!(
                b.build_discretized(recursion).unwrap_err().parameter,
                "discretized"
            );
        }
        Err(e) => prop_assert_eq!(b.build_discretized(recursion).unwrap_err().parameter, e.parameter),
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    #[test]
    fn a_precomputed_recursion_gives_builds_configuration(
        mu in 1e-3_f64..0.1,
        per_mu in 0.01_f64..4.0,
        d in 0_usize..3,
        tau_per_mu in prop::sample::select(vec![0.0, 0.25, 0.5, 2.0]),
        integral in any::<bool>(),
    ) {
        let (dt, tau, d) = (per_mu * mu, tau_per_mu * mu, DISCRETIZATIONS[d]);
        agrees::<f64>(mu, dt, d, tau, integral)?;
        agrees::<f32>(mu, dt, d, tau, integral)?;
    }
}

fn paper_f32() -> (ConfigBuilder<f32, 3>, DiscreteHgd<f32, 3>) {
    let h = high_gain::<f32>(0.01, Discretization::Exact, 0.0, false);
    (builder(1e-3, h, false), h.discretize(1e-3).unwrap())
}

#[test]
fn a_non_finite_entry_is_rejected() {
    let (b, good) = paper_f32();
    assert!(b.build_discretized(good).is_ok());
    for v in [f32::NAN, f32::INFINITY] {
        let mut phi = good;
        phi.phi[2][0] = v;
        let mut gamma = good;
        gamma.gamma[1] = v;
        let mut feed = good;
        feed.feedthrough[2] = v;
        for bad in [phi, gamma, feed] {
            let e = b.build_discretized(bad).unwrap_err();
            assert_eq!(
                (e.parameter, e.rule),
                ("discretized", "must have finite Phi, Gamma and feedthrough")
            );
        }
    }
}

#[test]
fn a_prefilter_gain_outside_0_1_is_rejected() {
    let (b, good) = paper_f32();
    for g in [0.0, -0.5, 1.0 + f32::EPSILON, f32::NAN] {
        let bad = DiscreteHgd { prefilter: g, ..good };
        assert!(
            b.build_discretized(bad)
                .unwrap_err()
                .rule
                .contains("prefilter gain"),
            "{g}"
        );
    }
    assert!(b
        .build_discretized(DiscreteHgd {
            prefilter: 0.25,
            ..good
        })
        .is_ok());
}

#[test]
fn the_integrals_slot_must_be_unused() {
    let h = high_gain::<f64>(0.01, Discretization::Exact, 0.0, true);
    let b = builder(1e-3, h, true);
    let good = h.discretize_order(1e-3, 2).unwrap();
    assert_eq!(b.build_discretized(good), b.build());
    // The order-3 recursion where the integral belongs: every leading row,
    // column and input entry is checked.
    let full = high_gain::<f64>(0.01, Discretization::Exact, 0.0, false)
        .discretize(1e-3)
        .unwrap();
    assert!(b.build_discretized(full).unwrap_err().rule.contains("integral"));
    for (i, j) in [(0, 0), (0, 2), (2, 0)] {
        let mut bad = good;
        bad.phi[i][j] = 1e-300;
        assert!(
            b.build_discretized(bad).unwrap_err().rule.contains("integral"),
            "{i} {j}"
        );
    }
    let mut bad = good;
    bad.gamma[0] = -1e-300;
    assert!(b.build_discretized(bad).unwrap_err().rule.contains("integral"));
    // Without integral action there is no such slot.
    let plain = builder(
        1e-3,
        high_gain::<f64>(0.01, Discretization::Exact, 0.0, false),
        false,
    );
    assert!(plain.build_discretized(full).is_ok());
}

#[test]
fn an_unstable_or_marginal_recursion_is_rejected() {
    let (b, good) = paper_f32();
    let mut unstable = good;
    unstable.phi[0][0] = 1.5;
    let mut identity = good;
    identity.phi = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for bad in [unstable, identity] {
        assert!(b
            .build_discretized(bad)
            .unwrap_err()
            .rule
            .starts_with("is unstable"));
    }
}

#[test]
fn the_differentiator_must_be_given() {
    let (b, good) = paper_f32();
    let e = b.differentiator(None).build_discretized(good).unwrap_err();
    assert_eq!(e.parameter, "differentiator");
    // Its values are checked as in build.
    let bad_mu = HighGain::new(-0.01_f32, [4.0, 6.0, 4.0], Discretization::Exact);
    assert_eq!(
        b.differentiator(Some(bad_mu))
            .build_discretized(good)
            .unwrap_err()
            .parameter,
        "mu"
    );
}

#[test]
fn the_radius_in_f32_agrees_with_f64() {
    for d in DISCRETIZATIONS {
        for per_mu in [0.01, 0.1, 0.5, 1.0] {
            let h = HighGain::new(0.01_f64, [4.0, 6.0, 4.0], d);
            let Ok(r) = h.discretize(0.01 * per_mu) else {
                continue;
            };
            let r32 = spectral_radius(&r.phi.map(|row| row.map(|v| v as f32)));
            let r64 = r.spectral_radius();
            assert!(
                (f64::from(r32) - r64).abs() <= 2e-5 * r64.max(1e-3),
                "{d:?} {per_mu}: {r32} {r64}"
            );
        }
    }
}

/// Distance in units in the last place of `f32` (of the binade of `v`)
/// between `x` and the exact value `v` (known to `f64`, `v` normal in `f32`).
fn ulps(x: f32, v: f64) -> f64 {
    let ulp = 2f64.powi(v.abs().log2().floor() as i32) * f64::from(f32::EPSILON);
    (f64::from(x) - v).abs() / ulp
}

#[test]
fn the_octant_sine_and_cosine_in_f32_are_within_2_ulp() {
    let n = 200_000;
    let mut worst = (0.0_f64, 0.0_f64);
    for i in 1..=n {
        let x = (core::f32::consts::FRAC_PI_4 * i as f32) / n as f32;
        let (s, c) = x.sin_cos_octant();
        let (es, ec) = f64::from(x).sin_cos();
        worst = (worst.0.max(ulps(s, es)), worst.1.max(ulps(c, ec)));
        assert_eq!(x.sin_octant(), s);
    }
    assert!(worst.0 <= 2.0 && worst.1 <= 2.0, "{worst:?}");
    // Tiny arguments: sin x = x and cos x = 1 exactly.
    for x in [0.0_f32, 1e-30, 1e-8] {
        assert_eq!(x.sin_cos_octant(), (x, 1.0));
    }
    // f64 is the library's, bit for bit.
    for x in [0.1_f64, 0.5, core::f64::consts::FRAC_PI_4] {
        assert_eq!(x.sin_cos_octant(), x.sin_cos());
        assert_eq!(x.sin_octant().to_bits(), x.sin().to_bits());
    }
}
