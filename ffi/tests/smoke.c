/*
 * C smoke test of the aaglsd C ABI (ffi/include/aaglsd.h).
 *
 *   smoke INPUT.pgm EXPECTED.txt
 *
 * Both files are written by `cargo run -p aaglsd-ffi --example smoke_expected`
 * (the Rust core's own output); ffi/tests/run.sh builds and runs everything.
 * Checks that aaglsd_detect reproduces the Rust segments and their scores
 * bit for bit (also with a padded stride and an unaligned malloc'd
 * workspace), that a short output array keeps the highest-scoring ones,
 * best first, and that the README's rectangle has its brighter side on the
 * left of each segment; then provokes every status code. Exit status 0 only
 * when every check passed.
 */
#include "aaglsd.h"

#include <inttypes.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

_Static_assert(AAGLSD_STATUS_OK == 0, "OK is 0");
_Static_assert(sizeof(AaglsdSegment) == 5 * sizeof(float), "x0 y0 x1 y1 score");
_Static_assert(offsetof(AaglsdSegment, score) == 4 * sizeof(float), "the score last");
_Static_assert(sizeof(AaglsdStatus) == sizeof(int32_t), "status is an int32_t");

static int checks;
static int failures;

#define CHECK(cond, ...)                                                       \
    do {                                                                       \
        checks++;                                                              \
        if (!(cond)) {                                                         \
            failures++;                                                        \
            fprintf(stderr, "FAIL %s:%d: %s: ", __FILE__, __LINE__, #cond);    \
            fprintf(stderr, __VA_ARGS__);                                      \
            fputc('\n', stderr);                                               \
        }                                                                      \
    } while (0)

#define CHECK_STATUS(got, want, what)                                          \
    CHECK((got) == (want), "%s: got %d (%s), want %d (%s)", (what), (int)(got), \
          aaglsd_status_str(got), (int)(want), aaglsd_status_str(want))

/* ---- input files ------------------------------------------------------ */

typedef struct {
    size_t width, height;
    uint8_t *pixels; /* width * height bytes, rows packed */
} Image;

/* Reads a binary 8-bit PGM (P5, maxval 255, '#' comments allowed). */
static int read_pgm(const char *path, Image *img) {
    FILE *f = fopen(path, "rb");
    if (!f) {
        perror(path);
        return -1;
    }
    unsigned long field[3];
    int c = fgetc(f);
    int ok = c == 'P' && fgetc(f) == '5';
    for (int i = 0; ok && i < 3; i++) {
        c = fgetc(f);
        while (c == '#' || c == ' ' || c == '\t' || c == '\r' || c == '\n') {
            if (c == '#')
                while (c != '\n' && c != EOF) c = fgetc(f);
            c = fgetc(f);
        }
        ok = c >= '0' && c <= '9';
        field[i] = 0;
        while (c >= '0' && c <= '9') {
            field[i] = field[i] * 10 + (unsigned long)(c - '0');
            c = fgetc(f);
        }
    }
    /* exactly one whitespace byte (already consumed in c) before the data */
    ok = ok && field[2] == 255 && field[0] > 0 && field[1] > 0 &&
         field[0] <= 65535 && field[1] <= 65535;
    if (ok) {
        img->width = field[0];
        img->height = field[1];
        img->pixels = malloc(img->width * img->height);
        ok = img->pixels && fread(img->pixels, 1, img->width * img->height, f) ==
                                img->width * img->height;
    }
    fclose(f);
    if (!ok) fprintf(stderr, "%s: not a complete 8-bit P5 PGM\n", path);
    return ok ? 0 : -1;
}

typedef struct {
    uint32_t profile;
    AaglsdSummary summary;
    uint32_t (*bits)[5]; /* summary.segments entries: x0 y0 x1 y1 score as f32 bits */
} Expected;

/* Reads the runs of expected.txt (see examples/smoke_expected.rs). */
static int read_expected(const char *path, Expected *runs, int max_runs) {
    FILE *f = fopen(path, "r");
    if (!f) {
        perror(path);
        return -1;
    }
    char line[512];
    int n = -1;
    size_t filled = 0;
    while (fgets(line, sizeof line, f)) {
        if (line[0] == '#') continue;
        if (strncmp(line, "run ", 4) == 0) {
            if (n >= 0 && filled != runs[n].summary.segments) break;
            if (++n >= max_runs) break;
            Expected *e = &runs[n];
            AaglsdSummary *s = &e->summary;
            if (sscanf(line, "run %" SCNu32 " %zu %zu %zu %zu %zu %zu %zu", &e->profile,
                       &s->segments, &s->dropped_segments,
                       &s->dropped_candidates, &s->truncated_linkings,
                       &s->candidates, &s->groups, &s->merged) != 8)
                break;
            e->bits = calloc(s->segments + 1, sizeof *e->bits);
            if (!e->bits) break;
            filled = 0;
        } else if (n >= 0 && filled < runs[n].summary.segments) {
            uint32_t *b = runs[n].bits[filled++];
            if (sscanf(line, "%" SCNx32 " %" SCNx32 " %" SCNx32 " %" SCNx32 " %" SCNx32, &b[0],
                       &b[1], &b[2], &b[3], &b[4]) != 5)
                break;
        }
    }
    fclose(f);
    if (n < 0 || n >= max_runs || filled != runs[n].summary.segments) {
        fprintf(stderr, "%s: malformed expected output\n", path);
        return -1;
    }
    return n + 1;
}

/* ---- helpers ------------------------------------------------------------ */

static void segment_bits(const AaglsdSegment *s, uint32_t b[5]) {
    memcpy(&b[0], &s->x0, 4);
    memcpy(&b[1], &s->y0, 4);
    memcpy(&b[2], &s->x1, 4);
    memcpy(&b[3], &s->y1, 4);
    memcpy(&b[4], &s->score, 4);
}

static float bits_f32(uint32_t b) {
    float f;
    memcpy(&f, &b, 4);
    return f;
}

/* Number of segments in out[0..n) that differ from want[0..n), scores included. */
static size_t count_mismatches(const AaglsdSegment *out, uint32_t (*want)[5], size_t n) {
    size_t bad = 0;
    for (size_t i = 0; i < n; i++) {
        uint32_t b[5];
        segment_bits(&out[i], b);
        if (memcmp(b, want[i], sizeof b) != 0) {
            if (bad < 3)
                fprintf(stderr,
                        "  segment %zu: got %g %g %g %g score %.0f, want bits %08x %08x %08x "
                        "%08x %08x\n",
                        i, (double)out[i].x0, (double)out[i].y0, (double)out[i].x1,
                        (double)out[i].y1, (double)out[i].score, (unsigned)want[i][0],
                        (unsigned)want[i][1], (unsigned)want[i][2], (unsigned)want[i][3],
                        (unsigned)want[i][4]);
            bad++;
        }
    }
    return bad;
}

/* Index of `s` among want[0..n) (all five fields), or n. */
static size_t find_segment(const AaglsdSegment *s, uint32_t (*want)[5], size_t n) {
    uint32_t b[5];
    segment_bits(s, b);
    size_t i = 0;
    while (i < n && memcmp(b, want[i], sizeof b) != 0) i++;
    return i;
}

static int summaries_equal(const AaglsdSummary *a, const AaglsdSummary *b) {
    return a->segments == b->segments && a->dropped_segments == b->dropped_segments &&
           a->dropped_candidates == b->dropped_candidates &&
           a->truncated_linkings == b->truncated_linkings &&
           a->candidates == b->candidates && a->groups == b->groups &&
           a->merged == b->merged;
}

static int summary_is_zero(const AaglsdSummary *s) {
    static const AaglsdSummary zero;
    return summaries_equal(s, &zero);
}

/* ---- bit-exact agreement with the Rust core ----------------------------- */

static void check_run(const Image *img, const Expected *e) {
    const int failures_before = failures;
    AaglsdConfig cfg;
    CHECK_STATUS(aaglsd_config_profile(e->profile, &cfg), AAGLSD_STATUS_OK, "profile");
    size_t ws_len = 0;
    CHECK_STATUS(aaglsd_workspace_size(img->width, img->height, &cfg, &ws_len),
                 AAGLSD_STATUS_OK, "workspace size");
    const size_t n = e->summary.segments;
    /* With merging on, the output array also holds the fragments until they
     * are merged: size it for segments + merged (the Rust run had room). */
    const size_t cap = n + e->summary.merged + 16;
    uint8_t *ws = malloc(ws_len + 1); /* uninitialised, as C callers have it */
    AaglsdSegment *out = malloc(cap * sizeof *out);
    if (!ws || !out) {
        CHECK(0, "out of memory");
        free(ws);
        free(out);
        return;
    }

    /* 1. Packed rows: the Rust core's segments, bit for bit. */
    AaglsdSummary s;
    AaglsdStatus st = aaglsd_detect(img->pixels, img->width * img->height, img->width,
                                    img->height, img->width, &cfg, ws, ws_len, out, cap, &s);
    CHECK_STATUS(st, AAGLSD_STATUS_OK, "detect");
    CHECK(summaries_equal(&s, &e->summary),
          "profile %u: summary differs (segments %zu vs %zu, groups %zu vs %zu)",
          (unsigned)e->profile, s.segments, e->summary.segments, s.groups, e->summary.groups);
    size_t bad = count_mismatches(out, e->bits, s.segments < n ? s.segments : n);
    CHECK(bad == 0, "profile %u: %zu of %zu segments differ from Rust", (unsigned)e->profile,
          bad, n);

    /* 2. Padded stride, workspace at an odd address: same result. */
    const size_t stride = img->width + 13;
    const size_t len = stride * (img->height - 1) + img->width; /* no padding after the last row */
    uint8_t *padded = malloc(len);
    if (padded) {
        memset(padded, 0xEE, len);
        for (size_t y = 0; y < img->height; y++)
            memcpy(padded + y * stride, img->pixels + y * img->width, img->width);
        memset(out, 0, cap * sizeof *out);
        st = aaglsd_detect(padded, len, img->width, img->height, stride, &cfg, ws + 1, ws_len,
                           out, cap, &s);
        CHECK_STATUS(st, AAGLSD_STATUS_OK, "detect (padded stride)");
        CHECK(summaries_equal(&s, &e->summary), "profile %u, padded: summary differs",
              (unsigned)e->profile);
        bad = count_mismatches(out, e->bits, s.segments < n ? s.segments : n);
        CHECK(bad == 0, "profile %u, padded: %zu segments differ", (unsigned)e->profile, bad);
        free(padded);
    } else {
        CHECK(0, "out of memory");
    }

    /* 3. A short output array: the highest-scoring segments, best first, the
     * rest counted (before merging, which then only sees the segments that
     * fit). Without merging, the three are the best three of the full run. */
    const size_t found = n + e->summary.merged;
    if (found > 3) {
        st = aaglsd_detect(img->pixels, img->width * img->height, img->width, img->height,
                           img->width, &cfg, ws, ws_len, out, 3, &s);
        CHECK_STATUS(st, AAGLSD_STATUS_OK, "detect (3 slots)");
        CHECK(s.segments + s.merged == 3 && s.dropped_segments == found - 3,
              "3 slots: segments %zu merged %zu dropped %zu, want 3 in all and %zu dropped",
              s.segments, s.merged, s.dropped_segments, found - 3);
        if (e->summary.merged == 0 && s.segments == 3) {
            size_t at[3];
            for (int k = 0; k < 3; k++) {
                at[k] = find_segment(&out[k], e->bits, n);
                CHECK(at[k] < n, "3 slots: segment %d is not one of the full run's", k);
            }
            CHECK(out[0].score >= out[1].score && out[1].score >= out[2].score,
                  "3 slots: not best first (%.0f %.0f %.0f)", (double)out[0].score,
                  (double)out[1].score, (double)out[2].score);
            for (size_t i = 0; i < n; i++)
                if (i != at[0] && i != at[1] && i != at[2])
                    CHECK(bits_f32(e->bits[i][4]) <= out[2].score,
                          "3 slots: segment %zu (score %.0f) left out for one of %.0f", i,
                          (double)bits_f32(e->bits[i][4]), (double)out[2].score);
        }
    }
    printf("profile %u: %zu segments, %s\n", (unsigned)e->profile, n,
           failures == failures_before ? "bit-exact with Rust" : "MISMATCH");
    free(ws);
    free(out);
}

/* ---- every status code -------------------------------------------------- */

typedef struct {
    const Image *img;
    AaglsdConfig cfg;
    uint8_t *ws;
    size_t ws_len;
    AaglsdSegment out[8];
} Fixture;

static const AaglsdSegment SENTINEL = {-1.0f, -2.0f, -3.0f, -4.0f, -5.0f};

/* Calls aaglsd_detect with the fixture's buffers, overridden by the
 * arguments, and checks the status, the zeroed summary and the untouched
 * output. */
static void expect_detect(Fixture *fx, const uint8_t *pixels, size_t pixels_len, size_t width,
                          size_t height, size_t stride, const AaglsdConfig *cfg, uint8_t *ws,
                          size_t ws_len, AaglsdSegment *out, size_t cap, AaglsdSummary *summary,
                          AaglsdStatus want, const char *what) {
    for (int i = 0; i < 8; i++) fx->out[i] = SENTINEL;
    if (summary) memset(summary, 0x5A, sizeof *summary);
    AaglsdStatus st = aaglsd_detect(pixels, pixels_len, width, height, stride, cfg, ws, ws_len,
                                    out, cap, summary);
    CHECK_STATUS(st, want, what);
    if (summary) CHECK(summary_is_zero(summary), "%s: summary not zeroed", what);
    int untouched = 1;
    for (int i = 0; i < 8; i++)
        untouched &= memcmp(&fx->out[i], &SENTINEL, sizeof SENTINEL) == 0;
    CHECK(untouched, "%s: output written on error", what);
}

static void check_errors(const Image *img) {
    Fixture fx = {.img = img};
    CHECK_STATUS(aaglsd_config_default(&fx.cfg), AAGLSD_STATUS_OK, "config default");
    CHECK_STATUS(aaglsd_workspace_size(img->width, img->height, &fx.cfg, &fx.ws_len),
                 AAGLSD_STATUS_OK, "workspace size");
    fx.ws = malloc(fx.ws_len);
    if (!fx.ws) {
        CHECK(0, "out of memory");
        return;
    }
    const uint8_t *px = img->pixels;
    const size_t w = img->width, h = img->height, len = w * h;
    AaglsdSummary s;
    const AaglsdConfig *cfg = &fx.cfg;

    /* Each pointer argument NULL. */
    expect_detect(&fx, NULL, len, w, h, w, cfg, fx.ws, fx.ws_len, fx.out, 8, &s,
                  AAGLSD_STATUS_NULL_POINTER, "NULL pixels");
    expect_detect(&fx, px, len, w, h, w, NULL, fx.ws, fx.ws_len, fx.out, 8, &s,
                  AAGLSD_STATUS_NULL_POINTER, "NULL config");
    expect_detect(&fx, px, len, w, h, w, cfg, NULL, fx.ws_len, fx.out, 8, &s,
                  AAGLSD_STATUS_NULL_POINTER, "NULL workspace");
    expect_detect(&fx, px, len, w, h, w, cfg, fx.ws, fx.ws_len, NULL, 8, &s,
                  AAGLSD_STATUS_NULL_POINTER, "NULL output");
    expect_detect(&fx, px, len, w, h, w, cfg, fx.ws, fx.ws_len, fx.out, 8, NULL,
                  AAGLSD_STATUS_NULL_POINTER, "NULL summary");

    /* Image geometry. */
    expect_detect(&fx, px, len, 0, h, w, cfg, fx.ws, fx.ws_len, fx.out, 8, &s,
                  AAGLSD_STATUS_ZERO_DIMENSION, "zero width");
    expect_detect(&fx, px, len, w, 0, w, cfg, fx.ws, fx.ws_len, fx.out, 8, &s,
                  AAGLSD_STATUS_ZERO_DIMENSION, "zero height");
    expect_detect(&fx, px, len, AAGLSD_MAX_DIMENSION + 1, 1, AAGLSD_MAX_DIMENSION + 1, cfg,
                  fx.ws, fx.ws_len, fx.out, 8, &s, AAGLSD_STATUS_IMAGE_TOO_LARGE, "width 32768");
    expect_detect(&fx, px, len, 8193, 8193, 8193, cfg, fx.ws, fx.ws_len, fx.out, 8, &s,
                  AAGLSD_STATUS_IMAGE_TOO_LARGE, "8193x8193 pixels");
    expect_detect(&fx, px, len, SIZE_MAX, SIZE_MAX, SIZE_MAX, cfg, fx.ws, fx.ws_len, fx.out, 8,
                  &s, AAGLSD_STATUS_IMAGE_TOO_LARGE, "SIZE_MAX dimensions");
    expect_detect(&fx, px, len, w, h, w - 1, cfg, fx.ws, fx.ws_len, fx.out, 8, &s,
                  AAGLSD_STATUS_STRIDE_TOO_SMALL, "stride < width");
    expect_detect(&fx, px, len - 1, w, h, w, cfg, fx.ws, fx.ws_len, fx.out, 8, &s,
                  AAGLSD_STATUS_BUFFER_TOO_SHORT, "pixel buffer one byte short");
    expect_detect(&fx, px, len, w, h, SIZE_MAX, cfg, fx.ws, fx.ws_len, fx.out, 8, &s,
                  AAGLSD_STATUS_BUFFER_TOO_SHORT, "stride * height overflows");

    /* Workspace and output. */
    expect_detect(&fx, px, len, w, h, w, cfg, fx.ws, fx.ws_len - 1, fx.out, 8, &s,
                  AAGLSD_STATUS_WORKSPACE_TOO_SMALL, "workspace one byte short");
    expect_detect(&fx, px, len, w, h, w, cfg, fx.ws, fx.ws_len, fx.out, 0, &s,
                  AAGLSD_STATUS_OUTPUT_EMPTY, "zero output capacity");
    /* A misaligned output pointer (never dereferenced by C here). */
    expect_detect(&fx, px, len, w, h, w, cfg, fx.ws, fx.ws_len,
                  (AaglsdSegment *)(void *)((char *)(void *)fx.out + 2), 7, &s,
                  AAGLSD_STATUS_MISALIGNED, "misaligned output");
    /* The output array inside the workspace, the workspace inside the pixels. */
    expect_detect(&fx, px, len, w, h, w, cfg, fx.ws, fx.ws_len,
                  (AaglsdSegment *)(void *)(fx.ws + 64), 8, &s, AAGLSD_STATUS_BUFFERS_OVERLAP,
                  "output overlaps workspace");
    expect_detect(&fx, fx.ws, fx.ws_len, 16, 16, 16, cfg, fx.ws + 16, fx.ws_len - 16, fx.out,
                  8, &s, AAGLSD_STATUS_BUFFERS_OVERLAP, "pixels overlap workspace");

    /* One bad value per configuration field category, and NaN for every float field. */
    struct {
        const char *what;
        AaglsdConfigField field;
        AaglsdConfig cfg;
    } bad[32];
    int nbad = 0;
#define BAD(FIELD, member, value)                                                \
    do {                                                                         \
        bad[nbad].what = #member " = " #value;                                   \
        bad[nbad].field = AAGLSD_CONFIG_FIELD_##FIELD;                           \
        bad[nbad].cfg = fx.cfg;                                                  \
        bad[nbad].cfg.member = value;                                            \
        nbad++;                                                                  \
    } while (0)
#define BAD_FLOAT(FIELD, member, value)                                          \
    do {                                                                         \
        BAD(FIELD, member, value);                                               \
        BAD(FIELD, member, NAN);                                                 \
    } while (0)
    BAD_FLOAT(MAGNITUDE_THRESHOLD, magnitude_threshold, -0.5f);
    BAD(ANCHOR_MARGIN, anchor_margin, 1021);
    BAD_FLOAT(ALIGN_TOLERANCE, align_tolerance_deg, 90.0f);
    BAD_FLOAT(DIST_TOLERANCE, dist_tolerance_px, 0.0f);
    BAD(SKIP_STEPS, skip_min, 0);
    BAD(SKIP_STEPS, skip_regular, 0);
    BAD(SKIP_STEPS, skip_group, 0);
    BAD(MIN_LENGTH, min_length_px, INFINITY);
    BAD_FLOAT(MIN_LENGTH, min_length_px, -1.0f);
    BAD(MIN_GROUPS, min_groups, 0);
    BAD_FLOAT(ANCHOR_DENSITY, anchor_density, 1.01f);
    BAD_FLOAT(ALIGNED_DENSITY, aligned_density, -0.01f);
    BAD_FLOAT(MERGE_CENTER, merge_center_px, 65.0f);
    BAD_FLOAT(MERGE_ANGLE, merge_angle_deg, 0.0f);
    BAD_FLOAT(MERGE_GAP, merge_gap_px, 5000.0f);
    BAD(CANDIDATE_CAPACITY, candidates_per_mille, 0);
    BAD(CANDIDATE_CAPACITY, candidates_per_mille, 1001);
    BAD(LINK_CAPACITY, max_link_pixels, 15);
    BAD(LINK_CAPACITY, max_link_pixels, 65536);
    BAD(EXTEND_MAX, extend_max_px, 1025);
    BAD(WORK_LIMIT, work_per_mille, 0);
    BAD(BRIDGE_MAX, bridge_px, 33);
    BAD(MIN_SCORE, min_score, 16777216);
#undef BAD_FLOAT
#undef BAD
    int seen[AAGLSD_CONFIG_FIELD_UNKNOWN + 1] = {0};
    for (int i = 0; i < nbad; i++) {
        AaglsdConfigField f = AAGLSD_CONFIG_FIELD_NONE;
        CHECK_STATUS(aaglsd_config_validate(&bad[i].cfg, &f), AAGLSD_STATUS_INVALID_CONFIG,
                     bad[i].what);
        CHECK(f == bad[i].field, "%s: field %d (%s), want %d (%s)", bad[i].what, (int)f,
              aaglsd_config_field_str(f), (int)bad[i].field,
              aaglsd_config_field_str(bad[i].field));
        expect_detect(&fx, px, len, w, h, w, &bad[i].cfg, fx.ws, fx.ws_len, fx.out, 8, &s,
                      AAGLSD_STATUS_INVALID_CONFIG, bad[i].what);
        size_t n = 1;
        CHECK_STATUS(aaglsd_workspace_size(w, h, &bad[i].cfg, &n), AAGLSD_STATUS_INVALID_CONFIG,
                     bad[i].what);
        CHECK(n == 0, "%s: workspace size not zeroed", bad[i].what);
        seen[bad[i].field] = 1;
    }
    for (int f = AAGLSD_CONFIG_FIELD_MAGNITUDE_THRESHOLD; f <= AAGLSD_CONFIG_FIELD_MIN_SCORE; f++)
        CHECK(seen[f], "config field %d (%s) not exercised", f, aaglsd_config_field_str(f));
    AaglsdConfigField f = AAGLSD_CONFIG_FIELD_UNKNOWN;
    CHECK_STATUS(aaglsd_config_validate(cfg, &f), AAGLSD_STATUS_OK, "valid config");
    CHECK(f == AAGLSD_CONFIG_FIELD_NONE, "valid config: field %d", (int)f);
    CHECK_STATUS(aaglsd_config_validate(cfg, NULL), AAGLSD_STATUS_OK, "optional field pointer");
    CHECK_STATUS(aaglsd_config_validate(NULL, &f), AAGLSD_STATUS_NULL_POINTER, "validate NULL");

    /* The other functions. */
    size_t n = 0;
    CHECK_STATUS(aaglsd_workspace_size(w, h, NULL, &n), AAGLSD_STATUS_NULL_POINTER,
                 "workspace size, NULL config");
    CHECK_STATUS(aaglsd_workspace_size(w, h, cfg, NULL), AAGLSD_STATUS_NULL_POINTER,
                 "workspace size, NULL output");
    CHECK_STATUS(aaglsd_workspace_size(0, h, cfg, &n), AAGLSD_STATUS_ZERO_DIMENSION,
                 "workspace size, zero width");
    CHECK_STATUS(aaglsd_workspace_size(8193, 8193, cfg, &n), AAGLSD_STATUS_IMAGE_TOO_LARGE,
                 "workspace size, 8193x8193");
    AaglsdConfig c = fx.cfg;
    CHECK_STATUS(aaglsd_config_default(NULL), AAGLSD_STATUS_NULL_POINTER, "default NULL");
    CHECK_STATUS(aaglsd_config_profile(AAGLSD_PROFILE_PAPER, NULL), AAGLSD_STATUS_NULL_POINTER,
                 "profile NULL");
    CHECK_STATUS(aaglsd_config_profile(3, &c), AAGLSD_STATUS_INVALID_ARGUMENT, "profile 3");
    CHECK(memcmp(&c, &fx.cfg, sizeof c) == 0, "unknown profile wrote the config");

    /* Every status has its own static string. */
    for (int32_t a = AAGLSD_STATUS_OK; a <= AAGLSD_STATUS_UNKNOWN; a++) {
        const char *sa = aaglsd_status_str(a);
        CHECK(sa && *sa && strcmp(sa, "unknown status") != 0, "status %d has no string",
              (int)a);
        for (int32_t b = a + 1; b <= AAGLSD_STATUS_UNKNOWN; b++)
            CHECK(strcmp(sa, aaglsd_status_str(b)) != 0, "statuses %d and %d share a string",
                  (int)a, (int)b);
    }
    CHECK(strcmp(aaglsd_status_str(-1), "unknown status") == 0, "status -1");
    CHECK(strcmp(aaglsd_status_str(AAGLSD_STATUS_UNKNOWN + 1), "unknown status") == 0,
          "status past the last");
    free(fx.ws);
}

/* ---- the usage example of ffi/README.md (keep the two in sync) ---------- */

/* pixels: `height` rows of `width` 8-bit gray values, rows `stride` bytes apart. */
static int print_segments(const uint8_t *pixels, size_t width, size_t height, size_t stride) {
    AaglsdConfig cfg;
    aaglsd_config_profile(AAGLSD_PROFILE_OFFICIAL, &cfg); /* or aaglsd_config_default(&cfg) */
    cfg.min_length_px = 10.0f;                            /* then change any field */

    size_t ws_len;
    AaglsdStatus st = aaglsd_workspace_size(width, height, &cfg, &ws_len);
    if (st != AAGLSD_STATUS_OK) {
        fprintf(stderr, "aaglsd: %s\n", aaglsd_status_str(st));
        return -1;
    }
    uint8_t *ws = malloc(ws_len); /* any alignment, uninitialised is fine; reuse it per frame */
    if (!ws) return -1;
    static AaglsdSegment out[1024];
    AaglsdSummary summary;
    st = aaglsd_detect(pixels, stride * (height - 1) + width, width, height, stride, &cfg,
                       ws, ws_len, out, sizeof out / sizeof out[0], &summary);
    free(ws);
    if (st != AAGLSD_STATUS_OK) {
        fprintf(stderr, "aaglsd: %s\n", aaglsd_status_str(st));
        return -1;
    }
    /* x0 y0 x1 y1, the brighter side on the left (x right, y down), then the score */
    for (size_t i = 0; i < summary.segments; i++)
        printf("%g %g %g %g %.0f\n", (double)out[i].x0, (double)out[i].y0, (double)out[i].x1,
               (double)out[i].y1, (double)out[i].score);
    if (summary.dropped_segments > 0)
        fprintf(stderr, "aaglsd: %zu segments did not fit\n", summary.dropped_segments);
    return (int)summary.segments;
}

/* The README example's scene: a dark 32 x 24 rectangle, rows padded to 80 bytes.
 * Then the polarity of its sides: three pixels to the left of each (as
 * displayed, x right, y down) is the light background, three to the right
 * the dark rectangle; and every score is a positive integer. */
static void check_readme_example(void) {
    static uint8_t px[48 * 80];
    for (size_t y = 0; y < 48; y++)
        for (size_t x = 0; x < 80; x++)
            px[y * 80 + x] = (y >= 12 && y < 36 && x >= 16 && x < 48) ? 40 : 200;
    CHECK(print_segments(px, 64, 48, 80) == 4, "README example: four sides");

    AaglsdConfig cfg;
    aaglsd_config_default(&cfg);
    static uint8_t ws[AAGLSD_WORKSPACE_BYTES(64, 48)];
    AaglsdSegment out[8];
    AaglsdSummary s;
    AaglsdStatus st = aaglsd_detect(px, sizeof px, 64, 48, 80, &cfg, ws, sizeof ws, out, 8, &s);
    CHECK_STATUS(st, AAGLSD_STATUS_OK, "rectangle");
    CHECK(s.segments == 4, "rectangle: %zu segments", s.segments);
    for (size_t i = 0; i < s.segments && i < 8; i++) {
        const AaglsdSegment *g = &out[i];
        const double dx = g->x1 - g->x0, dy = g->y1 - g->y0;
        const double m = dx * dx > dy * dy ? (dx > 0 ? dx : -dx) : (dy > 0 ? dy : -dy);
        const double mx = (g->x0 + g->x1) / 2, my = (g->y0 + g->y1) / 2;
        const double lx = dy / m, ly = -dx / m; /* the left, as displayed (no libm) */
        const uint8_t left = px[(size_t)(my + 3 * ly + 0.5) * 80 + (size_t)(mx + 3 * lx + 0.5)];
        const uint8_t right = px[(size_t)(my - 3 * ly + 0.5) * 80 + (size_t)(mx - 3 * lx + 0.5)];
        CHECK(left == 200 && right == 40, "side %zu (%g %g %g %g): left %u, right %u", i,
              (double)g->x0, (double)g->y0, (double)g->x1, (double)g->y1, left, right);
        CHECK(g->score >= 1.0f && g->score < 16777216.0f && (float)(long)g->score == g->score,
              "side %zu: score %g", i, (double)g->score);
    }
}

int main(int argc, char **argv) {
    if (argc != 3) {
        fprintf(stderr, "usage: %s INPUT.pgm EXPECTED.txt\n", argv[0]);
        return 2;
    }
    Image img;
    Expected runs[4];
    memset(runs, 0, sizeof runs);
    if (read_pgm(argv[1], &img) != 0) return 2;
    int nruns = read_expected(argv[2], runs, 4);
    if (nruns <= 0) return 2;

    const char *version = aaglsd_version();
    CHECK(version && version[0] >= '0' && version[0] <= '9', "version string");
    printf("aaglsd %s, image %zux%zu\n", version, img.width, img.height);

    check_readme_example();
    for (int i = 0; i < nruns; i++) check_run(&img, &runs[i]);
    check_errors(&img);

    printf("%d checks, %d failures\n", checks, failures);
    puts(failures ? "FAIL" : "PASS");
    for (int i = 0; i < nruns; i++) free(runs[i].bits);
    free(img.pixels);
    return failures ? 1 : 0;
}
