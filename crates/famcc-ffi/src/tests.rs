//! The C ABI against famcc-core used directly: same outputs bit for bit,
//! and the error paths.
#![allow(clippy::unwrap_used, clippy::indexing_slicing, clippy::float_cmp)]

extern crate std;

use super::*;
use core::mem::MaybeUninit;
use famcc_core::{Config, Constraint, Controller, Feedback, Real, SkewKind};
use famcc_paper::designs::{self, Variant};
use std::vec::Vec;

/// The C configuration of a famcc-core configuration (the reverse of
/// `convert::to_config`), so that the designs come from famcc-paper alone.
pub(super) fn c_config<T: Real, const N: usize>(cfg: &Config<T, N>) -> FamccConfig<T> {
    let mut c = convert::defaults::<T>();
    c.dt = cfg.dt();
    c.settle_time = cfg.settle_time();
    c.k0 = cfg.k0();
    c.k_u = cfg.k_u();
    let (eps_x, eps_y) = cfg.constraint().eps();
    let kind = match cfg.constraint() {
        Constraint::Longitudinal { .. } => FamccConstraintKind::Longitudinal,
        Constraint::Lateral { .. } => FamccConstraintKind::Lateral,
        Constraint::Oblique { .. } => FamccConstraintKind::Oblique,
    };
    c.constraint = FamccConstraint {
        kind: kind as u32,
        eps_x,
        eps_y,
    };
    c.gamma = convert::to_c(&convert::GAMMAS, cfg.gamma());
    c.transition = convert::to_c(&convert::TRANSITIONS, cfg.transition());
    c.latch = convert::to_c(&convert::LATCHES, cfg.latch());
    (c.flexible, c.rho_e) = match cfg.rho_e() {
        Some(r) => (FamccFlexible::On as u32, r),
        None => (FamccFlexible::Off as u32, T::zero()),
    };
    for (stage, law) in c.stages.iter_mut().zip(cfg.laws()) {
        stage.feedback = c_feedback(law.feedback());
        stage.skew = law.skew().map_or(FamccSkew::default(), |s| FamccSkew {
            kind: match s.kind {
                SkewKind::Smooth => FamccSkewKind::Smooth as u32,
                SkewKind::Nonsingular { .. } => FamccSkewKind::Nonsingular as u32,
            },
            eps_s: s.eps_s,
            eps_z: s.eps_z,
            k_pp: match s.kind {
                SkewKind::Nonsingular { k_pp } => k_pp,
                SkewKind::Smooth => T::zero(),
            },
            transition: convert::to_c(&convert::TRANSITIONS, s.transition),
        });
    }
    if let Some(h) = cfg.differentiator() {
        c.differentiator.enabled = 1;
        c.differentiator.mu = h.mu;
        c.differentiator.a.iter_mut().zip(h.a).for_each(|(d, s)| *d = s);
        c.differentiator.discretization = convert::to_c(&convert::DISCRETIZATIONS, h.discretization);
        c.differentiator.prefilter = h.prefilter;
    }
    if let Some((lo, hi)) = cfg.output_limits() {
        (c.has_output_limits, c.output_limits) = (1, [lo, hi]);
    }
    c.direction = convert::to_c(&convert::DIRECTIONS, cfg.direction());
    if let Some(o) = cfg.observer() {
        c.observer = observer::to_c(o);
        c.observer.has_cancellation_limit = 1;
        c.observer.cancellation_limit = cfg.cancellation_limit().unwrap();
    }
    c
}

fn c_feedback<T: Real>(f: &Feedback<T>) -> FamccFeedback<T> {
    let (kind, params) = match *f {
        Feedback::Linear { k } => (
            FamccFeedbackKind::Linear,
            FamccFeedbackParams {
                linear: FamccLinear { k },
            },
        ),
        Feedback::FiniteTime { k, p } => (
            FamccFeedbackKind::FiniteTime,
            FamccFeedbackParams {
                finite_time: FamccFiniteTime { k, p },
            },
        ),
        Feedback::FixedTime { alpha, p, beta, q } => (
            FamccFeedbackKind::FixedTime,
            FamccFeedbackParams {
                fixed_time: FamccFixedTime { alpha, p, beta, q },
            },
        ),
        Feedback::VariableExponent { k, r_b, r_1, r_t } => (
            FamccFeedbackKind::VariableExponent,
            FamccFeedbackParams {
                variable_exponent: FamccVariableExponent { k, r_b, r_1, r_t },
            },
        ),
        Feedback::MoulayDiscontinuous { beta, lambda, mu } => (
            FamccFeedbackKind::MoulayDiscontinuous,
            FamccFeedbackParams {
                moulay: FamccMoulay { beta, lambda, mu },
            },
        ),
    };
    FamccFeedback {
        kind: kind as u32,
        params,
    }
}

pub(super) fn rust_example1<T: Real>() -> Controller<T, 2> {
    Controller::new(designs::example1(Variant::Code, T::from_f64(1e-3)).unwrap())
}

pub(super) fn rust_example3<T: Real>() -> Controller<T, 3> {
    Controller::new(designs::example3(Variant::Code, T::from_f64(1e-3)).unwrap())
}

pub(super) fn c_example1<T: Real>() -> FamccConfig<T> {
    c_config(rust_example1::<T>().config())
}

pub(super) fn c_example3<T: Real>() -> FamccConfig<T> {
    c_config(rust_example3::<T>().config())
}

/// A decaying oscillation with a pulse (drives the flexible boundary).
pub(super) fn signal<T: Real>(n: usize) -> Vec<T> {
    (0..n)
        .map(|k| {
            let t = k as f64 * 1e-3;
            let pulse = if (1200..1350).contains(&k) { 0.8 } else { 0.0 };
            T::from_f64(-(-1.5 * t).exp() * (8.17 * t).cos() + pulse)
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

/// `famcc_config_*_defaults` are famcc-core's defaults: with the required
/// values set, the C configuration builds the same controller as the core's
/// builder left at its defaults.
#[test]
fn c_defaults_are_the_core_defaults() {
    let mut c = MaybeUninit::<FamccConfigF64>::uninit();
    assert_eq!(
        unsafe { famcc_config_f64_defaults(c.as_mut_ptr()) },
        FamccStatus::Ok
    );
    let mut c = unsafe { c.assume_init() };
    c.dt = 1e-3;
    c.k_u = 5.0;
    c.constraint.eps_y = 0.05;
    c.stages[0].feedback.params.linear.k = 2.0;
    let from_c = convert::to_config::<f64, 2>(&c).unwrap();
    let core = Config::<f64, 2>::builder(
        1e-3,
        &[(Feedback::Linear { k: 2.0 }, None)],
        Constraint::Longitudinal { eps: 0.05 },
        5.0,
    )
    .build()
    .unwrap();
    assert_eq!(from_c, core);
    assert_eq!(from_c.rho_e(), Some(0.05 * 0.1));
    // What has no default must be set.
    let mut unset = c;
    unset.stages[0].feedback.params.linear.k = 0.0;
    assert_eq!(convert::to_config::<f64, 2>(&unset).unwrap_err().parameter, "k");
    unset = c;
    unset.flexible = 7;
    assert_eq!(
        convert::to_config::<f64, 2>(&unset).unwrap_err().parameter,
        "flexible"
    );
}
