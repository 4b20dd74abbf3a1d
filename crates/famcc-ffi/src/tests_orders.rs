//! Every order of the generated C functions (1 to 6, `float` and `double`)
//! against famcc-core used directly: the same outputs and estimates bit for
//! bit, the storage's size and tag, and the lint.
#![allow(clippy::unwrap_used, clippy::indexing_slicing, clippy::float_cmp)]

extern crate std;

use super::*;
use core::mem::{align_of, size_of, MaybeUninit};
use famcc_core::differentiator::paper_coefficients;
use famcc_core::{Config, Constraint, Controller, Discretization, Feedback, HighGain, Real};

/// Linear stage laws `k = 1.5, 2, ...`, LaMC `eps = 0.2` (LoMC at order 1), `k_u = 3`, the
/// paper's differentiator coefficients with Tustin (stable at every order):
/// built through the C structs.
fn c_config<T: Real>(order: usize) -> FamccConfig<T> {
    let f = T::from_f64;
    let mut c = convert::defaults::<T>();
    c.dt = f(1e-3);
    c.k_u = f(3.0);
    // LaMC from order 2 (at order 1 only LoMC exists: no s_(n-1)).
    c.constraint = match order {
        1 => FamccConstraint {
            kind: FamccConstraintKind::Longitudinal as u32,
            eps_x: T::zero(),
            eps_y: f(0.2),
        },
        _ => FamccConstraint {
            kind: FamccConstraintKind::Lateral as u32,
            eps_x: f(0.2),
            eps_y: T::zero(),
        },
    };
    for (i, s) in c.stages.iter_mut().take(order - 1).enumerate() {
        s.feedback.kind = FamccFeedbackKind::Linear as u32;
        s.feedback.params.linear = FamccLinear {
            k: f(1.5 + 0.5 * i as f64),
        };
    }
    c.differentiator.enabled = 1;
    c.differentiator.mu = f(0.01);
    paper_coefficients(&mut c.differentiator.a[..order]);
    c.differentiator.discretization = convert::to_c(&convert::DISCRETIZATIONS, Discretization::Tustin);
    c
}

/// The same configuration with famcc-core's builder.
fn core_config<T: Real, const N: usize>() -> Config<T, N> {
    let f = T::from_f64;
    let laws: [(Feedback<T>, _); N] = core::array::from_fn(|i| {
        (
            Feedback::Linear {
                k: f(1.5 + 0.5 * i as f64),
            },
            None,
        )
    });
    let mut a = [T::zero(); N];
    paper_coefficients(&mut a);
    let constraint = if N == 1 {
        Constraint::Longitudinal { eps: f(0.2) }
    } else {
        Constraint::Lateral { eps: f(0.2) }
    };
    Config::builder(f(1e-3), &laws[..N - 1], constraint, f(3.0))
        .differentiator(Some(HighGain::new(f(0.01), a, Discretization::Tustin)))
        .build()
        .unwrap()
}

/// A slow decaying oscillation with a jump: the estimate and the bounds move.
fn signal(k: usize) -> f64 {
    let t = k as f64 * 1e-3;
    0.8 * (-t).exp() * (7.0 * t).cos() + if k > 900 { 0.05 } else { 0.0 }
}

