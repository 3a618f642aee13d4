/* What the example needs from the board: an instruction counter, the
 * semihosting trap (for the calls the C library does not make: the
 * command line), the streams reaching the host, and the stack pointer. One
 * implementation per core family (board_*.c). */
#ifndef BOARD_H
#define BOARD_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

/* Starts the instruction counter. */
void board_counter_start(void);

/* Guest instructions since board_counter_start, under QEMU -icount shift=0
 * (1 ns of virtual time per instruction). */
uint64_t board_counter_insns(void);

/* The semihosting call `op` with the parameter block `arg`; returns what
 * the host put in the result register. */
uintptr_t board_semihost(uintptr_t op, void *arg);

/* The streams that reach the host's stdout and stderr. */
FILE *board_stdout(void);
FILE *board_stderr(void);

/* The current stack pointer. */
static inline uintptr_t board_sp(void) {
    uintptr_t sp;
#if defined(__arm__)
    __asm__ volatile("mov %0, sp" : "=r"(sp));
#elif defined(__riscv)
    __asm__ volatile("mv %0, sp" : "=r"(sp));
#else
#error "board.h: Arm or RISC-V only"
#endif
    return sp;
}

#endif
