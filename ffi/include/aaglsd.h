#ifndef AAGLSD_H
#define AAGLSD_H

/* Generated with cbindgen:0.29.4 */

/* Generated from ffi/src by `cargo run -p aaglsd-gen-header` (cbindgen); do not edit. */

#include <stdint.h>
#include <stddef.h>
#include <stdbool.h>

// Compile-time workspace sizes: integer constant expressions, usable as a
// static array length, equal to what the size functions write:
//   AAGLSD_WORKSPACE_BYTES(w, h)           aaglsd_workspace_size, default profile
//   AAGLSD_WORKSPACE_BYTES_IN_PLACE(w, h)  aaglsd_workspace_size_in_place, default profile
//   AAGLSD_WORKSPACE_BYTES_FAST(w, h)      aaglsd_workspace_size_fast, default profile
//   AAGLSD_WORKSPACE_BYTES_PROFILE(P, w, h) and ..._IN_PLACE_PROFILE, ..._FAST_PROFILE:
//       the same for the profile P (DEFAULT, OFFICIAL or PAPER)
//   AAGLSD_WORKSPACE_BYTES_FOR(w, h, candidates_per_mille, max_link_pixels) and
//       ..._IN_PLACE_FOR, ..._FAST_FOR: for any configuration with those
//       capacities (the only fields the size depends on)
// Each is 0 where the function fails (a zero or too large dimension, or a
// size over SIZE_MAX), so declaring an array of it fails to compile. The
// arguments are evaluated more than once. Generated from the core's
// `Workspace` formula (docs/design.md, section 13) by ffi/gen-header;
// ffi/tests/sizes.c compares them with the functions.
#define AAGLSD_WS_U_(x) ((unsigned long long)(x))
#define AAGLSD_WS_PIXELS_(w, h, pm, v) (AAGLSD_WS_U_(w) * AAGLSD_WS_U_(h))
#define AAGLSD_WS_BAD_(w, h, pm, v) ((((AAGLSD_WS_U_(w) == 0ull) || (AAGLSD_WS_U_(h) == 0ull)) || ((AAGLSD_WS_U_(w) > 32767ull) || (AAGLSD_WS_U_(h) > 32767ull))) || ((AAGLSD_WS_PIXELS_(w, h, pm, v) > 67108864ull) || ((AAGLSD_WS_PIXELS_(w, h, pm, v) * AAGLSD_WS_U_(pm)) / 2ull > SIZE_MAX / 2)))
#define AAGLSD_WS_CANDIDATES_(w, h, pm, v) (((AAGLSD_WS_PIXELS_(w, h, pm, v) * AAGLSD_WS_U_(pm)) / 1000ull) + 64ull)
#define AAGLSD_WS_COMMON_(w, h, pm, v) (((((3ull + (4ull * (((AAGLSD_WS_CANDIDATES_(w, h, pm, v) + (AAGLSD_WS_U_(h) + 1ull)) + (((AAGLSD_WS_U_(v) + (AAGLSD_WS_U_(v) / 3ull)) + 1ull) + (2ull * (AAGLSD_WS_U_(v) / 6ull)))) + 512ull))) + (4ull * (((9ull * AAGLSD_WS_U_(w)) + 1ull) / 2ull))) + ((((2ull * AAGLSD_WS_U_(w)) + 7ull) / 8ull) * AAGLSD_WS_U_(h))) + ((((AAGLSD_WS_U_(w) + 7ull) / 8ull) * AAGLSD_WS_U_(h)) > (AAGLSD_WS_CANDIDATES_(w, h, pm, v) - 64ull) ? (((AAGLSD_WS_U_(w) + 7ull) / 8ull) * AAGLSD_WS_U_(h)) : (AAGLSD_WS_CANDIDATES_(w, h, pm, v) - 64ull))) + AAGLSD_WS_U_(w))
#define AAGLSD_WS_PLAIN_(w, h, pm, v) (AAGLSD_WS_COMMON_(w, h, pm, v) + AAGLSD_WS_PIXELS_(w, h, pm, v))
#define AAGLSD_WORKSPACE_BYTES_FOR(width, height, candidates_per_mille, max_link_pixels) \
  ((size_t)AAGLSD_WS_SIZE_((width), (height), (candidates_per_mille), (max_link_pixels)))
