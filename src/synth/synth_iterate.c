/* synth_iterate.c - the correction iteration (docs/synthesis.md 3.2):
 * spectrum of the iterate (coarse and full), spectral checks, r(f_k). */
#include "synth/synth_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Spectral checks of psa against the target over the checked range. */
void sl_synth_spectral_check(const sl_synth_motion *m, const double *psa, sl_synth_spec_check *c)
{
    const sl_synth *s = m->s;
    c->min_ratio = INFINITY;
    c->max_ratio = -INFINITY;
    c->f_min = c->f_max = NAN;
    c->run = c->n_below = 0;
    size_t run = 0;
    for (size_t j = m->j_lo; j < m->j_hi; j++) {
        double r = psa[j] / m->tgt[j];
        if (m->coarse) {
            if (isnan(psa[j]))
                continue; /* not computed in the coarse phase */
            /* coarse phase: a margin inside the band for the points between */
            r = r < 1 ? r - SYNTH_COARSE_MARGIN : r + SYNTH_COARSE_MARGIN;
        }
        if (!(r >= c->min_ratio)) { /* also takes NaN, so NaN fails the check */
            c->min_ratio = r;
            c->f_min = s->grid[j];
        }
        if (r > c->max_ratio) {
            c->max_ratio = r;
            c->f_max = s->grid[j];
        }
        if (!(r >= 1)) {
            run += m->coarse ? m->stride : 1;
            c->n_below++;
            if (run > c->run)
                c->run = run;
        } else {
            run = 0;
        }
    }
}

/* Violation of the spectral limits: 0 when every one holds. */
double sl_synth_violation(const sl_synth_params *p, const sl_synth_spec_check *c, size_t npoints)
{
    double v = 0;
    double lo = 1 - p->tol_below, hi = 1 + p->tol_above;
    if (!(c->min_ratio >= lo))
        v += isnan(c->min_ratio) ? INFINITY : lo - c->min_ratio;
    if (!(c->max_ratio <= hi))
        v += isnan(c->max_ratio) ? INFINITY : c->max_ratio - hi;
    if (c->run > p->max_run_below)
        v += (double)(c->run - p->max_run_below) / (double)npoints;
    return v;
}

/* The plans of the checked range [j_lo, j_hi) at m->damping, remade only
 * when these change. */
static sl_status make_plans(sl_synth_motion *m, sl_error *err)
{
    const sl_synth *s = m->s;
    if (m->plan_full && m->plan_lo == m->j_lo && m->plan_hi == m->j_hi &&
        m->plan_zeta == m->damping && m->plan_record == m->record)
        return SL_OK;
    sl_spectrum_plan_free(m->plan_full);
    sl_spectrum_plan_free(m->plan_coarse);
    m->plan_full = m->plan_coarse = NULL;
    /* coarse points: j_lo, j_lo + stride, ..., and j_hi - 1 */
    size_t nc = 0;
    for (size_t j = m->j_lo; j < m->j_hi; j += SYNTH_COARSE_STRIDE)
        m->cidx[nc++] = j;
    if (m->cidx[nc - 1] != m->j_hi - 1)
        m->cidx[nc++] = m->j_hi - 1;
    m->ncoarse = nc;
    for (size_t q = 0; q < nc; q++)
        m->cval[q] = s->grid[m->cidx[q]];
    sl_spectrum_opts o;
    sl_spectrum_opts_default(&o);
    m->plan_full = sl_spectrum_plan_alloc(s->n, s->dt, s->grid + m->j_lo, m->j_hi - m->j_lo,
                                          m->damping, &o, 0.0, err);
    o.steps_per_period = SYNTH_COARSE_SPP;
    o.free_vibration = 0; /* coarse: no free-vibration tail (about 10 % of the time) */
    if (m->plan_full)
        m->plan_coarse = sl_spectrum_plan_alloc(s->n, s->dt, m->cval, nc, m->damping, &o,
                                                m->record ? 0.0 : SYNTH_COARSE_RATIO, err);
    if (!m->plan_full || !m->plan_coarse) {
        sl_spectrum_plan_free(m->plan_full);
        m->plan_full = NULL;
        return err ? err->code : SL_ENOMEM;
    }
    m->plan_lo = m->j_lo;
    m->plan_hi = m->j_hi;
    m->plan_zeta = m->damping;
    m->plan_record = m->record;
    return SL_OK;
}

/* Spectrum of m->acc into m->psa: at every checked grid point at full
 * accuracy, or in the coarse phase at the coarse points (NAN elsewhere). */
sl_status sl_synth_spectrum_of_acc(sl_synth_motion *m, sl_error *err)
{
    const sl_synth *s = m->s;
    for (size_t j = 0; j < s->ngrid; j++)
        m->psa[j] = NAN;
    sl_status st = make_plans(m, err);
    if (st)
        return st;
    if (!m->coarse)
        return sl_spectrum_plan_compute(m->plan_full, m->acc, m->psa + m->j_lo, NULL, NULL,
                                        err);
    st = sl_spectrum_plan_compute(m->plan_coarse, m->acc, m->cval, NULL, NULL, err);
    for (size_t q = 0; q < m->ncoarse && !st; q++)
        m->psa[m->cidx[q]] = m->cval[q];
    return st;
}

/* End of the coarse phase: the best iterate and its spectrum at every
 * checked point at full accuracy (the checks are always made on this). */
