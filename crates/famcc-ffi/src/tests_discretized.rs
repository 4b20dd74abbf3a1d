//! The precomputed recursion through the C ABI: `*_discretize` on the host
//! side, `*_init_discretized` on the target side, the same outputs bit for
//! bit as `*_init`, and the checks of a recursion that is not usable.
#![allow(clippy::unwrap_used, clippy::indexing_slicing, clippy::float_cmp)]

extern crate std;

use super::tests::{c_example1, c_example3, signal};
use super::*;
use core::ffi::CStr;
use core::mem::MaybeUninit;

/// Two controllers of `$storage` from `cfg`: one by `init`, one by
/// `init_discretized` with the precomputed recursion `d` (both must succeed).
macro_rules! init_both {
    ($storage:ty, $cfg:expr, $d:expr, $err:ident) => {{
        let mut a = MaybeUninit::<$storage>::zeroed();
        let mut b = MaybeUninit::<$storage>::zeroed();
        assert_eq!(
            unsafe { init(a.as_mut_ptr(), $cfg, $err.as_mut_ptr()) },
            FamccStatus::Ok
        );
        let status = unsafe { init_discretized(b.as_mut_ptr(), $cfg, $d, $err.as_mut_ptr()) };
        assert_eq!(status, FamccStatus::Ok);
        (a, b)
    }};
}
pub(super) use init_both;

macro_rules! precomputed_matches_init {
    ($name:ident, $t:ty, $storage:ty, $p:ident, $cfg:ident) => {
        #[test]
        fn $name() {
            use $p::*;
            let cfg = $cfg::<$t>();
            let mut err = MaybeUninit::<FamccError>::zeroed();
            let mut d = FamccDiscretized::<$t>::default();
            assert_eq!(
                unsafe { discretize(&cfg, &mut d, err.as_mut_ptr()) },
                FamccStatus::Ok
            );
            assert!(d.prefilter == 1.0 && d.phi[0][0] != 0.0);
            let (mut a, mut b) = init_both!($storage, &cfg, &d, err);
            for e in signal::<$t>(2000) {
                let (mut va, mut vb): ($t, $t) = (0.0, 0.0);
                assert_eq!(unsafe { step(a.as_mut_ptr(), e, &mut va) }, FamccStatus::Ok);
                assert_eq!(unsafe { step(b.as_mut_ptr(), e, &mut vb) }, FamccStatus::Ok);
                assert_eq!(va.to_bits(), vb.to_bits());
            }

            // An unstable recursion is rejected, and names the parameter.
            let mut unstable = d;
            unstable.phi[1][1] = 1.5;
            let mut c = MaybeUninit::<$storage>::zeroed();
            let status = unsafe { init_discretized(c.as_mut_ptr(), &cfg, &unstable, err.as_mut_ptr()) };
            assert_eq!(status, FamccStatus::InvalidConfig);
            let err_v = unsafe { err.assume_init() };
            let parameter = unsafe { CStr::from_ptr(err_v.parameter.as_ptr()) };
            assert_eq!(parameter.to_str().unwrap(), "discretized");
            // ... as is a NaN entry, and a prefilter gain outside (0, 1].
            let mut nan = d;
            nan.gamma[0] = <$t>::NAN;
            let status = unsafe { init_discretized(c.as_mut_ptr(), &cfg, &nan, core::ptr::null_mut()) };
            assert_eq!(status, FamccStatus::InvalidConfig);
            let gain = FamccDiscretized {
                prefilter: 0.0,
                ..d
            };
            let status = unsafe { init_discretized(c.as_mut_ptr(), &cfg, &gain, core::ptr::null_mut()) };
            assert_eq!(status, FamccStatus::InvalidConfig);
            // The storage of a rejected configuration is not a controller.
            let mut v: $t = 0.0;
            assert_eq!(
                unsafe { step(c.as_mut_ptr(), 0.1, &mut v) },
                FamccStatus::NotInitialized
            );

            // Null pointers.
            let null = core::ptr::null();
            let status = unsafe { init_discretized(c.as_mut_ptr(), &cfg, null, core::ptr::null_mut()) };
            assert_eq!(status, FamccStatus::NullPointer);
            let status = unsafe { discretize(&cfg, core::ptr::null_mut(), core::ptr::null_mut()) };
            assert_eq!(status, FamccStatus::NullPointer);

            // Without a differentiator there is nothing to precompute.
            let mut state_feedback = cfg;
            state_feedback.differentiator.enabled = 0;
            let status = unsafe { discretize(&state_feedback, &mut d, err.as_mut_ptr()) };
            assert_eq!(status, FamccStatus::InvalidConfig);
            let err_v = unsafe { err.assume_init() };
            let parameter = unsafe { CStr::from_ptr(err_v.parameter.as_ptr()) };
            assert_eq!(parameter.to_str().unwrap(), "differentiator.enabled");
        }
    };
}

/// The order-2 `float` functions under short names (also for tests_foh.rs).
pub(super) mod o2_f32 {
    pub(crate) use crate::{
        famcc_o2_f32_diagnostics as diagnostics, famcc_o2_f32_discretize as discretize,
        famcc_o2_f32_init as init, famcc_o2_f32_init_discretized as init_discretized,
        famcc_o2_f32_reset as reset, famcc_o2_f32_step as step,
    };
}

/// The order-3 `double` functions under short names (also for tests_foh.rs).
pub(super) mod o3_f64 {
    pub(crate) use crate::{
        famcc_o3_f64_diagnostics as diagnostics, famcc_o3_f64_discretize as discretize,
        famcc_o3_f64_init as init, famcc_o3_f64_init_discretized as init_discretized,
        famcc_o3_f64_reset as reset, famcc_o3_f64_step as step,
    };
}

precomputed_matches_init!(
    o2_f32_precomputed_matches_init,
    f32,
    FamccO2F32,
    o2_f32,
    c_example1
);
precomputed_matches_init!(
    o3_f64_precomputed_matches_init,
    f64,
    FamccO3F64,
    o3_f64,
    c_example3
);
