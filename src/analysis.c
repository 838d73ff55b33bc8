/* analysis.c - the per-floor study; see analysis.h. */
#include "analysis.h"
#include "core/clock.h"

#include <gsl/gsl_statistics_double.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "method/asce.h"
#include "method/asce_input.h"
#include "method/stats.h"
#include "slide/slide.h"
#include "method/scatter.h"
#include "signal/spectrum.h"
#include "core/units.h"


void sl_analysis_opts_default(sl_analysis_opts *o)
{
    memset(o, 0, sizeof *o);
    o->n_sets = 0; /* adaptive */
    o->rel_se = SL_ANALYSIS_REL_SE;
    o->abs_se_m = SL_ANALYSIS_ABS_SE_M;
    o->max_sets = SL_ANALYSIS_MAX_SETS;
    o->first_batch = SL_ANALYSIS_FIRST_BATCH;
    o->min_batch = SL_ANALYSIS_MIN_BATCH;
    o->plan_margin = SL_ANALYSIS_PLAN_MARGIN;
    o->plan_growth = SL_ANALYSIS_PLAN_GROWTH;
    o->boot_resamples = SL_STATS_BOOT_RESAMPLES;
    o->band_level = SL_STATS_BAND_LEVEL;
    o->band_method = SL_STATS_BAND_STUDENT;
    o->seed = 1;
    o->substeps = SL_SLIDE_DEFAULT_SUBSTEPS;
    o->rtol = SL_SLIDE_DEFAULT_RTOL;
    o->scatter = SL_ANALYSIS_SCATTER;
    o->policy = SL_CLEARANCE_NLTHA;
    o->fs_nltha = SL_NLTHA_FS;
    o->fs_asce = SL_ASCE_FS;
}

static const char *const stop_names[] = {"fixed", "converged", "max_sets"};

const char *sl_analysis_stop_name(sl_analysis_stop s)
{
    return ((int)s >= 0 && s <= SL_ANALYSIS_STOP_MAX_SETS) ? stop_names[s] : "unknown";
}

/* SplitMix64 finaliser (Steele, Lea and Flood 2014). */
static uint64_t mix64(uint64_t x)
{
    x += 0x9e3779b97f4a7c15ULL;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
}

/* FNV-1a, 64 bits, over the IEEE-754 bits of v, least significant byte
 * first (the same on every byte order). */
static uint64_t fnv_double(uint64_t h, double v)
{
    uint64_t b;
    if (v == 0)
        v = 0.0; /* -0 and +0 alike */
    memcpy(&b, &v, sizeof b);
    for (int i = 0; i < 8; i++) {
        h ^= (b >> (8 * i)) & 0xffu;
        h *= 0x100000001b3ULL;
    }
    return h;
}

uint64_t sl_analysis_floor_seed(uint64_t seed, const sl_floor *fl)
{
    uint64_t base;
    if (fl->has_seed) {
        base = fl->seed;
    } else {
        base = 0xcbf29ce484222325ULL; /* FNV offset basis */
        for (int c = 0; c < SL_FLOOR_NCOMP; c++) {
            const sl_floor_component *fc = &fl->comp[c];
            base = fnv_double(base, (double)c);
            base = fnv_double(base, fc->zpa_ms2);
            for (size_t d = 0; d < fc->nspec; d++) {
                const sl_spectrum *sp = &fc->spec[d];
                base = fnv_double(base, sp->damping);
                for (size_t j = 0; j < sp->n; j++) {
                    base = fnv_double(base, sp->f_hz[j]);
                    base = fnv_double(base, sp->sa_ms2[j]);
                }
            }
        }
    }
    return mix64(base) ^ seed;
}

void sl_analysis_free(sl_analysis *a)
{
    if (!a)
        return;
    sl_design_free(a->design);
    free(a->conv);
    free(a->design_lo_m);
    free(a->design_hi_m);
    free(a->design_se_m);
    free(a->err_est_m);
    free(a->vr_f_hz);
    free(a->vr_corr_sa);
    free(a->vr_corr_pgv);
    free(a->vr_factor);
    if (a->sets)
        for (size_t s = 0; s < a->n_sets; s++)
            sl_synth_set_clear(&a->sets[s]);
    free(a->sets);
    free(a->pgd_m);
    free(a);
}

