/* What the example needs from the board: an instruction counter, the
 * semihosting calls the C library does not make (the command line, exit),
 * and the stack pointer. One implementation per core family (board_*.c). */
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

/* Writes the semihosting command line (the program's name and arguments,
 * separated by spaces) and a NUL to buf; returns 0, or -1 when there is
 * none. */
int board_cmdline(char *buf, size_t size);

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
