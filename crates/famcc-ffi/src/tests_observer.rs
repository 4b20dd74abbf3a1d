//! The observer through the C ABI: a C configuration with an observer
//! builds exactly famcc-core's and steps bit for bit as it (the applied
//! input too), its diagnostics carry the cancellation and the estimate of
//! the lumped term, the binomial helper is the core's, every bad field is
//! named, and in closed loop it removes the steady error of a constant load
//! that the plain differentiator leaves.
#![allow(clippy::unwrap_used, clippy::indexing_slicing, clippy::float_cmp)]

extern crate std;

use super::tests::{c_config, rust_example1, rust_example3, signal};
use super::tests_discretized::{o2_f32, o3_f64};
use super::*;
use core::ffi::CStr;
use core::mem::MaybeUninit;
use famcc_core::{Config, Controller, Direction, Discretization, ExtendedHighGain, Real};
use famcc_paper::rk4::{rk4_with, Instant};

/// `cfg` with the binomial observer (`mu`, `b0`) in its differentiator's
/// place, output limits `±limit` and the cancellation bounded by `delta`.
fn observed<T: Real, const N: usize>(
    cfg: &Config<T, N>,
    mu: f64,
    b0: f64,
    limit: f64,
    delta: f64,
) -> Config<T, N> {
    let f = T::from_f64;
    cfg.to_builder()
        .differentiator(None)
        .direction(Direction::of(b0).unwrap_or_default())
        .observer(Some(ExtendedHighGain::binomial(f(mu), f(b0))))
        .output_limits(Some((f(-limit), f(limit))))
        .cancellation_limit(Some(f(delta)))
        .build()
        .unwrap()
}

/// A change that spoils a configuration.
type Spoil = fn(&mut FamccConfigF64);

fn error_parameter(err: &MaybeUninit<FamccError>) -> std::string::String {
    let e = unsafe { err.assume_init_ref() };
    unsafe { CStr::from_ptr(e.parameter.as_ptr()) }
        .to_str()
        .unwrap()
        .into()
}

macro_rules! observer_matches_core {
    ($name:ident, $t:ty, $n:literal, $storage:ty, $p:ident, $applied:ident, $cfg:expr) => {
        #[test]
        fn $name() {
            use $p::*;
            let core_cfg: Config<$t, $n> = $cfg;
            let cfg = c_config(&core_cfg);
            assert_eq!(convert::to_config::<$t, $n>(&cfg).unwrap(), core_cfg);
            let mut storage = MaybeUninit::<$storage>::zeroed();
            let p = storage.as_mut_ptr();
            let mut err = MaybeUninit::<FamccError>::zeroed();
            assert_eq!(unsafe { init(p, &cfg, err.as_mut_ptr()) }, FamccStatus::Ok);
            let mut ctrl = Controller::new(core_cfg);
            let (mut cancelled, mut clipped) = (false, false);
            for (k, &e) in signal::<$t>(2000).iter().enumerate() {
                let mut v: $t = 0.0;
                // every third sample reports a clipped actuator
                let (status, want) = if k % 3 == 1 {
                    let a = (0.7 * k as f64).sin() as $t;
                    (
                        unsafe { crate::$applied(p, e, a, &mut v) },
                        ctrl.step_applied(e, Some(a)),
                    )
                } else {
                    (unsafe { step(p, e, &mut v) }, ctrl.step(e))
                };
                assert_eq!(status, FamccStatus::Ok, "step {k}");
                assert_eq!(v.to_bits(), want.unwrap().to_bits(), "step {k}");
                let mut dg = MaybeUninit::<FamccDiagnostics<$t>>::zeroed();
                assert_eq!(unsafe { diagnostics(p, dg.as_mut_ptr()) }, FamccStatus::Ok);
                let dg = unsafe { dg.assume_init() };
                let r = ctrl.diagnostics();
                assert_eq!(
                    dg.cancellation.to_bits(),
                    r.cancellation.to_bits(),
                    "step {k}"
                );
                assert_eq!(dg.lumped.to_bits(), ctrl.lumped().to_bits(), "step {k}");
                assert_eq!(dg.z_hat[..$n], r.z_hat[..]);
                cancelled |= dg.cancellation != 0.0;
                clipped |= dg.cancellation.abs() == core_cfg.cancellation_limit().unwrap();
            }
            assert!(
                cancelled && clipped,
                "the cancellation acted, and hit its bound"
            );
        }
    };
}

