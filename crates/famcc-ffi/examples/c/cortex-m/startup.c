/*
 * Minimal Cortex-M4F start-up for running the C example under QEMU
 * mps2-an386 with newlib's semihosting runtime (rdimon): a vector table at
 * address 0 (placed by link.ld), and a reset handler that enables the FPU
 * before any floating-point instruction and enters newlib's _start (which
 * sets up the stack and heap through semihosting, zeroes .bss, runs main and
 * exits through semihosting: QEMU's exit status is 0 for exit(0), 1 otherwise).
 */
#include <stdint.h>

extern void _start(void);
extern uint32_t __stack_top;
void famcc_example_reset(void);
void famcc_example_fault(void);
extern void (*const famcc_example_vectors[16])(void);

__attribute__((section(".vectors"), used)) void (*const famcc_example_vectors[16])(void) = {
    (void (*)(void))&__stack_top, /* initial SP */
    famcc_example_reset,          /* Reset */
    famcc_example_fault,          /* NMI */
    famcc_example_fault,          /* HardFault */
    famcc_example_fault,          /* MemManage */
    famcc_example_fault,          /* BusFault */
    famcc_example_fault,          /* UsageFault */
    0, 0, 0, 0,
    famcc_example_fault,          /* SVCall */
    famcc_example_fault,          /* DebugMon */
    0,
    famcc_example_fault,          /* PendSV */
    famcc_example_fault,          /* SysTick */
};

void famcc_example_reset(void)
{
    /* CPACR: full access to CP10 and CP11 (the FPU). */
    *(volatile uint32_t *)0xE000ED88u |= 0xFu << 20;
    __asm__ volatile("dsb\n\tisb" ::: "memory");
    _start();
    for (;;) {
    }
}

void famcc_example_fault(void)
{
    /* SYS_EXIT (0x18) with a non-zero reason: QEMU exits with status 1. */
    register uint32_t r0 __asm__("r0") = 0x18;
    register uint32_t r1 __asm__("r1") = 0x20024; /* ADP_Stopped_RunTimeErrorUnknown */
    __asm__ volatile("bkpt #0xab" : : "r"(r0), "r"(r1) : "memory");
    for (;;) {
    }
}
