/*
 * motion_read.h - what the motion readers share (internal; not installed):
 * the two format readers behind sl_motion_read() (io/motion.h) and the
 * checks every one of them applies to units, dt and accelerations.
 *
 * Each reader gets the file in memory (io/text.h) positioned at its first
 * line, converts values once to m/s^2 and, on failure, frees what it built
 * and fills err with the file, the 1-based line and the token quoted.
 */
#ifndef SL_IO_MOTION_READ_H
#define SL_IO_MOTION_READ_H

#include "io/motion.h"
#include "io/text.h"

/* PEER .AT2 (io/at2.c): 4 header lines (title, event/station, units,
 * NPTS/DT) then NPTS values. */
sl_motion *sl_motion_read_at2(const char *path, sl_text *t, const sl_read_opts *o,
                              sl_error *err);

/* One column, two columns or CSV with a header (io/columns.c); fmt is
 * SL_FORMAT_AUTO (decide from the first non-comment line), ONECOL, TWOCOL
 * or CSV. */
sl_motion *sl_motion_read_columns(const char *path, sl_text *t, sl_format fmt,
                                  const sl_read_opts *o, sl_error *err);

/* An acceleration after conversion to SI: finite and within
 * SL_MOTION_MAX_ABS_G g, else SL_EINVAL naming the raw value and unit. */
sl_status sl_motion_check_acc(double si, double raw, sl_unit u, const char *path, long line,
                              sl_error *err);

/* Decide the unit: from the file (`file_u`, SL_UNIT_NONE if the file names
 * none) and the caller (`opt_u`); an error when they disagree or neither
 * gives one. */
sl_status sl_motion_resolve_units(sl_unit file_u, sl_unit opt_u, const char *path, long line,
                                  sl_unit *out, sl_error *err);

/* An explicit dt (opts; 0 = none) must agree with the file's within
 * SL_MOTION_DT_REL_TOL. */
sl_status sl_motion_check_opt_dt(double opt_dt, double file_dt, const char *path, long line,
                                 sl_error *err);

#endif
