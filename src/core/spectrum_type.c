/* spectrum_type.c - the spectrum as plain data (see spectrum_type.h). */
#include "core/spectrum_type.h"

#include <math.h>
#include <stdlib.h>

sl_spectrum *sl_spectrum_alloc(size_t n, double damping)
{
    if (n == 0)
        return NULL;
    sl_spectrum *s = calloc(1, sizeof *s);
    if (!s)
        return NULL;
    s->f_hz = calloc(n, sizeof *s->f_hz);
    s->sa_ms2 = calloc(n, sizeof *s->sa_ms2);
    if (!s->f_hz || !s->sa_ms2) {
        sl_spectrum_free(s);
        return NULL;
    }
    s->n = n;
    s->damping = damping;
    return s;
}

void sl_spectrum_clear(sl_spectrum *s)
{
    if (!s)
        return;
    free(s->f_hz);
    free(s->sa_ms2);
    s->f_hz = NULL;
    s->sa_ms2 = NULL;
    s->n = 0;
}

void sl_spectrum_free(sl_spectrum *s)
{
    if (!s)
        return;
    sl_spectrum_clear(s);
    free(s);
}

double sl_spectrum_interp(const sl_spectrum *s, double f_hz)
{
    if (!s || s->n == 0 || !(f_hz >= s->f_hz[0]) || !(f_hz <= s->f_hz[s->n - 1]))
        return NAN;
    size_t lo = 0, hi = s->n - 1;
    if (f_hz == s->f_hz[hi])
        return s->sa_ms2[hi];
    while (hi - lo > 1) { /* f_hz[lo] <= f < f_hz[hi] */
        size_t mid = lo + (hi - lo) / 2;
        if (s->f_hz[mid] <= f_hz)
            lo = mid;
        else
            hi = mid;
    }
    if (f_hz == s->f_hz[lo])
        return s->sa_ms2[lo];
    double p = log(s->sa_ms2[hi] / s->sa_ms2[lo]) / log(s->f_hz[hi] / s->f_hz[lo]);
    return s->sa_ms2[lo] * pow(f_hz / s->f_hz[lo], p);
}
