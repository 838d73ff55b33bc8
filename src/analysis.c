/* analysis.c - the per-floor study; see analysis.h. */
#include "analysis.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <zlib.h>

#include "method/asce.h"
#include "method/asce_input.h"
#include "slide/slide.h"
#include "signal/spectrum.h"
#include "core/units.h"


static double wall_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void sl_analysis_opts_default(sl_analysis_opts *o)
{
    memset(o, 0, sizeof *o);
    o->n_sets = SL_ANALYSIS_DEFAULT_SETS;
    o->seed = 1;
    o->substeps = SL_SLIDE_DEFAULT_SUBSTEPS;
    o->rtol = SL_SLIDE_DEFAULT_RTOL;
    o->policy = SL_CLEARANCE_NLTHA;
    o->fs_nltha = SL_NLTHA_FS;
    o->fs_asce = SL_ASCE_FS;
}

uint64_t sl_analysis_floor_seed(uint64_t seed, const char *floor_name)
{
    uLong c = crc32(0L, Z_NULL, 0);
    c = crc32(c, (const Bytef *)floor_name, (uInt)strlen(floor_name));
    return seed ^ ((uint64_t)(c & 0xffffffffUL) << 32);
}

void sl_analysis_free(sl_analysis *a)
{
    if (!a)
        return;
    sl_design_free(a->design);
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

sl_analysis *sl_analysis_run(const sl_floor *fl, const sl_analysis_opts *o, sl_error *err)
{
    if (!fl || !o || o->n_sets < 1 || !o->mu || o->n_mu < 1) {
        sl_error_set(err, SL_EINVAL, fl ? fl->path : NULL, 0, "analysis: no sets or no friction values");
        return NULL;
    }
    sl_analysis *a = calloc(1, sizeof *a);
    sl_synth *plan = NULL;
    sl_set *sets = NULL;
    sl_slide_result *res = NULL;
    double *peak = NULL, *best = NULL;
    int *noslide = NULL;
    sl_spectrum *fb[2] = {NULL, NULL};
    sl_asce *asce = NULL;
    if (!a)
        goto nomem;
    a->n_sets = o->n_sets;
    a->sets = calloc(o->n_sets, sizeof *a->sets);
    a->pgd_m = calloc(o->n_sets, sizeof *a->pgd_m);
    if (!a->sets || !a->pgd_m)
        goto nomem;
    a->zpa_h_ms2 = sl_asce_floor_zpa_h(fl); /* the larger horizontal */
    a->av_ms2 = fl->comp[SL_FLOOR_V].zpa_ms2;

    /* 1. synthesis */
    double t0 = wall_s();
    sl_synth_params sp;
    sl_synth_params_default(&sp);
    sl_synth_target tgt[SL_SYNTH_NCOMP];
    if (sl_synth_targets_floor(fl, 0.0, tgt, err))
        goto fail;
    size_t n = (size_t)(SL_SYNTH_DURATION_S / SL_SYNTH_DT_S + 0.5) + 1;
    plan = sl_synth_alloc(n, SL_SYNTH_DT_S, &sp, err);
    if (!plan)
        goto fail;
    prog_ctx pc = {o};
    sl_status st = sl_synth_make_sets(plan, tgt, sl_analysis_floor_seed(o->seed, fl->name), 0,
                                      o->n_sets, a->sets, synth_progress, &pc, err);
    if (st != SL_OK && st != SL_ENOCONV)
        goto fail;
    for (size_t s = 0; s < o->n_sets; s++)
        for (int c = 0; c < SL_SYNTH_NCOMP; c++)
            a->n_failed_motions += !a->sets[s].check[c].pass;

    a->time_synth_s = wall_s() - t0;
    t0 = wall_s();
    /* 2. NLTHA */
    sets = calloc(o->n_sets, sizeof *sets);
    res = calloc(o->n_sets * o->n_mu, sizeof *res);
    peak = calloc(o->n_sets * o->n_mu, sizeof *peak);
    noslide = calloc(o->n_mu, sizeof *noslide);
    best = calloc(o->n_mu, sizeof *best);
    if (!sets || !res || !peak || !noslide || !best)
        goto nomem;
    for (size_t s = 0; s < o->n_sets; s++) {
        sets[s] = a->sets[s].set;
        a->pgd_m[s] = sl_set_pgd_100_40(&sets[s]);
    }
    if (o->progress)
        o->progress(o->progress_ctx, "nltha", 0, o->n_sets);
    sl_slide_opts so;
    sl_slide_opts_default(&so);
    so.substeps = o->substeps;
    so.rtol = o->rtol;
    if (sl_slide_batch(sets, o->n_sets, o->mu, o->n_mu, &so, res, err))
        goto fail;
    if (o->progress)
        o->progress(o->progress_ctx, "nltha", o->n_sets, o->n_sets);
    for (size_t k = 0; k < o->n_mu; k++) {
        int all = 1;
        for (size_t s = 0; s < o->n_sets; s++) {
            const sl_slide_result *r = &res[s * o->n_mu + k];
            peak[s * o->n_mu + k] = r->peak_m;
            all &= (r->flags & SL_SLIDE_SKIPPED) != 0;
        }
        noslide[k] = all;
        a->n_mu_skipped += (size_t)all;
    }

    a->time_nltha_s = wall_s() - t0;
    t0 = wall_s();
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
    for (size_t k = 0; k < o->n_mu; k++) {
        sl_asce_result ar;
        if (sl_asce_eval(asce, o->mu[k], &ar, err))
            goto fail;
        best[k] = ar.delta_best_m;
    }

    /* 4. design */
    sl_design_input di;
    sl_design_input_default(&di);
    di.n_mu = o->n_mu;
    di.n_sets = o->n_sets;
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

    a->time_asce_s = wall_s() - t0;
    size_t used = 0;
    a->note[0] = '\0';
#define NOTE(...)                                                                          \
    do {                                                                                   \
        int w_ = snprintf(a->note + used, sizeof a->note - used, __VA_ARGS__);             \
        if (w_ > 0 && (size_t)w_ < sizeof a->note - used)                                  \
            used += (size_t)w_;                                                            \
    } while (0)
    if (a->sa10_fallback)
        NOTE("the file gives no 10 %%-damped horizontal spectra: the ASCE method uses the "
             "mean 10 %%-damped spectra of the %zu synthesized sets. ", o->n_sets);
    if (a->n_failed_motions)
        NOTE("%zu synthesized motion(s) failed a quality check (see Motion quality). ",
             a->n_failed_motions);
    if (o->n_sets < SL_NLTHA_MIN_SETS)
        NOTE("only %zu motion sets: ASCE/SEI 43-05 asks for at least %d. ", o->n_sets,
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
    free(sets);
    free(res);
    free(peak);
    free(noslide);
    free(best);
    sl_spectrum_free(fb[0]);
    sl_spectrum_free(fb[1]);
    sl_asce_free(asce);
    sl_synth_free(plan);
    return a;
}
