/* realism.c - peaks near the PGA, characteristic ratios and the SRP 3.7.1
 * Appendix B minimum-PSD check (see realism.h). */
#include "signal/realism.h"
#include "core/fftw_safe.h"

#include <fftw3.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/units.h"
#include "signal/rg160.h"

size_t sl_realism_peaks_above(const double *acc, size_t n, double frac)
{
    double pga = 0;
    for (size_t i = 0; i < n; i++)
        pga = fabs(acc[i]) > pga ? fabs(acc[i]) : pga;
    if (!(pga > 0))
        return 0;
    const double lim = frac * pga;
    size_t count = 0;
    for (size_t i = 0; i < n; i++) {
        double x = fabs(acc[i]);
        if (x < lim)
            continue;
        double left = i > 0 ? fabs(acc[i - 1]) : 0.0;
        double right = i + 1 < n ? fabs(acc[i + 1]) : 0.0;
        if (x > left && x >= right)
            count++;
    }
    return count;
}

void sl_realism_ratios(double pga_ms2, double pgv_ms, double pgd_m, double *va_s, double *adv2)
{
    *va_s = pga_ms2 > 0 ? pgv_ms / pga_ms2 : NAN;
    *adv2 = pgv_ms > 0 ? pga_ms2 * pgd_m / (pgv_ms * pgv_ms) : NAN;
}

/* Moment ratios sqrt(int S^2 f^-1 (2 pi f)^-2q d f / int S^2 f^-1 df),
 * q = 1 (velocity) and 2 (displacement), trapezoid in ln f (df = f dln f). */
static void moment_ratios(const sl_spectrum *s, double *rv, double *rd)
{
    const double f0 = s->f_hz[0], f1 = s->f_hz[s->n - 1];
    size_t m = (size_t)ceil(100.0 * log10(f1 / f0));
    if (m < 1)
        m = 1;
    double m0 = 0, m2 = 0, m4 = 0;
    for (size_t i = 0; i <= m; i++) {
        double f = f0 * pow(f1 / f0, (double)i / (double)m);
        if (i == m)
            f = f1;
        double w = (i == 0 || i == m) ? 0.5 : 1.0;
        double sa = sl_spectrum_interp(s, f);
        double g = sa * sa; /* G(f) f = S^2 up to a constant (R1) */
        double om2 = (2 * SL_PI * f) * (2 * SL_PI * f);
        m0 += w * g;
        m2 += w * g / om2;
        m4 += w * g / (om2 * om2);
    }
    *rv = sqrt(m2 / m0);
    *rd = sqrt(m4 / m0);
}

/* Calibration on RG 1.60, 5 %, horizontal, 0.1-50 Hz. */
static void rg160_calibration(double *kv, double *kd)
{
    enum { NCAL = 271 };
    double f[NCAL], sa[NCAL];
    for (int i = 0; i < NCAL; i++)
        f[i] = 0.1 * pow(500.0, (double)i / (NCAL - 1));
    sl_error e;
    sl_rg160_psa(SL_RG160_HORIZONTAL, 0.05, SL_G, f, NCAL, sa, &e);
    sl_spectrum s = {.n = NCAL, .damping = 0.05, .f_hz = f, .sa_ms2 = sa};
    double rv, rd;
    moment_ratios(&s, &rv, &rd);
    *kv = (SL_NH_V_PER_G_MS / SL_G) / rv;
    *kd = (SL_NH_D_PER_G_M / SL_G) / rd;
}

sl_status sl_realism_expected(const sl_spectrum *s, double *va_s, double *da_s2, double *adv2,
                              sl_error *err)
{
    if (!s || s->n < 2)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "realism: spectrum needs >= 2 points");
    double kv, kd, rv, rd;
    rg160_calibration(&kv, &kd);
    moment_ratios(s, &rv, &rd);
    *va_s = kv * rv;
    *da_s2 = kd * rd;
    *adv2 = *da_s2 / (*va_s * *va_s);
    return SL_OK;
}

/* Husid times: first t with cumulative sum a^2 >= q of the total. */
static size_t husid_index(const double *a, size_t n, double q, double total)
{
    double c = 0;
    for (size_t i = 0; i < n; i++) {
        c += a[i] * a[i];
        if (c >= q * total)
            return i;
    }
    return n - 1;
}

/* Target PSD (R1, full Vanmarcke form) on n points f[] (log-spaced over
 * the target's range), for strong-motion duration ts: from the lowest
 * frequency up,
 *   G(f_i) = max(0, S_i^2/p_i^2 - int_0^{f_i} G df) / (f_i (pi/(4 zs_i) - 1)),
 * zs = zeta/(1 - exp(-4 pi zeta f ts)) (Vanmarcke's effective damping for a
 * finite duration), p Davenport's peak factor of 2 f ts cycles. */
static void target_psd_table(const sl_spectrum *t, double ts, const double *f, size_t n,
                             double *g)
{
    double cum = 0;
    for (size_t i = 0; i < n; i++) {
        double sa = sl_spectrum_interp(t, f[i]);
        double x = 2 * f[i] * ts;
        x = x > 2.0 ? x : 2.0; /* keeps ln > 0 for very short windows */
        double l = sqrt(2 * log(x));
        double pk = l + 0.5772 / l;
        double zs = t->damping / (1 - exp(-4 * SL_PI * t->damping * f[i] * ts));
        double num = sa * sa / (pk * pk) - cum;
        g[i] = num > 0 ? num / (f[i] * (SL_PI / (4 * zs) - 1)) : 0.0;
        if (i + 1 < n)
            cum += g[i] * (f[i + 1] - f[i]); /* left rectangle: G is known at f_i */
    }
}