typedef struct prog_ctx {
    const sl_analysis_opts *o;
} prog_ctx;

static void synth_progress(void *ctx, size_t done, size_t total)
{
    const sl_analysis_opts *o = ((prog_ctx *)ctx)->o;
    if (o->progress)
        o->progress(o->progress_ctx, "synthesis", done, total);
}

/* The mean 10 %-damped spectrum of component c of the sets, on the
 * default grid: the fallback target of the ASCE method. */
static sl_spectrum *mean_spectrum(const sl_analysis *a, int c, sl_error *err)
{
    size_t nf = 0;
    double *f = sl_spectrum_grid(SL_SPECTRUM_FMIN_HZ, SL_SPECTRUM_FMAX_HZ, SL_SPECTRUM_PER_DECADE, &nf);
    sl_spectrum *sp = f ? sl_spectrum_alloc(nf, SL_ASCE_DAMPING) : NULL;
    double *psa = malloc(nf * sizeof *psa);
    if (!f || !sp || !psa) {
        free(f);
        free(psa);
        sl_spectrum_free(sp);
        sl_error_set(err, SL_ENOMEM, NULL, 0, "out of memory");
        return NULL;
    }
    memcpy(sp->f_hz, f, nf * sizeof *f);
    memset(sp->sa_ms2, 0, nf * sizeof *sp->sa_ms2);
    for (size_t s = 0; s < a->n_sets; s++) {
        const sl_motion *m = sl_synth_set_motion(&a->sets[s], (sl_synth_comp)c);
        if (sl_spectrum_compute(m->acc_ms2, m->n, m->dt_s, f, nf, SL_ASCE_DAMPING, psa, NULL, NULL,
                                err)) {
            free(f);
            free(psa);
            sl_spectrum_free(sp);
            return NULL;
        }
        for (size_t j = 0; j < nf; j++)
            sp->sa_ms2[j] += psa[j] / (double)a->n_sets;
    }
    free(f);
    free(psa);
    return sp;
}

/* The convergence statistics of the n sets so far (section "Convergence"
 * of analysis.h), into a->conv; *worst = the largest SE / target over mu
 * (<= 1 when every mu is converged). */
static sl_status conv_update(sl_analysis *a, const double *peak, size_t n,
                             const sl_analysis_opts *o, double *worst, sl_error *err)
{
    sl_stats_mean sp;
    if (sl_stats_mean_compute(a->pgd_m, n, 1, &sp, err))
        return err ? err->code : SL_EINVAL;
    double cap = SL_DESIGN_CAP_FACTOR * sp.mean;
    double cap_se = SL_DESIGN_CAP_FACTOR * sp.se;
    double need = 0;
    a->n_unconverged = 0;
    a->worst_rel_se = 0;
    for (size_t k = 0; k < o->n_mu; k++) {
        sl_analysis_conv *c = &a->conv[k];
        sl_stats_mean st;
        if (sl_stats_mean_compute(peak + k, n, o->n_mu, &st, err))
            return err ? err->code : SL_EINVAL;
        c->n_sets = n;
        c->mean_m = st.mean;
        c->se_m = st.se;
        c->lognormal_mean_m = st.ln_mean;
        c->p_slide = st.p_pos;
        double dn = o->fs_nltha * st.mean;
        if (dn > cap) {
            c->design_m = cap;
            c->design_se_m = cap_se;
        } else {
            c->design_m = dn;
            c->design_se_m = o->fs_nltha * st.se;
        }
        c->target_se_m = fmax(o->rel_se * c->design_m, o->abs_se_m);
        c->converged = c->design_se_m <= c->target_se_m;
        c->design_lo_m = c->design_hi_m = NAN;
        a->n_unconverged += (size_t)!c->converged;
        double rel = c->design_se_m / fmax(c->design_m, o->rel_se > 0 ? o->abs_se_m / o->rel_se
                                                                       : c->design_m);
        if (isfinite(rel) && rel > a->worst_rel_se)
            a->worst_rel_se = rel;
        if (c->target_se_m > 0)
            need = fmax(need, c->design_se_m / c->target_se_m);
    }
    *worst = need;
    return SL_OK;
}