macro_rules! order_matches_core {
    ($name:ident, $t:ty, $n:literal, $storage:ty, $words:ident, $size:ident, $align:ident, $init:ident,
     $step:ident, $applied:ident, $diag:ident, $reset:ident, $lint:ident, $other_reset:ident) => {
        #[test]
        fn $name() {
            assert_eq!($size(), size_of::<$storage>());
            assert_eq!($size(), 8 * $words);
            assert_eq!($align(), align_of::<$storage>());
            assert_eq!($align(), 8);
            let cfg = c_config::<$t>($n);
            let mut storage = MaybeUninit::<$storage>::zeroed();
            let p = storage.as_mut_ptr();
            let mut err = MaybeUninit::<FamccError>::zeroed();
            let mut v: $t = 0.0;
            // Not initialised yet: every call says so.
            assert_eq!(
                unsafe { $step(p, 0.1, &mut v) },
                FamccStatus::NotInitialized
            );
            let status = unsafe { $init(p, &cfg, err.as_mut_ptr()) };
            let e = unsafe { err.assume_init_ref() };
            let text = |a: &[core::ffi::c_char]| {
                a.iter()
                    .take_while(|&&c| c != 0)
                    .map(|&c| c as u8 as char)
                    .collect::<std::string::String>()
            };
            assert_eq!(
                status,
                FamccStatus::Ok,
                "order {}: {} {}",
                $n,
                text(&e.parameter),
                text(&e.rule)
            );
            // Another order's (or float type's) functions refuse it.
            assert_eq!(
                unsafe { $other_reset(p.cast()) },
                FamccStatus::NotInitialized
            );
            let mut core = Controller::new(core_config::<$t, $n>());
            let mut d = FamccDiagnostics::<$t>::default();
            for k in 0..1500 {
                let e = <$t>::from_f64(signal(k));
                let want = core.step(e);
                let got = if k % 2 == 0 {
                    unsafe { $step(p, e, &mut v) }
                } else {
                    unsafe { $applied(p, e, v, &mut v) }
                };
                match want {
                    Ok(w) => {
                        assert_eq!(got, FamccStatus::Ok, "order {} step {k}", $n);
                        assert_eq!(v.to_bits(), w.to_bits(), "order {} step {k}", $n);
                    }
                    Err(_) => assert_ne!(got, FamccStatus::Ok, "order {} step {k}", $n),
                }
                assert_eq!(unsafe { $diag(p, &mut d) }, FamccStatus::Ok);
                let cd = core.diagnostics();
                for i in 0..$n {
                    assert_eq!(
                        d.z_hat[i].to_bits(),
                        cd.z_hat[i].to_bits(),
                        "order {} step {k} z_hat[{i}]",
                        $n
                    );
                }
                assert_eq!(d.xi.to_bits(), cd.xi.to_bits());
            }
            // The lint is the core's.
            let mut findings = MaybeUninit::<[FamccFinding; FAMCC_MAX_FINDINGS]>::zeroed();
            let mut count = usize::MAX;
            assert_eq!(
                unsafe {
                    $lint(
                        p,
                        findings.as_mut_ptr().cast(),
                        FAMCC_MAX_FINDINGS,
                        &mut count,
                    )
                },
                FamccStatus::Ok
            );
            assert_eq!(count, core.config().lint().iter().count(), "order {}", $n);
            // After a reset it starts over like a new controller.
            assert_eq!(unsafe { $reset(p) }, FamccStatus::Ok);
            let mut fresh = Controller::new(core_config::<$t, $n>());
            for k in 0..50 {
                let e = <$t>::from_f64(signal(k));
                assert_eq!(unsafe { $step(p, e, &mut v) }, FamccStatus::Ok);
                assert_eq!(v.to_bits(), fresh.step(e).unwrap().to_bits());
            }
        }
    };
}

