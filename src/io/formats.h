/*
 * formats.h - agency ground-motion formats beyond PEER .AT2 (docs/formats.md):
 *
 *  - GeoNet (New Zealand) Volume 2 ".V2A": several channels in one file, each
 *    16 text lines + 4 integer lines (10I8) + 6 real lines (10F8) of header,
 *    then npts accelerations in mm/s/s, 10 fields of 8 columns a line
 *    (velocity and displacement follow and are skipped). npts from "Number of
 *    points", dt from "data at D sec intervals", the component from
 *    "Component X", the unit from the "Acceleration:" line.
 *  - CSMIP (California) Volume 2 ".V2": several channels in one file; each
 *    channel's acceleration block starts with the line
 *    "N points of accel data equally spaced at D sec, in UNIT. (8f10.6)"
 *    (older files: "... (UNITS: CM/SEC/SEC)" and no format, read as 8f10);
 *    the component from the "Chan k: NAME" line.
 *  - CWA/TSMIP ".acc" as the Central Weather Administration distributes it: one component a file, two
 *    columns time (s) + acceleration in m/s^2, no header (the unit is the
 *    distribution's, MANIFEST.tsv "TWOCOL_MS2"); the component from the
 *    file name (_E, _N, _Z).
 *
 *  - USGS SMC ".smc" (type 2, corrected acceleration): one component a
 *    file; 11 text lines (line 6 "component=  360"), 48 integers 8I10
 *    (field 16 = comment lines, 17 = npts), 50 reals 5E15.7 (field 2 =
 *    samples per second), the comment lines, then npts values 8E10 in
 *    cm/s/s (the format's unit).
 *
 * Values are converted once to m/s^2 (SI). Errors name file, line, value.
 * Memory: sl_channels_read() fills a sl_channels the caller frees with
 * sl_channels_free(); motions taken out of it must be set to NULL there.
 */
#ifndef SL_FORMATS_H
#define SL_FORMATS_H

#include <stddef.h>

#include "core/status.h"
#include "io/motion.h"

#define SL_CHANNELS_MAX 16
#define SL_COMP_NAME_MAX 32

/* The channels of one multi-channel file, in file order. */
typedef struct sl_channels {
    size_t n;
    sl_motion *m[SL_CHANNELS_MAX];              /* owned; SI */
    char comp[SL_CHANNELS_MAX][SL_COMP_NAME_MAX]; /* as the file names it: "N10E", "Up", "90 Deg" */
} sl_channels;

/* 1 when the first line of a file marks a GeoNet V2A / CSMIP V2 file. */
int sl_formats_is_v2a(const char *first_line);
int sl_formats_is_csmip_v2(const char *first_line);

/* Read every acceleration channel of a GeoNet .V2A or CSMIP .V2 file (the
 * format is told by its content). Returns SL_OK, or SL_EIO (cannot open),
 * SL_EPARSE (not one of these formats, bad header, bad or missing values:
 * file, line and value named), SL_EINVAL (npts or dt out of range, unknown
 * unit, |a| > SL_MOTION_MAX_ABS_G g), SL_ENOMEM. On failure *out is empty. */
sl_status sl_channels_read(const char *path, sl_channels *out, sl_error *err);

/* Free the motions still in c and zero it; harmless on NULL. */
void sl_channels_free(sl_channels *c);

/* A CWA/TSMIP .acc component: two columns, time in s and acceleration in
 * m/s^2. NULL and err filled on failure (the two-column reader's errors). */
sl_motion *sl_cwa_acc_read(const char *path, sl_error *err);

/* A USGS SMC corrected accelerogram (type 2); its component name ("360",
 * "up") is copied to comp (compn bytes, may be NULL). NULL and err filled
 * (file, line, value) on failure. */
sl_motion *sl_smc_read(const char *path, char *comp, size_t compn, sl_error *err);

/* 1 when a component name from a file header names the vertical: "Up",
 * "UP", "Z", "V", "Ver", "Vertical", "Down", "DWN" (any case, surrounding
 * blanks ignored). */
int sl_component_is_vertical(const char *comp);

#endif
