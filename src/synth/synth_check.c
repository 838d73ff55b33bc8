/* synth_check.c - the SRP 3.7.1 checks of a motion and the other
 * dampings of a floor file (docs/synthesis.md 4). */
#include "synth/synth_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

double sl_synth_end_residual(double x, double peak)
{
    return fabs(x) <= SL_SYNTH_END_ROUNDOFF * fabs(peak) ? 0.0 : x;
}

void sl_synth_check_motion(const sl_synth_motion *m, sl_synth_check *out)
{
    sl_synth_check_motion_psd(m, out, 1);
}

/* The App. B PSD of acc against target spectrum ts into out (ok_psd only
 * required when psd_frac > 0); pass updated. */
void sl_synth_check_psd(const double *acc, size_t n, double dt, const sl_spectrum *ts,
                        double psd_frac, sl_synth_check *out)
{
    sl_psd_check pc;
    sl_error e;
    out->ok_psd = 1;
    out->psd_min_ratio = out->f_psd_min_hz = NAN;
    if (!sl_psd_check_motion(acc, n, dt, ts, psd_frac, SL_PSD_FMIN_HZ, SL_PSD_FMAX_HZ, &pc,
                             &e)) {
        out->psd_min_ratio = pc.min_ratio;
        out->f_psd_min_hz = pc.f_min_ratio_hz;
        out->ok_psd = psd_frac > 0 ? pc.ok : 1; /* 0: reported only */
    }
}

void sl_synth_check_motion_psd(const sl_synth_motion *m, sl_synth_check *out, int with_psd)
{
    const sl_synth *s = m->s;
    const sl_synth_params *p = &s->p;
    memset(out, 0, sizeof *out);
    sl_synth_spec_check c;
    sl_synth_spectral_check(m, m->best_psa, &c);
    out->damping = m->damping;
    out->f_lo_hz = s->grid[m->j_lo];
    out->f_hi_hz = s->grid[m->j_hi - 1];
    out->npoints = m->j_hi - m->j_lo;
    out->min_ratio = c.min_ratio;
    out->f_min_ratio_hz = c.f_min;
    out->max_ratio = c.max_ratio;
    out->f_max_ratio_hz = c.f_max;
    out->run_below = c.run;
    out->n_below = c.n_below;
    /* Integrals and peaks of the best iterate (piecewise-linear, exact). */
    const double *a = m->best_acc;
    const double dt = s->dt;
    double v = 0, d = 0, pv = 0, pd = 0, pa = fabs(a[0]);
    for (size_t i = 0; i + 1 < s->n; i++) {
        d += dt * v + dt * dt * (2 * a[i] + a[i + 1]) / 6;
        v += dt * (a[i] + a[i + 1]) / 2;
        pv = fabs(v) > pv ? fabs(v) : pv;
        pd = fabs(d) > pd ? fabs(d) : pd;
        pa = fabs(a[i + 1]) > pa ? fabs(a[i + 1]) : pa;
    }
    sl_motion tmp = {.path = NULL, .label = NULL, .n = s->n, .dt_s = dt,
                     .acc_ms2 = m->best_acc};
    out->d5_75_s = sl_motion_d5_75(&tmp);
    out->duration_s = dt * (double)(s->n - 1);
    out->pga_ms2 = pa;
    out->zpa_ms2 = m->zpa;
    out->pgv_ms = pv;
    out->pgd_m = pd;
    out->v_end_ms = v;
    out->d_end_m = d;
    out->max_corr = NAN;
    out->corr_record = out->peaks_record = NAN;
    out->iterations = m->best_iter;
    out->attempt = m->attempt;
    out->ok_below = c.min_ratio >= 1 - p->tol_below;
    out->ok_above = c.max_ratio <= 1 + p->tol_above;
    out->ok_run = c.run <= p->max_run_below;
    out->ok_d5_75 = out->d5_75_s >= p->min_d5_75_s;
    /* Compare with a tolerance of rounding so that 4000 x 0.005 passes 20 s. */
    out->ok_duration = out->duration_s >= p->min_duration_s * (1 - 1e-9);
    out->ok_end = fabs(v) <= p->end_vel_frac * pv && fabs(d) <= p->end_disp_frac * pd;
    /* PGA/ZPA inside the spectral band (SA at the high-frequency end is the
     * PGA; nothing pins it). */
    out->pga_zpa = pa / m->zpa;
    /* The spectrum's high-frequency end bounds the PGA only when the motion
     * has little content near the highest checked frequency; a PGA far below
     * the ZPA means the target's ZPA and its spectrum disagree (or the
     * motion resonates the stiff oscillators): below 1 - pga_tol_below
     * fails. */
    /* Checked when the target is rigid at its end (SA within 5 % of its
     * last value over the last 0.6 octave, as RG 1.60 from 33 to 50 Hz);
     * a spectrum cut while still falling only bounds the PGA from above. */
    const sl_spectrum *ts = m->tspec;
    double fe = ts->f_hz[ts->n - 1], se = ts->sa_ms2[ts->n - 1];
    double sb = fe / 1.5 >= ts->f_hz[0] ? sl_spectrum_interp(ts, fe / 1.5) : NAN;
    int rigid = sb <= 1.05 * se && sb >= se / 1.05;
    out->ok_pga = out->pga_zpa <= 1 + p->tol_above &&
                  (!rigid || out->pga_zpa >= 1 - p->pga_tol_below);
    out->peaks = sl_realism_peaks_above(m->best_acc, s->n, SL_REALISM_PEAK_FRAC);
    /* Checked for broadband (ground-like) targets, max SA/ZPA <= 
     * SL_SYNTH_PEAKS_MAX_AMP; narrow-band floor targets are reported only
     * (docs/synthesis.md 9). */
    double amp = 0;
    for (size_t j = m->j_lo; j < m->j_hi; j++)
        amp = m->tgt[j] / m->zpa > amp ? m->tgt[j] / m->zpa : amp;
    out->ok_peaks = amp > SL_SYNTH_PEAKS_MAX_AMP || out->peaks <= p->max_peaks;
    sl_realism_ratios(pa, pv, pd, &out->va_s, &out->adv2);
    double da;
    sl_error e;
    if (sl_realism_expected(m->tspec, &out->va_expect_s, &da, &out->adv2_expect, &e)) {
        out->va_expect_s = out->adv2_expect = NAN;
    }
    out->ok_psd = 1;
    out->psd_min_ratio = out->f_psd_min_hz = NAN;
    if (with_psd)
        sl_synth_check_psd(m->best_acc, s->n, dt, m->tspec, p->psd_frac, out);
    out->ok_corr = 1;
    out->pass = out->ok_below && out->ok_above && out->ok_run && out->ok_d5_75 &&
                out->ok_duration && out->ok_end && out->ok_pga && out->ok_peaks && out->ok_psd;
}