/* Bootstrap band of the design value at every mu (stats.h (3) by default):
 * resample the n sets (their peaks and PGD together), recompute
 * min(FS mean, cap) and its SE. */
static sl_status conv_band(sl_analysis *a, const double *peak, size_t n, const sl_analysis_opts *o,
                           sl_error *err)
{
    if (o->boot_resamples == 0)
        return SL_OK;
    double *lo = malloc(2 * o->n_mu * sizeof *lo);
    if (!lo)
        return sl_error_set(err, SL_ENOMEM, NULL, 0, "analysis: out of memory");
    double *hi = lo + o->n_mu;
    sl_status st = sl_stats_design_band(peak, n, o->n_mu, a->pgd_m, o->fs_nltha,
                                        SL_DESIGN_CAP_FACTOR, o->boot_resamples, o->band_level,
                                        a->floor_seed ^ 0x626f6f7473747261ULL, o->band_method,
                                        lo, hi, err);
    for (size_t k = 0; !st && k < o->n_mu; k++) {
        a->conv[k].design_lo_m = lo[k];
        a->conv[k].design_hi_m = hi[k];
    }
    free(lo);
    return st;
}

/* Pearson correlation of x[i stride_x] and y[i stride_y], i < n: NAN when
 * n < 3 or either is constant (gsl_stats_correlation would divide by 0). */
static double corr_or_nan(const double *x, size_t stride_x, const double *y, size_t stride_y,
                          size_t n)
{
    if (n < 3 || !(gsl_stats_sd(x, stride_x, n) > 0) || !(gsl_stats_sd(y, stride_y, n) > 0))
        return NAN;
    return gsl_stats_correlation(x, stride_x, y, stride_y, n);
}

/* The variance-reduction diagnostic (analysis.h, vr_*; docs/run.md,
 * "Variance reduction"): at each mu with an f_es (a->vr_f_hz), the
 * correlation over the n sets of the peak with Y_sa = sqrt(S_H1 S_H2)(f_es),
 * the set's own 10 %-damped pseudo-acceleration (eq. (1)-(2) of spectrum.h),
 * and with Y_pgv = PGV_H1 + PGV_H2; vr_factor = 1 - max rho^2, the variance
 * left by the best linear control variate on either (Rubinstein and
 * Marcus 1985: Var(m_cv) = (1 - rho^2) Var(m)) if its mean were known. */
static sl_status vr_measure(sl_analysis *a, const double *peak, size_t n, size_t n_mu,
                            sl_error *err)
{
    size_t nf = 0;
    double *f = malloc(n_mu * sizeof *f);
    double *psa = malloc(2 * n * n_mu * sizeof *psa);
    double *ysa = malloc(n * n_mu * sizeof *ysa);
    double *ypgv = malloc(n * sizeof *ypgv);
    const sl_motion **mh = malloc(2 * n * sizeof *mh);
    sl_status st = SL_OK;
    if (!f || !psa || !ysa || !ypgv || !mh) {
        st = sl_error_set(err, SL_ENOMEM, NULL, 0, "analysis: out of memory");
        goto done;
    }
    for (size_t k = 0; k < n_mu; k++)
        if (isfinite(a->vr_f_hz[k]))
            f[nf++] = a->vr_f_hz[k];
    for (size_t s = 0; s < n; s++) {
        mh[2 * s] = a->sets[s].set.h1;
        mh[2 * s + 1] = a->sets[s].set.h2;
        ypgv[s] = a->sets[s].check[SL_SYNTH_H1].pgv_ms + a->sets[s].check[SL_SYNTH_H2].pgv_ms;
    }
    if (nf > 0 && n >= 3 &&
        (st = sl_spectrum_batch((const sl_motion *const *)mh, 2 * n, f, nf, SL_ASCE_DAMPING,
                                NULL, psa, NULL, NULL, err)))
        goto done;
    for (size_t k = 0, j = 0; k < n_mu; k++) {
        double rs = NAN, rp = corr_or_nan(peak + k, n_mu, ypgv, 1, n);
        if (isfinite(a->vr_f_hz[k])) {
            for (size_t s = 0; nf > 0 && n >= 3 && s < n; s++)
                ysa[s] = sqrt(psa[2 * s * nf + j] * psa[(2 * s + 1) * nf + j]);
            rs = corr_or_nan(peak + k, n_mu, ysa, 1, n);
            j++;
        }
        a->vr_corr_sa[k] = rs;
        a->vr_corr_pgv[k] = rp;
        double r2 = fmax(isfinite(rs) ? rs * rs : 0, isfinite(rp) ? rp * rp : 0);
        a->vr_factor[k] = isfinite(rs) || isfinite(rp) ? 1 - r2 : NAN;
    }
done:
    free(f);
    free(psa);
    free(ysa);
    free(ypgv);
    free(mh);
    return st;
}

