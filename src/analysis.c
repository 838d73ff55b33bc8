/* analysis.c - the per-floor study; see analysis.h. */
#include "analysis.h"
#include "core/clock.h"

#include <gsl/gsl_statistics_double.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <omp.h>

#include "method/asce.h"
#include "method/asce_input.h"
#include "method/stats.h"
#include "slide/slide.h"
#include "method/scatter.h"
#include "plant/identity.h"
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

/* The one identity of a floor gives its seed (plant/identity.h). */
uint64_t sl_analysis_floor_seed(uint64_t seed, const sl_floor *fl)
{
    return sl_identity_seed(seed, fl);
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
    free(a->rock_lookup);
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
    if (isnan(o->scatter) || o->scatter > SL_SCATTER_SIGMA_MAX) /* < 0: the floor's */
        return sl_error_set(err, SL_EINVAL, path, 0,
                            "analysis: intensity scatter %g outside [0, %g] (or < 0: the "
                            "floor's)", o->scatter, SL_SCATTER_SIGMA_MAX);
    if (o->boot_resamples > 0 && !(o->band_level > 0 && o->band_level < 1))
        return sl_error_set(err, SL_EINVAL, path, 0, "analysis: band level %g outside (0, 1)",
                            o->band_level);
    return SL_OK;
}

/* One floor's run: the floor, the options, the result being built and the
 * working arrays of the steps below. */
typedef struct run {
    const sl_floor *fl;
    const sl_analysis_opts *o;
    sl_analysis *a;
    int adaptive;            /* o->n_sets == 0: sets added until converged */
    size_t cap_sets, n_mu;
    size_t n;                /* sets synthesized and run so far */
    sl_synth_params sp;
    sl_synth_target tgt[SL_SYNTH_NCOMP];
    sl_synth *plan;
    sl_slide_opts so;
    sl_scatter *scat;        /* with intensity scatter, else NULL */
    sl_set *sets;            /* the sets' motions, borrowed from a->sets */
    sl_slide_result *res;    /* n x n_mu (one when scat keeps its own) */
    double *peak, *err_k;    /* n x n_mu peaks and error estimates, m */
    double *best;            /* ASCE best estimate per mu, m */
    int *noslide;            /* per mu: no set slides */
    size_t *n_skip;          /* per mu: sets that need no NLTHA */
    sl_spectrum *fb[2];      /* the ASCE fallback spectra (H1, H2) */
    sl_asce *asce;
    prog_ctx pc;
} run;

static void run_free(run *r)
{
    sl_scatter_free(r->scat);
    free(r->err_k);
    free(r->sets);
    free(r->res);
    free(r->peak);
    free(r->n_skip);
    free(r->noslide);
    free(r->best);
    sl_spectrum_free(r->fb[0]);
    sl_spectrum_free(r->fb[1]);
    sl_asce_free(r->asce);
    sl_synth_free(r->plan);
}

