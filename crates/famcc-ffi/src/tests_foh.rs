//! The first-order hold (`FAMCC_DISCRETIZATION_FOH`) through the C ABI: a
//! configuration built from C steps bit for bit as the same famcc-core
//! configuration, and its precomputed recursion carries the feedthrough
//! from `*_discretize` to `*_init_discretized` and back.
#![allow(clippy::unwrap_used, clippy::indexing_slicing, clippy::float_cmp)]

extern crate std;

use super::tests::{c_config, rust_example1, rust_example3, signal};
use super::tests_discretized::{init_both, o2_f32, o3_f64};
use super::*;
use core::ffi::CStr;
use core::mem::{offset_of, size_of, MaybeUninit};
use famcc_core::{Config, Controller, Discretization, HighGain, Real};

/// `cfg` with its differentiator switched to the first-order hold.
fn with_foh<T: Real, const N: usize>(cfg: &Config<T, N>) -> Config<T, N> {
    let h = *cfg.differentiator().unwrap();
    cfg.to_builder()
        .differentiator(Some(HighGain {
            discretization: Discretization::Foh,
            ..h
        }))
        .build()
        .unwrap()
}

fn foh_example1<T: Real>() -> Config<T, 2> {
    with_foh(rust_example1::<T>().config())
}

fn foh_example3<T: Real>() -> Config<T, 3> {
    with_foh(rust_example3::<T>().config())
}

macro_rules! foh_matches_core {
    ($name:ident, $t:ty, $n:literal, $storage:ty, $p:ident, $core:ident, $held:ident) => {
        #[test]
        fn $name() {
            use $p::*;
            let core_cfg = $core::<$t>();
            let cfg = c_config(&core_cfg);
            assert_eq!(
                cfg.differentiator.discretization,
                FamccDiscretization::Foh as u32
            );
            // The C ABI builds exactly this configuration, with a feedthrough.
            assert_eq!(convert::to_config::<$t, $n>(&cfg).unwrap(), core_cfg);
            let d = core_cfg.discretized().unwrap();
            assert!(d.feedthrough.iter().all(|x| *x != 0.0), "{d:?}");

            let mut storage = MaybeUninit::<$storage>::zeroed();
            let p = storage.as_mut_ptr();
            let mut err = MaybeUninit::<FamccError>::zeroed();
            assert_eq!(unsafe { init(p, &cfg, err.as_mut_ptr()) }, FamccStatus::Ok);
            let mut ctrl = Controller::new(core_cfg);
            // The held (exact) recursion of the same design, to see that FOH
            // is what runs.
            let mut held = $held::<$t>();
            let input = signal::<$t>(2000);
            let mut first = std::vec::Vec::new();
            let mut differs = false;
            for &e in &input {
                let mut v: $t = 0.0;
                assert_eq!(unsafe { step(p, e, &mut v) }, FamccStatus::Ok);
                let want = ctrl.step(e).unwrap();
                assert_eq!(v.to_bits(), want.to_bits());
                differs |= held.step(e).unwrap().to_bits() != want.to_bits();
                let mut dg = MaybeUninit::<FamccDiagnostics<$t>>::zeroed();
                assert_eq!(unsafe { diagnostics(p, dg.as_mut_ptr()) }, FamccStatus::Ok);
                let dg = unsafe { dg.assume_init() };
                let r = ctrl.diagnostics();
                assert_eq!(dg.z_hat[..$n], r.z_hat[..]);
                assert_eq!(dg.xi.to_bits(), r.xi.to_bits());
                assert_eq!(dg.s.to_bits(), r.s.to_bits());
                assert_eq!(dg.bounds, [r.bounds.0, r.bounds.1]);
                first.push(v);
            }
            assert!(differs, "the first-order hold steps as the held recursion");
            // reset: the same outputs again
            assert_eq!(unsafe { reset(p) }, FamccStatus::Ok);
            for (&e, &want) in input.iter().zip(&first) {
                let mut v: $t = 0.0;
                assert_eq!(unsafe { step(p, e, &mut v) }, FamccStatus::Ok);
                assert_eq!(v.to_bits(), want.to_bits());
            }
        }
    };
}

