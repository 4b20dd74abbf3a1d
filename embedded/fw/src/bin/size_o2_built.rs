//! Size probe: example 1's order-2 controller built (configuration,
//! validation, discretization of the differentiator, `Controller::new`) but
//! never stepped. `.text(size-o2-stepped) - .text(size-o2-built)` is the
//! code only `step` needs.
#![cfg_attr(target_os = "none", no_std, no_main)]

famcc_fw::size_probe!(
    famcc_fw_common::suite::example1().map(core::hint::black_box),
    |c, e| e + c.estimate()[0]
);
