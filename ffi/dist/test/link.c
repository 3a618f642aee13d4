/* Compiles and links against the distributable: every aaglsd_ function,
 * the compile-time sizes as static buffer lengths. Not run (check.sh only
 * links it, for each core and float ABI). */
#include "aaglsd.h"

static uint8_t image[64 * 48];
static uint8_t workspace[AAGLSD_WORKSPACE_BYTES(64, 48)];
static uint8_t workspace_in_place[AAGLSD_WORKSPACE_BYTES_IN_PLACE(64, 48)];
static AaglsdSegment out[64];

int main(void) {
    AaglsdConfig cfg;
    AaglsdSummary summary;
    AaglsdConfigField field;
    size_t n = 0, m = 0, k = 0;
    int bad = aaglsd_config_default(&cfg) != AAGLSD_STATUS_OK;
    bad |= aaglsd_config_profile(AAGLSD_PROFILE_PAPER, &cfg) != AAGLSD_STATUS_OK;
    bad |= aaglsd_config_validate(&cfg, &field) != AAGLSD_STATUS_OK;
    bad |= aaglsd_workspace_size(64, 48, &cfg, &n) != AAGLSD_STATUS_OK;
    bad |= aaglsd_workspace_size_in_place(64, 48, &cfg, &m) != AAGLSD_STATUS_OK;
    bad |= aaglsd_workspace_size_fast(64, 48, &cfg, &k) != AAGLSD_STATUS_OK;
    bad |= n != sizeof workspace || m != sizeof workspace_in_place || k < n;
    bad |= aaglsd_detect(image, sizeof image, 64, 48, 64, &cfg, workspace, sizeof workspace, out,
                         64, &summary) != AAGLSD_STATUS_OK;
    bad |= aaglsd_detect_in_place(image, sizeof image, 64, 48, 64, &cfg, workspace_in_place,
                                  sizeof workspace_in_place, out, 64,
                                  &summary) != AAGLSD_STATUS_OK;
    bad |= aaglsd_status_str(AAGLSD_STATUS_OK)[0] == 0;
    bad |= aaglsd_config_field_str(field)[0] == 0;
    bad |= aaglsd_version()[0] == 0;
    return bad;
}
