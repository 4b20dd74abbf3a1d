//! The C ABI against famcc-core used directly: same outputs bit for bit,
//! and the error paths.
#![allow(clippy::unwrap_used, clippy::indexing_slicing, clippy::float_cmp)]

extern crate std;

use super::*;
use core::mem::MaybeUninit;
use famcc_core::{Config, Constraint, Controller, Discretization, Feedback, HighGain, Latch, Real, Skew};
use std::vec::Vec;

fn c_example1<T: Real>() -> FamccConfig<T> {
    let mut c = MaybeUninit::<FamccConfig<T>>::uninit();
    assert_eq!(unsafe { defaults(c.as_mut_ptr()) }, FamccStatus::Ok);
    let mut c = unsafe { c.assume_init() };
    c.dt = T::c(1e-3);
    c.k_u = T::c(5.0);
    c.constraint = FamccConstraint {
        kind: FamccConstraintKind::Lateral as u32,
        eps_x: T::c(0.1),
        eps_y: T::zero(),
    };
    c.latch = FamccLatch::Authors as u32;
    c.stages[0].feedback = FamccFeedback {
        kind: FamccFeedbackKind::FiniteTime as u32,
        params: FamccFeedbackParams {
            finite_time: FamccFiniteTime {
                k: T::one(),
                p: T::c(0.5),
            },
        },
    };
    c.differentiator = FamccDifferentiator {
        enabled: 1,
        mu: T::c(0.01),
        a: [T::c(4.0), T::c(4.0), T::zero()],
        discretization: FamccDiscretization::Exact as u32,
    };
    c
}

fn rust_example1<T: Real>() -> Controller<T, 2> {
    let mut cfg = Config::<T, 2>::new(
        T::c(1e-3),
        &[(
            Feedback::FiniteTime {
                k: T::one(),
                p: T::c(0.5),
            },
            None,
        )],
        Constraint::Lateral { eps: T::c(0.1) },
        T::one(),
        T::c(5.0),
    )
    .unwrap();
    cfg.differentiator = Some(HighGain::new(
        T::c(0.01),
        [T::c(4.0), T::c(4.0)],
        Discretization::Exact,
    ));
    cfg.latch = Latch::Authors;
    Controller::new(cfg).unwrap()
}

fn c_example3<T: Real>() -> FamccConfig<T> {
    let mut c = c_example1::<T>();
    c.k_u = T::c(30.0);
    c.constraint = FamccConstraint {
        kind: FamccConstraintKind::Longitudinal as u32,
        eps_x: T::zero(),
        eps_y: T::c(3.0),
    };
    let fixed = |alpha: f64, beta: f64| FamccFeedback {
        kind: FamccFeedbackKind::FixedTime as u32,
        params: FamccFeedbackParams {
            fixed_time: FamccFixedTime {
                alpha: T::c(alpha),
                p: T::c(0.5),
                beta: T::c(beta),
                q: T::c(2.0),
            },
        },
    };
    let nsmd = |eps_s: f64, eps_z: f64, k_pp: f64| FamccSkew {
        kind: FamccSkewKind::Nonsingular as u32,
        eps_s: T::c(eps_s),
        eps_z: T::c(eps_z),
        k_pp: T::c(k_pp),
        transition: FamccTransition::Exponential as u32,
    };
    c.stages = [
        FamccStage {
            feedback: fixed(1.0, 0.5),
            skew: nsmd(0.1, 0.1, 0.1),
        },
        FamccStage {
            feedback: fixed(2.0, 1.0),
            skew: nsmd(3.0, 0.2, 1.0),
        },
    ];
    c.differentiator.a = [T::c(4.0), T::c(6.0), T::c(4.0)];
    c
}

fn rust_example3<T: Real>() -> Controller<T, 3> {
    let fixed = |alpha: f64, beta: f64| Feedback::FixedTime {
        alpha: T::c(alpha),
        p: T::c(0.5),
        beta: T::c(beta),
        q: T::c(2.0),
    };
    let mut cfg = Config::<T, 3>::new(
        T::c(1e-3),
        &[
            (
                fixed(1.0, 0.5),
                Some(Skew::nonsingular(T::c(0.1), T::c(0.1), T::c(0.1))),
            ),
            (
                fixed(2.0, 1.0),
                Some(Skew::nonsingular(T::c(3.0), T::c(0.2), T::c(1.0))),
            ),
        ],
        Constraint::Longitudinal { eps: T::c(3.0) },
        T::one(),
        T::c(30.0),
    )
    .unwrap();
    cfg.differentiator = Some(HighGain::new(
        T::c(0.01),
        [T::c(4.0), T::c(6.0), T::c(4.0)],
        Discretization::Exact,
    ));
    cfg.latch = Latch::Authors;
    Controller::new(cfg).unwrap()
}

