//! Runtime for the famcc firmware on QEMU mps2-an386 (Cortex-M4F): vector
//! table and reset handler, ARM semihosting (text output, command line, exit
//! status), the SysTick counter, and the measured step wrappers.
//!
//! Everything target-specific is compiled for `target_os = "none"` only; on
//! the host this crate is empty so that workspace-wide host builds work.
#![no_std]

use famcc_core::Controller;

/// One order-2 controller step, kept out of line so that it can be found
/// and measured (instruction counts, `nm`). NaN on a step error.
#[inline(never)]
#[no_mangle]
pub fn famcc_fw_step_o2(c: &mut Controller<f32, 2>, e: f32) -> f32 {
    c.step(e).unwrap_or(f32::NAN)
}

/// One order-3 controller step (see [`famcc_fw_step_o2`]).
#[inline(never)]
#[no_mangle]
pub fn famcc_fw_step_o3(c: &mut Controller<f32, 3>, e: f32) -> f32 {
    c.step(e).unwrap_or(f32::NAN)
}

#[cfg(target_os = "none")]
pub use rt::*;

#[cfg(target_os = "none")]
mod rt {
    use core::ptr::{read_volatile, write_volatile};
    use famcc_fw_common::out::Sink;

    core::arch::global_asm!(
        r#"
        .section .vector_table, "a", %progbits
        .global __vectors
    __vectors:
        .word _stack_top
        .word Reset
        .word famcc_fw_trap      /* NMI */
        .word famcc_fw_hardfault /* HardFault */
        .word famcc_fw_trap      /* MemManage */
        .word famcc_fw_trap      /* BusFault */
        .word famcc_fw_trap      /* UsageFault */
        .word 0, 0, 0, 0
        .word famcc_fw_trap      /* SVCall */
        .word famcc_fw_trap      /* DebugMon */
        .word 0
        .word famcc_fw_trap      /* PendSV */
        .word famcc_fw_trap      /* SysTick */

        .section .text.Reset, "ax", %progbits
        .global Reset
        .type Reset, %function
        .thumb_func
    Reset:
        /* FPU on (CPACR: CP10 and CP11 full access) before any VFP instruction */
        ldr   r0, =0xE000ED88
        ldr   r1, [r0]
        orr   r1, r1, #(0xF << 20)
        str   r1, [r0]
        dsb
        isb
        /* .data: copy the load image from flash */
        ldr   r0, =__sdata
        ldr   r1, =__edata
        ldr   r2, =__sidata
    1:  cmp   r0, r1
        bhs   2f
        ldr   r3, [r2], #4
        str   r3, [r0], #4
        b     1b
        /* .bss: zero */
    2:  ldr   r0, =__sbss
        ldr   r1, =__ebss
        movs  r2, #0
    3:  cmp   r0, r1
        bhs   4f
        str   r2, [r0], #4
        b     3b
    4:  bl    famcc_fw_main
        b     .

        .section .text.famcc_fw_trap, "ax", %progbits
        .type famcc_fw_trap, %function
        .thumb_func
    famcc_fw_trap:
        movs  r0, #2
        b     famcc_fw_fault

        .section .text.famcc_fw_hardfault, "ax", %progbits
        .type famcc_fw_hardfault, %function
        .thumb_func
    famcc_fw_hardfault:
        movs  r0, #3
        b     famcc_fw_fault
    "#
    );

    const SYS_WRITE0: u32 = 0x04;
    const SYS_GET_CMDLINE: u32 = 0x15;
    const SYS_EXIT_EXTENDED: u32 = 0x20;
    const ADP_STOPPED_APPLICATION_EXIT: u32 = 0x20026;

    /// One semihosting call (`BKPT 0xAB`): operation in r0, argument in r1.
    ///
    /// # Safety
    /// `arg` must be what the operation expects (a valid parameter block).
    #[inline(always)]
    unsafe fn semihost(op: u32, arg: usize) -> u32 {
        let r: u32;
        core::arch::asm!("bkpt #0xab", inout("r0") op => r, in("r1") arg, options(nostack));
        r
    }

    /// Ends the emulation with `code` as QEMU's exit status.
    pub fn exit(code: u32) -> ! {
        let block = [ADP_STOPPED_APPLICATION_EXIT, code];
        // SAFETY: a two-word parameter block, as SYS_EXIT_EXTENDED expects.
        unsafe { semihost(SYS_EXIT_EXTENDED, block.as_ptr() as usize) };
        #[allow(clippy::empty_loop)]
        loop {}
    }

