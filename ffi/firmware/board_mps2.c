/* The MPS2 AN386 board (Cortex-M4) under QEMU: vector table and reset
 * (with the FPU enabled on hard-float builds), the CMSDK timer 0 as the
 * instruction counter, and Arm semihosting for the command line and exit.
 * Linked with mps2-an386.ld; newlib-nano's stdio reaches the host through
 * librdimon (--specs=rdimon.specs), which the reset code initialises. */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "board.h"

extern int main(void);
extern void exit(int status) __attribute__((noreturn));
extern void initialise_monitor_handles(void);

/* From the linker script. */
extern uint32_t __data_load__[], __data_start__[], __data_end__[];
extern uint32_t __bss_start__[], __bss_end__[];
extern uint32_t __stack_top[];

/* Semihosting: operation `op` with parameter block `arg` (bkpt 0xab). */
uintptr_t board_semihost(uintptr_t op, void *arg) {
    register uintptr_t r0 __asm__("r0") = op;
    register void *r1 __asm__("r1") = arg;
    __asm__ volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
    return r0;
}

#define SYS_EXIT_EXTENDED 0x20
#define ADP_STOPPED_APPLICATION_EXIT 0x20026

static __attribute__((noreturn)) void semihost_exit(int status) {
    uintptr_t block[2] = {ADP_STOPPED_APPLICATION_EXIT, (uintptr_t)status};
    for (;;) board_semihost(SYS_EXIT_EXTENDED, block);
}


/* librdimon opens them on the host's stdout and stderr. */
FILE *board_stdout(void) { return stdout; }
FILE *board_stderr(void) { return stderr; }

/* CMSDK APB timer 0: a 32-bit down-counter at SYSCLK, 25 MHz, so one tick
 * per 40 instructions under -icount shift=0. */
#define TIMER0_CTRL (*(volatile uint32_t *)0x40000000u)
#define TIMER0_VALUE (*(volatile uint32_t *)0x40000004u)
#define TIMER0_RELOAD (*(volatile uint32_t *)0x40000008u)

void board_counter_start(void) {
    TIMER0_CTRL = 0;
    TIMER0_RELOAD = 0xffffffffu;
    TIMER0_VALUE = 0xffffffffu;
    TIMER0_CTRL = 1;
}

uint64_t board_counter_insns(void) {
    return (uint64_t)(0xffffffffu - TIMER0_VALUE) * 40u;
}

void Reset_Handler(void) {
    memcpy(__data_start__, __data_load__, (size_t)((char *)__data_end__ - (char *)__data_start__));
    memset(__bss_start__, 0, (size_t)((char *)__bss_end__ - (char *)__bss_start__));
#if defined(__ARM_FP)
    /* Full access to CP10 and CP11, the FPU: a hard-float (or softfp) build
     * executes VFP instructions, which fault (NOCP UsageFault) until then. */
    *(volatile uint32_t *)0xE000ED88u |= 0xFu << 20;
    __asm__ volatile("dsb\n\tisb" ::: "memory");
#endif
    initialise_monitor_handles();
    exit(main());
}

/* Any fault (a trap in the library's panic handler included): exit 101,
 * as the Rust firmware does on a panic. */
static void Fault_Handler(void) { semihost_exit(101); }

__attribute__((section(".vectors"), used)) static void (*const vectors[16])(void) = {
    (void (*)(void))__stack_top,
    Reset_Handler,
    Fault_Handler, /* NMI */
    Fault_Handler, /* HardFault */
    Fault_Handler, /* MemManage */
    Fault_Handler, /* BusFault */
    Fault_Handler, /* UsageFault */
    0, 0, 0, 0,
    Fault_Handler, /* SVCall */
    Fault_Handler, /* DebugMonitor */
    0,
    Fault_Handler, /* PendSV */
    Fault_Handler, /* SysTick */
};
