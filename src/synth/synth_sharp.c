/* synth_sharp.c - crest reservation for very sharp floor targets
 * (docs/synthesis.md 4, "Limit: very sharp floors"). PROTOTYPE. */
#include "synth/synth_internal.h"

#include <math.h>
#include <stdlib.h>

#include <gsl/gsl_rng.h>

#include "core/units.h"

static double env_d(const char *k, double d)
{
    const char *v = getenv(k);
    return v ? atof(v) : d;
}

int sl_synth_is_sharp(const sl_synth_motion *m)
{
    double amp = 0;
    for (size_t j = m->j_lo; j < m->j_hi; j++)
        amp = m->tgt[j] / m->zpa > amp ? m->tgt[j] / m->zpa : amp;
    return !m->record && amp > env_d("SH_AMP", 6.0);
}

/* half-cycle [i, j) of h (sign run), the largest |a| in it and where */
static size_t next_half(const double *h, const double *a, size_t i, size_t n, double *x,
                        size_t *ip)
{
    size_t j = i;
    *x = 0;
    *ip = i;
    while (j < n && (h[j] >= 0) == (h[i] >= 0)) {
        if (fabs(a[j]) > *x) {
            *x = fabs(a[j]);
            *ip = j;
        }
        j++;
    }
    return j;
}

size_t sl_synth_reserve_crest(sl_synth_motion *m)
{
    if (!sl_synth_is_sharp(m))
        return 0;
    const sl_synth *s = m->s;
    const size_t n = s->n;
    double *a = m->acc;
    const size_t keep = (size_t)env_d("SH_KEEP", 2);
    const double q = env_d("SH_Q", 0.86), k0 = env_d("SH_K0", 0.7);
    const int whole = env_d("SH_WHOLE", 0) > 0;
    /* a_low into rwork, a_high = a - a_low */
    double *lo = m->rwork;
    if (whole) {
        for (size_t j = 0; j < n; j++)
            lo[j] = 0;
    } else {
        for (size_t j = 0; j < s->nfft; j++)
            m->rwork[j] = j < n ? a[j] : 0.0;
        fftw_execute_dft_r2c(s->r2c, m->rwork, m->cwork);
        for (size_t k = 0; k < s->nbin; k++)
            if (s->df * (double)k >= m->fc_hz)
                m->cwork[k][0] = m->cwork[k][1] = 0;
        fftw_execute_dft_c2r(s->c2r, m->cwork, m->rwork);
        const double inv_n = 1.0 / (double)s->nfft;
        for (size_t j = 0; j < n; j++)
            lo[j] *= inv_n;
    }
    double *h = malloc(n * sizeof *h);
    if (!h)
        return 0;
    for (size_t j = 0; j < n; j++)
        h[j] = a[j] - lo[j];
    double top[16] = {0};
    size_t i = 0, ip;
    double x;
    while (i < n) {
        size_t j = next_half(h, a, i, n, &x, &ip);
        for (size_t r = 0; r < keep; r++)
            if (x > top[r]) {
                for (size_t t = keep - 1; t > r; t--)
                    top[t] = top[t - 1];
                top[r] = x;
                break;
            }
        i = j;
    }
    const double P = top[0], thr = top[keep - 1];
    double xm = 0;
    for (i = 0; i < n;) {
        size_t j = next_half(h, a, i, n, &x, &ip);
        if (x < thr && x > xm)
            xm = x;
        i = j;
    }
    const double cap = q * P, K = k0 * P;
    size_t count = 0;
    if (xm > cap) {
        for (i = 0; i < n;) {
            size_t j = next_half(h, a, i, n, &x, &ip);
            if (x < thr && x > K) {
                double y = K + (x - K) * (cap - K) / (xm - K);
                double g = h[ip] != 0 ? ((a[ip] >= 0 ? y : -y) - lo[ip]) / h[ip] : 1;
                g = g < 0 ? 0 : g > 1 ? 1 : g;
                for (size_t r = i; r < j; r++)
                    a[r] = lo[r] + g * h[r];
                count++;
            }
            i = j;
        }
    }
    free(h);
    return count;
}

/* A constant-amplitude chirp across the band where the target is within
 * SH_BAND of its largest value, added to the start of a sharp target's
 * motion. */
void sl_synth_add_mode_sweep(sl_synth_motion *m, gsl_rng *rng)
{
    if (!sl_synth_is_sharp(m) || env_d("SH_SWEEP", 1) <= 0)
        return;
    const sl_synth *s = m->s;
    const size_t n = s->n;
    double tmax = 0;
    for (size_t j = m->j_lo; j < m->j_hi; j++)
        tmax = m->tgt[j] > tmax ? m->tgt[j] : tmax;
    const double band = env_d("SH_BAND", 0.75);
    double fa = INFINITY, fb = 0;
    for (size_t j = m->j_lo; j < m->j_hi; j++)
        if (m->tgt[j] >= band * tmax) {
            fa = s->grid[j] < fa ? s->grid[j] : fa;
            fb = s->grid[j] > fb ? s->grid[j] : fb;
        }
    double pk = 0;
    for (size_t j = 0; j < n; j++)
        pk = fabs(m->acc[j]) > pk ? fabs(m->acc[j]) : pk;
    const double T = s->dt * (double)(n - 1);
    const double D = env_d("SH_DUR", 0.3) * T, rise = env_d("SH_RISE", 1.0);
    const double ts = (0.1 + gsl_rng_uniform(rng) * (0.55 - 0.1)) * T - 0.3 * D;
    const int up = gsl_rng_uniform(rng) < 0.5;
    const double phi = 2 * SL_PI * gsl_rng_uniform(rng);
    const double amp = env_d("SH_BETA", 0.8) * pk;
    const double f0 = up ? fa : fb, f1 = up ? fb : fa;
    for (size_t j = 0; j < n; j++) {
        double t = s->dt * (double)j - ts;
        if (t < 0 || t > D)
            continue;
        double e = 1;
        if (t < rise)
            e = 0.5 * (1 - cos(SL_PI * t / rise));
        else if (t > D - rise)
            e = 0.5 * (1 - cos(SL_PI * (D - t) / rise));
        double ph = 2 * SL_PI * (f0 * t + 0.5 * (f1 - f0) / D * t * t) + phi;
        m->acc[j] += amp * e * cos(ph);
    }
}
