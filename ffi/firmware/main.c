/* aaglsd from a bare-metal C program: the detector on an image read from
 * the host through semihosting, with every buffer static and sized at
 * compile time by the header's macros. The detector allocates nothing (the
 * C library's stdio allocates its own buffers).
 *
 *   fw IMAGE.pgm                  8-bit binary PGM (P5), at most
 *                                 FW_MAX_WIDTH x FW_MAX_HEIGHT
 *   fw FRAME.yuyv WIDTH HEIGHT    a camera frame in YUYV 4:2:2 (Y0 U Y1 V),
 *                                 2 bytes a pixel: its luma is compacted in
 *                                 place and detected there (see load_yuyv)
 *
 * stdout: the segments, one "x0 y0 x1 y1 score" line each (the brighter side
 * on the left of (x0, y0) -> (x1, y1), x right, y down), in the host CLI's
 * text with --scores (examples/detect.rs: Rust's shortest round-trip f32
 * text). stderr: what the CLI writes there with --stats (the summary, a
 * warning when the
 * detection dropped or cut anything, the segment count), then "fw: " lines:
 * the stack high-water mark of the detection and its instruction count.
 * Exit 0, or 1 on an error. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "aaglsd.h"
#include "board.h"
#include "f32_text.h"

#ifndef FW_MAX_WIDTH
#define FW_MAX_WIDTH 640
#endif
#ifndef FW_MAX_HEIGHT
#define FW_MAX_HEIGHT 480
#endif
/* Output slots. With merging on (the default profile) they also hold the
 * fragments until they are merged: room for segments + merged. */
#ifndef FW_MAX_SEGMENTS
#define FW_MAX_SEGMENTS 4096
#endif
/* Bytes of stack painted below the detection's caller to find its
 * high-water mark. */
#define STACK_PAINT (32u * 1024u)
#define PAINT_WORD 0xDEADBEEFu

#define MAX_PIXELS ((size_t)FW_MAX_WIDTH * FW_MAX_HEIGHT)

/* The two ways in, sharing one block of RAM of the same size: a gray image
 * and aaglsd_detect's workspace, or a YUYV frame (2 bytes a pixel) and the
 * in-place workspace, w*h bytes smaller because the smoothed image stays in
 * the frame. Each workspace is for the largest frame; a smaller frame needs
 * less (the sizes grow with the width and with the height). */
static union {
    struct {
        uint8_t pixels[MAX_PIXELS];
        uint8_t workspace[AAGLSD_WORKSPACE_BYTES(FW_MAX_WIDTH, FW_MAX_HEIGHT)];
    } gray;
    struct {
        uint8_t frame[2 * MAX_PIXELS];
        uint8_t workspace[AAGLSD_WORKSPACE_BYTES_IN_PLACE(FW_MAX_WIDTH, FW_MAX_HEIGHT)];
    } yuyv;
} mem;

static AaglsdSegment segments[FW_MAX_SEGMENTS];

/* One detection's arguments and result, for the measured call. */
struct job {
    uint8_t *pixels;
    size_t pixels_len, width, height;
    int in_place;
    uint8_t *workspace;
    size_t workspace_len;
    AaglsdConfig cfg;
    AaglsdSummary summary;
    AaglsdStatus status;
};

/* One output line per segment: the only place that knows the fields. */
static void print_segment(FILE *f, const AaglsdSegment *s) {
    char x0[F32_TEXT_MAX], y0[F32_TEXT_MAX], x1[F32_TEXT_MAX], y1[F32_TEXT_MAX];
    char score[F32_TEXT_MAX];
    uint32_t b[5];
    memcpy(&b[0], &s->x0, 4);
    memcpy(&b[1], &s->y0, 4);
    memcpy(&b[2], &s->x1, 4);
    memcpy(&b[3], &s->y1, 4);
    memcpy(&b[4], &s->score, 4);
    f32_text(x0, b[0]);
    f32_text(y0, b[1]);
    f32_text(x1, b[2]);
    f32_text(y1, b[3]);
    f32_text(score, b[4]);
    fprintf(f, "%s %s %s %s %s\n", x0, y0, x1, y1, score);
}

/* The summary as the CLI writes it (aaglsd_support::fields::summary_line),
 * after `prefix`. */