/// A decaying oscillation with a pulse (drives the flexible boundary).
fn signal<T: Real>(n: usize) -> Vec<T> {
    (0..n)
        .map(|k| {
            let t = k as f64 * 1e-3;
            let pulse = if (1200..1350).contains(&k) { 0.8 } else { 0.0 };
            T::c(-(-1.5 * t).exp() * (8.17 * t).cos() + pulse)
        })
        .collect()
}

macro_rules! same_as_core {
    ($name:ident, $t:ty, $storage:ty, $init:ident, $step:ident, $diag:ident, $reset:ident, $cfg:ident, $rust:ident) => {
        #[test]
        fn $name() {
            let cfg = $cfg::<$t>();
            let mut storage = MaybeUninit::<$storage>::zeroed();
            let p = storage.as_mut_ptr();
            let mut err = MaybeUninit::<FamccError>::zeroed();
            assert_eq!(unsafe { $init(p, &cfg, err.as_mut_ptr()) }, FamccStatus::Ok);
            let mut ctrl = $rust::<$t>();
            let input = signal::<$t>(2000);
            let mut first = Vec::new();
            for &e in &input {
                let mut v: $t = 0.0;
                assert_eq!(unsafe { $step(p, e, &mut v) }, FamccStatus::Ok);
                let want = ctrl.step(e).unwrap();
                assert_eq!(v.to_bits(), want.to_bits());
                let mut d = MaybeUninit::<FamccDiagnostics<$t>>::zeroed();
                assert_eq!(unsafe { $diag(p, d.as_mut_ptr()) }, FamccStatus::Ok);
                let d = unsafe { d.assume_init() };
                let r = ctrl.diagnostics();
                assert_eq!(d.xi.to_bits(), r.xi.to_bits());
                assert_eq!(d.s.to_bits(), r.s.to_bits());
                assert_eq!(d.expanded != 0, r.expanded);
                assert_eq!(d.clamp_count, r.clamp_count);
                assert_eq!(d.bounds, [r.bounds.0, r.bounds.1]);
                first.push(v);
            }
            // reset: the same outputs again
            assert_eq!(unsafe { $reset(p) }, FamccStatus::Ok);
            for (&e, &want) in input.iter().zip(&first) {
                let mut v: $t = 0.0;
                assert_eq!(unsafe { $step(p, e, &mut v) }, FamccStatus::Ok);
                assert_eq!(v.to_bits(), want.to_bits());
            }
        }
    };
}

same_as_core!(
    o2_f32_matches_core,
    f32,
    FamccO2F32,
    famcc_o2_f32_init,
    famcc_o2_f32_step,
    famcc_o2_f32_diagnostics,
    famcc_o2_f32_reset,
    c_example1,
    rust_example1
);
same_as_core!(
    o2_f64_matches_core,
    f64,
    FamccO2F64,
    famcc_o2_f64_init,
    famcc_o2_f64_step,
    famcc_o2_f64_diagnostics,
    famcc_o2_f64_reset,
    c_example1,
    rust_example1
);
same_as_core!(
    o3_f32_matches_core,
    f32,
    FamccO3F32,
    famcc_o3_f32_init,
    famcc_o3_f32_step,
    famcc_o3_f32_diagnostics,
    famcc_o3_f32_reset,
    c_example3,
    rust_example3
);
same_as_core!(
    o3_f64_matches_core,
    f64,
    FamccO3F64,
    famcc_o3_f64_init,
    famcc_o3_f64_step,
    famcc_o3_f64_diagnostics,
    famcc_o3_f64_reset,
    c_example3,
    rust_example3
);

fn text(a: &[c_char]) -> std::string::String {
    let bytes: Vec<u8> = a.iter().take_while(|c| **c != 0).map(|c| *c as u8).collect();
    std::string::String::from_utf8(bytes).unwrap()
}

