//! Every configuration variant, C ABI and core side by side, bit for bit.
//!
//! The C configurations below are written with the `FamccXxx::Yyy as u32`
//! constants of the header and the core's with its own enumerations: nothing
//! goes through `convert`'s tables, so a wrong entry there (say
//! `FAMCC_GAMMA_RATIONAL` mapped to Log) fails here.
#![allow(clippy::unwrap_used, clippy::indexing_slicing, clippy::float_cmp)]

extern crate std;

use super::tests_variant_build::*;
use super::tests_variant_cases::*;
use super::*;
use core::mem::MaybeUninit;
use famcc_core::{Controller, Real};

/// A signal that saturates, expands and clamps somewhere across the table:
/// a decaying oscillation, a pulse and a slow ramp.
fn wild_signal<T: Real>(n: usize) -> std::vec::Vec<T> {
    (0..n)
        .map(|k| {
            let t = k as f64 * 1e-3;
            let pulse = if (300..360).contains(&k) { 1.5 } else { 0.0 };
            T::from_f64(0.9 * (-t).exp() * (6.0 * t).cos() - 0.3 + pulse + 0.2 * t)
        })
        .collect()
}

/// Every diagnostics field, bit for bit.
fn same_diagnostics<T: Real + core::fmt::Debug, const N: usize>(
    c: &FamccDiagnostics<T>,
    r: &famcc_core::Diagnostics<T, N>,
    lumped: T,
    what: &str,
) {
    let want = convert::diag_to_c(r, lumped);
    let bits = |d: &FamccDiagnostics<T>| std::format!("{d:?}");
    // Debug text of the floats is exact (shortest round trip) and NaN-free here.
    assert_eq!(bits(c), bits(&want), "{what}");
    assert_eq!(
        c.v.to_f64_lossless().to_bits(),
        r.v.to_f64_lossless().to_bits(),
        "{what}"
    );
    assert_eq!(
        c.xi.to_f64_lossless().to_bits(),
        r.xi.to_f64_lossless().to_bits(),
        "{what}"
    );
    assert_eq!(c.clamp_count, r.clamp_count, "{what}");
    assert_eq!(c.expanded != 0, r.expanded, "{what}");
    assert_eq!(c.has_saturation_gap != 0, r.saturation_gap.is_some(), "{what}");
}

macro_rules! variants_match {
    ($name:ident, $t:ty, $n:literal, $storage:ty, $init:ident, $step:ident, $applied:ident, $diag:ident, $reset:ident) => {
        #[test]
        fn $name() {
            let input = wild_signal::<$t>(700);
            let mut stats = [0usize; 3]; // expanded, clamped, rational
            let mut rejected = 0usize;
            for (i, (order, v)) in variants().into_iter().enumerate() {
                if order != $n {
                    continue;
                }
                let what = std::format!("variant {i}: {v:?}");
                let cfg = c_variant::<$t>(&v, $n);
                let mut storage = MaybeUninit::<$storage>::zeroed();
                let p = storage.as_mut_ptr();
                let mut err = MaybeUninit::<FamccError>::zeroed();
                let status = unsafe { $init(p, &cfg, err.as_mut_ptr()) };
                // The C ABI accepts exactly what the core's builder accepts
                // (e.g. the validation probe rejects some f32 variants).
                let core_cfg = match core_config::<$t, $n>(&v) {
                    Ok(c) => c,
                    Err(e) => {
                        assert_eq!(status, FamccStatus::InvalidConfig, "{what}: {e:?}");
                        let got = unsafe { err.assume_init() };
                        let name: std::vec::Vec<u8> = got.parameter[..e.parameter.len()]
                            .iter()
                            .map(|&c| c as u8)
                            .collect();
                        assert_eq!(name, e.parameter.as_bytes(), "{what}");
                        rejected += 1;
                        continue;
                    }
                };
                assert_eq!(status, FamccStatus::Ok, "{what}: {:?}", unsafe {
                    err.assume_init()
                });
                // The C ABI builds exactly this configuration.
                assert_eq!(
                    convert::to_config::<$t, $n>(&cfg).unwrap(),
                    core_cfg,
                    "{what}"
                );
                let mut ctrl = Controller::new(core_cfg);
                for pass in 0..2 {
                    for (k, &e) in input.iter().enumerate() {
                        let mut out: $t = 0.0;
                        let (status, want) = if k % 7 == 3 {
                            let a = (0.8 * (k as f64)).sin() as $t;
                            (
                                unsafe { $applied(p, e, a, &mut out) },
                                ctrl.step_applied(e, Some(a)),
                            )
                        } else {
                            (unsafe { $step(p, e, &mut out) }, ctrl.step(e))
                        };
                        match want {
                            Ok(w) => {
                                assert_eq!(status, FamccStatus::Ok, "{what} step {k}");
                                assert_eq!(out.to_bits(), w.to_bits(), "{what} step {k}");
                            }
                            Err(e) => assert_eq!(status, convert::status_of(e), "{what} step {k}"),
                        }
                        let mut d = MaybeUninit::<FamccDiagnostics<$t>>::zeroed();
                        assert_eq!(unsafe { $diag(p, d.as_mut_ptr()) }, FamccStatus::Ok);
                        let r = ctrl.diagnostics();
                        same_diagnostics(
                            &unsafe { d.assume_init() },
                            &r,
                            ctrl.lumped(),
                            &std::format!("{what} step {k}"),
                        );
                        if pass == 0 {
                            stats[0] += usize::from(r.expanded);
                        }
                    }
                    if pass == 0 {
                        stats[1] += ctrl.diagnostics().clamp_count as usize;
                        stats[2] += usize::from(v.gamma == FamccGamma::Rational);
                        assert_eq!(unsafe { $reset(p) }, FamccStatus::Ok);
                        ctrl.reset();
                    }
                }
            }
            // Most of the table runs; the flexible boundary, the clamp and
            // both maps are exercised.
            let total = variants().iter().filter(|(o, _)| *o == $n).count();
            assert!(
                rejected * 10 <= total,
                "{rejected} of {total} variants rejected"
            );
            assert!(
                stats.iter().all(|s| *s > 0),
                "expanded, clamped, rational: {stats:?}"
            );
        }
    };
}

