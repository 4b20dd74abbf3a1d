//! Size probe: the runtime alone (reset, semihosting exit, panic handler) and
//! the same volatile I/O loop as the controller probes, with no controller.
//! `.text(size-o2-stepped) - .text(size-base)` is the order-2 controller's flash.
#![cfg_attr(target_os = "none", no_std, no_main)]

famcc_fw::size_probe!(Ok::<(), ()>(()), |c, e| e);