#define AAGLSD_WS_SIZE_(w, h, pm, v) ((AAGLSD_WS_BAD_(w, h, pm, v) || (AAGLSD_WS_PLAIN_(w, h, pm, v) / 2ull > SIZE_MAX / 2)) ? 0ull : AAGLSD_WS_PLAIN_(w, h, pm, v))
#define AAGLSD_WORKSPACE_BYTES_IN_PLACE_FOR(width, height, candidates_per_mille, max_link_pixels) \
  ((size_t)AAGLSD_WS_SIZE_IN_PLACE_((width), (height), (candidates_per_mille), (max_link_pixels)))
#define AAGLSD_WS_SIZE_IN_PLACE_(w, h, pm, v) ((AAGLSD_WS_BAD_(w, h, pm, v) || (AAGLSD_WS_COMMON_(w, h, pm, v) / 2ull > SIZE_MAX / 2)) ? 0ull : AAGLSD_WS_COMMON_(w, h, pm, v))
#define AAGLSD_WORKSPACE_BYTES_FAST_FOR(width, height, candidates_per_mille, max_link_pixels) \
  ((size_t)AAGLSD_WS_SIZE_FAST_((width), (height), (candidates_per_mille), (max_link_pixels)))
#define AAGLSD_WS_SIZE_FAST_(w, h, pm, v) ((AAGLSD_WS_BAD_(w, h, pm, v) || ((AAGLSD_WS_PLAIN_(w, h, pm, v) + ((4097ull > AAGLSD_WS_U_(w)) ? ((4ull * ((AAGLSD_WS_PIXELS_(w, h, pm, v) + 1ull) / 2ull)) + AAGLSD_WS_PIXELS_(w, h, pm, v)) : 0ull)) / 2ull > SIZE_MAX / 2)) ? 0ull : (AAGLSD_WS_PLAIN_(w, h, pm, v) + ((4097ull > AAGLSD_WS_U_(w)) ? ((4ull * ((AAGLSD_WS_PIXELS_(w, h, pm, v) + 1ull) / 2ull)) + AAGLSD_WS_PIXELS_(w, h, pm, v)) : 0ull)))
#define AAGLSD_DEFAULT_CANDIDATES_PER_MILLE 100
#define AAGLSD_DEFAULT_MAX_LINK_PIXELS 1024
#define AAGLSD_OFFICIAL_CANDIDATES_PER_MILLE 100
#define AAGLSD_OFFICIAL_MAX_LINK_PIXELS 1024
#define AAGLSD_PAPER_CANDIDATES_PER_MILLE 100
#define AAGLSD_PAPER_MAX_LINK_PIXELS 1024
#define AAGLSD_WORKSPACE_BYTES_PROFILE(profile, width, height) \
  AAGLSD_WORKSPACE_BYTES_FOR(width, height, AAGLSD_##profile##_CANDIDATES_PER_MILLE, AAGLSD_##profile##_MAX_LINK_PIXELS)
#define AAGLSD_WORKSPACE_BYTES(width, height) AAGLSD_WORKSPACE_BYTES_PROFILE(DEFAULT, width, height)
#define AAGLSD_WORKSPACE_BYTES_IN_PLACE_PROFILE(profile, width, height) \
  AAGLSD_WORKSPACE_BYTES_IN_PLACE_FOR(width, height, AAGLSD_##profile##_CANDIDATES_PER_MILLE, AAGLSD_##profile##_MAX_LINK_PIXELS)
#define AAGLSD_WORKSPACE_BYTES_IN_PLACE(width, height) AAGLSD_WORKSPACE_BYTES_IN_PLACE_PROFILE(DEFAULT, width, height)
#define AAGLSD_WORKSPACE_BYTES_FAST_PROFILE(profile, width, height) \
  AAGLSD_WORKSPACE_BYTES_FAST_FOR(width, height, AAGLSD_##profile##_CANDIDATES_PER_MILLE, AAGLSD_##profile##_MAX_LINK_PIXELS)
#define AAGLSD_WORKSPACE_BYTES_FAST(width, height) AAGLSD_WORKSPACE_BYTES_FAST_PROFILE(DEFAULT, width, height)


// Largest accepted width or height, in pixels (`aaglsd::MAX_DIMENSION`).
#define AAGLSD_MAX_DIMENSION 32767

// Largest accepted pixel count `width * height` (`aaglsd::MAX_PIXELS`, 2^26).
#define AAGLSD_MAX_PIXELS 67108864

// Result of every `aaglsd_*` function that can fail. `AAGLSD_STATUS_OK` is
// 0; the values are stable. `aaglsd_status_str` names each one.
enum AaglsdStatus
#if defined(__cplusplus) || __STDC_VERSION__ >= 202311L
  : int32_t
#endif // defined(__cplusplus) || __STDC_VERSION__ >= 202311L
 {
  // Success.
  AAGLSD_STATUS_OK = 0,
  // Width or height is zero.
  AAGLSD_STATUS_ZERO_DIMENSION = 1,
  // A side exceeds `AAGLSD_MAX_DIMENSION` or the pixel count exceeds
  // `AAGLSD_MAX_PIXELS`.
  AAGLSD_STATUS_IMAGE_TOO_LARGE = 2,
  // The row stride is smaller than the width.
  AAGLSD_STATUS_STRIDE_TOO_SMALL = 3,
  // `pixels_len < stride * (height - 1) + width`.
  AAGLSD_STATUS_BUFFER_TOO_SHORT = 4,
  // `workspace_len` is below what `aaglsd_workspace_size` returns.
  AAGLSD_STATUS_WORKSPACE_TOO_SMALL = 5,
  // `out_capacity` is zero.
  AAGLSD_STATUS_OUTPUT_EMPTY = 6,
  // A configuration field is out of range or NaN; `aaglsd_config_validate`
  // names the field.
  AAGLSD_STATUS_INVALID_CONFIG = 7,
  // A required pointer argument is NULL.
  AAGLSD_STATUS_NULL_POINTER = 8,
  // The output array is not aligned for `AaglsdSegment` (4 bytes).
  AAGLSD_STATUS_MISALIGNED = 9,
  // Two of the pixel, workspace and output buffers overlap.
  AAGLSD_STATUS_BUFFERS_OVERLAP = 10,
  // An enumerated argument (e.g. a profile number) has no meaning.
  AAGLSD_STATUS_INVALID_ARGUMENT = 11,
  // An error of the Rust core that this version of the C API does not
  // know (never returned while the two are built together).
  AAGLSD_STATUS_UNKNOWN = 12,
};
#ifndef __cplusplus
#if __STDC_VERSION__ >= 202311L
typedef enum AaglsdStatus AaglsdStatus;
#else
typedef int32_t AaglsdStatus;
#endif // __STDC_VERSION__ >= 202311L
#endif // __cplusplus

// Which `AaglsdConfig` field is out of range (`aaglsd_config_validate`).
enum AaglsdConfigField
#if defined(__cplusplus) || __STDC_VERSION__ >= 202311L
  : int32_t
#endif // defined(__cplusplus) || __STDC_VERSION__ >= 202311L
 {
  // No field: the configuration is valid.
  AAGLSD_CONFIG_FIELD_NONE = 0,
  // `magnitude_threshold`
  AAGLSD_CONFIG_FIELD_MAGNITUDE_THRESHOLD = 1,
  // `anchor_margin`
  AAGLSD_CONFIG_FIELD_ANCHOR_MARGIN = 2,
  // `align_tolerance_deg`
  AAGLSD_CONFIG_FIELD_ALIGN_TOLERANCE = 3,
  // `dist_tolerance_px`
  AAGLSD_CONFIG_FIELD_DIST_TOLERANCE = 4,
  // `skip_min`, `skip_regular` or `skip_group`
  AAGLSD_CONFIG_FIELD_SKIP_STEPS = 5,
  // `min_length_px`
  AAGLSD_CONFIG_FIELD_MIN_LENGTH = 6,
  // `min_groups`
  AAGLSD_CONFIG_FIELD_MIN_GROUPS = 7,
  // `anchor_density`
  AAGLSD_CONFIG_FIELD_ANCHOR_DENSITY = 8,
  // `aligned_density`
  AAGLSD_CONFIG_FIELD_ALIGNED_DENSITY = 9,
  // `merge_center_px`
  AAGLSD_CONFIG_FIELD_MERGE_CENTER = 10,
  // `merge_angle_deg`
  AAGLSD_CONFIG_FIELD_MERGE_ANGLE = 11,
  // `merge_gap_px`
  AAGLSD_CONFIG_FIELD_MERGE_GAP = 12,
  // `candidates_per_mille`
  AAGLSD_CONFIG_FIELD_CANDIDATE_CAPACITY = 13,
  // `max_link_pixels`
  AAGLSD_CONFIG_FIELD_LINK_CAPACITY = 14,
  // `extend_max_px`
  AAGLSD_CONFIG_FIELD_EXTEND_MAX = 15,
  // `work_per_mille`
  AAGLSD_CONFIG_FIELD_WORK_LIMIT = 16,
  // `bridge_px`
  AAGLSD_CONFIG_FIELD_BRIDGE_MAX = 17,
  // `min_score`
  AAGLSD_CONFIG_FIELD_MIN_SCORE = 18,
  // A field the Rust core reports but this version of the C API does not
  // know (never returned while the two are built together).
  AAGLSD_CONFIG_FIELD_UNKNOWN = 255,
};
#ifndef __cplusplus
#if __STDC_VERSION__ >= 202311L
typedef enum AaglsdConfigField AaglsdConfigField;
#else
typedef int32_t AaglsdConfigField;
#endif // __STDC_VERSION__ >= 202311L
#endif // __cplusplus

// Named parameter sets for `aaglsd_config_profile`.
enum AaglsdProfile
#if defined(__cplusplus) || __STDC_VERSION__ >= 202311L
  : uint32_t
#endif // defined(__cplusplus) || __STDC_VERSION__ >= 202311L
 {
  // `Config::DEFAULT`: the official thresholds with endpoint extension, merging and
  // one round of reseeding for the groups of misfit lines.
  AAGLSD_PROFILE_DEFAULT = 0,
  // `Config::OFFICIAL`: the thresholds of the authors' released code.
  AAGLSD_PROFILE_OFFICIAL = 1,
  // `Config::PAPER`: the paper's values, with merging (paper §3.3).
  AAGLSD_PROFILE_PAPER = 2,
};
#ifndef __cplusplus
#if __STDC_VERSION__ >= 202311L
typedef enum AaglsdProfile AaglsdProfile;
#else
typedef uint32_t AaglsdProfile;
#endif // __STDC_VERSION__ >= 202311L
#endif // __cplusplus

// Detector parameters: a field-by-field mirror of `aaglsd::Config` (see
// its documentation for each meaning and range). Fill it with
// `aaglsd_config_default` or `aaglsd_config_profile`, then change fields.
typedef struct AaglsdConfig {
  // T_mag, L1 gradient levels, 0..=1020.
  float magnitude_threshold;
  // T_anchor, L1 gradient levels, 0..=1020.
  uint16_t anchor_margin;
  // T_aligned, degrees, (0, 90).
  float align_tolerance_deg;
  // T_dist, pixels, (0, 64].
  float dist_tolerance_px;
  // S_min, gap steps, 1..=255.
  uint8_t skip_min;
  // S_ra, gap steps, 1..=255.
  uint8_t skip_regular;
  // S_aag, gap steps, 1..=255.
  uint8_t skip_group;
  // T_len, pixels, 0..=65536.
  float min_length_px;
  // N_aag, 1..=255.
  uint8_t min_groups;
  // rho1, 0..=1.
  float anchor_density;
  // rho2, 0..=1.
  float aligned_density;
  // The least score of a reported segment, 0..=16777215 (0 = every
  // segment).
  uint32_t min_score;
  // Endpoint extension limit, pixels, 0..=1024 (0 = off).
  uint16_t extend_max_px;
  // Whether groups released by a weak linking may seed again
  // (`aaglsd::Reseed`): 0 = never, 2 = once, 3 = misfit (the default), any other
  // value = always (the authors' code; 1 as `Reseed::Always`).
  uint8_t reseed;
  // How the anchors' maximum tests treat profiles symmetric about a
  // pixel (`aaglsd::Maxima`): 1 = symmetric (the default), any other
  // value = strict (the authors' code; 0 as `Maxima::Strict`).
  uint8_t maxima;
  // Bridging along a linking's line, pixels, 0..=32 (0 = off).
  uint8_t bridge_px;
  // Paper §3.3 merging: 0 = off, any other value = on.
  uint8_t merge;
  // Keep the longest part of a linking that fails rho2 (design §8.2):
  // 0 = off, any other value = on.
  uint8_t trim;
  // D_c, pixels, (0, 64].
  float merge_center_px;
  // D_a, degrees, (0, 90).
  float merge_angle_deg;
  // D_e, pixels, 0..=4096.
  float merge_gap_px;
  // Group-candidate capacity per 1000 pixels, 1..=1000.
  uint16_t candidates_per_mille;
  // Visited-list capacity per linking, pixels, 16..=65535.
  uint32_t max_link_pixels;
  // The frame's work limit, work units per 1000 pixels, 1..=100000.
  uint32_t work_per_mille;
  // A hard cap on the frame's work units; 0 = none.
  uint32_t work_budget;
} AaglsdConfig;

// A detected segment in 0-based pixel-centre coordinates (pixel (col, row)
// is centred at x = col, y = row). Same layout as `aaglsd::Segment`.
typedef struct AaglsdSegment {
  // First endpoint, x (column).
  float x0;
  // First endpoint, y (row).
  float y0;
  // Second endpoint, x (column).
  float x1;
  // Second endpoint, y (row).
  float y1;
  // The score: the gradient contrast integrated along the segment
  // (higher: likelier a true line). The brighter side lies on the left
  // of (x0, y0) -> (x1, y1) as displayed (x right, y down).
  float score;
} AaglsdSegment;

// What an `aaglsd_detect` call did: a mirror of `aaglsd::Summary`.
// Zeroed when the call fails.
typedef struct AaglsdSummary {
  // Segments written to the front of the output array.
  size_t segments;
  // Segments found but not written because the output array was full.
  size_t dropped_segments;
  // Group candidates dropped because the candidate list was full.
  size_t dropped_candidates;
  // Linkings stopped early because the visited list was full.
  size_t truncated_linkings;
  // Group candidates kept for extraction.
  size_t candidates;
  // Aligned anchor groups extracted.
  size_t groups;
  // Segments removed by merging (0 when merging is off).
  size_t merged;
  // Work units spent by the linking, validation, extension and merging.
  size_t work;
  // Seeds and segment pairs left unprocessed at the work limit or budget.
  size_t work_cut;
} AaglsdSummary;

#ifdef __cplusplus
extern "C" {
#endif // __cplusplus

// The library version, e.g. `"0.1.0"`: a static NUL-terminated string.
const char *aaglsd_version(void);

// A static NUL-terminated English description of `status` (an
// `AaglsdStatus` value); `"unknown status"` for any other value. Never NULL.
const char *aaglsd_status_str(int32_t status);

// A static NUL-terminated name of `field` (an `AaglsdConfigField` value),
// as written in `AaglsdConfig`; `"none"` for `AAGLSD_CONFIG_FIELD_NONE` and
// `"unknown field"` for any other value. Never NULL.
const char *aaglsd_config_field_str(int32_t field);

// Writes the default profile (`Config::DEFAULT`) to `*out`.
//
// Returns `AAGLSD_STATUS_NULL_POINTER` when `out` is NULL.
//
// # Safety
// `out` is NULL or valid for writing one `AaglsdConfig` (any alignment).
AaglsdStatus aaglsd_config_default(struct AaglsdConfig *out);

// Writes the named profile (an `AaglsdProfile` value) to `*out`.
//
// Returns `AAGLSD_STATUS_NULL_POINTER` when `out` is NULL and
// `AAGLSD_STATUS_INVALID_ARGUMENT` (leaving `*out` untouched) for an unknown
// profile.
//
// # Safety
// `out` is NULL or valid for writing one `AaglsdConfig` (any alignment).
AaglsdStatus aaglsd_config_profile(uint32_t profile, struct AaglsdConfig *out);

// Checks every field of `*cfg` against its documented range (NaN is out of
// range). Returns `AAGLSD_STATUS_OK` or `AAGLSD_STATUS_INVALID_CONFIG`, and
// writes the first offending field (or `AAGLSD_CONFIG_FIELD_NONE`) to
// `*field` unless `field` is NULL (it is optional).
//
// Returns `AAGLSD_STATUS_NULL_POINTER` when `cfg` is NULL.
//
// # Safety
// `cfg` is NULL or valid for reading one `AaglsdConfig`; `field` is NULL or
// valid for writing one `AaglsdConfigField` (any alignment).
AaglsdStatus aaglsd_config_validate(const struct AaglsdConfig *cfg, AaglsdConfigField *field);

// Writes to `*out_bytes` the workspace size in bytes that `aaglsd_detect`
// needs for a `width` x `height` image with `*cfg`'s capacities (the same
// for every stride). The slab needs no particular alignment and may be
// uninitialised; reuse it for any number of calls.
//
// Checked in this order: `AAGLSD_STATUS_NULL_POINTER` (`cfg`,
// `out_bytes`), `AAGLSD_STATUS_ZERO_DIMENSION`,
// `AAGLSD_STATUS_IMAGE_TOO_LARGE`, `AAGLSD_STATUS_INVALID_CONFIG`. On error
// `*out_bytes` is set to 0 (when not NULL).
//
// # Safety
// `cfg` is NULL or valid for reading one `AaglsdConfig`; `out_bytes` is NULL
// or valid for writing one `size_t` (any alignment).
AaglsdStatus aaglsd_workspace_size(size_t width,
                                   size_t height,
                                   const struct AaglsdConfig *cfg,
                                   size_t *out_bytes);

// Writes to `*out_bytes` the workspace size with which `aaglsd_detect`
// runs faster: `aaglsd_workspace_size`'s plus `3·width·height` bytes
// (rounded up to 4) for a group index (one load per group lookup in the
// linking) and a cache of the gradient magnitudes (read by the walk's
// steps); the same size for an image wider than 4096 pixels, which gets
// neither. The segments are the same with either size; this one
// is for hosts with memory to spare. Checks and errors as
// `aaglsd_workspace_size`.
//
// # Safety
// As `aaglsd_workspace_size`.
AaglsdStatus aaglsd_workspace_size_fast(size_t width,
                                        size_t height,
                                        const struct AaglsdConfig *cfg,
                                        size_t *out_bytes);

// Writes to `*out_bytes` the workspace size that `aaglsd_detect_in_place`
// needs: `aaglsd_workspace_size`'s less the `width·height` bytes of the
// smoothed image, which stays in the caller's frame. Adding the same
// `3·width·height` bytes (rounded up to 4) as `aaglsd_workspace_size_fast`
// adds gives `aaglsd_detect_in_place` the faster layout. Checks and errors
// as `aaglsd_workspace_size`.
//
// # Safety
// As `aaglsd_workspace_size`.
AaglsdStatus aaglsd_workspace_size_in_place(size_t width,
                                            size_t height,
                                            const struct AaglsdConfig *cfg,
                                            size_t *out_bytes);

// Detects line segments in an 8-bit grayscale image.
//
// `pixels` holds `height` rows of `width` bytes, each row starting `stride`
// bytes after the previous one (`pixels_len >= stride * (height - 1) +
// width`). `workspace` is a scratch slab of at least
// `aaglsd_workspace_size` bytes, or of `aaglsd_workspace_size_fast` bytes
// for the faster run with the same result (any alignment, may be
// uninitialised: the first `aaglsd_workspace_size` or
// `aaglsd_workspace_size_fast` bytes, whichever the slab holds, are zeroed
// before use, and so are the `out_capacity` output slots, once every check
// has passed).
// Up to `out_capacity` segments are written to the front of `out`; the
// summary gives their number and counts those that did not fit.
//
// Checked in this order, before anything is written:
// 1. `AAGLSD_STATUS_NULL_POINTER`: any pointer is NULL (all are required);
// 2. `AAGLSD_STATUS_MISALIGNED`: `out` is not 4-byte aligned;
// 3. `AAGLSD_STATUS_BUFFERS_OVERLAP`: two of `pixels[0..pixels_len]`,
//    `workspace[0..workspace_len]`, `out[0..out_capacity]` share a byte;
// 4. the image: `ZERO_DIMENSION`, `IMAGE_TOO_LARGE`, `STRIDE_TOO_SMALL`,
//    `BUFFER_TOO_SHORT`;
// 5. `AAGLSD_STATUS_INVALID_CONFIG` (see `aaglsd_config_validate`);
// 6. `AAGLSD_STATUS_WORKSPACE_TOO_SMALL`;
// 7. `AAGLSD_STATUS_OUTPUT_EMPTY`: `out_capacity` is 0.
//
// On error, `out` is untouched, the workspace content is unspecified and
// `*summary` is zeroed (when not NULL).
//
// # Safety
// Each pointer is NULL or valid for its length: `pixels` readable for
// `pixels_len` bytes, `workspace` writable for `workspace_len` bytes, `out`
// writable for `out_capacity` segments, `cfg` readable and `summary`
// writable for one struct (any alignment). The buffers may not be written
// by anyone else during the call.
AaglsdStatus aaglsd_detect(const uint8_t *pixels,
                           size_t pixels_len,
                           size_t width,
                           size_t height,
                           size_t stride,
                           const struct AaglsdConfig *cfg,
                           uint8_t *workspace,
                           size_t workspace_len,
                           struct AaglsdSegment *out,
                           size_t out_capacity,
                           struct AaglsdSummary *summary);

// `aaglsd_detect` on a frame that it may overwrite: the frame is smoothed
// in place, so the workspace needs no copy of the image
// (`aaglsd_workspace_size_in_place`, `width·height` bytes less than
// `aaglsd_workspace_size`). The segments and the summary are the same as
// `aaglsd_detect`'s on the same pixels. Afterwards the first
// `width·height` bytes of `frame` hold the smoothed image, rows packed;
// the rest of it is unchanged.
//
// A camera frame in another format (YUYV, RGB565) can be reduced to its
// luma in the same buffer first, rows packed, so that one `w·h` buffer
// serves both (`ffi/firmware/`).
//
// Checks and errors as `aaglsd_detect`, with the workspace checked against
// `aaglsd_workspace_size_in_place`. On error, `frame` and `out` are
// untouched, and `*summary` is zeroed (when not NULL).
//
// # Safety
// As `aaglsd_detect`, with `frame` readable and writable for `frame_len`
// bytes.
AaglsdStatus aaglsd_detect_in_place(uint8_t *frame,
                                    size_t frame_len,
                                    size_t width,
                                    size_t height,
                                    size_t stride,
                                    const struct AaglsdConfig *cfg,
                                    uint8_t *workspace,
                                    size_t workspace_len,
                                    struct AaglsdSegment *out,
                                    size_t out_capacity,
                                    struct AaglsdSummary *summary);

#ifdef __cplusplus
}  // extern "C"
#endif  // __cplusplus

#endif  /* AAGLSD_H */