variants_match!(
    every_variant_o2_f32_matches_core,
    f32,
    2,
    FamccO2F32,
    famcc_o2_f32_init,
    famcc_o2_f32_step,
    famcc_o2_f32_step_applied,
    famcc_o2_f32_diagnostics,
    famcc_o2_f32_reset
);
variants_match!(
    every_variant_o2_f64_matches_core,
    f64,
    2,
    FamccO2F64,
    famcc_o2_f64_init,
    famcc_o2_f64_step,
    famcc_o2_f64_step_applied,
    famcc_o2_f64_diagnostics,
    famcc_o2_f64_reset
);
variants_match!(
    every_variant_o3_f32_matches_core,
    f32,
    3,
    FamccO3F32,
    famcc_o3_f32_init,
    famcc_o3_f32_step,
    famcc_o3_f32_step_applied,
    famcc_o3_f32_diagnostics,
    famcc_o3_f32_reset
);
variants_match!(
    every_variant_o3_f64_matches_core,
    f64,
    3,
    FamccO3F64,
    famcc_o3_f64_init,
    famcc_o3_f64_step,
    famcc_o3_f64_step_applied,
    famcc_o3_f64_diagnostics,
    famcc_o3_f64_reset
);

/// The table covers every enumeration value of the header.
#[test]
fn the_variant_table_covers_every_enumeration_value() {
    let vs = variants();
    let has = |f: &dyn Fn(&Case) -> bool| vs.iter().any(|(_, v)| f(v));
    for g in [FamccGamma::Log, FamccGamma::Rational] {
        assert!(has(&|v| v.gamma == g));
    }
    for d in [
        FamccDiscretization::Exact,
        FamccDiscretization::Euler,
        FamccDiscretization::Tustin,
        FamccDiscretization::Foh,
    ] {
        assert!(has(&|v| v.discretization == d));
    }
    for c in [
        FamccConstraintKind::Longitudinal,
        FamccConstraintKind::Lateral,
        FamccConstraintKind::Oblique,
    ] {
        assert!(has(&|v| v.constraint.0 == c));
    }
    for l in [FamccLatch::Paper, FamccLatch::Authors] {
        assert!(has(&|v| v.latch == l));
    }
    for t in [
        FamccTransition::Exponential,
        FamccTransition::Cubic,
        FamccTransition::Quintic,
        FamccTransition::Sine,
    ] {
        assert!(has(&|v| v.transition == t));
        assert!(has(&|v| v.stages.iter().any(
            |s| matches!(s.1, SkewSpec::Nsmd(_, _, _, x) | SkewSpec::Smooth(_, _, x) if x == t)
        )));
    }
    assert!(has(&|v| matches!(v.flex, Flex::Off)) && has(&|v| matches!(v.flex, Flex::On(_))));
    assert!(has(&|v| v.limits.is_some()) && has(&|v| v.init.is_some()));
    for k in 0..5 {
        assert!(
            has(&|v| v.stages.iter().any(|s| c_law::<f64>(s.0).kind == k)),
            "law kind {k}"
        );
    }
}