observer_matches_core!(
    o2_f32_observer_matches_core,
    f32,
    2,
    FamccO2F32,
    o2_f32,
    famcc_o2_f32_step_applied,
    observed(rust_example1::<f32>().config(), 0.02, 2.0, 10.0, 0.5)
);
observer_matches_core!(
    o3_f64_observer_matches_core,
    f64,
    3,
    FamccO3F64,
    o3_f64,
    famcc_o3_f64_step_applied,
    observed(rust_example3::<f64>().config(), 0.01, 2.0, 20.0, 1.0)
);
observer_matches_core!(
    o2_f64_foh_observer_matches_core,
    f64,
    2,
    FamccO2F64,
    o2_f64,
    famcc_o2_f64_step_applied,
    {
        let c = observed(rust_example1::<f64>().config(), 0.02, -2.0, 10.0, 0.5);
        let o = c.observer().unwrap().with_discretization(Discretization::Foh);
        c.to_builder().observer(Some(o)).build().unwrap()
    }
);

mod o2_f64 {
    pub(crate) use crate::{
        famcc_o2_f64_diagnostics as diagnostics, famcc_o2_f64_init as init, famcc_o2_f64_step as step,
    };
}

#[test]
fn binomial_is_the_cores_at_every_order() {
    fn check<const N: usize>() {
        let mut c = FamccObserverF64::default();
        let s = unsafe { famcc_observer_f64_binomial(N as u32, 0.02, -1.5, &mut c) };
        assert_eq!(s, FamccStatus::Ok);
        let want = ExtendedHighGain::<f64, N>::binomial(0.02, -1.5);
        assert_eq!(observer::to_core::<f64, N>(&c).unwrap(), Some(want));
        assert_eq!((c.enabled, c.has_cancellation_limit), (1, 0));
        assert!(c.a[N + 1..].iter().all(|x| *x == 0.0), "{c:?}");
        let mut c32 = FamccObserverF32::default();
        assert_eq!(
            unsafe { famcc_observer_f32_binomial(N as u32, 0.02, 2.0, &mut c32) },
            FamccStatus::Ok
        );
        assert_eq!(c32.a[N], 2f32.powi(N as i32 + 1)); // (s + 2)^(N+1)
    }
    check::<1>();
    check::<2>();
    check::<3>();
    check::<4>();
    check::<5>();
    check::<6>();
    let mut c = FamccObserverF64::default();
    for bad in [0, 7, u32::MAX] {
        let s = unsafe { famcc_observer_f64_binomial(bad, 0.02, 1.0, &mut c) };
        assert_eq!(s, FamccStatus::InvalidConfig, "order {bad}");
    }
    assert_eq!(c, FamccObserverF64::default(), "nothing written on error");
    let null = unsafe { famcc_observer_f64_binomial(2, 0.02, 1.0, core::ptr::null_mut()) };
    assert_eq!(null, FamccStatus::NullPointer);
}

#[test]
fn every_bad_observer_field_is_named() {
    let good = c_config(&observed(rust_example1::<f64>().config(), 0.02, 2.0, 10.0, 0.5));
    let cases: [(&str, Spoil); 8] = [
        ("b0", |c| c.observer.b0 = 0.0),
        ("observer_mu", |c| c.observer.mu = -1.0),
        ("observer_a", |c| c.observer.a[2] = 100.0), // s^3 + 6 s^2 + 12 s + 100: not Hurwitz
        ("observer.discretization", |c| c.observer.discretization = 99),
        ("observer_discretization", |c| {
            c.observer.discretization = FamccDiscretization::Tustin as u32
        }),
        ("differentiator", |c| {
            c.differentiator = c_config(rust_example1::<f64>().config()).differentiator
        }),
        ("cancellation_limit", |c| {
            (c.observer.has_cancellation_limit, c.has_output_limits) = (0, 0)
        }),
        ("cancellation_limit", |c| c.observer.cancellation_limit = 0.0),
    ];
    for (want, spoil) in cases {
        let mut cfg = good;
        spoil(&mut cfg);
        let mut s = MaybeUninit::<FamccO2F64>::zeroed();
        let mut err = MaybeUninit::<FamccError>::zeroed();
        let status = unsafe { famcc_o2_f64_init(s.as_mut_ptr(), &cfg, err.as_mut_ptr()) };
        assert_eq!(status, FamccStatus::InvalidConfig, "{want}");
        assert_eq!(error_parameter(&err), want);
        // and the storage reads as not initialised
        let mut v = 0.0;
        let st = unsafe { famcc_o2_f64_step(s.as_mut_ptr(), 0.1, &mut v) };
        assert_eq!(st, FamccStatus::NotInitialized, "{want}");
    }
    // A cancellation limit without an observer is named too.
    let mut plain = c_config(rust_example1::<f64>().config());
    (
        plain.observer.has_cancellation_limit,
        plain.observer.cancellation_limit,
    ) = (1, 1.0);
    let mut s = MaybeUninit::<FamccO2F64>::zeroed();
    let mut err = MaybeUninit::<FamccError>::zeroed();
    let status = unsafe { famcc_o2_f64_init(s.as_mut_ptr(), &plain, err.as_mut_ptr()) };
    assert_eq!(status, FamccStatus::InvalidConfig);
    assert_eq!(error_parameter(&err), "cancellation_limit");
}

