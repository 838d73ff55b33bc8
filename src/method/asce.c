/* asce.c - ASCE/SEI 43-05 approximate sliding displacement and Newmark's
 * estimates (see asce.h). */
#include "method/asce.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/units.h"

/* Frequencies of the two spectra closer than this (relative) are merged. */
#define ASCE_MERGE_REL 1e-12
/* Damping of an input spectrum may differ from 10 % by this much. */
#define ASCE_DAMPING_TOL 1e-9

struct sl_asce {
    size_t n;
    double *f_hz;
    double *savh_ms2;
    sl_asce_input in; /* spectra pointers are not used after alloc */
};

void sl_asce_input_default(sl_asce_input *in)
{
    memset(in, 0, sizeof *in);
    in->pgd_m = NAN;
    in->fs = SL_ASCE_FS;
    in->g_ms2 = SL_G;
}

static sl_status check_spectrum(const sl_spectrum *s, const char *what, sl_error *err)
{
    if (!s || s->n < 2 || !s->f_hz || !s->sa_ms2)
        return sl_error_set(err, SL_EINVAL, NULL, 0,
                            "asce: %s spectrum missing or with fewer than 2 points", what);
    if (fabs(s->damping - SL_ASCE_DAMPING) > ASCE_DAMPING_TOL)
        return sl_error_set(err, SL_EINVAL, NULL, 0,
                            "asce: %s spectrum is %g-damped; the method uses %g", what,
                            s->damping, SL_ASCE_DAMPING);
    for (size_t i = 0; i < s->n; i++) {
        if (!(s->f_hz[i] > 0) || !isfinite(s->f_hz[i]) || (i > 0 && !(s->f_hz[i] > s->f_hz[i - 1])))
            return sl_error_set(err, SL_EINVAL, NULL, 0,
                                "asce: %s frequencies must be positive and increase strictly "
                                "(%g Hz at point %zu)",
                                what, s->f_hz[i], i);
        if (!(s->sa_ms2[i] > 0) || !isfinite(s->sa_ms2[i]))
            return sl_error_set(err, SL_EINVAL, NULL, 0,
                                "asce: %s spectral value %g at %g Hz must be positive", what,
                                s->sa_ms2[i], s->f_hz[i]);
    }
    return SL_OK;
}

void sl_asce_free(sl_asce *a)
{
    if (!a)
        return;
    free(a->f_hz);
    free(a->savh_ms2);
    free(a);
}

/* Push f onto the merged grid unless it repeats the last point. */
static void push_freq(double *out, size_t *k, double f)
{
    if (*k > 0 && f - out[*k - 1] <= ASCE_MERGE_REL * f)
        return;
    out[(*k)++] = f;
}

sl_asce *sl_asce_alloc(const sl_asce_input *in, sl_error *err)
{
    if (!in) {
        sl_error_set(err, SL_EINVAL, NULL, 0, "asce: no input");
        return NULL;
    }
    if (check_spectrum(in->h1, "H1", err) || check_spectrum(in->h2, "H2", err))
        return NULL;
    if (!(in->av_ms2 >= 0) || !isfinite(in->av_ms2)) {
        sl_error_set(err, SL_EINVAL, NULL, 0, "asce: A_v %g must be >= 0", in->av_ms2);
        return NULL;
    }
    if (!(in->zpa_h_ms2 > 0) || !isfinite(in->zpa_h_ms2)) {
        sl_error_set(err, SL_EINVAL, NULL, 0, "asce: horizontal ZPA %g must be > 0",
                     in->zpa_h_ms2);
        return NULL;
    }
    if (!(in->fs > 0) || !isfinite(in->fs) || !(in->g_ms2 > 0) || !isfinite(in->g_ms2)) {
        sl_error_set(err, SL_EINVAL, NULL, 0, "asce: factor of safety %g and g %g must be > 0",
                     in->fs, in->g_ms2);
        return NULL;
    }
    const sl_spectrum *s1 = in->h1, *s2 = in->h2;
    double lo = fmax(s1->f_hz[0], s2->f_hz[0]);
    double hi = fmin(s1->f_hz[s1->n - 1], s2->f_hz[s2->n - 1]);
    if (!(hi > lo)) {
        sl_error_set(err, SL_EINVAL, NULL, 0,
                     "asce: the H1 (%g-%g Hz) and H2 (%g-%g Hz) spectra do not overlap",
                     s1->f_hz[0], s1->f_hz[s1->n - 1], s2->f_hz[0], s2->f_hz[s2->n - 1]);
        return NULL;
    }
    sl_asce *a = calloc(1, sizeof *a);
    size_t cap = s1->n + s2->n;
    if (a) {
        a->f_hz = malloc(cap * sizeof *a->f_hz);
        a->savh_ms2 = malloc(cap * sizeof *a->savh_ms2);
    }
    if (!a || !a->f_hz || !a->savh_ms2) {
        sl_asce_free(a);
        sl_error_set(err, SL_ENOMEM, NULL, 0, "asce: out of memory");
        return NULL;
    }
    /* merge the two grids inside [lo, hi] */
    size_t i = 0, j = 0, k = 0;
    while (i < s1->n || j < s2->n) {
        double f;
        if (j >= s2->n || (i < s1->n && s1->f_hz[i] <= s2->f_hz[j]))
            f = s1->f_hz[i++];
        else
            f = s2->f_hz[j++];
        if (f >= lo && f <= hi)
            push_freq(a->f_hz, &k, f);
    }
    a->n = k;
    for (size_t p = 0; p < k; p++) {
        double x = sl_spectrum_interp(s1, a->f_hz[p]);
        double y = sl_spectrum_interp(s2, a->f_hz[p]);
        double big = fmax(x, y), small = fmin(x, y); /* H1 the larger */
        double s = SL_ASCE_H2_COEF * small;
        a->savh_ms2[p] = sqrt(big * big + s * s);
    }
    a->in = *in;
    a->in.h1 = a->in.h2 = NULL;
    return a;
}

