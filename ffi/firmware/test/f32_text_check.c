/* Prints f32_text of a sequence of bit patterns, one a line, for
 * comparison with Rust's `{}` of the same values (f32_text_check.rs, the
 * same sequence): every STEP-th pattern, every pattern in [LO, LO + N),
 * and the special values. Run by run.sh --check on the host. */
#include <stdio.h>
#include <stdlib.h>

#include "f32_text.h"

int main(int argc, char **argv) {
    if (argc != 4) {
        fprintf(stderr, "usage: f32_text_check STEP LO N\n");
        return 2;
    }
    unsigned long long step = strtoull(argv[1], NULL, 0);
    uint32_t lo = (uint32_t)strtoul(argv[2], NULL, 0);
    uint32_t n = (uint32_t)strtoul(argv[3], NULL, 0);
    char buf[F32_TEXT_MAX];
    for (unsigned long long b = 0; b <= 0xffffffffull; b += step) {
        f32_text(buf, (uint32_t)b);
        puts(buf);
    }
    for (uint32_t i = 0; i < n; i++) {
        f32_text(buf, lo + i);
        puts(buf);
    }
    static const uint32_t special[] = {0x00000000u, 0x80000000u, 0x7f800000u, 0xff800000u,
                                       0x7fc00000u, 0x00000001u, 0x807fffffu, 0x00800000u,
                                       0x7f7fffffu, 0x4b800000u, 0x4c000000u, 0x3f800000u};
    for (size_t i = 0; i < sizeof special / sizeof special[0]; i++) {
        f32_text(buf, special[i]);
        puts(buf);
    }
    return 0;
}
