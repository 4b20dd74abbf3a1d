//! The options of issue 13 through the C ABI: integral action, output and
//! rate limits, bumpless start, and their diagnostics, against famcc-core.
#![allow(clippy::unwrap_used, clippy::indexing_slicing, clippy::float_cmp)]

extern crate std;

use super::*;
use core::mem::MaybeUninit;
use famcc_core::{Config, Constraint, Controller, Discretization, Feedback, HighGain};

/// An order-2 plant with integral action: an order-3 controller.
fn c_config() -> FamccConfigF64 {
    let mut c = convert::defaults::<f64>();
    c.dt = 1e-3;
    c.k_u = 4.0;
    c.constraint = FamccConstraint {
        kind: FamccConstraintKind::Longitudinal as u32,
        eps_x: 0.0,
        eps_y: 2.0,
    };
    for s in c.stages.iter_mut().take(2) {
        s.feedback.kind = FamccFeedbackKind::Linear as u32;
        s.feedback.params.linear = FamccLinear { k: 2.0 };
    }
    c.differentiator.enabled = 1;
    c.differentiator.mu = 0.01;
    c.differentiator.a[0] = 4.0;
    c.differentiator.a[1] = 4.0;
    c.differentiator.discretization = convert::to_c(&convert::DISCRETIZATIONS, Discretization::Exact);
    c.integral = 1;
    c.has_output_limits = 1;
    c.output_limits = [-1.5, 1.5];
    c.has_rate_limit = 1;
    c.rate_limit = 200.0;
    c.has_initial_output = 1;
    c.initial_output = 0.25;
    c
}

fn core_config() -> Config<f64, 3> {
    let laws = [(Feedback::Linear { k: 2.0 }, None); 2];
    Config::<f64, 3>::builder(1e-3, &laws, Constraint::Longitudinal { eps: 2.0 }, 4.0)
        .differentiator(Some(HighGain::new(0.01, [4.0, 4.0, 0.0], Discretization::Exact)))
        .integral(true)
        .output_limits(Some((-1.5, 1.5)))
        .rate_limit(Some(200.0))
        .initial_output(Some(0.25))
        .build()
        .unwrap()
}

#[test]
fn integral_and_limits_match_the_core() {
    let mut storage = MaybeUninit::<FamccO3F64>::uninit();
    let cfg = c_config();
    let st = unsafe { famcc_o3_f64_init(storage.as_mut_ptr(), &cfg, core::ptr::null_mut()) };
    assert_eq!(st, FamccStatus::Ok);
    let mut core = Controller::new(core_config());
    let mut v = 0.0;
    for k in 0..500 {
        let e = 0.8 * (k as f64 * 0.01).cos();
        let st = unsafe { famcc_o3_f64_step(storage.as_mut_ptr(), e, &mut v) };
        assert_eq!(st, FamccStatus::Ok);
        let expected = core.step(e).unwrap();
        assert_eq!(v.to_bits(), expected.to_bits());
        assert!((-1.5..=1.5).contains(&v));
        if k == 0 {
            assert!((v - 0.25).abs() < 1e-6, "bumpless start: {v}");
        }
    }
    let mut d = MaybeUninit::<FamccDiagnosticsF64>::uninit();
    let st = unsafe { famcc_o3_f64_diagnostics(storage.as_ptr(), d.as_mut_ptr()) };
    assert_eq!(st, FamccStatus::Ok);
    let d = unsafe { d.assume_init() };
    let cd = core.diagnostics();
    assert_eq!(d.has_integral, 1);
    assert_eq!(d.integral, cd.integral.unwrap());
    assert_eq!((d.v, d.v_unlimited), (cd.v, cd.v_unlimited));
    assert_eq!(d.integrating, u32::from(cd.integrating));
    assert_eq!(d.unsaturated_expansions, cd.unsaturated_expansions);
}

#[test]
fn bad_output_limits_are_rejected() {
    let mut cfg = c_config();
    cfg.output_limits = [1.0, -1.0];
    let mut storage = MaybeUninit::<FamccO3F64>::uninit();
    let mut err = MaybeUninit::<FamccError>::uninit();
    let st = unsafe { famcc_o3_f64_init(storage.as_mut_ptr(), &cfg, err.as_mut_ptr()) };
    assert_eq!(st, FamccStatus::InvalidConfig);
    let err = unsafe { err.assume_init() };
    let name: std::vec::Vec<u8> = err
        .parameter
        .iter()
        .take_while(|c| **c != 0)
        .map(|c| *c as u8)
        .collect();
    assert_eq!(name, b"output_limits");
}

