/*
 * motion_type.h - the acceleration history (sl_motion) and the
 * three-component set (sl_set) as plain data, with their allocation and the
 * intensity measures computed from them. No file is read here: the readers
 * are in io/motion.h, and signal/ (which only needs the type) includes this
 * header, never io/.
 *
 * Units: SI (s, m/s^2, m/s, m).
 *
 * Memory: a motion owns its path, label and samples; free it with
 * sl_motion_free(). sl_set holds borrowed pointers and owns nothing.
 */
#ifndef SL_MOTION_TYPE_H
#define SL_MOTION_TYPE_H

#include <stddef.h>

#include "core/api.h"

/* Relative tolerance on sample intervals: the steps of a time column
 * against their mean, an explicit dt against the file's, and the dt of the
 * components of a set against each other (dimensionless). */
#define SL_MOTION_DT_REL_TOL 1e-6

/* One acceleration history, uniformly sampled, SI units. */
typedef struct sl_motion {
    char *path;        /* file it came from ("" if synthesized) */
    char *label;       /* free text, e.g. the AT2 title line */
    size_t n;          /* number of samples */
    double dt_s;       /* sample interval, s (> 0) */
    double *acc_ms2;   /* n samples, m/s^2 */
} sl_motion;

/* A three-component set: H1 required, H2 and V optional (NULL). Borrowed
 * pointers; after sl_set_check() (core/motion_set.h) succeeds all present
 * components share n and dt_s. */
typedef struct sl_set {
    sl_motion *h1, *h2, *v;
} sl_set;

/* Make a motion that takes ownership of acc_owned (n samples, malloc'd):
 * path and label[0..label_len) are copied (label NULL gives ""). Returns
 * NULL on allocation failure, and then acc_owned still belongs to the
 * caller. For readers; callers with an array use sl_motion_from_array(). */
SL_API sl_motion *sl_motion_new_owned(const char *path, const char *label, size_t label_len,
                                      double *acc_owned, size_t n, double dt_s);

/* Make a motion from an array (copied). Returns NULL on bad dt or n == 0. */
SL_API sl_motion *sl_motion_from_array(const double *acc_ms2, size_t n, double dt_s,
                                       const char *label);

/* Deep copy; NULL on allocation failure. */
SL_API sl_motion *sl_motion_copy(const sl_motion *m);

SL_API void sl_motion_free(sl_motion *m);

/* Derived quantities of one component (SI). The acceleration is taken as
 * piecewise linear between samples and integrated exactly:
 *   v_{i+1} = v_i + dt (a_i + a_{i+1})/2,
 *   d_{i+1} = d_i + dt v_i + dt^2 (2 a_i + a_{i+1})/6,
 * from rest, with no baseline correction (see docs/formats.md). */
SL_API double sl_motion_pga(const sl_motion *m);  /* max |a|, m/s^2 */
SL_API double sl_motion_pgv(const sl_motion *m);  /* max |v|, m/s   */
SL_API double sl_motion_pgd(const sl_motion *m);  /* max |d|, m     */
/* Arias intensity I_a = pi/(2 g) * integral a^2 dt, m/s (exact for
 * piecewise-linear a). */
SL_API double sl_motion_arias(const sl_motion *m);
/* Significant duration between 5 % and 75 % of I_a, s (linear
 * interpolation of the normalised Husid curve). */
SL_API double sl_motion_d5_75(const sl_motion *m);
/* Velocity and displacement histories (n samples each, caller-allocated). */
SL_API void sl_motion_integrate(const sl_motion *m, double *vel_ms, double *disp_m);

/* Multiply all samples by s. */
SL_API void sl_motion_scale(sl_motion *m, double s);

#endif