static void print_summary(FILE *f, const char *prefix, const AaglsdSummary *s) {
    fprintf(f,
            "%ssegments=%lu dropped_segments=%lu dropped_candidates=%lu truncated_linkings=%lu "
            "candidates=%lu groups=%lu merged=%lu work=%lu work_cut=%lu\n",
            prefix, (unsigned long)s->segments, (unsigned long)s->dropped_segments,
            (unsigned long)s->dropped_candidates, (unsigned long)s->truncated_linkings,
            (unsigned long)s->candidates, (unsigned long)s->groups, (unsigned long)s->merged,
            (unsigned long)s->work, (unsigned long)s->work_cut);
}

/* The detection itself, not inlined so that its stack is measured. */
static __attribute__((noinline)) void run_detect(struct job *j) {
    if (j->in_place)
        j->status = aaglsd_detect_in_place(j->pixels, j->pixels_len, j->width, j->height,
                                           j->width, &j->cfg, j->workspace, j->workspace_len,
                                           segments, FW_MAX_SEGMENTS, &j->summary);
    else
        j->status = aaglsd_detect(j->pixels, j->pixels_len, j->width, j->height, j->width,
                                  &j->cfg, j->workspace, j->workspace_len, segments,
                                  FW_MAX_SEGMENTS, &j->summary);
}

/* Runs the detection with the STACK_PAINT bytes below this frame painted;
 * returns the deepest stack use below it (run_detect's frame included), or
 * 0 when the whole painted area was used. Writes the instruction count. */
static __attribute__((noinline)) size_t measure(struct job *j, uint64_t *insns) {
    volatile uint32_t *top = (volatile uint32_t *)(board_sp() & ~(uintptr_t)3);
    volatile uint32_t *bottom = top - STACK_PAINT / 4;
    /* A 64-byte margin below the stack pointer stays unpainted; the
     * detection goes far deeper, so the figure does not depend on it. */
    for (volatile uint32_t *p = bottom; p < top - 16; p++) *p = PAINT_WORD;
    board_counter_start();
    run_detect(j);
    *insns = board_counter_insns();
    volatile uint32_t *p = bottom;
    while (p < top && *p == PAINT_WORD) p++;
    return p == bottom ? 0 : (size_t)((uintptr_t)top - (uintptr_t)p);
}

/* Reads the PGM header's next number, skipping white space and comments. */
static int pgm_number(FILE *f, size_t *out) {
    int c = fgetc(f);
    for (;;) {
        while (c == ' ' || c == '\t' || c == '\n' || c == '\r') c = fgetc(f);
        if (c != '#') break;
        while (c != '\n' && c != EOF) c = fgetc(f);
    }
    if (c < '0' || c > '9') return -1;
    size_t v = 0;
    while (c >= '0' && c <= '9') {
        if (v > 100000) return -1;
        v = v * 10 + (size_t)(c - '0');
        c = fgetc(f);
    }
    *out = v;
    /* One white-space byte ends the number (before the pixels, exactly one). */
    return (c == ' ' || c == '\t' || c == '\n' || c == '\r') ? 0 : -1;
}

/* Decimal text of a 64-bit count (newlib-nano's printf may lack %llu). */
static const char *u64_text(char buf[21], uint64_t v) {
    char *p = buf + 20;
    *p = 0;
    do *--p = (char)('0' + v % 10);
    while (v /= 10);
    return p;
}

static int fail(const char *path, const char *why) {
    fprintf(board_stderr(), "fw: %s: %s\n", path, why);
    return 1;
}

/* Loads a P5 PGM into mem.gray.pixels. */
static int load_pgm(const char *path, struct job *j) {
    FILE *f = fopen(path, "rb");
    if (!f) return fail(path, "cannot open");
    size_t maxval;
    int bad = fgetc(f) != 'P' || fgetc(f) != '5' || pgm_number(f, &j->width) ||
              pgm_number(f, &j->height) || pgm_number(f, &maxval) || maxval != 255;
    if (!bad && (j->width > FW_MAX_WIDTH || j->height > FW_MAX_HEIGHT)) {
        fclose(f);
        return fail(path, "larger than FW_MAX_WIDTH x FW_MAX_HEIGHT");
    }
    j->pixels_len = j->width * j->height;
    bad = bad || fread(mem.gray.pixels, 1, j->pixels_len, f) != j->pixels_len;
    fclose(f);
    if (bad) return fail(path, "not an 8-bit binary PGM (P5, maxval 255), or truncated");
    j->pixels = mem.gray.pixels;
    j->in_place = 0;
    j->workspace = mem.gray.workspace;
    j->workspace_len = sizeof mem.gray.workspace;
    return 0;
}

