//! Size probe: example 3's order-3 controller built but never stepped (see
//! `size_o2_built.rs`).
#![cfg_attr(target_os = "none", no_std, no_main)]

famcc_fw::size_probe!(
    famcc_fw_common::suite::example3().map(core::hint::black_box),
    |c, e| e + c.estimate()[0]
);
