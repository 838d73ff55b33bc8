/*
 * motion.h - ground-motion records in, as SI acceleration histories.
 *
 * Formats read (see docs/formats.md):
 *  - PEER NGA .AT2, both header layouts:
 *      NGA-West2:  "NPTS=  1991, DT=   .0100 SEC, ..."   (line 4)
 *      older NGA:  "  1991   0.0100   NPTS, DT"          (line 4)
 *    units from line 3 ("... IN UNITS OF G" or "The units are (g)").
 *  - plain text, one column (needs dt and units from the caller),
 *  - plain text, two columns time + acceleration (dt from the time column,
 *    which must be uniform to 1e-6 relative),
 *  - CSV with a header line: a time column and one acceleration column.
 *  Comment lines starting with '#', blank lines, CRLF line ends and a UTF-8
 *  byte-order mark are tolerated everywhere.
 *
 * Values are converted once to m/s^2. A unit is never guessed: AT2 takes it
 * from its header (an explicit unit that disagrees is an error); other
 * formats need it from the caller or from a CSV header such as "acc_g",
 * "acc_m/s2" or "acc (cm/s2)".
 *
 * The motion and set types, their measures (PGA, PGV, PGD, Arias, D5-75)
 * and the set checks are plain data below io/ (core/motion_type.h,
 * core/motion_set.h), included here so one header gives the whole motion
 * API. The readers: motion.c (dispatch), at2.c, columns.c, on the shared
 * text helpers of io/text.h.
 *
 * Memory: sl_motion_read() returns a motion the caller frees with
 * sl_motion_free(). sl_set holds borrowed pointers and owns nothing.
 */
#ifndef SL_MOTION_H
#define SL_MOTION_H

#include <stddef.h>

#include "core/api.h"
#include "core/motion_set.h"
#include "core/motion_type.h"
#include "core/status.h"
#include "core/units.h"

/* The reader's limits. A file larger than SL_MOTION_MAX_BYTES is refused
 * before it is read (the message gives the limit); an acceleration whose
 * magnitude in SI exceeds SL_MOTION_MAX_ABS_G g (including one that
 * overflows to infinity when converted) is refused with its file, line and
 * value: no floor or ground motion comes near it, and every result computed
 * from the motion stays finite. Time-column values must lie within
 * +-SL_MOTION_MAX_TIME_S. */
#define SL_MOTION_MAX_BYTES (256L * 1024 * 1024)
#define SL_MOTION_MAX_ABS_G 100.0
#define SL_MOTION_MAX_TIME_S 1e6

typedef enum sl_format {
    SL_FORMAT_AUTO = 0, /* decide from the content (AT2 header, CSV header, columns) */
    SL_FORMAT_AT2,
    SL_FORMAT_ONECOL,
    SL_FORMAT_TWOCOL,
    SL_FORMAT_CSV
} sl_format;

/* How to read a file. Zero-initialise, then set what you know. */
typedef struct sl_read_opts {
    sl_format format;  /* SL_FORMAT_AUTO to detect */
    sl_unit units;     /* SL_UNIT_NONE: take from the file, else error */
    double dt_s;       /* for one-column files; 0 = not given */
} sl_read_opts;

/* Read one component. Returns NULL and fills err (file, line, message) on
 * failure: missing file, truncated AT2 or NPTS disagreeing with the data,
 * non-numeric token, NaN/Inf, dt <= 0, non-uniform time column, unknown or
 * missing units. */
SL_API sl_motion *sl_motion_read(const char *path, const sl_read_opts *opts, sl_error *err);

/* 1 when a file name (folders stripped) names a vertical component by the
 * PEER and agency conventions: the component code ends the name, before
 * the extension, as UP, DWN, DOWN, VER, VRT, -V, -Z, _Z or _V (any case):
 * "...-UP.AT2", "RinaldiUP.AT2", "...DWN-up.AT2", "...HECVER.AT2". Station
 * codes inside a name ("H-VC1", "H-Z11") do not count. */
SL_API int sl_motion_name_is_vertical(const char *path);

#endif