/* Every other damping the floor file gives, checked on the motions' own
 * spectra over all a->n_sets sets (sl_synth_check_dampings: the set mean
 * of S/T against [1 - tol_below, 1 + tol_above]); the results, the same in
 * every set, are copied from set 0 into a->dampings. */
static sl_status store_dampings(sl_analysis *a, const sl_synth *plan, const sl_floor *fl,
                                const sl_synth_params *sp, sl_error *err)
{
    a->damping_lim_lo = 1 - sp->tol_below;
    a->damping_lim_hi = 1 + sp->tol_above;
    a->dampings_ok = 1;
    a->n_dampings = 0;
    sl_status st = sl_synth_check_dampings(plan, fl, a->sets, a->n_sets, err);
    if (st)
        return st;
    for (int c = 0; c < SL_SYNTH_NCOMP; c++) {
        const sl_synth_check *k = &a->sets[0].check[c];
        for (size_t q = 0; q < k->n_other && a->n_dampings < SL_ANALYSIS_MAX_DAMPINGS; q++) {
            const sl_synth_other *ot = &k->other[q];
            a->dampings[a->n_dampings++] = (sl_analysis_damping){
                .comp = (sl_synth_comp)c, .damping = ot->damping, .set_min = ot->set_min,
                .set_max = ot->set_max, .f_min_hz = ot->f_set_min_hz,
                .f_max_hz = ot->f_set_max_hz, .ok = ot->ok_set};
        }
    }
    a->dampings_ok = sl_synth_dampings_ok(a->sets, a->n_sets);
    return SL_OK;
}

const char *sl_analysis_dampings_text(const sl_analysis *a, char *buf, size_t n)
{
    static const char *const comp[SL_SYNTH_NCOMP] = {"H1", "H2", "V"};
    if (!buf || n == 0)
        return buf;
    buf[0] = '\0';
    if (!a || a->n_dampings == 0) {
        snprintf(buf, n, "none");
        return buf;
    }
    size_t used = 0;
    for (size_t q = 0; q < a->n_dampings && used < n; q++) {
        const sl_analysis_damping *d = &a->dampings[q];
        int w = snprintf(buf + used, n - used, "%s%s %g %%: %.3f-%.3f %s", q ? "; " : "",
                         comp[d->comp], 100 * d->damping, d->set_min, d->set_max,
                         d->ok ? "ok" : "OUTSIDE");
        if (w < 0)
            break;
        used += (size_t)w;
    }
    return buf;
}

static sl_status check_opts(const sl_floor *fl, const sl_analysis_opts *o, sl_error *err)
{
    const char *path = fl ? fl->path : NULL;
    if (!fl || !o || !o->mu || o->n_mu < 1)
        return sl_error_set(err, SL_EINVAL, path, 0, "analysis: no friction values");
    if (o->n_sets == 0) {
        if (!(o->rel_se >= 0) || !(o->abs_se_m >= 0) || !(o->rel_se > 0 || o->abs_se_m > 0))
            return sl_error_set(err, SL_EINVAL, path, 0, "analysis: target standard errors "
                                "(relative %g, absolute %g m) must be >= 0, one > 0",
                                o->rel_se, o->abs_se_m);
        if (!(o->plan_margin >= 1) || !(o->plan_growth > 1))
            return sl_error_set(err, SL_EINVAL, path, 0, "analysis: plan margin %g must be >= 1, "
                                "growth %g > 1", o->plan_margin, o->plan_growth);
        if (o->max_sets < 2 || o->first_batch < 2 || o->min_batch < 1)
            return sl_error_set(err, SL_EINVAL, path, 0, "analysis: max_sets %zu and first "
                                "batch %zu must be >= 2, min batch %zu >= 1", o->max_sets,
                                o->first_batch, o->min_batch);
    }
    if (!(o->scatter >= 0 && o->scatter <= SL_SCATTER_SIGMA_MAX))
        return sl_error_set(err, SL_EINVAL, path, 0,
                            "analysis: intensity scatter %g outside [0, %g]", o->scatter,
                            SL_SCATTER_SIGMA_MAX);
    if (o->boot_resamples > 0 && !(o->band_level > 0 && o->band_level < 1))
        return sl_error_set(err, SL_EINVAL, path, 0, "analysis: band level %g outside (0, 1)",
                            o->band_level);
    return SL_OK;
}

