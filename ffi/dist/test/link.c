/* Compiles and links against the distributable: every aaglsd_ function,
 * the compile-time sizes as static buffer lengths. Not run (check.sh only
 * links it, for each core and float ABI). */
#include "aaglsd.h"

/* Small enough for the 32 KiB RAM of picolibc's default RISC-V link. */
#define W 32
#define H 24
static uint8_t image[W * H];
static uint8_t workspace[AAGLSD_WORKSPACE_BYTES(W, H)];
static uint8_t workspace_in_place[AAGLSD_WORKSPACE_BYTES_IN_PLACE(W, H)];
static AaglsdSegment out[64];

int main(void) {
    AaglsdConfig cfg;
    AaglsdSummary summary;
    AaglsdConfigField field;
    size_t n = 0, m = 0, k = 0;
    int bad = aaglsd_config_default(&cfg) != AAGLSD_STATUS_OK;
    bad |= aaglsd_config_profile(AAGLSD_PROFILE_PAPER, &cfg) != AAGLSD_STATUS_OK;
    bad |= aaglsd_config_validate(&cfg, &field) != AAGLSD_STATUS_OK;
    bad |= aaglsd_workspace_size(W, H, &cfg, &n) != AAGLSD_STATUS_OK;
    bad |= aaglsd_workspace_size_in_place(W, H, &cfg, &m) != AAGLSD_STATUS_OK;
    bad |= aaglsd_workspace_size_fast(W, H, &cfg, &k) != AAGLSD_STATUS_OK;
    bad |= n != sizeof workspace || m != sizeof workspace_in_place || k < n;
    bad |= aaglsd_detect(image, sizeof image, W, H, W, &cfg, workspace, sizeof workspace, out,
                         64, &summary) != AAGLSD_STATUS_OK;
    bad |= aaglsd_detect_in_place(image, sizeof image, W, H, W, &cfg, workspace_in_place,
                                  sizeof workspace_in_place, out, 64,
                                  &summary) != AAGLSD_STATUS_OK;
    bad |= aaglsd_status_str(AAGLSD_STATUS_OK)[0] == 0;
    bad |= aaglsd_config_field_str(field)[0] == 0;
    bad |= aaglsd_version()[0] == 0;
    return bad;
}