double sl_synth_corr(const double *a, const double *b, size_t n)
{
    if (n == 0)
        return 0;
    double ma = 0, mb = 0;
    for (size_t i = 0; i < n; i++) {
        ma += a[i];
        mb += b[i];
    }
    ma /= (double)n;
    mb /= (double)n;
    double sab = 0, saa = 0, sbb = 0;
    for (size_t i = 0; i < n; i++) {
        double x = a[i] - ma, y = b[i] - mb;
        sab += x * y;
        saa += x * x;
        sbb += y * y;
    }
    if (!(saa > 0) || !(sbb > 0))
        return 0;
    return sab / sqrt(saa * sbb);
}

/* ------------------------------------------------------------------ */
/* Other dampings of a floor file                                      */
/* ------------------------------------------------------------------ */

/* Component c of every set against table `spec` (damping z): per-motion
 * and set-mean S/T on the plan's grid inside the table's range, into
 * check[c].other[q]. */
static sl_status check_one_damping(const sl_synth *s, const sl_spectrum *spec,
                                   sl_synth_set *sets, size_t nsets, sl_synth_comp c, size_t q,
                                   sl_error *err)
{
    const double slack = 1e-12; /* as set_target */
    const double f0 = spec->f_hz[0], f1 = spec->f_hz[spec->n - 1];
    size_t ja = s->ngrid, jb = 0;
    for (size_t j = 0; j < s->ngrid; j++)
        if (s->grid[j] >= f0 * (1 - slack) && s->grid[j] <= f1 * (1 + slack)) {
            ja = ja == s->ngrid ? j : ja;
            jb = j + 1;
        }
    for (size_t k = 0; k < nsets; k++) {
        sl_synth_other *o = &sets[k].check[c].other[q];
        o->damping = spec->damping;
        o->min_ratio = o->max_ratio = o->set_min = o->set_max = NAN;
        o->f_set_min_hz = o->f_set_max_hz = NAN;
        o->ok_set = 1;
    }
    if (ja >= jb)
        return SL_OK; /* no grid point inside the table: nothing to check */
    const size_t nf = jb - ja;
    double *tgt = malloc(nf * sizeof *tgt);
    double *sum = calloc(nf, sizeof *sum);
    double *psa = malloc(nsets * nf * sizeof *psa);
    if (!tgt || !sum || !psa) {
        free(tgt);
        free(sum);
        free(psa);
        return sl_error_set(err, SL_ENOMEM, NULL, 0, "synth: out of memory");
    }
    for (size_t j = 0; j < nf; j++) {
        double f = s->grid[ja + j];
        tgt[j] = sl_spectrum_interp(spec, f < f0 ? f0 : f > f1 ? f1 : f);
    }
    sl_status st = SL_OK;
    long long nk = (long long)nsets;
#pragma omp parallel for schedule(dynamic, 1)
    for (long long k = 0; k < nk; k++) {
        const sl_motion *mo = sl_synth_set_motion(&sets[k], c);
        sl_error e;
        sl_status sk = sl_spectrum_compute(mo->acc_ms2, mo->n, mo->dt_s, s->grid + ja, nf,
                                           spec->damping, psa + (size_t)k * nf, NULL, NULL, &e);
        if (sk) {
#pragma omp critical(sl_synth_dampings)
            if (!st)
                st = sl_error_set(err, sk, NULL, 0, "%s", e.msg);
        }
    }
    for (size_t k = 0; k < nsets && !st; k++) {
        sl_synth_other *o = &sets[k].check[c].other[q];
        o->min_ratio = INFINITY;
        o->max_ratio = -INFINITY;
        for (size_t j = 0; j < nf; j++) {
            double r = psa[k * nf + j] / tgt[j];
            o->min_ratio = r < o->min_ratio ? r : o->min_ratio;
            o->max_ratio = r > o->max_ratio ? r : o->max_ratio;
            sum[j] += r; /* summed in set order: the same bits for any thread count */
        }
    }
    if (!st) {
        double lo = INFINITY, hi = -INFINITY, flo = NAN, fhi = NAN;
        for (size_t j = 0; j < nf; j++) {
            double r = sum[j] / (double)nsets;
            if (r < lo) {
                lo = r;
                flo = s->grid[ja + j];
            }
            if (r > hi) {
                hi = r;
                fhi = s->grid[ja + j];
            }
        }
        int ok = lo >= 1 - s->p.tol_below && hi <= 1 + s->p.tol_above;
        for (size_t k = 0; k < nsets; k++) {
            sl_synth_other *o = &sets[k].check[c].other[q];
            o->set_min = lo;
            o->set_max = hi;
            o->f_set_min_hz = flo;
            o->f_set_max_hz = fhi;
            o->ok_set = ok;
        }
    }
    free(tgt);
    free(sum);
    free(psa);
    return st;
}