/// `y'' = -y' + 2 u + load` sampled at 1 kHz (famcc-paper's RK4, four
/// substeps under the held input): the steady error `|y - r|` over the last second of 12 s.
fn steady_error(cfg: &FamccConfigF64, load: f64) -> f64 {
    let mut s = MaybeUninit::<FamccO2F64>::zeroed();
    let mut err = MaybeUninit::<FamccError>::zeroed();
    assert_eq!(
        unsafe { famcc_o2_f64_init(s.as_mut_ptr(), cfg, err.as_mut_ptr()) },
        FamccStatus::Ok
    );
    let (r, mut x, mut worst) = (1.0, [0.0f64, 0.0], 0.0f64);
    for k in 0..12000 {
        let mut u = 0.0;
        assert_eq!(
            unsafe { famcc_o2_f64_step(s.as_mut_ptr(), x[0] - r, &mut u) },
            FamccStatus::Ok
        );
        let f = |_: Instant, x: &[f64; 2]| [x[1], -x[1] + 2.0 * u + load];
        for _ in 0..4 {
            x = rk4_with(f, &x, 1e-3 / 4.0);
        }
        if k >= 11000 {
            worst = worst.max((x[0] - r).abs());
        }
    }
    worst
}

#[test]
fn the_observer_removes_a_constant_loads_steady_error() {
    let plain = rust_example1::<f64>();
    let plain = plain
        .config()
        .to_builder()
        .output_limits(Some((-10.0, 10.0)))
        .build()
        .unwrap();
    let with = observed(&plain, 0.02, 2.0, 10.0, 5.0);
    let load = 3.0; // holding needs u = -1.5 (and y' = 0)
    let e_plain = steady_error(&c_config(&plain), load);
    let e_obs = steady_error(&c_config(&with), load);
    let eps = plain.constraint().eps().0;
    // Both keep the preset accuracy; only the observer removes the floor.
    assert!(e_plain < eps && e_obs < eps, "{e_plain} {e_obs}");
    // Measured: 1.1e-4 against 1.5e-2 (the plain law's holding-input floor).
    assert!(e_obs < 0.02 * e_plain, "observer {e_obs:e} vs plain {e_plain:e}");
}

#[test]
fn a_precomputed_recursion_is_refused_with_an_observer() {
    let with = c_config(&observed(rust_example1::<f64>().config(), 0.02, 2.0, 10.0, 0.5));
    let plain = c_config(rust_example1::<f64>().config());
    let mut d = FamccDiscretizedF64::default();
    let mut err = MaybeUninit::<FamccError>::zeroed();
    assert_eq!(
        unsafe { famcc_o2_f64_discretize(&plain, &mut d, err.as_mut_ptr()) },
        FamccStatus::Ok
    );
    let mut s = MaybeUninit::<FamccO2F64>::zeroed();
    let status = unsafe { famcc_o2_f64_init_discretized(s.as_mut_ptr(), &with, &d, err.as_mut_ptr()) };
    assert_eq!(status, FamccStatus::InvalidConfig);
    assert_eq!(error_parameter(&err), "differentiator");
    assert_eq!(
        unsafe { famcc_o2_f64_discretize(&with, &mut d, err.as_mut_ptr()) },
        FamccStatus::InvalidConfig
    );
}
