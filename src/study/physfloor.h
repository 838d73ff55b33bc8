/*
 * physfloor.h - physical floor motions from many real records, and the
 * statistics of comparing sliding on two independent samples of sets
 * (docs/synthesis.md 10; tests/test_physical_floors.c, tools/physfloors.c).
 *
 * Records. Every sub-directory of a records directory that reads as a full
 * three-component set (sl_set_read_dir) and passes the quality rule
 *     larger horizontal PGA >= min_pga_g (0.05 g) as recorded,
 *     duration (n - 1) dt >= min_duration_s (15 s),
 *     dt <= max_dt_s (0.02 s),
 * in name order. A used record is resampled to sl_synth_match_dt(dt)
 * (synth.h: every sample kept, step <= 0.01 s) and scaled so that its
 * larger horizontal PGA is the given value (all three components by the
 * same factor).
 *
 * Ratio of two independent means (sample a: n_a values, sample b: n_b):
 *     R = mean(a) / mean(b),
 *     SE(R) = R sqrt(s_a^2 / (n_a mean(a)^2) + s_b^2 / (n_b mean(b)^2))   (P1)
 * (first-order delta method; s the sample standard deviations).
 *
 * Units: SI. Library code: no printing.
 */
#ifndef SL_PHYSFLOOR_H
#define SL_PHYSFLOOR_H

#include <stddef.h>

#include "core/status.h"
#include "io/motion.h"

/* Quality rule of the records used (defaults below). */
typedef struct sl_pf_rule {
    double min_pga_g;      /* larger horizontal PGA as recorded, g */
    double min_duration_s; /* (n - 1) dt, s */
    double max_dt_s;       /* time step, s */
} sl_pf_rule;

#define SL_PF_MIN_PGA_G 0.05
#define SL_PF_MIN_DURATION_S 15.0
#define SL_PF_MAX_DT_S 0.02

void sl_pf_rule_default(sl_pf_rule *r);

/* The sub-directory names of dir, sorted (strcmp); *names is malloc'd, each
 * name too (free with sl_pf_names_free). Returns the count; 0 with *names
 * NULL when dir cannot be read (err set). */
size_t sl_pf_list_dirs(const char *dir, char ***names, sl_error *err);
void sl_pf_names_free(char **names, size_t n);

/* The records folder: dir when given, else $SEISLIDE_SHARED/records or
 * ../shared/records, written into buf (n bytes). */
const char *sl_pf_records_dir(const char *dir, char *buf, size_t n);

/* Every sub-folder of dir (in name order) whose record passes the default
 * rule, read by sl_pf_read_record at pga_ms2, at most max of them (0: all):
 * *sets (malloc'd; free with sl_pf_sets_free) holds *n sets; *n_dirs (NULL:
 * not wanted) counts the sub-folders. SL_OK, or the failure to list dir or
 * to allocate (err set); records that fail the rule are skipped. */
sl_status sl_pf_read_records(const char *dir, size_t max, double pga_ms2, sl_set **sets,
                             size_t *n, size_t *n_dirs, sl_error *err);
void sl_pf_sets_free(sl_set *sets, size_t n);

/* Read record directory `dir` as a three-component set, apply the rule,
 * resample and scale to larger horizontal PGA pga_ms2 (> 0). Returns SL_OK
 * (out owns its motions: sl_set_free_motions), the failure of reading
 * (err set), or SL_EINVAL when the record is not three-component or
 * fails the rule (err says which value). */
sl_status sl_pf_read_record(const char *dir, const sl_pf_rule *rule, double pga_ms2,
                            sl_set *out, sl_error *err);

/* Mean and sample standard deviation of x[0], x[stride], ... (n values). */
void sl_pf_mean_sd(const double *x, size_t n, size_t stride, double *mean, double *sd);

/* (P1): ratio of the mean of a (n_a values at stride sa) to the mean of b,
 * and its standard error. NAN when a mean of b is 0 or n < 2. */
double sl_pf_ratio(const double *a, size_t n_a, size_t sa, const double *b, size_t n_b,
                   size_t sb, double *se);

/* Mean 2 %, 5 % and 10 % pseudo-spectra of components (H1, H2, V) of n sets on
 * f_hz[nf], optionally broadened (SA_b(f) = max SA over [f/1.15, 1.15 f]),
 * and the mean component PGA as ZPA, written as a floor file (io/floor.h
 * format: "units = m/s2", values m/s^2) at path. Returns SL_OK or SL_EIO /
 * SL_ENOMEM (err names the file); no half-written file is left. */
sl_status sl_pf_write_floor(const char *path, const char *name, const sl_set *sets, size_t n,
                            const double *f_hz, size_t nf, int broaden, sl_error *err);

#endif
