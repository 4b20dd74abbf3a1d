//! Size probe: example 3's order-3 controller (`Controller::new` with the
//! discretization of the differentiator, and `step`) over volatile I/O.
//! Compare with `size-base`.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(not(target_os = "none"))]
fn main() {}

#[cfg(target_os = "none")]
mod app {
    use core::ptr::{addr_of, addr_of_mut, read_volatile, write_volatile};
    use famcc_fw_common::designs;
    use famcc_fw_common::plant::Variant;

    static mut INPUT: f32 = 0.0;
    static mut OUTPUT: f32 = 0.0;
    static mut COUNT: u32 = 0;

    #[no_mangle]
    extern "C" fn famcc_fw_main() -> ! {
        let Ok(mut c) = designs::example3(Variant::Code, 1e-3) else {
            famcc_fw::exit(1)
        };
        // SAFETY: single-threaded; volatile so that nothing is optimised away.
        unsafe {
            for _ in 0..read_volatile(addr_of!(COUNT)) {
                let e = read_volatile(addr_of!(INPUT));
                write_volatile(addr_of_mut!(OUTPUT), famcc_fw::famcc_fw_step_o3(&mut c, e));
            }
        }
        famcc_fw::exit(0)
    }
}
