/* study_cross.c - part 5 of the study (study_parts.h): where the crossover
 * of part 3 comes from. One change at a time from part 3's setting, leaving
 * one record out, and random seven-record draws from the recorded sets. */
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/motion_set.h"
#include "io/setdir.h"
#include "study/study_parts.h"

const char *const sl_study_p5_change_names[SL_STUDY_P5_NCHANGES] = {
    "none (part 3 at 0.4 g)",
    "no high-pass before matching",
    "matching aimed at the target itself (aim 1.00, not 1.03)",
    "no vertical (NLTHA without V, ASCE with A_v = 0)",
    "scaled to 0.8 g instead of 0.4 g",
    "elastic-plastic friction model (U_y 1e-4 m) instead of the Coulomb engine",
    "no cap",
    "cap on the mean PGD of H1 instead of the 100-40 combination",
};

/* A design recomputed from the spectra sp with per-set displacements pgd
 * and the cap factor cap; its crossover x (NAN: none). */
static double cross_with_cap(const sl_study_spectra *sp, const double *pgd, double cap,
                             sl_error *err)
{
    int *noslide = calloc(sp->n_mu, sizeof *noslide);
    if (!noslide)
        return NAN;
    for (size_t k = 0; k < sp->n_mu; k++) {
        noslide[k] = 1;
        for (size_t s = 0; s < sp->n_sets; s++)
            noslide[k] &= sp->peak_m[s * sp->n_mu + k] == 0.0;
    }
    sl_design_input di;
    sl_design_input_default(&di);
    di.n_mu = sp->n_mu;
    di.n_sets = sp->n_sets;
    di.mu = sp->mu;
    di.peak_m = sp->peak_m;
    di.no_slide = noslide;
    di.asce_best_m = sp->asce_mean_m;
    di.pgd_m = pgd;
    di.zpa_h_ms2 = sp->pga_ms2;
    di.cap_factor = cap;
    sl_design *d = sl_design_compute(&di, err);
    double x = d && d->has_crossover ? d->crossover_x : NAN;
    sl_design_free(d);
    free(noslide);
    return x;
}

/* Spectra of the sets m[idx[0..n-1]] scaled to level_g (V zero when no_v),
 * on part 3's grid of x, with engine options so (NULL: defaults). */
static sl_study_spectra *spectra_of(const sl_synth_set *m, const size_t *idx, size_t n,
                                    double level_g, int no_v, const sl_slide_opts *so,
                                    sl_error *err)
{
    sl_motion **own = calloc(3 * n, sizeof *own);
    sl_set *sets = calloc(n, sizeof *sets);
    sl_study_spectra *sp = NULL;
    int bad = !own || !sets;
    for (size_t i = 0; i < n && !bad; i++) {
        for (int c = 0; c < SL_SYNTH_NCOMP; c++) {
            sl_motion *x = own[3 * i + (size_t)c] =
                sl_motion_copy(sl_synth_set_motion(&m[idx[i]], (sl_synth_comp)c));
            if (!x)
                bad = 1;
            else
                sl_motion_scale(x, c == SL_SYNTH_V && no_v ? 0.0 : level_g);
        }
        sets[i] = (sl_set){own[3 * i], own[3 * i + 1], own[3 * i + 2]};
    }
    const double pga = level_g * SL_G;
    double mu[SL_STUDY_P3_NX];
    for (size_t k = 0; k < SL_STUDY_P3_NX; k++)
        mu[k] = (SL_STUDY_P3_X0 + SL_STUDY_P3_DX * (double)k) * pga / SL_G;
    if (bad)
        sl_error_set(err, SL_ENOMEM, NULL, 0, "out of memory");
    else
        sp = sl_study_spectra_compute(sets, n, mu, SL_STUDY_P3_NX, so, err);
    for (size_t i = 0; own && i < 3 * n; i++)
        sl_motion_free(own[i]);
    free(own);
    free(sets);
    return sp;
}

static double cross_of(const sl_study_spectra *sp)
{
    return sp->design->has_crossover ? sp->design->crossover_x : NAN;
}