/* Loads a YUYV frame into mem.yuyv.frame and keeps its luma: Y0 U Y1 V
 * holds the luma of two pixels at bytes 0 and 2, so pixel i's luma is byte
 * 2i. Moving byte 2i to byte i for i = 0, 1, ... reads every byte before it
 * is overwritten, so the w*h luma bytes end up packed at the front of the
 * frame without a second buffer; aaglsd_detect_in_place then smooths them
 * there. A camera driver would do the same on the frame it just captured. */
static int load_yuyv(const char *path, const char *w, const char *h, struct job *j) {
    j->width = (size_t)strtoul(w, NULL, 10);
    j->height = (size_t)strtoul(h, NULL, 10);
    if (j->width == 0 || j->height == 0 || j->width > FW_MAX_WIDTH || j->height > FW_MAX_HEIGHT)
        return fail(path, "WIDTH and HEIGHT: 1 to FW_MAX_WIDTH and FW_MAX_HEIGHT");
    FILE *f = fopen(path, "rb");
    if (!f) return fail(path, "cannot open");
    size_t n = 2 * j->width * j->height;
    size_t got = fread(mem.yuyv.frame, 1, n, f);
    fclose(f);
    if (got != n) return fail(path, "shorter than 2 * WIDTH * HEIGHT bytes");
    uint8_t *frame = mem.yuyv.frame;
    for (size_t i = 0; i < n / 2; i++) frame[i] = frame[2 * i];
    j->pixels = frame;
    j->pixels_len = n / 2;
    j->in_place = 1;
    j->workspace = mem.yuyv.workspace;
    j->workspace_len = sizeof mem.yuyv.workspace;
    return 0;
}

#define SYS_GET_CMDLINE 0x15

/* Splits the semihosting command line at spaces (paths with spaces are
 * not supported) into at most `max` arguments; returns their count. */
static int command_line(char **argv, int max) {
    static char line[512];
    struct {
        char *buf;
        uintptr_t len;
    } block = {line, sizeof line - 1};
    int argc = 0;
    if (board_semihost(SYS_GET_CMDLINE, &block) != 0) return 0;
    line[block.len] = 0;
    for (char *p = line; *p && argc < max;) {
        while (*p == ' ') *p++ = 0;
        if (!*p) break;
        argv[argc++] = p;
        while (*p && *p != ' ') p++;
    }
    return argc;
}

int main(void) {
    static struct job j;
    /* The command line from semihosting, whatever the C library's startup
     * code makes of it (newlib's is not used here; picolibc's puts a name
     * of its own in front). */
    static char *argv[8];
    int argc = command_line(argv, 8);
    if (argc == 2) {
        if (load_pgm(argv[1], &j)) return 1;
    } else if (argc == 4) {
        if (load_yuyv(argv[1], argv[2], argv[3], &j)) return 1;
    } else {
        fprintf(board_stderr(), "usage: fw IMAGE.pgm | fw FRAME.yuyv WIDTH HEIGHT\n");
        return 1;
    }
    FILE *out = board_stdout(), *err = board_stderr();
    aaglsd_config_default(&j.cfg);
    uint64_t insns;
    size_t stack = measure(&j, &insns);
    if (j.status != AAGLSD_STATUS_OK) return fail(argv[1], aaglsd_status_str(j.status));
    for (size_t i = 0; i < j.summary.segments; i++) print_segment(out, &segments[i]);
    fflush(out);
    /* The CLI's --stats line, its warning when something was dropped or
     * cut (aaglsd's Summary::is_complete), and its count. */
    print_summary(err, "stats: ", &j.summary);
    const AaglsdSummary *m = &j.summary;
    if (m->dropped_segments || m->dropped_candidates || m->truncated_linkings || m->work_cut)
        print_summary(err, "warning: detection incomplete: ", m);
    fprintf(err, "%lu segments\n", (unsigned long)j.summary.segments);
    if (stack)
        fprintf(err, "fw: stack high-water of the detection: %lu bytes\n",
                (unsigned long)stack);
    else
        fprintf(err, "fw: stack high-water of the detection: over %u bytes\n", STACK_PAINT);
    char n[21];
    fprintf(err, "fw: instructions in the detection: %s (%s, %lux%lu, workspace %lu bytes)\n",
            u64_text(n, insns), j.in_place ? "aaglsd_detect_in_place" : "aaglsd_detect",
            (unsigned long)j.width, (unsigned long)j.height, (unsigned long)j.workspace_len);
    fflush(err);
    return 0;
}