sl_status sl_psd_check_motion(const double *acc, size_t n, double dt_s,
                              const sl_spectrum *target, double frac, double fmin_hz,
                              double fmax_hz, sl_psd_check *out, sl_error *err)
{
    memset(out, 0, sizeof *out);
    if (!acc || n < 4 || !(dt_s > 0) || !target || target->n < 2)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "psd: bad arguments");
    double total = 0;
    for (size_t i = 0; i < n; i++)
        total += acc[i] * acc[i];
    if (!(total > 0))
        return sl_error_set(err, SL_EINVAL, NULL, 0, "psd: motion is all zeros");
    size_t i5 = husid_index(acc, n, 0.05, total), i75 = husid_index(acc, n, 0.75, total);
    if (i75 < i5 + 4)
        i75 = i5 + 4 < n ? i5 + 4 : n - 1;
    size_t m = i75 - i5 + 1;
    out->t5_s = dt_s * (double)i5;
    out->t75_s = dt_s * (double)i75;
    const double ts = dt_s * (double)m;
    double *r = fftw_malloc(m * sizeof *r);
    fftw_complex *c = fftw_malloc((m / 2 + 1) * sizeof *c);
    fftw_plan plan = NULL;
    if (r && c) {
        sl_fftw_thread_safe();
        plan = fftw_plan_dft_r2c_1d((int)m, r, c, FFTW_ESTIMATE);
    }
    if (!plan) {
        fftw_free(r);
        fftw_free(c);
        return sl_error_set(err, SL_ENOMEM, NULL, 0, "psd: cannot make the FFT of %zu", m);
    }
    memcpy(r, acc + i5, m * sizeof *r);
    fftw_execute(plan);
    const size_t nb = m / 2 + 1;
    const double df = 1.0 / ts;
    /* G_k (R2), then running sums for the +-20 % averages. */
    double *cum = malloc((nb + 1) * sizeof *cum);
    if (!cum) {
        fftw_destroy_plan(plan);
        fftw_free(r);
        fftw_free(c);
        return sl_error_set(err, SL_ENOMEM, NULL, 0, "psd: out of memory");
    }
    cum[0] = 0;
    for (size_t k = 0; k < nb; k++) {
        double g = 2 * dt_s * dt_s * (c[k][0] * c[k][0] + c[k][1] * c[k][1]) / ts;
        cum[k + 1] = cum[k] + g;
    }
    const size_t ntf = 1 + (size_t)ceil(200 * log10(target->f_hz[target->n - 1] /
                                                    target->f_hz[0]));
    double *tf = malloc(2 * (ntf > 2 ? ntf : 2) * sizeof *tf);
    if (!tf) {
        free(cum);
        fftw_destroy_plan(plan);
        fftw_free(r);
        fftw_free(c);
        return sl_error_set(err, SL_ENOMEM, NULL, 0, "psd: out of memory");
    }
    double *tg = tf + (ntf > 2 ? ntf : 2);
    for (size_t i = 0; i < ntf; i++)
        tf[i] = target->f_hz[0] *
                pow(target->f_hz[target->n - 1] / target->f_hz[0], (double)i / (double)(ntf - 1));
    tf[ntf - 1] = target->f_hz[target->n - 1];
    target_psd_table(target, ts, tf, ntf, tg);
    double lo = fmin_hz > target->f_hz[0] ? fmin_hz : target->f_hz[0];
    double hi = fmax_hz < target->f_hz[target->n - 1] ? fmax_hz : target->f_hz[target->n - 1];
    out->min_ratio = INFINITY;
    out->f_min_ratio_hz = NAN;
    for (size_t k = 1; k < nb; k++) {
        double f = df * (double)k;
        if (f < lo || f > hi)
            continue;
        size_t ka = (size_t)ceil(f * (1 - SL_PSD_WINDOW) / df);
        size_t kb = (size_t)floor(f * (1 + SL_PSD_WINDOW) / df);
        if (kb >= nb)
            kb = nb - 1;
        if (ka < 1)
            ka = 1;
        double avg = (cum[kb + 1] - cum[ka]) / (double)(kb + 1 - ka);
        double ti = log(f / tf[0]) / log(tf[ntf - 1] / tf[0]) * (double)(ntf - 1);
        size_t i0 = ti <= 0 ? 0 : (size_t)ti;
        if (i0 + 1 >= ntf)
            i0 = ntf - 2;
        double w = ti - (double)i0;
        double gt = tg[i0] * (1 - w) + tg[i0 + 1] * w;
        double ratio = gt > 0 ? avg / gt : INFINITY;
        if (ratio < out->min_ratio) {
            out->min_ratio = ratio;
            out->f_min_ratio_hz = f;
        }
    }
    free(cum);
    free(tf);
    fftw_destroy_plan(plan);
    fftw_free(r);
    fftw_free(c);
    out->ok = out->min_ratio >= frac;
    return SL_OK;
}