// Each against the core; the last argument is another type's reset (another
// order, or the other float type), which must refuse the storage.
order_matches_core!(
    order1_f32,
    f32,
    1,
    FamccO1F32,
    FAMCC_O1_F32_WORDS,
    famcc_o1_f32_size,
    famcc_o1_f32_align,
    famcc_o1_f32_init,
    famcc_o1_f32_step,
    famcc_o1_f32_step_applied,
    famcc_o1_f32_diagnostics,
    famcc_o1_f32_reset,
    famcc_o1_f32_lint,
    famcc_o2_f32_reset
);
order_matches_core!(
    order1_f64,
    f64,
    1,
    FamccO1F64,
    FAMCC_O1_F64_WORDS,
    famcc_o1_f64_size,
    famcc_o1_f64_align,
    famcc_o1_f64_init,
    famcc_o1_f64_step,
    famcc_o1_f64_step_applied,
    famcc_o1_f64_diagnostics,
    famcc_o1_f64_reset,
    famcc_o1_f64_lint,
    famcc_o1_f32_reset
);
order_matches_core!(
    order2_f32,
    f32,
    2,
    FamccO2F32,
    FAMCC_O2_F32_WORDS,
    famcc_o2_f32_size,
    famcc_o2_f32_align,
    famcc_o2_f32_init,
    famcc_o2_f32_step,
    famcc_o2_f32_step_applied,
    famcc_o2_f32_diagnostics,
    famcc_o2_f32_reset,
    famcc_o2_f32_lint,
    famcc_o3_f32_reset
);
order_matches_core!(
    order2_f64,
    f64,
    2,
    FamccO2F64,
    FAMCC_O2_F64_WORDS,
    famcc_o2_f64_size,
    famcc_o2_f64_align,
    famcc_o2_f64_init,
    famcc_o2_f64_step,
    famcc_o2_f64_step_applied,
    famcc_o2_f64_diagnostics,
    famcc_o2_f64_reset,
    famcc_o2_f64_lint,
    famcc_o2_f32_reset
);
order_matches_core!(
    order3_f32,
    f32,
    3,
    FamccO3F32,
    FAMCC_O3_F32_WORDS,
    famcc_o3_f32_size,
    famcc_o3_f32_align,
    famcc_o3_f32_init,
    famcc_o3_f32_step,
    famcc_o3_f32_step_applied,
    famcc_o3_f32_diagnostics,
    famcc_o3_f32_reset,
    famcc_o3_f32_lint,
    famcc_o4_f32_reset
);
order_matches_core!(
    order3_f64,
    f64,
    3,
    FamccO3F64,
    FAMCC_O3_F64_WORDS,
    famcc_o3_f64_size,
    famcc_o3_f64_align,
    famcc_o3_f64_init,
    famcc_o3_f64_step,
    famcc_o3_f64_step_applied,
    famcc_o3_f64_diagnostics,
    famcc_o3_f64_reset,
    famcc_o3_f64_lint,
    famcc_o3_f32_reset
);
order_matches_core!(
    order4_f32,
    f32,
    4,
    FamccO4F32,
    FAMCC_O4_F32_WORDS,
    famcc_o4_f32_size,
    famcc_o4_f32_align,
    famcc_o4_f32_init,
    famcc_o4_f32_step,
    famcc_o4_f32_step_applied,
    famcc_o4_f32_diagnostics,
    famcc_o4_f32_reset,
    famcc_o4_f32_lint,
    famcc_o5_f32_reset
);
order_matches_core!(
    order4_f64,
    f64,
    4,
    FamccO4F64,
    FAMCC_O4_F64_WORDS,
    famcc_o4_f64_size,
    famcc_o4_f64_align,
    famcc_o4_f64_init,
    famcc_o4_f64_step,
    famcc_o4_f64_step_applied,
    famcc_o4_f64_diagnostics,
    famcc_o4_f64_reset,
    famcc_o4_f64_lint,
    famcc_o4_f32_reset
);
order_matches_core!(
    order5_f32,
    f32,
    5,
    FamccO5F32,
    FAMCC_O5_F32_WORDS,
    famcc_o5_f32_size,
    famcc_o5_f32_align,
    famcc_o5_f32_init,
    famcc_o5_f32_step,
    famcc_o5_f32_step_applied,
    famcc_o5_f32_diagnostics,
    famcc_o5_f32_reset,
    famcc_o5_f32_lint,
    famcc_o6_f32_reset
);
order_matches_core!(
    order5_f64,
    f64,
    5,
    FamccO5F64,
    FAMCC_O5_F64_WORDS,
    famcc_o5_f64_size,
    famcc_o5_f64_align,
    famcc_o5_f64_init,
    famcc_o5_f64_step,
    famcc_o5_f64_step_applied,
    famcc_o5_f64_diagnostics,
    famcc_o5_f64_reset,
    famcc_o5_f64_lint,
    famcc_o5_f32_reset
);
order_matches_core!(
    order6_f32,
    f32,
    6,
    FamccO6F32,
    FAMCC_O6_F32_WORDS,
    famcc_o6_f32_size,
    famcc_o6_f32_align,
    famcc_o6_f32_init,
    famcc_o6_f32_step,
    famcc_o6_f32_step_applied,
    famcc_o6_f32_diagnostics,
    famcc_o6_f32_reset,
    famcc_o6_f32_lint,
    famcc_o1_f32_reset
);
order_matches_core!(
    order6_f64,
    f64,
    6,
    FamccO6F64,
    FAMCC_O6_F64_WORDS,
    famcc_o6_f64_size,
    famcc_o6_f64_align,
    famcc_o6_f64_init,
    famcc_o6_f64_step,
    famcc_o6_f64_step_applied,
    famcc_o6_f64_diagnostics,
    famcc_o6_f64_reset,
    famcc_o6_f64_lint,
    famcc_o6_f32_reset
);
