/* QEMU's RISC-V `virt` machine, RV32 (qemu-system-riscv32 -bios none):
 * picolibc's crt0 starts the program in machine mode and, with
 * --oslib=semihost --crt0=semihost, exits through semihosting; its stdio
 * reaches the host the same way. The command line is read here (that crt0
 * makes up a program name). The instruction counter is the minstret CSR,
 * which QEMU counts exactly under -icount. */
#include "board.h"

/* Semihosting: operation `op` with parameter block `arg`. The trap is
 * ebreak between two marker instructions, uncompressed and in one page
 * (the RISC-V semihosting specification). */
uintptr_t board_semihost(uintptr_t op, void *arg) {
    register uintptr_t a0 __asm__("a0") = op;
    register void *a1 __asm__("a1") = arg;
    __asm__ volatile(".option push\n\t.option norvc\n\t.balign 16\n\t"
                     "slli zero, zero, 0x1f\n\tebreak\n\tsrai zero, zero, 0x7\n\t.option pop"
                     : "+r"(a0)
                     : "r"(a1)
                     : "memory");
    return a0;
}



/* picolibc's stdout and stderr both write to the semihosting console, one
 * stream on the host. The special file ":tt" opened for writing is the
 * host's stdout, opened for appending its stderr (Arm's semihosting
 * specification, which RISC-V's follows). */
static FILE *tt(FILE **f, const char *mode, FILE *fallback) {
    if (!*f) *f = fopen(":tt", mode);
    return *f ? *f : fallback;
}

FILE *board_stdout(void) {
    static FILE *f;
    return tt(&f, "w", stdout);
}

FILE *board_stderr(void) {
    static FILE *f;
    return tt(&f, "a", stderr);
}

/* minstret / minstreth, read with .insn: the encoding needs no Zicsr in
 * -march (picolibc's multilibs are named without it). The CSR numbers are
 * written as signed 12-bit immediates. */
static inline uint32_t instret_lo(void) {
    uint32_t v;
    __asm__ volatile(".insn i 0x73, 2, %0, x0, -1278" : "=r"(v)); /* csrr v, minstret (0xb02) */
    return v;
}

static inline uint32_t instret_hi(void) {
    uint32_t v;
    __asm__ volatile(".insn i 0x73, 2, %0, x0, -1150" : "=r"(v)); /* csrr v, minstreth (0xb82) */
    return v;
}

static uint64_t instret(void) {
    uint32_t hi, lo;
    do {
        hi = instret_hi();
        lo = instret_lo();
    } while (hi != instret_hi());
    return ((uint64_t)hi << 32) | lo;
}

static uint64_t start;

void board_counter_start(void) { start = instret(); }

uint64_t board_counter_insns(void) { return instret() - start; }
