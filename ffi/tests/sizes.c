/* The header's compile-time workspace sizes (AAGLSD_WORKSPACE_BYTES and its
 * variants) against the library's size functions, over many sizes, every
 * profile and a few other capacities; and their use as array lengths.
 * Run on the host by ffi/tests/run.sh, and on the firmware boards (32-bit
 * size_t, where the sizes of the largest images overflow and both sides
 * must say 0) by ffi/firmware/run.sh --check. Exit status 0 when every size
 * agrees. */
#include "aaglsd.h"

#include <stdio.h>

/* Integer constant expressions: a file-scope array length and a static
 * assertion (each would fail to compile otherwise). */
static uint8_t slab[AAGLSD_WORKSPACE_BYTES(320, 240)];
static uint8_t slab_in_place[AAGLSD_WORKSPACE_BYTES_IN_PLACE(320, 240)];
_Static_assert(AAGLSD_WORKSPACE_BYTES(320, 240) - AAGLSD_WORKSPACE_BYTES_IN_PLACE(320, 240) ==
                   320 * 240,
               "in place: one frame less");
_Static_assert(AAGLSD_WORKSPACE_BYTES(0, 240) == 0, "0 for a zero dimension");
_Static_assert(AAGLSD_WORKSPACE_BYTES_PROFILE(PAPER, 64, 48) > 0, "profile form");

typedef AaglsdStatus (*size_fn)(size_t, size_t, const AaglsdConfig *, size_t *);

static size_t sides[] = {1,    2,    3,    4,    5,    6,    7,    8,     9,     10,   11,
                         12,   13,   15,   16,   17,   31,   32,   33,    47,    63,   64,
                         65,   100,  127,  128,  129,  239,  240,  241,   320,   479,  480,
                         481,  640,  708,  1064, 1080, 1920, 2048, 4095,  4096,  4097, 8191,
                         8192, 8193, 16383, 16384, 32767, 32768, 65536, 0};
#define N_SIDES (sizeof sides / sizeof sides[0])

static int failures;

/* One size: macro value `got` against the function's. */
static void check(const char *what, size_t w, size_t h, const AaglsdConfig *cfg, size_fn f,
                  size_t got) {
    size_t want = 12345;
    AaglsdStatus st = f(w, h, cfg, &want);
    if (st != AAGLSD_STATUS_OK && want != 0) {
        printf("FAIL: %s %lux%lu: status %d but size %lu\n", what, (unsigned long)w,
               (unsigned long)h, (int)st, (unsigned long)want);
        failures++;
    }
    if (got != want) {
        if (failures < 20)
            printf("FAIL: %s %lux%lu (candidates_per_mille %u, max_link_pixels %u): macro %lu, "
                   "function %lu\n",
                   what, (unsigned long)w, (unsigned long)h, (unsigned)cfg->candidates_per_mille,
                   (unsigned)cfg->max_link_pixels, (unsigned long)got, (unsigned long)want);
        failures++;
    }
}

/* Every pair of sides for one configuration, with the _FOR macros. */
static size_t check_config(const AaglsdConfig *cfg) {
    size_t n = 0;
    unsigned pm = cfg->candidates_per_mille, v = cfg->max_link_pixels;
    for (size_t i = 0; i < N_SIDES; i++) {
        for (size_t j = 0; j < N_SIDES; j++) {
            size_t w = sides[i], h = sides[j];
            check("plain", w, h, cfg, aaglsd_workspace_size,
                  AAGLSD_WORKSPACE_BYTES_FOR(w, h, pm, v));
            check("in place", w, h, cfg, aaglsd_workspace_size_in_place,
                  AAGLSD_WORKSPACE_BYTES_IN_PLACE_FOR(w, h, pm, v));
            check("fast", w, h, cfg, aaglsd_workspace_size_fast,
                  AAGLSD_WORKSPACE_BYTES_FAST_FOR(w, h, pm, v));
            n += 3;
        }
    }
    return n;
}

int main(void) {
    size_t n = 0;
    AaglsdConfig cfg;

    /* The profile macros against the profiles' functions. */
    struct {
        AaglsdProfile profile;
        size_t plain, in_place, fast;
    } profiles[] = {
        {AAGLSD_PROFILE_DEFAULT, AAGLSD_WORKSPACE_BYTES(640, 480),
         AAGLSD_WORKSPACE_BYTES_IN_PLACE(640, 480), AAGLSD_WORKSPACE_BYTES_FAST(640, 480)},
        {AAGLSD_PROFILE_OFFICIAL, AAGLSD_WORKSPACE_BYTES_PROFILE(OFFICIAL, 640, 480),
         AAGLSD_WORKSPACE_BYTES_IN_PLACE_PROFILE(OFFICIAL, 640, 480),
         AAGLSD_WORKSPACE_BYTES_FAST_PROFILE(OFFICIAL, 640, 480)},
        {AAGLSD_PROFILE_PAPER, AAGLSD_WORKSPACE_BYTES_PROFILE(PAPER, 640, 480),
         AAGLSD_WORKSPACE_BYTES_IN_PLACE_PROFILE(PAPER, 640, 480),
         AAGLSD_WORKSPACE_BYTES_FAST_PROFILE(PAPER, 640, 480)},
    };
    for (size_t p = 0; p < sizeof profiles / sizeof profiles[0]; p++) {
        if (aaglsd_config_profile(profiles[p].profile, &cfg) != AAGLSD_STATUS_OK) return 1;
        check("profile plain", 640, 480, &cfg, aaglsd_workspace_size, profiles[p].plain);
        check("profile in place", 640, 480, &cfg, aaglsd_workspace_size_in_place,
              profiles[p].in_place);
        check("profile fast", 640, 480, &cfg, aaglsd_workspace_size_fast, profiles[p].fast);
        n += 3 + check_config(&cfg);
    }
    /* The default profile's constants are what aaglsd_config_default writes. */
    aaglsd_config_default(&cfg);
    if (cfg.candidates_per_mille != AAGLSD_DEFAULT_CANDIDATES_PER_MILLE ||
        cfg.max_link_pixels != AAGLSD_DEFAULT_MAX_LINK_PIXELS) {
        printf("FAIL: AAGLSD_DEFAULT_* differ from aaglsd_config_default\n");
        failures++;
    }
    /* Other capacities, over their whole valid range's ends. */
    static const unsigned caps[][2] = {{1, 16}, {7, 17}, {500, 333}, {1000, 65535}};
    for (size_t c = 0; c < sizeof caps / sizeof caps[0]; c++) {
        cfg.candidates_per_mille = (uint16_t)caps[c][0];
        cfg.max_link_pixels = caps[c][1];
        n += check_config(&cfg);
    }
    slab[0] = slab_in_place[0] = 1; /* used */
    /* %lu, not %zu: newlib-nano's printf lacks the z modifier. */
    printf("%lu sizes checked, %d failed (size_t: %u bits): AAGLSD_WORKSPACE_BYTES(320, 240) = %lu\n",
           (unsigned long)n, failures, (unsigned)(8 * sizeof(size_t)), (unsigned long)sizeof slab);
    return failures ? 1 : 0;
}