#[test]
fn lint_through_the_c_abi() {
    let mut cfg = c_config();
    cfg.flexible = FamccFlexible::On as u32;
    cfg.rho_e = 1.0; // > 0.1 eps = 0.2
    let mut storage = MaybeUninit::<FamccO3F64>::uninit();
    let st = unsafe { famcc_o3_f64_init(storage.as_mut_ptr(), &cfg, core::ptr::null_mut()) };
    assert_eq!(st, FamccStatus::Ok);
    let mut count = 0usize;
    let st = unsafe { famcc_o3_f64_lint(storage.as_ptr(), core::ptr::null_mut(), 0, &mut count) };
    assert_eq!((st, count), (FamccStatus::Ok, 1));
    let mut out = [MaybeUninit::<FamccFinding>::uninit(); FAMCC_MAX_FINDINGS];
    let st = unsafe { famcc_o3_f64_lint(storage.as_ptr(), out[0].as_mut_ptr(), out.len(), &mut count) };
    assert_eq!((st, count), (FamccStatus::Ok, 1));
    let f = unsafe { out[0].assume_init() };
    let text: std::string::String = f
        .message
        .iter()
        .take_while(|c| **c != 0)
        .map(|c| *c as u8 as char)
        .collect();
    assert!(
        text.starts_with("rho_e: ") && text.contains("rule: rho_e <= 0.1 eps"),
        "{text}"
    );
    assert_eq!(f.stage, -1);
    // The paper-like configuration has none.
    let st = unsafe { famcc_o3_f64_init(storage.as_mut_ptr(), &c_config(), core::ptr::null_mut()) };
    assert_eq!(st, FamccStatus::Ok);
    let st = unsafe { famcc_o3_f64_lint(storage.as_ptr(), core::ptr::null_mut(), 0, &mut count) };
    assert_eq!((st, count), (FamccStatus::Ok, 0));
}

/// The name of the parameter in an init's error (empty when it succeeded).
fn init_error(cfg: &FamccConfigF64) -> std::vec::Vec<u8> {
    let mut storage = MaybeUninit::<FamccO3F64>::uninit();
    let mut err = MaybeUninit::<FamccError>::zeroed();
    let st = unsafe { famcc_o3_f64_init(storage.as_mut_ptr(), cfg, err.as_mut_ptr()) };
    if st == FamccStatus::Ok {
        return std::vec::Vec::new();
    }
    let err = unsafe { err.assume_init() };
    err.parameter
        .iter()
        .take_while(|c| **c != 0)
        .map(|c| *c as u8)
        .collect()
}

#[test]
fn a_negative_direction_steps_as_the_core() {
    let mut cfg = c_config();
    cfg.direction = FamccDirection::Negative as u32;
    let want = core_config()
        .to_builder()
        .direction(famcc_core::Direction::Negative)
        .build()
        .unwrap();
    assert_eq!(convert::to_config::<f64, 3>(&cfg).unwrap(), want);
    let mut storage = MaybeUninit::<FamccO3F64>::uninit();
    let st = unsafe { famcc_o3_f64_init(storage.as_mut_ptr(), &cfg, core::ptr::null_mut()) };
    assert_eq!(st, FamccStatus::Ok);
    let (mut core, mut positive) = (Controller::new(want), Controller::new(core_config()));
    let mut v = 0.0;
    let mut opposite = 0;
    for k in 0..300 {
        let e = 0.8 * (k as f64 * 0.01).cos();
        let st = unsafe { famcc_o3_f64_step(storage.as_mut_ptr(), e, &mut v) };
        assert_eq!(st, FamccStatus::Ok);
        assert_eq!(v.to_bits(), core.step(e).unwrap().to_bits());
        opposite += usize::from(v * positive.step(e).unwrap() < 0.0);
    }
    assert!(opposite > 250, "{opposite} of 300 outputs of the opposite sign");
    assert_eq!(
        convert::defaults::<f64>().direction,
        FamccDirection::Positive as u32
    );
    cfg.direction = 2;
    assert_eq!(init_error(&cfg), b"direction");
}