macro_rules! foh_precomputed_round_trips {
    ($name:ident, $t:ty, $n:literal, $storage:ty, $p:ident, $core:ident) => {
        #[test]
        fn $name() {
            use $p::*;
            let core_cfg = $core::<$t>();
            let cfg = c_config(&core_cfg);
            let mut err = MaybeUninit::<FamccError>::zeroed();
            let mut d = FamccDiscretized::<$t>::default();
            assert_eq!(
                unsafe { discretize(&cfg, &mut d, err.as_mut_ptr()) },
                FamccStatus::Ok
            );
            // The core's feedthrough, bit for bit, in the first N entries.
            let want = core_cfg.discretized().unwrap();
            assert!(want.feedthrough.iter().all(|x| *x != 0.0));
            for i in 0..FAMCC_MAX_ORDER {
                let ft = want.feedthrough.get(i).copied().unwrap_or(0.0);
                assert_eq!(d.feedthrough[i].to_bits(), ft.to_bits(), "entry {i}");
            }
            // ... and back: C recursion -> core -> C recursion is the identity.
            let back = convert::to_config_discretized::<$t, $n>(&cfg, &d).unwrap();
            assert_eq!(back, core_cfg);
            assert_eq!(convert::discretized_to_c(&back.discretized().unwrap()), d);

            // The target side steps as `*_init`.
            let (mut a, mut b) = init_both!($storage, &cfg, &d, err);
            // Without the feedthrough the recursion is another (valid) one:
            // the feedthrough is read, not ignored.
            let mut c = MaybeUninit::<$storage>::zeroed();
            let dropped = FamccDiscretized {
                feedthrough: [0.0; FAMCC_MAX_ORDER],
                ..d
            };
            let status = unsafe { init_discretized(c.as_mut_ptr(), &cfg, &dropped, err.as_mut_ptr()) };
            assert_eq!(status, FamccStatus::Ok);
            let mut differs = false;
            for e in signal::<$t>(2000) {
                let (mut va, mut vb, mut vc): ($t, $t, $t) = (0.0, 0.0, 0.0);
                assert_eq!(unsafe { step(a.as_mut_ptr(), e, &mut va) }, FamccStatus::Ok);
                assert_eq!(unsafe { step(b.as_mut_ptr(), e, &mut vb) }, FamccStatus::Ok);
                assert_eq!(unsafe { step(c.as_mut_ptr(), e, &mut vc) }, FamccStatus::Ok);
                assert_eq!(va.to_bits(), vb.to_bits());
                differs |= va.to_bits() != vc.to_bits();
            }
            assert!(differs);

            // A non-finite feedthrough is rejected, naming the parameter.
            let mut nan = d;
            nan.feedthrough[$n - 1] = <$t>::INFINITY;
            let status = unsafe { init_discretized(c.as_mut_ptr(), &cfg, &nan, err.as_mut_ptr()) };
            assert_eq!(status, FamccStatus::InvalidConfig);
            let err_v = unsafe { err.assume_init() };
            let parameter = unsafe { CStr::from_ptr(err_v.parameter.as_ptr()) };
            assert_eq!(parameter.to_str().unwrap(), "discretized");
            let rule = unsafe { CStr::from_ptr(err_v.rule.as_ptr()) };
            assert!(rule.to_str().unwrap().contains("feedthrough"));
        }
    };
}

foh_matches_core!(
    o2_f32_foh_matches_core,
    f32,
    2,
    FamccO2F32,
    o2_f32,
    foh_example1,
    rust_example1
);
foh_matches_core!(
    o3_f64_foh_matches_core,
    f64,
    3,
    FamccO3F64,
    o3_f64,
    foh_example3,
    rust_example3
);
foh_precomputed_round_trips!(
    o2_f32_foh_precomputed_round_trips,
    f32,
    2,
    FamccO2F32,
    o2_f32,
    foh_example1
);
foh_precomputed_round_trips!(
    o3_f64_foh_precomputed_round_trips,
    f64,
    3,
    FamccO3F64,
    o3_f64,
    foh_example3
);

/// `feedthrough` is appended: the fields before it keep their offsets.
#[test]
fn feedthrough_is_the_last_field() {
    fn check<T>() {
        let t = size_of::<T>();
        let n = FAMCC_MAX_ORDER;
        assert_eq!(offset_of!(FamccDiscretized<T>, phi), 0);
        assert_eq!(offset_of!(FamccDiscretized<T>, gamma), n * n * t);
        assert_eq!(offset_of!(FamccDiscretized<T>, prefilter), (n * n + n) * t);
        assert_eq!(offset_of!(FamccDiscretized<T>, feedthrough), (n * n + n + 1) * t);
        assert_eq!(size_of::<FamccDiscretized<T>>(), (n * n + 2 * n + 1) * t);
    }
    check::<f32>();
    check::<f64>();
}