sl_status sl_synth_end_coarse(sl_synth_motion *m, sl_error *err)
{
    const sl_synth *s = m->s;
    m->coarse = 0;
    memcpy(m->acc, m->best_acc, s->n * sizeof *m->acc);
    sl_status st = sl_synth_spectrum_of_acc(m, err);
    if (st) {
        m->ready = 0;
        return st;
    }
    sl_synth_spec_check c;
    sl_synth_spectral_check(m, m->psa, &c);
    m->best_score = sl_synth_violation(&s->p, &c, m->j_hi - m->j_lo);
    memcpy(m->best_psa, m->psa, s->ngrid * sizeof *m->psa);
    return SL_OK;
}

sl_status sl_synth_iterate(sl_synth_motion *m, sl_error *err)
{
    if (!m->ready)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "synth: iterate before set");
    const sl_synth *s = m->s;
    if (m->coarse && (m->best_score == 0 || m->iter + 1 >= s->p.max_iter)) {
        sl_status st = sl_synth_end_coarse(m, err);
        if (!st)
            m->iter++;
        return st;
    }
    const double lo = -log(SL_SYNTH_RATIO_CLAMP), hi = log(SL_SYNTH_RATIO_CLAMP);
    /* records: the dead band where S/T already complies (no correction) */
    const double band_lo = m->record && s->p.match_margin > 0 ? 1 + s->p.match_margin : INFINITY;
    const double band_hi = 1 + s->p.tol_above - s->p.match_margin;
    size_t jprev = m->j_lo;
    for (size_t j = m->j_lo; j < m->j_hi; j++) {
        if (isnan(m->psa[j]) && m->coarse)
            continue;
        double ratio = m->psa[j] / m->tgt[j];
        /* records: no correction inside the dead band; elsewhere (and for
         * synthetic motions) towards aim x T */
        double x = ratio >= band_lo && ratio <= band_hi
                       ? 0.0
                       : SYNTH_RELAX * log(s->p.aim * m->tgt[j] / m->psa[j]);
        if (!isfinite(x)) {
            m->ready = 0;
            return sl_error_set(err, SL_ESOLVER, NULL, 0, "synth: spectrum not finite at %g Hz",
                                s->grid[j]);
        }
        m->lnr[j] = x < lo ? lo : x > hi ? hi : x;
        for (size_t q = jprev + 1; q < j; q++) /* coarse phase: linear between */
            m->lnr[q] = m->lnr[jprev] +
                        (m->lnr[j] - m->lnr[jprev]) * (double)(q - jprev) / (double)(j - jprev);
        jprev = j;
    }
    for (size_t j = 0; j < m->j_lo; j++)
        m->lnr[j] = m->lnr[m->j_lo];
    for (size_t j = m->j_hi; j < s->ngrid; j++)
        m->lnr[j] = m->lnr[m->j_hi - 1];
    /* X = DFT of the current iterate, zero-padded (FFTW r2c, unnormalised). */
    for (size_t j = 0; j < s->nfft; j++)
        m->rwork[j] = j < s->n ? m->acc[j] : 0.0;
    fftw_execute_dft_r2c(s->r2c, m->rwork, m->cwork);
    /* X_k *= r(f_k). Outside the checked range the correction fades
     * out linearly in log2 f over SL_SYNTH_EDGE_OCTAVES: those bins have no
     * check of their own, and a full correction there drifts. */
    const double f_lo = s->grid[m->j_lo], f_hi = s->grid[m->j_hi - 1];
    const double *fade_of = m->j_lo == 0 && m->j_hi == s->ngrid ? s->bin_fade : NULL;
    for (size_t k = 1; k < s->nbin; k++) {
        size_t j = s->bin_j[k];
        double w = s->bin_w[k], f = s->df * (double)k, x = 0;
        if (s->bin_jb[k] > s->bin_ja[k]) {
            for (size_t q = s->bin_ja[k]; q < s->bin_jb[k]; q++)
                x += m->lnr[q];
            x /= (double)(s->bin_jb[k] - s->bin_ja[k]);
        } else {
            x = s->ngrid == 1 ? m->lnr[0] : (1 - w) * m->lnr[j] + w * m->lnr[j + 1];
        }
        double fade = fade_of ? fade_of[k] : sl_synth_edge_fade(f, f_lo, f_hi);
        double g = exp(fade * x) * m->hp[k]; /* correction, then the high-pass */
        m->cwork[k][0] *= g;
        m->cwork[k][1] *= g;
    }
    m->cwork[0][0] = m->cwork[0][1] = 0; /* no mean */
    fftw_execute_dft_c2r(s->c2r, m->cwork, m->rwork);
    const double inv_n = 1.0 / (double)s->nfft;
    for (size_t j = 0; j < s->n; j++)
        m->acc[j] = m->rwork[j] * inv_n;
    m->iter++;
    sl_status st = sl_synth_finish(m, err);
    if (st)
        m->ready = 0;
    return st;
}

int sl_synth_test(const sl_synth_motion *m)
{
    return m->ready && !m->coarse && m->best_score == 0;
}

unsigned sl_synth_iterations(const sl_synth_motion *m) { return m->iter; }

const double *sl_synth_acc(const sl_synth_motion *m) { return m->best_acc; }
const double *sl_synth_psa(const sl_synth_motion *m) { return m->best_psa; }
const double *sl_synth_target_psa(const sl_synth_motion *m) { return m->tgt; }
