/* synth_admissible.c - the admissible motion (docs/synthesis.md 3.3):
 * end taper, soft peak compression/expansion (eq. C2), baseline correction. */
#include "synth/synth_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* End values (v(T), d(T)) of a from rest by the exact piecewise-linear
 * integration of motion.h. */
void sl_synth_end_values(const double *a, size_t n, double dt, double *v_end, double *d_end)
{
    double v = 0, d = 0;
    for (size_t i = 0; i + 1 < n; i++) {
        d += dt * v + dt * dt * (2 * a[i] + a[i + 1]) / 6;
        v += dt * (a[i] + a[i + 1]) / 2;
    }
    *v_end = v;
    *d_end = d;
}

void sl_synth_low_part(sl_synth_motion *m)
{
    const sl_synth *s = m->s;
    for (size_t j = 0; j < s->nfft; j++)
        m->rwork[j] = j < s->n ? m->acc[j] : 0.0;
    fftw_execute_dft_r2c(s->r2c, m->rwork, m->cwork);
    for (size_t k = 0; k < s->nbin; k++)
        if (s->df * (double)k >= m->fc_hz)
            m->cwork[k][0] = m->cwork[k][1] = 0;
    fftw_execute_dft_c2r(s->c2r, m->cwork, m->rwork);
    const double inv_n = 1.0 / (double)s->nfft;
    for (size_t j = 0; j < s->n; j++)
        m->rwork[j] *= inv_n;
}

/* Soft-knee compression of the peaks (the time-domain part of matching the
 * high-frequency end, SA -> PGA; as REQPY's local PGA correction). With
 * L = aim x ZPA, K = knee x L and P = max|a| > L: the motion is split
 * exactly into a_low (DFT bins below fc = SL_SYNTH_COMPRESS_FC_FRAC x the
 * frequency of the target's largest SA) and
 * a_high = a - a_low; every half-cycle of a (samples between two sign
 * changes) whose peak x exceeds K has its a_high part multiplied by y(x)/x,
 *     y(x) = K + (x - K) (L - K)/(P - K),
 * the linear map of [K, P] onto [K, L]. Half-cycles keep their zero
 * crossings and shape, peaks keep their order with their spacing shrunk in
 * proportion: no flat tops and no run of equal peaks (the count above
 * 0.9 PGA is checked, sl_synth_check.peaks); the long-period content is
 * untouched. The spectral step does the rest. Returns the number of
 * half-cycles scaled. */
size_t sl_synth_compress_peaks(sl_synth_motion *m, double level, double knee)
{
    const sl_synth *s = m->s;
    double *a = m->acc;
    const size_t n = s->n;
    double pk = 0;
    for (size_t i = 0; i < n; i++)
        pk = fabs(a[i]) > pk ? fabs(a[i]) : pk;
    /* Expansion (eq. C2; synthetic motions for a target rigid at its end,
     * set_target): when P < L, K = knee x P and the same map
     *     y(x) = K + (x - K)(L - K)/(P - K)
     * takes [K, P] onto [K, L] with a gain > 1: the high-frequency part of
     * the half-cycles above knee x P is raised so that the PGA comes to
     * about L. Without it the correction lifts SA at the rigid end by
     * resonant content near the end frequency instead of by the peak
     * (SA(50 Hz)/PGA 1.10-1.22, PGA 0.86-0.93 ZPA on physical floor
     * spectra; docs/synthesis.md 3.3, 10). Records: compression only. */
    const int expand = !(pk > level);
    if (expand && (m->record || !m->rigid_end || !(pk > 0)))
        return 0;
    const double K = knee * (expand ? pk : level);
    sl_synth_low_part(m);
    size_t count = 0, i = 0;
    while (i < n) {
        size_t j = i;
        double hp = 0;
        while (j < n && (a[j] >= 0) == (a[i] >= 0)) {
            hp = fabs(a[j]) > hp ? fabs(a[j]) : hp;
            j++;
        }
        if (hp > K) {
            double g = (K + (hp - K) * (level - K) / (pk - K)) / hp;
            for (size_t q = i; q < j; q++) {
                double lo = m->rwork[q];
                a[q] = lo + g * (a[q] - lo);
            }
            count++;
        }
        i = j;
    }
    return count;
}

/* Make m->acc (any level) an admissible iterate: end taper, the soft peak
 * compression of §3.3 above its knee (sl_synth_compress_peaks), for sharp
 * targets the crest reservation (eq. S2, synth_sharp.c), and the baseline
 * correction (no peak scaling: the PGA is what the spectral matching of the
 * high-frequency end makes it); then its spectrum, and keep it if it is the
 * best so far. */
sl_status sl_synth_finish(sl_synth_motion *m, sl_error *err)
{
    const sl_synth *s = m->s;
    const size_t n = s->n;
    for (size_t j = 0; j < s->ntaper && j < n; j++) {
        m->acc[j] *= s->taper[j];
        m->acc[n - 1 - j] *= s->taper[j];
    }
    sl_synth_compress_peaks(m, m->level * m->zpa, m->knee);
    if ((m->sharp & SYNTH_SHARP_CREST) && !m->record) /* sharp targets: eq. S2 (synth_sharp.c) */
        sl_synth_reserve_crest(m);
    /* Baseline: subtract c0 bl0 + c1 bl1 so that v(T) = d(T) = 0. */
    double ve, de;
    sl_synth_end_values(m->acc, n, s->dt, &ve, &de);
    double c0 = s->bl_inv[0][0] * ve + s->bl_inv[0][1] * de;
    double c1 = s->bl_inv[1][0] * ve + s->bl_inv[1][1] * de;
    double peak = 0;
    for (size_t j = 0; j < n; j++) {
        m->acc[j] -= c0 * s->bl[0][j] + c1 * s->bl[1][j];
        double x = fabs(m->acc[j]);
        peak = x > peak ? x : peak;
    }
    if (!(peak > 0) || !isfinite(peak))
        return sl_error_set(err, SL_ESOLVER, NULL, 0, "synth: motion vanished or overflowed");
    sl_status st = sl_synth_spectrum_of_acc(m, err);
    if (st)
        return st;
    sl_synth_spec_check c;
    sl_synth_spectral_check(m, m->psa, &c);
    double v = sl_synth_violation(&s->p, &c, m->j_hi - m->j_lo);
    if (m->iter == 0 || v < m->best_score) {
        m->best_score = v;
        m->best_iter = m->iter;
        memcpy(m->best_acc, m->acc, n * sizeof *m->acc);
        memcpy(m->best_psa, m->psa, s->ngrid * sizeof *m->psa);
    }
    return SL_OK;
}