/* The result and the working arrays, for up to cap_sets sets. */
static sl_status run_alloc(run *r, sl_error *err)
{
    const size_t cap_sets = r->cap_sets, n_mu = r->n_mu;
    sl_analysis *a = r->a = calloc(1, sizeof *a);
    if (!a)
        return sl_error_set(err, SL_ENOMEM, r->fl->path, 0, "out of memory");
    /* with scatter, each set's expected peak over its intensity (R3),
     * from the NLTHA on the scatter's log grid */
    a->scatter = r->o->scatter < 0 ? sl_scatter_sigma_of_floor(r->fl) : r->o->scatter; /* (R4) */
    a->n_nltha_mu = n_mu;
    if (!(a->scatter >= 0))
        return sl_error_set(err, SL_EINVAL, r->fl->path, 0,
                            "analysis: no intensity scatter from the floor's spectra");
    if (a->scatter > 0) {
        if (!(r->scat = sl_scatter_alloc(a->scatter, r->o->mu, n_mu, err)))
            return err ? err->code : SL_ENOMEM;
        sl_scatter_grid(r->scat, &a->n_nltha_mu);
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
    r->sets = calloc(cap_sets, sizeof *r->sets);
    r->res = calloc(r->scat ? 1 : cap_sets * n_mu, sizeof *r->res); /* (R3) keeps its own */
    r->err_k = calloc(cap_sets * n_mu, sizeof *r->err_k);
    r->peak = calloc(cap_sets * n_mu, sizeof *r->peak);
    r->n_skip = calloc(n_mu, sizeof *r->n_skip);
    r->noslide = calloc(n_mu, sizeof *r->noslide);
    r->best = calloc(n_mu, sizeof *r->best);
    if (!a->sets || !a->pgd_m || !a->conv || !a->design_lo_m || !a->design_hi_m ||
        !a->design_se_m || !a->err_est_m || !a->vr_f_hz || !a->vr_corr_sa || !a->vr_corr_pgv ||
        !a->vr_factor || !r->sets || !r->res || !r->peak || !r->n_skip || !r->noslide ||
        !r->best || !r->err_k)
        return sl_error_set(err, SL_ENOMEM, r->fl->path, 0, "out of memory");
    a->zpa_h_ms2 = sl_asce_floor_zpa_h(r->fl); /* the larger horizontal */
    a->av_ms2 = r->fl->comp[SL_FLOOR_V].zpa_ms2;
    a->floor_seed = sl_analysis_floor_seed(r->o->seed, r->fl);
    return SL_OK;
}

/* The floor's targets, the synthesis plan and the NLTHA options. */
static sl_status run_plan(run *r, sl_error *err)
{
    sl_synth_params_default(&r->sp);
    r->sp.psd_report = 0; /* the App. B PSD (psd_frac 0: reported only) is shown nowhere here */
    if (sl_synth_targets_floor(r->fl, 0.0, r->tgt, err))
        return err ? err->code : SL_EINVAL;
    size_t n_t = (size_t)(SL_SYNTH_DURATION_S / SL_SYNTH_DT_S + 0.5) + 1;
    if (!(r->plan = sl_synth_alloc(n_t, SL_SYNTH_DT_S, &r->sp, err)))
        return err ? err->code : SL_ENOMEM;
    sl_slide_opts_default(&r->so);
    r->so.substeps = r->o->substeps;
    r->so.rtol = r->o->rtol;
    r->pc.o = r->o;
    return SL_OK;
}

sl_status sl_analysis_make_sets(const sl_floor *fl, const sl_analysis_opts *o, size_t first,
                                size_t count, sl_synth_set *out, sl_error *err)
{
    run r = {.fl = fl, .o = o};
    sl_status st = run_plan(&r, err);
    if (!st)
        st = sl_synth_make_sets(r.plan, r.tgt, sl_analysis_floor_seed(o->seed, fl), first, count,
                                out, NULL, NULL, err);
    sl_synth_free(r.plan);
    return st == SL_ENOCONV ? SL_OK : st; /* a failed check is kept, as the run keeps it */
}

/* The NLTHA of one batch, each set's started as soon as its synthesis is
 * final (the ready callback of sl_synth_make_sets_then): a task per chunk
 * of SL_SLIDE_BATCH_CHUNK friction values, as sl_slide_batch would run it. */
typedef struct batch {
    run *r;
    size_t n;                /* the batch's first set */
    const double *grid;      /* the friction values integrated: o->mu, or the scatter grid */
    size_t nq, per_set;      /* their count, and chunks of them per set */
    sl_slide_result *res;    /* nb x nq */
    double nltha_s;          /* thread time of the NLTHA (and the sets' PGD), s */
    int team;                /* threads of the flow */
    sl_status st;            /* the first failure in (set, chunk) order, as sl_slide_batch */
    size_t first_item;
    sl_error err;
} batch;

static void nltha_chunk(batch *b, size_t k, size_t c)
{
    double t0 = sl_clock_s();
    const size_t k0 = c * SL_SLIDE_BATCH_CHUNK;
    const size_t kn = k0 + SL_SLIDE_BATCH_CHUNK <= b->nq ? SL_SLIDE_BATCH_CHUNK : b->nq - k0;
    sl_error e;
    sl_error_clear(&e);
    sl_status st = sl_slide_run(&b->r->sets[b->n + k], b->grid + k0, kn, &b->r->so,
                                b->res + k * b->nq + k0, &e);
    double dt = sl_clock_s() - t0;
    size_t item = k * b->per_set + c;
#pragma omp critical(sl_analysis_nltha)
    {
        b->nltha_s += dt;
        if (st && (!b->st || item < b->first_item)) {
            b->st = st;
            b->first_item = item;
            b->err = e;
        }
    }
}

/* Set b->n + k is synthesized: its PGD, then its NLTHA as tasks. */
static sl_status set_ready(void *ctx, size_t k, sl_error *err)
{
    (void)err;
    batch *b = ctx;
    run *r = b->r;
    const size_t s = b->n + k;
    double t0 = sl_clock_s();
    r->sets[s] = r->a->sets[s].set;
    r->a->pgd_m[s] = sl_set_pgd_100_40(&r->sets[s]);
    double dt = sl_clock_s() - t0;
    int team = omp_get_num_threads();
#pragma omp critical(sl_analysis_nltha)
    {
        b->nltha_s += dt;
        b->team = team;
    }
    for (size_t c = 0; c < b->per_set; c++) {
#pragma omp task default(none) firstprivate(b, k, c) /* by value: this frame may be gone */
        nltha_chunk(b, k, c);
    }
    return SL_OK;
}

/* One batch: sets r->n .. want-1 synthesized, each going on to its NLTHA at
 * every mu as soon as it is final, in one flow of tasks. time_synth_s and
 * time_nltha_s get thread time: the NLTHA's tasks are timed, and the rest
 * of the flow's wall time x threads (the synthesis, with the time threads
 * wait at the flow's end) is the synthesis'; on 1 thread, wall time. */
static sl_status run_batch(run *r, size_t want, sl_error *err)
{
    sl_analysis *a = r->a;
    const sl_analysis_opts *o = r->o;
    const size_t n = r->n, nb = want - n, n_mu = r->n_mu;
    batch b = {.r = r, .n = n, .grid = o->mu, .nq = n_mu, .team = 1};
    if (r->scat)
        b.grid = sl_scatter_grid(r->scat, &b.nq);
    b.per_set = (b.nq + SL_SLIDE_BATCH_CHUNK - 1) / SL_SLIDE_BATCH_CHUNK;
    b.res = r->scat ? calloc(nb * b.nq, sizeof *b.res) : r->res + n * n_mu;
    if (!b.res)
        return sl_error_set(err, SL_ENOMEM, NULL, 0, "analysis: out of memory");
    double t0 = sl_clock_s();
    sl_status st = sl_synth_make_sets_then(r->plan, r->tgt, a->floor_seed, n, nb, a->sets + n,
                                           synth_progress, &r->pc, set_ready, &b, err);
    double flow_s = (sl_clock_s() - t0) * (double)b.team;
    t0 = sl_clock_s();
    if (st == SL_OK || st == SL_ENOCONV) {
        st = b.st;
        if (st && err)
            *err = b.err;
    }
    if (!st && r->scat)
        st = sl_scatter_results(r->scat, b.res, nb, r->peak + n * n_mu, r->err_k + n * n_mu,
                                err);
    if (r->scat)
        free(b.res);
    if (st != SL_OK && st != SL_ENOCONV)
        return st;
    a->n_sets = want;
    for (size_t s = n; s < want; s++)
        for (int c = 0; c < SL_SYNTH_NCOMP; c++) {
            a->n_failed_motions += !a->sets[s].check[c].pass;
            a->n_extra_attempts += a->sets[s].check[c].attempt;
        }
    for (size_t i = n * n_mu; i < want * n_mu; i++) {
        size_t k = i % n_mu;
        /* "need no NLTHA": skipped (mu above the set's threshold), or
         * with scatter zero at every intensity */
        if (r->scat) {
            r->n_skip[k] += r->peak[i] == 0;
        } else {
            r->peak[i] = r->res[i].peak_m;
            r->err_k[i] = r->res[i].err_est_m;
            r->n_skip[k] += (r->res[i].flags & SL_SLIDE_SKIPPED) != 0;
        }
        a->err_est_m[k] = fmax(a->err_est_m[k], r->err_k[i]);
    }
    b.nltha_s += sl_clock_s() - t0;
    a->time_synth_s += flow_s > b.nltha_s ? flow_s - b.nltha_s : 0;
    a->time_nltha_s += b.nltha_s;
    if (o->progress)
        o->progress(o->progress_ctx, "nltha", want, want);
    r->n = want;
    a->n_batches++;
    return SL_OK;
}

/* 1-2. Batches of synthesis and NLTHA until converged, at the cap, or the
 * fixed count; the convergence statistics after each (time_stats_s). */
static sl_status run_sets(run *r, sl_error *err)
{
    sl_analysis *a = r->a;
    const sl_analysis_opts *o = r->o;
    size_t want = r->adaptive ? (o->first_batch < r->cap_sets ? o->first_batch : r->cap_sets)
                              : o->n_sets;
    for (;;) {
        sl_status st = run_batch(r, want, err);
        if (st)
            return st;
        double t0 = sl_clock_s(), worst = 0;
        if ((st = conv_update(a, r->peak, r->n, o, &worst, err)))
            return st;
        a->time_stats_s += sl_clock_s() - t0;
        if (!r->adaptive) {
            a->stop = SL_ANALYSIS_STOP_FIXED;
            return SL_OK;
        }
        if (a->n_unconverged == 0) {
            a->stop = SL_ANALYSIS_STOP_CONVERGED;
            return SL_OK;
        }
        if (r->n >= r->cap_sets) {
            a->stop = SL_ANALYSIS_STOP_MAX_SETS;
            return SL_OK;
        }
        /* next batch: what the worst mu needs with the margin (stats.h (4)) */
        want = sl_stats_plan_next(r->n, worst, o->plan_margin, o->min_batch, o->plan_growth,
                                  r->cap_sets);
    }
}

/* Every other damping of the file on the motions' own spectra, once on all
 * n sets (time_synth_s: the set mean is over every set of the floor); the
 * bootstrap band (time_stats_s); the mu at which no set slides. */
static sl_status run_bands(run *r, sl_error *err)
{
    sl_analysis *a = r->a;
    double t0 = sl_clock_s();
    sl_status st = store_dampings(a, r->plan, r->fl, &r->sp, err);
    if (st)
        return st;
    /* thread time: every thread is in the checks' loops */
    a->time_checks_s = (sl_clock_s() - t0) * (double)omp_get_max_threads();
    a->time_synth_s += a->time_checks_s;

    t0 = sl_clock_s();
    if ((st = conv_band(a, r->peak, r->n, r->o, err)))
        return st;
    a->time_stats_s += sl_clock_s() - t0;
    for (size_t k = 0; k < r->n_mu; k++) {
        a->design_lo_m[k] = a->conv[k].design_lo_m;
        a->design_hi_m[k] = a->conv[k].design_hi_m;
        a->design_se_m[k] = a->conv[k].design_se_m;
        r->noslide[k] = r->n_skip[k] == r->n;
        a->n_mu_skipped += (size_t)r->noslide[k];
    }
    return SL_OK;
}

/* 3. ASCE on the 10 % spectra (or the documented fallback): the best
 * estimate and f_es at every mu. */
static sl_status run_asce(run *r, sl_error *err)
{
    sl_analysis *a = r->a;
    const sl_spectrum *s10[2] = {sl_floor_sa10(r->fl, SL_FLOOR_H1),
                                 sl_floor_sa10(r->fl, SL_FLOOR_H2)};
    if (!s10[0] || !s10[1]) {
        a->sa10_fallback = 1;
        for (int c = 0; c < 2; c++)
            if (!(r->fb[c] = mean_spectrum(a, c, err)))
                return err ? err->code : SL_ENOMEM;
        s10[0] = r->fb[0];
        s10[1] = r->fb[1];
    }
    sl_asce_source ai; /* borrows the floor's or the fallback spectra: nothing to free */
    sl_status st = sl_asce_input_from_floor(r->fl, s10, &ai, err);
    if (st)
        return st;
    ai.in.fs = r->o->fs_asce; /* pgd_m NAN: the common cap is applied in design.c */
    if (!(r->asce = sl_asce_alloc(&ai.in, err)))
        return err ? err->code : SL_ENOMEM;
    for (size_t k = 0; k < r->n_mu; k++) {
        sl_asce_result ar;
        if ((st = sl_asce_eval(r->asce, r->o->mu[k], &ar, err)))
            return st;
        r->best[k] = ar.delta_best_m;
        a->vr_f_hz[k] = ar.fes_hz > 0 && isfinite(ar.fes_hz) ? ar.fes_hz : NAN;
    }
    return SL_OK;
}

/* 4. The design values of both methods, the cap and the policy. */
static sl_status run_design(run *r, sl_error *err)
{
    sl_analysis *a = r->a;
    const sl_analysis_opts *o = r->o;
    sl_design_input di;
    sl_design_input_default(&di);
    di.n_mu = r->n_mu;
    di.n_sets = r->n;
    di.mu = o->mu;
    di.peak_m = r->peak;
    di.no_slide = r->noslide;
    di.asce_best_m = r->best;
    di.pgd_m = a->pgd_m;
    di.zpa_h_ms2 = a->zpa_h_ms2;
    di.fs_nltha = o->fs_nltha;
    di.fs_asce = o->fs_asce;
    di.policy = o->policy;
    a->design = sl_design_compute(&di, err);
    return a->design ? SL_OK : err ? err->code : SL_ENOMEM;
}

/* The run's note (analysis.h): what the reader must know about n sets. */
static void run_note(sl_analysis *a, size_t n)
{
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
}

/* The steps in order, each timed once: synthesis and NLTHA (time_synth_s,
 * time_nltha_s, in run_batch and run_bands), the statistics (time_stats_s:
 * convergence, band and the variance-reduction diagnostic), ASCE and the
 * design (time_asce_s). */
sl_analysis *sl_analysis_run(const sl_floor *fl, const sl_analysis_opts *o, sl_error *err)
{
    if (check_opts(fl, o, err))
        return NULL;
    run r = {.fl = fl, .o = o, .adaptive = o->n_sets == 0, .n_mu = o->n_mu};
    r.cap_sets = r.adaptive ? o->max_sets : o->n_sets;
    sl_status st = run_alloc(&r, err);
    if (!st)
        st = run_plan(&r, err);
    if (!st)
        st = run_sets(&r, err);
    if (!st)
        st = run_bands(&r, err);
    double t0 = sl_clock_s();
    if (!st)
        st = run_asce(&r, err);
    double t_asce = sl_clock_s() - t0;
    t0 = sl_clock_s();
    if (!st)
        st = vr_measure(r.a, r.peak, r.n, r.n_mu, err);
    if (!st)
        r.a->time_stats_s += sl_clock_s() - t0;
    t0 = sl_clock_s(); /* the design: timed from here, not over the diagnostic */
    if (!st)
        st = run_design(&r, err);
    if (!st) {
        r.a->time_asce_s = t_asce + (sl_clock_s() - t0);
        run_note(r.a, r.n);
    } else {
        if (err && !err->file[0] && fl->path)
            snprintf(err->file, sizeof err->file, "%s", fl->path);
        sl_analysis_free(r.a);
        r.a = NULL;
    }
    run_free(&r);
    return r.a;
}