sl_analysis *sl_analysis_run(const sl_floor *fl, const sl_analysis_opts *o, sl_error *err)
{
    if (check_opts(fl, o, err))
        return NULL;
    const int adaptive = o->n_sets == 0;
    const size_t cap_sets = adaptive ? o->max_sets : o->n_sets;
    const size_t n_mu = o->n_mu;
    sl_analysis *a = calloc(1, sizeof *a);
    sl_synth *plan = NULL;
    sl_set *sets = NULL;
    sl_slide_result *res = NULL;
    double *peak = NULL, *best = NULL;
    int *noslide = NULL;
    size_t *n_skip = NULL;
    sl_spectrum *fb[2] = {NULL, NULL};
    sl_asce *asce = NULL;
    sl_scatter *scat = NULL;
    double *err_k = NULL;
    if (!a)
        goto nomem;
    /* with scatter, each set's expected peak over its intensity (R3),
     * from the NLTHA on the scatter's log grid */
    a->scatter = o->scatter;
    a->n_nltha_mu = n_mu;
    if (o->scatter > 0) {
        if (!(scat = sl_scatter_alloc(o->scatter, o->mu, n_mu, err)))
            goto fail;
        sl_scatter_grid(scat, &a->n_nltha_mu);
    }
    a->sets = calloc(cap_sets, sizeof *a->sets);
    a->pgd_m = calloc(cap_sets, sizeof *a->pgd_m);
    a->conv = calloc(n_mu, sizeof *a->conv);
    a->design_lo_m = calloc(n_mu, sizeof *a->design_lo_m);
    a->design_hi_m = calloc(n_mu, sizeof *a->design_hi_m);
    a->design_se_m = calloc(n_mu, sizeof *a->design_se_m);
    a->err_est_m = calloc(n_mu, sizeof *a->err_est_m);
    a->vr_f_hz = calloc(n_mu, sizeof *a->vr_f_hz);
    a->vr_corr_sa = calloc(n_mu, sizeof *a->vr_corr_sa);
    a->vr_corr_pgv = calloc(n_mu, sizeof *a->vr_corr_pgv);
    a->vr_factor = calloc(n_mu, sizeof *a->vr_factor);
    sets = calloc(cap_sets, sizeof *sets);
    res = calloc(scat ? 1 : cap_sets * n_mu, sizeof *res); /* (R3) keeps its own */
    err_k = calloc(cap_sets * n_mu, sizeof *err_k);
    peak = calloc(cap_sets * n_mu, sizeof *peak);
    n_skip = calloc(n_mu, sizeof *n_skip);
    noslide = calloc(n_mu, sizeof *noslide);
    best = calloc(n_mu, sizeof *best);
    if (!a->sets || !a->pgd_m || !a->conv || !a->design_lo_m || !a->design_hi_m || !a->design_se_m ||
        !a->err_est_m || !a->vr_f_hz || !a->vr_corr_sa || !a->vr_corr_pgv || !a->vr_factor ||
        !sets ||
        !res || !peak || !n_skip || !noslide || !best || !err_k)
        goto nomem;
    a->zpa_h_ms2 = sl_asce_floor_zpa_h(fl); /* the larger horizontal */
    a->av_ms2 = fl->comp[SL_FLOOR_V].zpa_ms2;
    a->floor_seed = sl_analysis_floor_seed(o->seed, fl);

    sl_synth_params sp;
    sl_synth_params_default(&sp);
    sp.psd_report = 0; /* the App. B PSD (psd_frac 0: reported only) is shown nowhere here */
    sl_synth_target tgt[SL_SYNTH_NCOMP];
    if (sl_synth_targets_floor(fl, 0.0, tgt, err))
        goto fail;
    size_t n_t = (size_t)(SL_SYNTH_DURATION_S / SL_SYNTH_DT_S + 0.5) + 1;
    plan = sl_synth_alloc(n_t, SL_SYNTH_DT_S, &sp, err);
    if (!plan)
        goto fail;
    sl_slide_opts so;
    sl_slide_opts_default(&so);
    so.substeps = o->substeps;
    so.rtol = o->rtol;
    prog_ctx pc = {o};

    /* 1-2. batches of synthesis and NLTHA until converged (or the fixed count) */
    size_t n = 0, want = adaptive ? (o->first_batch < cap_sets ? o->first_batch : cap_sets)
                                  : o->n_sets;
    for (;;) {
        size_t nb = want - n;
        double t0 = sl_clock_s();
        sl_status st = sl_synth_make_sets(plan, tgt, a->floor_seed, n, nb, a->sets + n,
                                          synth_progress, &pc, err);
        if (st != SL_OK && st != SL_ENOCONV)
            goto fail;
        a->n_sets = want;
        for (size_t s = n; s < want; s++)
            for (int c = 0; c < SL_SYNTH_NCOMP; c++) {
                a->n_failed_motions += !a->sets[s].check[c].pass;
                a->n_extra_attempts += a->sets[s].check[c].attempt;
            }
        a->time_synth_s += sl_clock_s() - t0;

        t0 = sl_clock_s();
        for (size_t s = n; s < want; s++) {
            sets[s] = a->sets[s].set;
            a->pgd_m[s] = sl_set_pgd_100_40(&sets[s]);
        }
        if (o->progress)
            o->progress(o->progress_ctx, "nltha", n, want);
        if (scat ? sl_scatter_slide_batch(scat, sets + n, nb, &so, peak + n * n_mu,
                                          err_k + n * n_mu, err)
                 : sl_slide_batch(sets + n, nb, o->mu, n_mu, &so, res + n * n_mu, err))
            goto fail;
        if (o->progress)
            o->progress(o->progress_ctx, "nltha", want, want);
        for (size_t i = n * n_mu; i < want * n_mu; i++) {
            size_t k = i % n_mu;
            /* "need no NLTHA": skipped (mu above the set's threshold), or
             * with scatter zero at every intensity */
            if (scat) {
                n_skip[k] += peak[i] == 0;
            } else {
                peak[i] = res[i].peak_m;
                err_k[i] = res[i].err_est_m;
                n_skip[k] += (res[i].flags & SL_SLIDE_SKIPPED) != 0;
            }
            a->err_est_m[k] = fmax(a->err_est_m[k], err_k[i]);
        }
        a->time_nltha_s += sl_clock_s() - t0;
        n = want;
        a->n_batches++;

        t0 = sl_clock_s();
        double worst = 0;
        if (conv_update(a, peak, n, o, &worst, err))
            goto fail;
        a->time_stats_s += sl_clock_s() - t0;
        if (!adaptive) {
            a->stop = SL_ANALYSIS_STOP_FIXED;
            break;
        }
        if (a->n_unconverged == 0) {
            a->stop = SL_ANALYSIS_STOP_CONVERGED;
            break;
        }
        if (n >= cap_sets) {
            a->stop = SL_ANALYSIS_STOP_MAX_SETS;
            break;
        }
        /* next batch: what the worst mu needs with the margin (stats.h (4)) */
        want = sl_stats_plan_next(n, worst, o->plan_margin, o->min_batch, o->plan_growth,
                                  cap_sets);
    }
    /* every other damping of the file on the motions' own spectra, once on
     * all n sets (the set mean is over every set of the floor) */
    double t0 = sl_clock_s();
    if (store_dampings(a, plan, fl, &sp, err))
        goto fail;
    a->time_checks_s = sl_clock_s() - t0;
    a->time_synth_s += a->time_checks_s;

    t0 = sl_clock_s();
    if (conv_band(a, peak, n, o, err))
        goto fail;
    a->time_stats_s += sl_clock_s() - t0;
    for (size_t k = 0; k < n_mu; k++) {
        a->design_lo_m[k] = a->conv[k].design_lo_m;
        a->design_hi_m[k] = a->conv[k].design_hi_m;
        a->design_se_m[k] = a->conv[k].design_se_m;
        noslide[k] = n_skip[k] == n;
        a->n_mu_skipped += (size_t)noslide[k];
    }

    t0 = sl_clock_s();
    /* 3. ASCE on the 10 % spectra (or the documented fallback) */
    const sl_spectrum *s10[2] = {sl_floor_sa10(fl, SL_FLOOR_H1), sl_floor_sa10(fl, SL_FLOOR_H2)};
    if (!s10[0] || !s10[1]) {
        a->sa10_fallback = 1;
        for (int c = 0; c < 2; c++)
            if (!(fb[c] = mean_spectrum(a, c, err)))
                goto fail;
        s10[0] = fb[0];
        s10[1] = fb[1];
    }
    sl_asce_source ai; /* borrows the floor's or the fallback spectra: nothing to free */
    if (sl_asce_input_from_floor(fl, s10, &ai, err))
        goto fail;
    ai.in.fs = o->fs_asce; /* pgd_m NAN: the common cap is applied in design.c */
    asce = sl_asce_alloc(&ai.in, err);
    if (!asce)
        goto fail;
    for (size_t k = 0; k < n_mu; k++) {
        sl_asce_result ar;
        if (sl_asce_eval(asce, o->mu[k], &ar, err))
            goto fail;
        best[k] = ar.delta_best_m;
        a->vr_f_hz[k] = ar.fes_hz > 0 && isfinite(ar.fes_hz) ? ar.fes_hz : NAN;
    }
    double t1 = sl_clock_s();
    if (vr_measure(a, peak, n, n_mu, err))
        goto fail;
    a->time_stats_s += sl_clock_s() - t1;

    /* 4. design */
    sl_design_input di;
    sl_design_input_default(&di);
    di.n_mu = n_mu;
    di.n_sets = n;
    di.mu = o->mu;
    di.peak_m = peak;
    di.no_slide = noslide;
    di.asce_best_m = best;
    di.pgd_m = a->pgd_m;
    di.zpa_h_ms2 = a->zpa_h_ms2;
    di.fs_nltha = o->fs_nltha;
    di.fs_asce = o->fs_asce;
    di.policy = o->policy;
    a->design = sl_design_compute(&di, err);
    if (!a->design)
        goto fail;

    a->time_asce_s = sl_clock_s() - t0;
    size_t used = 0;
    a->note[0] = '\0';
#define NOTE(...)                                                                          \
    do {                                                                                   \
        int w_ = snprintf(a->note + used, sizeof a->note - used, __VA_ARGS__);             \
        if (w_ > 0 && (size_t)w_ < sizeof a->note - used)                                  \
            used += (size_t)w_;                                                            \
    } while (0)
    if (a->stop == SL_ANALYSIS_STOP_MAX_SETS)
        NOTE("not converged: after %zu sets the standard error of the design value is above "
             "its target at %zu friction value(s), at worst %.1f %% of the value. ",
             n, a->n_unconverged, 100 * a->worst_rel_se);
    if (a->sa10_fallback)
        NOTE("the file gives no 10 %%-damped horizontal spectra: the ASCE method uses the "
             "mean 10 %%-damped spectra of the %zu synthesized sets. ", n);
    if (a->n_failed_motions)
        NOTE("%zu synthesized motion(s) failed a quality check (see Motion quality). ",
             a->n_failed_motions);
    if (n < SL_NLTHA_MIN_SETS)
        NOTE("only %zu motion sets: ASCE/SEI 43-05 asks for at least %d. ", n,
             SL_NLTHA_MIN_SETS);
#undef NOTE
    goto cleanup;
nomem:
    sl_error_set(err, SL_ENOMEM, fl->path, 0, "out of memory");
fail:
    if (err && !err->file[0] && fl->path)
        snprintf(err->file, sizeof err->file, "%s", fl->path);
    sl_analysis_free(a);
    a = NULL;
cleanup:
    sl_scatter_free(scat);
    free(err_k);
    free(sets);
    free(res);
    free(peak);
    free(n_skip);
    free(noslide);
    free(best);
    sl_spectrum_free(fb[0]);
    sl_spectrum_free(fb[1]);
    sl_asce_free(asce);
    sl_synth_free(plan);
    return a;
}
