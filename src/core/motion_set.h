/*
 * motion_set.h - checks and combinations of a three-component set (sl_set,
 * core/motion_type.h): common sample interval and length, peak horizontal
 * acceleration, scaling, and the 100-40 peak displacement.
 *
 * Units: SI. Errors name the component's file and the value.
 */
#ifndef SL_MOTION_SET_H
#define SL_MOTION_SET_H

#include <stddef.h>

#include "core/api.h"
#include "core/motion_type.h"
#include "core/status.h"

/* What sl_set_check_fit() did to the lengths: n_in[k] samples of H1, H2, V
 * as read (0 when absent), n the common length after the check, and
 * `changed` nonzero when a length was altered (padded or cut). */
typedef struct sl_set_fit {
    size_t n_in[3];
    size_t n;
    int truncated; /* 1: cut to the shortest, 0: padded to the longest */
    int changed;
} sl_set_fit;

/* Check a set: H1 present; same dt (relative SL_MOTION_DT_REL_TOL) or an
 * error naming both files and values; all values finite. Components of
 * different length are padded with zeros to the longest (the ground is at
 * rest after its record ends; the padded arrays are reallocated, so the
 * motions must own their samples, as those from the readers do), or with
 * `truncate` nonzero cut to the shortest (the old behaviour). fit (may be
 * NULL) reports the lengths so the caller can say what was done. On error
 * the set is unchanged. */
SL_API sl_status sl_set_check_fit(sl_set *set, int truncate, sl_set_fit *fit, sl_error *err);

/* sl_set_check_fit() without the report. */
SL_API sl_status sl_set_check(sl_set *set, int truncate, sl_error *err);

/* Peak horizontal acceleration of the set: the larger component peak,
 * m/s^2. */
SL_API double sl_set_pga_h(const sl_set *set);

/* Scale every component of the set by s = pga_ms2 / sl_set_pga_h(set), so
 * the larger horizontal peak becomes pga_ms2 (m/s^2). Returns s, or 0 with
 * the set unchanged when the horizontals are all zero (nothing to scale). */
SL_API double sl_set_scale_pga_h(sl_set *set, double pga_ms2);

/* Peak displacement by the 100-40 rule: max(PGD1 + 0.4 PGD2, PGD2 + 0.4 PGD1),
 * m; PGD1 alone when H2 is absent. */
SL_API double sl_set_pgd_100_40(const sl_set *set);

#endif