    /// The semihosting command line (QEMU: `-semihosting-config arg=...`),
    /// copied into `buf`; the used part is returned.
    pub fn cmdline(buf: &mut [u8; 128]) -> &[u8] {
        let mut block = [buf.as_mut_ptr() as usize, buf.len() - 1];
        // SAFETY: block = {buffer, capacity}; the host writes at most that much.
        let r = unsafe { semihost(SYS_GET_CMDLINE, block.as_mut_ptr() as usize) };
        if r != 0 {
            return &[];
        }
        let n = block[1].min(buf.len());
        &buf[..n]
    }

    /// Semihosting text output, buffered, flushed on newline and on drop.
    pub struct Out {
        buf: [u8; 257],
        n: usize,
    }

    impl Out {
        /// An empty buffer.
        pub const fn new() -> Self {
            Self { buf: [0; 257], n: 0 }
        }

        /// Sends the buffered text.
        pub fn flush(&mut self) {
            if self.n > 0 {
                self.buf[self.n] = 0;
                // SAFETY: a NUL-terminated string in our buffer.
                unsafe { semihost(SYS_WRITE0, self.buf.as_ptr() as usize) };
                self.n = 0;
            }
        }
    }

    impl Default for Out {
        fn default() -> Self {
            Self::new()
        }
    }

    impl Sink for Out {
        fn bytes(&mut self, b: &[u8]) {
            for &c in b {
                if self.n == self.buf.len() - 1 {
                    self.flush();
                }
                self.buf[self.n] = if c == 0 { b'?' } else { c };
                self.n += 1;
            }
        }
    }

    impl Drop for Out {
        fn drop(&mut self) {
            self.flush();
        }
    }

    #[no_mangle]
    extern "C" fn famcc_fw_fault(kind: u32) -> ! {
        Out::new().s("*** fault: exception trap ").u(u64::from(kind)).nl();
        exit(kind)
    }

    #[panic_handler]
    fn panic(info: &core::panic::PanicInfo) -> ! {
        let mut o = Out::new();
        o.s("*** panic");
        if let Some(l) = info.location() {
            o.s(" at ").s(l.file()).s(":").u(u64::from(l.line()));
        }
        o.nl();
        drop(o);
        exit(101)
    }

    const SYST_CSR: *mut u32 = 0xE000_E010 as *mut u32;
    const SYST_RVR: *mut u32 = 0xE000_E014 as *mut u32;
    const SYST_CVR: *mut u32 = 0xE000_E018 as *mut u32;

    /// Starts SysTick as a free-running 24-bit down-counter on the processor
    /// clock (25 MHz on mps2-an386; QEMU advances it from virtual time, so it
    /// counts instructions under `-icount`).
    pub fn systick_start() {
        // SAFETY: the architectural SysTick registers.
        unsafe {
            write_volatile(SYST_RVR, 0x00FF_FFFF);
            write_volatile(SYST_CVR, 0);
            write_volatile(SYST_CSR, 0b101);
        }
    }

    /// The current SysTick value.
    #[inline(always)]
    pub fn systick_now() -> u32 {
        // SAFETY: the architectural SysTick current-value register.
        unsafe { read_volatile(SYST_CVR) }
    }

    /// Ticks elapsed from `start` to `end` (down-counter, 24 bits).
    #[inline(always)]
    pub fn ticks(start: u32, end: u32) -> u32 {
        start.wrapping_sub(end) & 0x00FF_FFFF
    }
}

/// A flash-size probe program: builds `$build` (a `Result`; exit status 1 on
/// error), then maps a volatile input to a volatile output with `$each` as
/// many times as a volatile count says (never, in practice), so that exactly
/// the code `$build` and `$each` need is linked. On the host the program is
/// empty.
#[macro_export]
macro_rules! size_probe {
    ($build:expr, |$c:ident, $e:ident| $each:expr) => {
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
                #[allow(unused_mut, unused_variables)]
                let Ok(mut $c) = $build
                else {
                    $crate::exit(1)
                };
                // SAFETY: single-threaded; volatile so that nothing is optimised away.
                unsafe {
                    for _ in 0..read_volatile(addr_of!(COUNT)) {
                        let $e = read_volatile(addr_of!(INPUT));
                        write_volatile(addr_of_mut!(OUTPUT), $each);
                    }
                }
                $crate::exit(0)
            }
        }
    };
}
