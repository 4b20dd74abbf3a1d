//! Size probe: the runtime alone (reset, semihosting exit, panic handler) and
//! the same volatile I/O loop as the controller probes, with no controller.
//! `.text(size-o2) - .text(size-base)` is the order-2 controller's flash.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(not(target_os = "none"))]
fn main() {}

#[cfg(target_os = "none")]
mod app {
    use core::ptr::{addr_of, addr_of_mut, read_volatile, write_volatile};

    static mut INPUT: f32 = 0.0;
    static mut OUTPUT: f32 = 0.0;
    static mut COUNT: u32 = 0;

    #[no_mangle]
    extern "C" fn famcc_fw_main() -> ! {
        // SAFETY: single-threaded; volatile so that nothing is optimised away.
        unsafe {
            for _ in 0..read_volatile(addr_of!(COUNT)) {
                let e = read_volatile(addr_of!(INPUT));
                write_volatile(addr_of_mut!(OUTPUT), e);
            }
        }
        famcc_fw::exit(0)
    }
}