#[test]
fn errors_are_status_codes() {
    let mut storage = MaybeUninit::<FamccO2F32>::zeroed();
    let p = storage.as_mut_ptr();
    let mut v = 0.0f32;
    // never initialised (zeroed storage)
    assert_eq!(
        unsafe { famcc_o2_f32_step(p, 0.1, &mut v) },
        FamccStatus::NotInitialized
    );
    assert_eq!(unsafe { famcc_o2_f32_reset(p) }, FamccStatus::NotInitialized);
    // NULL pointers
    let cfg = c_example1::<f32>();
    assert_eq!(
        unsafe { famcc_o2_f32_init(ptr::null_mut(), &cfg, ptr::null_mut()) },
        FamccStatus::NullPointer
    );
    assert_eq!(
        unsafe { famcc_o2_f32_init(p, ptr::null(), ptr::null_mut()) },
        FamccStatus::NullPointer
    );
    assert_eq!(
        unsafe { famcc_o2_f32_step(ptr::null_mut(), 0.1, &mut v) },
        FamccStatus::NullPointer
    );
    assert_eq!(
        unsafe { famcc_o2_f32_step(p, 0.1, ptr::null_mut()) },
        FamccStatus::NullPointer
    );
    assert_eq!(
        unsafe { famcc_config_f32_defaults(ptr::null_mut()) },
        FamccStatus::NullPointer
    );
    // invalid values, with the reason
    let mut err = MaybeUninit::<FamccError>::zeroed();
    let mut bad = cfg;
    bad.stages[0].feedback.kind = 77;
    assert_eq!(
        unsafe { famcc_o2_f32_init(p, &bad, err.as_mut_ptr()) },
        FamccStatus::InvalidConfig
    );
    let e = unsafe { err.assume_init() };
    assert_eq!(text(&e.parameter), "feedback.kind");
    assert_eq!(e.stage, 0);
    let mut bad = cfg;
    bad.k_u = -1.0;
    assert_eq!(
        unsafe { famcc_o2_f32_init(p, &bad, err.as_mut_ptr()) },
        FamccStatus::InvalidConfig
    );
    let e = unsafe { err.assume_init() };
    assert_eq!(text(&e.parameter), "k_u");
    assert_eq!(e.stage, -1);
    assert!(text(&e.rule).contains("> 0"));
    // a failed init leaves the storage unusable, not half-configured
    assert_eq!(
        unsafe { famcc_o2_f32_step(p, 0.1, &mut v) },
        FamccStatus::NotInitialized
    );
    // the wrong controller type for the storage
    assert_eq!(
        unsafe { famcc_o2_f32_init(p, &cfg, ptr::null_mut()) },
        FamccStatus::Ok
    );
    let p3 = p.cast::<FamccO3F32>();
    assert_eq!(unsafe { famcc_o3_f32_reset(p3) }, FamccStatus::NotInitialized);
    // non-finite input: status, no change of v or state
    v = 42.0;
    assert_eq!(
        unsafe { famcc_o2_f32_step(p, f32::NAN, &mut v) },
        FamccStatus::NonFiniteInput
    );
    assert_eq!(v, 42.0);
    assert_eq!(unsafe { famcc_o2_f32_step(p, 0.5, &mut v) }, FamccStatus::Ok);
    // applied input
    assert_eq!(
        unsafe { famcc_o2_f32_step_applied(p, 0.5, f32::INFINITY, &mut v) },
        FamccStatus::NonFiniteApplied
    );
    assert_eq!(
        unsafe { famcc_o2_f32_step_applied(p, 0.5, 1.0, &mut v) },
        FamccStatus::Ok
    );
    let mut d = MaybeUninit::<FamccDiagnosticsF32>::zeroed();
    assert_eq!(
        unsafe { famcc_o2_f32_diagnostics(p, d.as_mut_ptr()) },
        FamccStatus::Ok
    );
    let d = unsafe { d.assume_init() };
    assert_eq!(d.order, 2);
    assert_eq!(d.has_saturation_gap, 1);
    // misaligned storage
    let mut raw = [0u64; FAMCC_O2_F32_WORDS + 1];
    let odd = unsafe { raw.as_mut_ptr().cast::<u8>().add(4) }.cast::<FamccO2F32>();
    assert_eq!(
        unsafe { famcc_o2_f32_init(odd, &cfg, ptr::null_mut()) },
        FamccStatus::Misaligned
    );
    // no differentiator: step needs one
    let mut nod = cfg;
    nod.differentiator.enabled = 0;
    assert_eq!(
        unsafe { famcc_o2_f32_init(p, &nod, ptr::null_mut()) },
        FamccStatus::Ok
    );
    assert_eq!(
        unsafe { famcc_o2_f32_step(p, 0.5, &mut v) },
        FamccStatus::NoDifferentiator
    );
}

#[test]
fn sizes_and_strings() {
    assert_eq!(famcc_o2_f32_size(), FAMCC_O2_F32_WORDS * 8);
    assert_eq!(famcc_o3_f64_size(), FAMCC_O3_F64_WORDS * 8);
    assert_eq!(famcc_o2_f64_align(), 8);
    let s = unsafe { core::ffi::CStr::from_ptr(famcc_status_str(FamccStatus::NonFiniteInput as u32)) };
    assert!(s.to_str().unwrap().contains("finite"));
    let s = unsafe { core::ffi::CStr::from_ptr(famcc_status_str(1234)) };
    assert_eq!(s.to_str().unwrap(), "unknown status");
}
