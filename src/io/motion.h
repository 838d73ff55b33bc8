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
 * Memory: sl_motion_read() returns a motion the caller frees with
 * sl_motion_free(). sl_set holds borrowed pointers and owns nothing.
 */
#ifndef SL_MOTION_H
#define SL_MOTION_H

#include <stddef.h>

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

/* One acceleration history, uniformly sampled, SI units. */
typedef struct sl_motion {
    char *path;        /* file it came from ("" if synthesized) */
    char *label;       /* free text, e.g. the AT2 title line */
    size_t n;          /* number of samples */
    double dt_s;       /* sample interval, s (> 0) */
    double *acc_ms2;   /* n samples, m/s^2 */
} sl_motion;

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
sl_motion *sl_motion_read(const char *path, const sl_read_opts *opts, sl_error *err);

/* Make a motion from an array (copied). Returns NULL on bad dt or n == 0. */
sl_motion *sl_motion_from_array(const double *acc_ms2, size_t n, double dt_s,
                                const char *label);

/* Deep copy; NULL on allocation failure. */
sl_motion *sl_motion_copy(const sl_motion *m);

void sl_motion_free(sl_motion *m);

/* Derived quantities of one component (SI). The acceleration is taken as
 * piecewise linear between samples and integrated exactly:
 *   v_{i+1} = v_i + dt (a_i + a_{i+1})/2,
 *   d_{i+1} = d_i + dt v_i + dt^2 (2 a_i + a_{i+1})/6,
 * from rest, with no baseline correction (see docs/formats.md). */
double sl_motion_pga(const sl_motion *m);  /* max |a|, m/s^2 */
double sl_motion_pgv(const sl_motion *m);  /* max |v|, m/s   */
double sl_motion_pgd(const sl_motion *m);  /* max |d|, m     */
/* Arias intensity I_a = pi/(2 g) * integral a^2 dt, m/s (exact for
 * piecewise-linear a). */
double sl_motion_arias(const sl_motion *m);
/* Significant duration between 5 % and 75 % of I_a, s (linear
 * interpolation of the normalised Husid curve). */
double sl_motion_d5_75(const sl_motion *m);
/* Velocity and displacement histories (n samples each, caller-allocated). */
void sl_motion_integrate(const sl_motion *m, double *vel_ms, double *disp_m);

/* Multiply all samples by s. */
void sl_motion_scale(sl_motion *m, double s);

/* 1 when a file name (folders stripped) names a vertical component by the
 * PEER and agency conventions: the component code ends the name, before
 * the extension, as UP, DWN, DOWN, VER, VRT, -V, -Z, _Z or _V (any case):
 * "...-UP.AT2", "RinaldiUP.AT2", "...DWN-up.AT2", "...HECVER.AT2". Station
 * codes inside a name ("H-VC1", "H-Z11") do not count. */
int sl_motion_name_is_vertical(const char *path);

/* A three-component set: H1 required, H2 and V optional (NULL). Borrowed
 * pointers; after sl_set_check() succeeds all present components share n
 * and dt_s. */
typedef struct sl_set {
    sl_motion *h1, *h2, *v;
} sl_set;

/* What sl_set_check_fit() did to the lengths: n_in[k] samples of H1, H2, V
 * as read (0 when absent), n the common length after the check, and
 * `changed` nonzero when a length was altered (padded or cut). */
typedef struct sl_set_fit {
    size_t n_in[3];
    size_t n;
    int truncated; /* 1: cut to the shortest, 0: padded to the longest */
    int changed;
} sl_set_fit;

/* Check a set: H1 present; same dt (relative 1e-6) or an error naming both
 * files and values; all values finite. Components of different length are
 * padded with zeros to the longest (the ground is at rest after its record
 * ends; the padded arrays are reallocated, so the motions must own their
 * samples, as those from the readers do), or with `truncate` nonzero cut to
 * the shortest (the old behaviour). fit (may be NULL) reports the lengths so
 * the caller can say what was done. On error the set is unchanged. */
sl_status sl_set_check_fit(sl_set *set, int truncate, sl_set_fit *fit, sl_error *err);

/* sl_set_check_fit() without the report. */
sl_status sl_set_check(sl_set *set, int truncate, sl_error *err);

/* Peak horizontal acceleration of the set: the larger component peak,
 * m/s^2. */
double sl_set_pga_h(const sl_set *set);

/* Scale every component of the set by s = pga_ms2 / sl_set_pga_h(set), so
 * the larger horizontal peak becomes pga_ms2 (m/s^2). Returns s, or 0 with
 * the set unchanged when the horizontals are all zero (nothing to scale). */
double sl_set_scale_pga_h(sl_set *set, double pga_ms2);

/* Peak displacement by the 100-40 rule: max(PGD1 + 0.4 PGD2, PGD2 + 0.4 PGD1),
 * m; PGD1 alone when H2 is absent. */
double sl_set_pgd_100_40(const sl_set *set);

#endif
