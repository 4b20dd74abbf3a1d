//! Size probe: example 1's order-2 controller built and stepped over
//! volatile I/O. Compare with `size-base` and `size-o2-built`.
#![cfg_attr(target_os = "none", no_std, no_main)]

famcc_fw::size_probe!(famcc_fw_common::suite::example1(), |c, e| {
    famcc_fw::famcc_fw_step_o2(&mut c, e)
});