/* Crossover of the seven ground records matched with params p at 1 g. */
static sl_status rematch(const char *records, const sl_synth_params *p, double *x,
                         sl_error *err)
{
    sl_synth_set m[SL_STUDY_NGROUND];
    memset(m, 0, sizeof m);
    sl_status st = SL_OK;
    for (size_t i = 0; i < SL_STUDY_NGROUND && st == SL_OK; i++) {
        char dir[4200];
        sl_set rec;
        snprintf(dir, sizeof dir, "%s/%s", records, sl_study_ground.e[i].dir);
        if ((st = sl_set_read_dir(dir, &rec, err)))
            break;
        st = sl_study_match_rg160_p(&rec, SL_STUDY_ZETA, SL_G, p, &m[i], err);
        sl_set_free_motions(&rec);
        if (st == SL_ENOCONV)
            st = SL_OK; /* kept, as in part 3 */
    }
    size_t idx[SL_STUDY_NGROUND];
    for (size_t i = 0; i < SL_STUDY_NGROUND; i++)
        idx[i] = i;
    sl_study_spectra *sp = NULL;
    if (st == SL_OK && !(sp = spectra_of(m, idx, SL_STUDY_NGROUND, SL_STUDY_P5_PGA_G, 0, NULL, err)))
        st = err ? err->code : SL_ENOMEM;
    *x = sp ? cross_of(sp) : NAN;
    sl_study_spectra_free(sp);
    for (size_t i = 0; i < SL_STUDY_NGROUND; i++)
        sl_synth_set_clear(&m[i]);
    return st;
}

static void range_of(const double *x, size_t n, double *lo, double *hi, size_t *none)
{
    *lo = INFINITY;
    *hi = -INFINITY;
    size_t k = 0;
    for (size_t i = 0; i < n; i++) {
        if (isnan(x[i])) {
            k++;
            continue;
        }
        *lo = fmin(*lo, x[i]);
        *hi = fmax(*hi, x[i]);
    }
    if (k == n)
        *lo = *hi = NAN;
    if (none)
        *none = k;
}

/* The changes that reuse part 3's matched sets. */
static sl_status changes_on_part3(const sl_study_part3 *p3, sl_study_part5 *p, sl_error *err)
{
    size_t idx[SL_STUDY_NGROUND];
    for (size_t i = 0; i < SL_STUDY_NGROUND; i++)
        idx[i] = i;
    const sl_synth_set *m = p3->matched;
    sl_study_spectra *sp = spectra_of(m, idx, SL_STUDY_NGROUND, SL_STUDY_P5_PGA_G, 0, NULL, err);
    if (!sp)
        return err ? err->code : SL_ENOMEM;
    p->cross[SL_STUDY_P5_BASE] = cross_of(sp);
    /* the ASCE level below x 0.2, and the NLTHA/ASCE ratio at the crossover */
    p->asce_lo_m = INFINITY;
    p->asce_hi_m = 0;
    p->ratio_at_cross = NAN;
    for (size_t k = 0; k < sp->n_mu; k++) {
        const sl_design_row *r = &sp->design->rows[k];
        if (r->x < SL_STUDY_P5_FLAT_X) {
            p->asce_lo_m = fmin(p->asce_lo_m, sp->asce_mean_m[k]);
            p->asce_hi_m = fmax(p->asce_hi_m, sp->asce_mean_m[k]);
        }
        if (isnan(p->ratio_at_cross) && r->x >= p->cross[SL_STUDY_P5_BASE])
            p->ratio_at_cross = sp->nltha_mean_m[k] / sp->asce_mean_m[k];
    }
    p->cross[SL_STUDY_P5_NO_CAP] = cross_with_cap(sp, sp->pgd_m, 1e6, err);
    double pgd_h1[SL_STUDY_NGROUND];
    for (size_t i = 0; i < SL_STUDY_NGROUND; i++)
        pgd_h1[i] = sl_motion_pgd(m[i].set.h1) * SL_STUDY_P5_PGA_G;
    p->cross[SL_STUDY_P5_CAP_H1] = cross_with_cap(sp, pgd_h1, SL_CAP_FACTOR, err);
    sl_study_spectra_free(sp);

    struct {
        int which;
        double level;
        int no_v;
        int plastic;
    } runs[] = {{SL_STUDY_P5_NO_V, SL_STUDY_P5_PGA_G, 1, 0},
                {SL_STUDY_P5_SCALE, 0.8, 0, 0},
                {SL_STUDY_P5_PLASTIC, SL_STUDY_P5_PGA_G, 0, 1}};
    for (size_t q = 0; q < sizeof runs / sizeof runs[0]; q++) {
        sl_slide_opts so;
        sl_slide_opts_default(&so);
        if (runs[q].plastic)
            so.model = SL_MODEL_PLASTIC;
        sp = spectra_of(m, idx, SL_STUDY_NGROUND, runs[q].level, runs[q].no_v, &so, err);
        if (!sp)
            return err ? err->code : SL_ENOMEM;
        p->cross[runs[q].which] = cross_of(sp);
        sl_study_spectra_free(sp);
    }
    /* leave one out */
    for (size_t out = 0; out < SL_STUDY_NGROUND; out++) {
        size_t six[SL_STUDY_NGROUND - 1], k = 0;
        for (size_t i = 0; i < SL_STUDY_NGROUND; i++)
            if (i != out)
                six[k++] = i;
        sp = spectra_of(m, six, k, SL_STUDY_P5_PGA_G, 0, NULL, err);
        if (!sp)
            return err ? err->code : SL_ENOMEM;
        p->loo[out] = cross_of(sp);
        sl_study_spectra_free(sp);
    }
    range_of(p->loo, SL_STUDY_NGROUND, &p->loo_lo, &p->loo_hi, NULL);
    return SL_OK;
}