sl_status sl_synth_check_dampings(const sl_synth *s, const sl_floor *fl, sl_synth_set *sets,
                                  size_t nsets, sl_error *err)
{
    if (!s || !fl || !sets || nsets == 0)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "synth: no sets to check");
    /* (components absent from a set, as with records, are skipped) */
    for (int c = 0; c < SL_SYNTH_NCOMP; c++) {
        int absent = 0; /* records: a component not given is not checked */
        for (size_t k = 0; k < nsets; k++) {
            sets[k].check[c].n_other = 0;
            absent = absent || !sl_synth_set_motion(&sets[k], (sl_synth_comp)c);
        }
        if (absent)
            continue;
        const sl_floor_component *fc = &fl->comp[c];
        const double zm = sets[0].check[c].damping;
        size_t q = 0;
        for (size_t i = 0; i < fc->nspec && q < SL_SYNTH_MAX_OTHER; i++) {
            const sl_spectrum *sp = &fc->spec[i];
            if (fabs(sp->damping - zm) <= SL_FLOOR_DAMPING_TOL * (zm > 1 ? zm : 1))
                continue; /* the damping matched */
            sl_status st = check_one_damping(s, sp, sets, nsets, (sl_synth_comp)c, q, err);
            if (st)
                return st;
            q++;
        }
        for (size_t k = 0; k < nsets; k++)
            sets[k].check[c].n_other = q;
    }
    return SL_OK;
}

int sl_synth_dampings_ok(const sl_synth_set *sets, size_t nsets)
{
    for (size_t k = 0; k < nsets; k++)
        for (int c = 0; c < SL_SYNTH_NCOMP; c++)
            for (size_t q = 0; q < sets[k].check[c].n_other; q++)
                if (!sets[k].check[c].other[q].ok_set)
                    return 0;
    return 1;
}
