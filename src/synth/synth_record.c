/* synth_record.c - recorded motions: the start from a record
 * (docs/synthesis.md 3.6) and resampling to the matching step. */
#include "synth/synth_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

sl_status sl_synth_set_record(sl_synth_motion *m, const sl_synth_target *t,
                              const double *acc_ms2, size_t n, sl_error *err)
{
    m->ready = 0;
    const sl_synth *s = m->s;
    if (!acc_ms2 || n == 0 || n > s->n)
        return sl_error_set(err, SL_EINVAL, NULL, 0,
                            "synth: record of %zu samples does not fit the plan (%zu)", n,
                            s->n);
    sl_status st = sl_synth_set_target(m, t, err);
    if (st)
        return st;
    double amax = 0;
    for (size_t j = 0; j < s->n; j++) {
        double x = j < n ? acc_ms2[j] : 0.0;
        if (!isfinite(x))
            return sl_error_set(err, SL_EINVAL, NULL, 0, "synth: record sample %zu not finite",
                                j);
        amax = fabs(x) > amax ? fabs(x) : amax;
        m->acc[j] = x;
    }
    if (!(amax > 0))
        return sl_error_set(err, SL_EINVAL, NULL, 0, "synth: record is all zeros");
    m->attempt = 0;
    m->knee = SL_SYNTH_KNEE_RECORD;
    m->level = s->p.aim;
    m->record = 1;
    return sl_synth_start(m, err);
}

/* ------------------------------------------------------------------ */
/* Input and output                                                    */
/* ------------------------------------------------------------------ */

double *sl_synth_resample(const double *acc_ms2, size_t n, double dt_s, double dt_new_s,
                          size_t *n_new)
{
    *n_new = 0;
    if (!acc_ms2 || n == 0 || !(dt_s > 0) || !(dt_new_s > 0) || !isfinite(dt_s) ||
        !isfinite(dt_new_s))
        return NULL;
    double dur = dt_s * (double)(n - 1);
    /* A relative slack keeps the last sample when dur/dt_new is whole. */
    double cnt = floor(dur / dt_new_s * (1 + 1e-12)) + 1;
    if (cnt > (double)SYNTH_MAX_NFFT)
        return NULL;
    size_t m = (size_t)cnt;
    double *out = malloc(m * sizeof *out);
    if (!out)
        return NULL;
    for (size_t j = 0; j < m; j++) {
        double x = dt_new_s * (double)j / dt_s;
        size_t i = (size_t)x;
        if (i + 1 >= n) {
            out[j] = acc_ms2[n - 1];
            continue;
        }
        double w = x - (double)i;
        out[j] = acc_ms2[i] + w * (acc_ms2[i + 1] - acc_ms2[i]);
    }
    *n_new = m;
    return out;
}

double sl_synth_match_dt(double dt_s)
{
    /* the slack keeps dt itself when it is SL_SYNTH_MAX_DT_S up to rounding */
    double k = ceil(dt_s / SL_SYNTH_MAX_DT_S * (1 - 1e-9));
    return dt_s / (k < 1 ? 1 : k);
}

sl_motion *sl_synth_resample_motion(const sl_motion *m, double dt_s)
{
    if (!m || !(dt_s > 0))
        return NULL;
    if (fabs(m->dt_s - dt_s) <= 1e-9 * dt_s)
        return sl_motion_copy(m);
    size_t n2 = 0;
    double *a = sl_synth_resample(m->acc_ms2, m->n, m->dt_s, dt_s, &n2);
    sl_motion *r = a ? sl_motion_from_array(a, n2, dt_s, m->label) : NULL;
    free(a);
    if (r && m->path) {
        char *p = strdup(m->path);
        if (!p) {
            sl_motion_free(r);
            return NULL;
        }
        free(r->path);
        r->path = p;
    }
    return r;
}