/* Random seven-record draws from the records of part 4's groups. */
static sl_status draws(const char *records, sl_study_part5 *p,
                       void (*progress)(void *, const char *), void *ctx, sl_error *err)
{
    size_t cap = 0;
    for (size_t g = 0; g < SL_STUDY_NGROUPS; g++)
        cap += sl_study_groups[g].n;
    sl_synth_set *pool = calloc(cap, sizeof *pool);
    if (!pool)
        return sl_error_set(err, SL_ENOMEM, NULL, 0, "out of memory");
    sl_status st = SL_OK;
    size_t n = 0;
    for (size_t g = 0; g < SL_STUDY_NGROUPS && st == SL_OK; g++)
        for (size_t i = 0; i < sl_study_groups[g].n && st == SL_OK; i++) {
            char dir[4200];
            sl_set rec;
            snprintf(dir, sizeof dir, "%s/%s", records, sl_study_groups[g].e[i].dir);
            if ((st = sl_set_read_dir(dir, &rec, err)))
                break;
            st = sl_study_match_rg160(&rec, SL_STUDY_ZETA, SL_G, &pool[n], err);
            sl_set_free_motions(&rec);
            if (st == SL_ENOCONV)
                st = SL_OK;
            n += st == SL_OK;
        }
    p->n_pool = n;
    if (progress && st == SL_OK) {
        char msg[96];
        snprintf(msg, sizeof msg, "part 5: %zu records matched for the draws", n);
        progress(ctx, msg);
    }
    gsl_rng *rng = st == SL_OK ? gsl_rng_alloc(gsl_rng_mt19937) : NULL;
    if (st == SL_OK && (!rng || n < SL_STUDY_NGROUND))
        st = sl_error_set(err, rng ? SL_EINVAL : SL_ENOMEM, NULL, 0,
                          "part 5: %zu records for seven-record draws", n);
    if (rng)
        gsl_rng_set(rng, SL_STUDY_P5_SEED);
    size_t all[256], pick[SL_STUDY_NGROUND];
    for (size_t i = 0; i < n && i < 256; i++)
        all[i] = i;
    for (size_t d = 0; d < SL_STUDY_P5_NDRAWS && st == SL_OK; d++) {
        gsl_ran_choose(rng, pick, SL_STUDY_NGROUND, all, n < 256 ? n : 256, sizeof(size_t));
        sl_study_spectra *sp = spectra_of(pool, pick, SL_STUDY_NGROUND, SL_STUDY_P5_PGA_G, 0,
                                          NULL, err);
        if (!sp) {
            st = err ? err->code : SL_ENOMEM;
            break;
        }
        p->draw[d] = cross_of(sp);
        const sl_design_row *r0 = &sp->design->rows[0];
        p->draws_cons += isnan(p->draw[d]) && !(r0->asce_design_m < r0->nltha_design_m);
        sl_study_spectra_free(sp);
    }
    if (st == SL_OK)
        range_of(p->draw, SL_STUDY_P5_NDRAWS, &p->draw_lo, &p->draw_hi, &p->draws_none);
    gsl_rng_free(rng);
    for (size_t i = 0; i < n; i++)
        sl_synth_set_clear(&pool[i]);
    free(pool);
    return st;
}

sl_status sl_study_part5_run(const char *records, const sl_study_part3 *p3, sl_study_part5 *p,
                             void (*progress)(void *, const char *), void *ctx, sl_error *err)
{
    memset(p, 0, sizeof *p);
    sl_status st = changes_on_part3(p3, p, err);
    sl_synth_params sp;
    sl_synth_params_default(&sp);
    sp.hp_frac = 0;
    if (st == SL_OK)
        st = rematch(records, &sp, &p->cross[SL_STUDY_P5_NO_HP], err);
    sl_synth_params_default(&sp);
    sp.aim = 1.0;
    if (st == SL_OK)
        st = rematch(records, &sp, &p->cross[SL_STUDY_P5_AIM1], err);
    if (progress && st == SL_OK)
        progress(ctx, "part 5: the changes and leave-one-out done");
    if (st == SL_OK)
        st = draws(records, p, progress, ctx, err);
    return st;
}