size_t sl_asce_combined(const sl_asce *a, const double **f_hz, const double **savh_ms2)
{
    if (f_hz)
        *f_hz = a ? a->f_hz : NULL;
    if (savh_ms2)
        *savh_ms2 = a ? a->savh_ms2 : NULL;
    return a ? a->n : 0;
}

sl_status sl_asce_eval(const sl_asce *a, double mu, sl_asce_result *res, sl_error *err)
{
    if (!a || !res)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "asce: no method or result");
    if (!(mu >= 0) || !isfinite(mu))
        return sl_error_set(err, SL_EINVAL, NULL, 0, "asce: mu %g must be >= 0", mu);
    const sl_asce_input *in = &a->in;
    double g = in->g_ms2;
    sl_asce_result r;
    r.mu = mu;
    r.mu_e = mu * (1.0 - SL_ASCE_VERTICAL_COEF * in->av_ms2 / g);  /* step 1 */
    r.cs_ms2 = SL_ASCE_CS_COEF * r.mu_e * g;                        /* step 2 */
    r.cap_m = (in->pgd_m > 0 && isfinite(in->pgd_m)) ? SL_CAP_FACTOR * in->pgd_m : (double)NAN;
    r.flags = 0;
    r.fes_hz = NAN;
    r.delta_best_m = NAN;
    r.delta_design_m = NAN;
    const double *f = a->f_hz, *s = a->savh_ms2;
    double cs = r.cs_ms2;
    if (r.mu_e * g >= in->zpa_h_ms2) {
        r.flags |= SL_ASCE_NO_SLIDING;
        r.delta_best_m = 0.0;
        r.delta_design_m = 0.0;
        *res = r;
        return SL_OK;
    }
    if (cs < s[0]) { /* constant-SD extension below f_min */
        r.flags |= SL_ASCE_BELOW_FMIN;
        r.fes_hz = cs > 0 ? f[0] * sqrt(cs / s[0]) : 0.0;
        double w0 = 2.0 * SL_PI * f[0];
        r.delta_best_m = s[0] / (w0 * w0);
    } else {
        if (cs == s[0]) {
            r.fes_hz = f[0];
        } else {
            for (size_t i = 0; i + 1 < a->n; i++) { /* step 4: first upward crossing */
                if (s[i] < cs && cs <= s[i + 1]) {
                    double t = log(cs / s[i]) / log(s[i + 1] / s[i]);
                    r.fes_hz = f[i] * pow(f[i + 1] / f[i], t);
                    break;
                }
            }
        }
        if (isnan(r.fes_hz)) {
            r.flags |= SL_ASCE_NO_CROSSING;
            *res = r;
            return SL_OK;
        }
        double w = 2.0 * SL_PI * r.fes_hz;
        r.delta_best_m = cs / (w * w); /* step 5 */
    }
    r.delta_design_m = in->fs * r.delta_best_m; /* step 6 */
    if (r.delta_design_m > r.cap_m) {          /* step 7; false when the cap is NAN */
        r.delta_design_m = r.cap_m;
        r.flags |= SL_ASCE_CAPPED;
    }
    *res = r;
    return SL_OK;
}

const char *sl_asce_status_name(unsigned flags, char *buf, size_t n)
{
    static const struct {
        unsigned flag;
        const char *name;
    } names[] = {
        {SL_ASCE_NO_SLIDING, "no_sliding"},
        {SL_ASCE_NO_CROSSING, "no_crossing"},
        {SL_ASCE_BELOW_FMIN, "below_fmin"},
        {SL_ASCE_CAPPED, "capped"},
    };
    if (!buf || n == 0)
        return "";
    buf[0] = '\0';
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        if (!(flags & names[i].flag))
            continue;
        if (buf[0])
            strncat(buf, "+", n - strlen(buf) - 1);
        strncat(buf, names[i].name, n - strlen(buf) - 1);
    }
    if (!buf[0])
        strncat(buf, "ok", n - 1);
    return buf;
}

static int newmark_args_ok(double v, double a, double mu, double g)
{
    return isfinite(v) && isfinite(a) && isfinite(mu) && isfinite(g) && v >= 0 && a > 0 &&
           mu > 0 && g > 0;
}

double sl_asce_newmark_sym(double pgv_ms, double pga_ms2, double mu, double g_ms2)
{
    if (!newmark_args_ok(pgv_ms, pga_ms2, mu, g_ms2))
        return NAN;
    double r = mu * g_ms2 / pga_ms2;
    if (r >= 1.0)
        return 0.0;
    return pgv_ms * pgv_ms / (2.0 * mu * g_ms2) * (1.0 - r);
}

double sl_asce_newmark_asym(double pgv_ms, double pga_ms2, double mu, double g_ms2)
{
    if (!newmark_args_ok(pgv_ms, pga_ms2, mu, g_ms2))
        return NAN;
    double r = mu * g_ms2 / pga_ms2;
    if (r >= 1.0)
        return 0.0;
    return 2.0 * pgv_ms * pgv_ms / (mu * g_ms2) * (1.0 - r) * (1.0 - r);
}
