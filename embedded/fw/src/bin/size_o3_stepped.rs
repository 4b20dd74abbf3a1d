//! Size probe: example 3's order-3 controller built and stepped (see
//! `size_o2_stepped.rs`).
#![cfg_attr(target_os = "none", no_std, no_main)]

famcc_fw::size_probe!(famcc_fw_common::suite::example3(), |c, e| {
    famcc_fw::famcc_fw_step_o3(&mut c, e)
});
