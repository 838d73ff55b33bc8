/*
 * study_parts.c - parts 1-4 of the study reproduction as data
 * (study_parts.h, docs/validation.md).
 */
#include "study/study_parts.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/setdir.h"
#include "core/clock.h"

const double sl_study_levels_g[SL_STUDY_NLEVELS] = {0.2, 0.4, 0.6, 0.8};
const sl_model sl_study_p1_models[SL_STUDY_P1_NMODELS] = {SL_MODEL_EXACT, SL_MODEL_SMOOTH,
                                                          SL_MODEL_PLASTIC};
const char *const sl_study_p1_model_names[SL_STUDY_P1_NMODELS] = {
    "engine (Coulomb)", "smoothed, GSL msbdf", "elastic-plastic"};
const char *const sl_study_p1_model_tags[SL_STUDY_P1_NMODELS] = {"engine", "smooth", "plastic"};

/* Longest record folder path. */
#define PARTS_PATH_MAX 4200

double sl_study_pct(double to, double from)
{
    return from > 0 ? 100.0 * (to - from) / from : NAN;
}

/* Read the set in records/sub. */
static sl_status read_set(const char *records, const char *sub, sl_set *set, sl_error *err)
{
    char dir[PARTS_PATH_MAX];
    snprintf(dir, sizeof dir, "%s/%s", records, sub);
    return sl_set_read_dir(dir, set, err);
}

/* ---- Part 1 ---------------------------------------------------------- */

void sl_study_part1_free(sl_study_part1 *p)
{
    if (!p)
        return;
    for (int two = 0; two < 2; two++)
        for (int m = 0; m < SL_STUDY_P1_NMODELS; m++)
            sl_history_free(p->run[two][m].h);
    memset(p, 0, sizeof *p);
}

sl_status sl_study_part1_run(const char *records, sl_study_part1 *p, sl_error *err)
{
    memset(p, 0, sizeof *p);
    sl_set rec;
    sl_status st = read_set(records, SL_STUDY_P1_DIR, &rec, err);
    for (int two = 0; two < 2 && st == SL_OK; two++) {
        sl_set set = {rec.h1, two ? rec.h2 : NULL, NULL};
        double peak_e = NAN, dev = 0;
        for (int m = 0; m < SL_STUDY_P1_NMODELS && st == SL_OK; m++) {
            sl_slide_opts so;
            sl_slide_opts_default(&so);
            so.model = sl_study_p1_models[m];
            so.smooth_eta = SL_STUDY_SMOOTH_ETA;
            so.smooth_uy_m = SL_STUDY_SMOOTH_UY_M;
            so.plastic_uy_m = SL_STUDY_SMOOTH_UY_M;
            sl_study_p1_run *x = &p->run[two][m];
            double t0 = sl_clock_s();
            st = sl_slide_history(&set, SL_STUDY_P1_MU, &so, &x->r, &x->h, err);
            x->run_ms = 1e3 * (sl_clock_s() - t0);
            if (st != SL_OK)
                break;
            if (m == 0)
                peak_e = x->r.peak_m;
            else
                dev = fmax(dev, fabs(x->r.peak_m - peak_e) / peak_e);
        }
        p->dev[two] = dev;
    }
    sl_set_free_motions(&rec);
    return st;
}

/* ---- Part 2 ---------------------------------------------------------- */

void sl_study_part2_free(sl_study_part2 *p)
{
    if (!p)
        return;
    for (int i = 0; i < SL_STUDY_P2_NCASES; i++)
        sl_history_free(p->c[i].h);
    sl_synth_set_clear(&p->matched);
    memset(p, 0, sizeof *p);
}

sl_status sl_study_part2_run(const char *records, sl_study_part2 *p, sl_error *err)
{
    memset(p, 0, sizeof *p);
    sl_set rec;
    sl_status st = read_set(records, SL_STUDY_P2_DIR, &rec, err);
    if (st != SL_OK)
        return st;
    st = sl_study_match_rg160(&rec, SL_STUDY_ZETA, SL_STUDY_P2_PGA_G * SL_G, &p->matched, err);
    sl_set_free_motions(&rec);
    if (st && st != SL_ENOCONV)
        return st;
    sl_motion *x = p->matched.set.h1, *y = p->matched.set.h2, *z = p->matched.set.v;
    const struct {
        const char *name, *tag;
        sl_motion *h1, *h2, *v;
        int y_first;
    } cases[SL_STUDY_P2_NCASES] = {
        {"x", "x", x, NULL, NULL, 0},  {"y", "y", y, NULL, NULL, 1},
        {"x+y", "xy", x, y, NULL, 0},  {"x+z", "xz", x, NULL, z, 0},
        {"y+z", "yz", y, NULL, z, 1},  {"x+y+z", "xyz", x, y, z, 0},
    };
    st = SL_OK;
    for (int i = 0; i < SL_STUDY_P2_NCASES && st == SL_OK; i++) {
        sl_study_p2_case *c = &p->c[i];
        c->name = cases[i].name;
        c->tag = cases[i].tag;
        c->y_first = cases[i].y_first;
        sl_set set = {cases[i].h1, cases[i].h2, cases[i].v};
        sl_slide_opts so;
        sl_slide_opts_default(&so);
        st = sl_slide_history(&set, SL_STUDY_P2_MU, &so, &c->r, &c->h, err);
        /* axis 1 of the run is y when y drives alone */
        c->ux_m = c->y_first ? NAN : c->r.peak_x_m;
        c->uy_m = c->y_first ? c->r.peak_x_m : (cases[i].h2 ? c->r.peak_y_m : NAN);
    }
    if (st != SL_OK)
        return st;
    /* cases: 0 x, 1 y, 2 x+y, 3 x+z, 4 y+z, 5 x+y+z */
    p->dux = sl_study_pct(p->c[2].ux_m, p->c[0].ux_m);
    p->duy = sl_study_pct(p->c[2].uy_m, p->c[1].uy_m);
    p->dvx = sl_study_pct(p->c[3].ux_m, p->c[0].ux_m);
    p->dvy = sl_study_pct(p->c[4].uy_m, p->c[1].uy_m);
    p->dvx3 = sl_study_pct(p->c[5].ux_m, p->c[2].ux_m);
    p->dvy3 = sl_study_pct(p->c[5].uy_m, p->c[2].uy_m);
    return SL_OK;
}

/* ---- Part 3 ---------------------------------------------------------- */

double sl_study_fs_limit(const sl_study_spectra *sp, double fs)
{
    double x = NAN;
    for (size_t k = 0; k < sp->n_mu; k++) {
        const sl_design_row *r = &sp->design->rows[k];
        double a = fmin(fs * r->asce_best_m, r->cap_m);
        if (a < r->nltha_design_m * (1 - 1e-9))
            x = r->x;
    }
    return x;
}

void sl_study_part3_free(sl_study_part3 *p)
{
    if (!p)
        return;
    for (size_t i = 0; i < SL_STUDY_NGROUND; i++)
        sl_synth_set_clear(&p->matched[i]);
    for (size_t l = 0; l < SL_STUDY_NLEVELS; l++)
        sl_study_spectra_free(p->level[l]);
    memset(p, 0, sizeof *p);
}

/* The spectra of the matched ground set scaled to PGA level_g. */
static sl_study_spectra *ground_level(const sl_study_part3 *p, double level_g, sl_error *err)
{
    double pga = level_g * SL_G;
    sl_motion *own[SL_STUDY_NGROUND][SL_SYNTH_NCOMP];
    sl_set sets[SL_STUDY_NGROUND];
    memset(own, 0, sizeof own);
    int bad = 0;
    for (size_t i = 0; i < SL_STUDY_NGROUND; i++) {
        for (int c = 0; c < SL_SYNTH_NCOMP; c++) {
            own[i][c] = sl_motion_copy(sl_synth_set_motion(&p->matched[i], (sl_synth_comp)c));
            if (own[i][c])
                sl_motion_scale(own[i][c], level_g);
            else
                bad = 1;
        }
        sets[i] = (sl_set){own[i][0], own[i][1], own[i][2]};
    }
    double mu[SL_STUDY_P3_NX];
    for (size_t k = 0; k < SL_STUDY_P3_NX; k++)
        mu[k] = (SL_STUDY_P3_X0 + SL_STUDY_P3_DX * (double)k) * pga / SL_G;
    sl_study_spectra *sp = NULL;
    if (bad)
        sl_error_set(err, SL_ENOMEM, NULL, 0, "out of memory");
    else
        sp = sl_study_spectra_compute(sets, SL_STUDY_NGROUND, mu, SL_STUDY_P3_NX, NULL, err);
    for (size_t i = 0; i < SL_STUDY_NGROUND; i++)
        for (int c = 0; c < SL_SYNTH_NCOMP; c++)
            sl_motion_free(own[i][c]);
    return sp;
}

sl_status sl_study_part3_run(const char *records, sl_study_part3 *p,
                             void (*progress)(void *, const char *), void *ctx, sl_error *err)
{
    memset(p, 0, sizeof *p);
    char msg[256];
    for (size_t i = 0; i < SL_STUDY_NGROUND; i++) {
        sl_set rec;
        sl_status st = read_set(records, sl_study_ground.e[i].dir, &rec, err);
        if (st != SL_OK)
            return st;
        st = sl_study_match_rg160(&rec, SL_STUDY_ZETA, SL_G, &p->matched[i], err);
        sl_set_free_motions(&rec);
        if (st && st != SL_ENOCONV)
            return st;
        double lo = INFINITY, hi = 0;
        for (int c = 0; c < SL_SYNTH_NCOMP; c++) {
            lo = fmin(lo, p->matched[i].check[c].min_ratio);
            hi = fmax(hi, p->matched[i].check[c].max_ratio);
        }
        p->ratio_lo[i] = lo;
        p->ratio_hi[i] = hi;
        p->pgd_m[i][0] = sl_motion_pgd(p->matched[i].set.h1);
        p->pgd_m[i][1] = sl_motion_pgd(p->matched[i].set.h2);
        p->pgd_mean_m += p->pgd_m[i][0] / (double)SL_STUDY_NGROUND;
        if (progress) {
            snprintf(msg, sizeof msg, "part 3: matched %s", sl_study_ground.e[i].dir);
            progress(ctx, msg);
        }
    }
    for (size_t l = 0; l < SL_STUDY_NLEVELS; l++) {
        sl_study_spectra *sp = p->level[l] = ground_level(p, sl_study_levels_g[l], err);
        if (!sp)
            return err ? err->code : SL_ENOMEM;
        const sl_design *d = sp->design;
        p->cross[l] = d->has_crossover ? d->crossover_x : NAN;
        p->fs3_x[l] = sl_study_fs_limit(sp, SL_STUDY_CLAIM_FS);
        /* ranges that start above the crossover (or anywhere, without one) */
        p->uncons_hi[l] = 0;
        for (size_t q = 0; q < d->n_ranges; q++)
            if (!d->has_crossover || d->ranges[q].x_from > d->crossover_x)
                p->uncons_hi[l] += 1;
        if (progress) {
            snprintf(msg, sizeof msg, "part 3: %.1f g done", sl_study_levels_g[l]);
            progress(ctx, msg);
        }
    }
    return SL_OK;
}

/* ---- Part 4 ---------------------------------------------------------- */

void sl_study_part4_free(sl_study_part4 *p)
{
    if (!p)
        return;
    for (size_t g = 0; g < SL_STUDY_NGROUPS; g++)
        sl_study_spectra_free(p->group[g]);
    memset(p, 0, sizeof *p);
}

/* Where the ASCE best estimate is below the NLTHA mean, for group g. */
static void best_below_mean(sl_study_part4 *p, size_t g)
{
    const sl_study_spectra *sp = p->group[g];
    p->below[g] = p->defined[g] = 0;
    p->xb_lo[g] = p->xb_hi[g] = NAN;
    for (size_t k = 0; k < sp->n_mu; k++) {
        const sl_design_row *r = &sp->design->rows[k];
        if (isnan(r->asce_best_m))
            continue;
        p->defined[g]++;
        if (r->asce_best_m < r->nltha_mean_m) {
            p->below[g]++;
            if (isnan(p->xb_lo[g]))
                p->xb_lo[g] = r->x;
            p->xb_hi[g] = r->x;
        }
    }
    p->frac_best[g] = p->defined[g] ? (double)p->below[g] / (double)p->defined[g] : NAN;
    p->cross[g] = sp->design->has_crossover ? sp->design->crossover_x : NAN;
}

sl_status sl_study_part4_run(const char *records, sl_study_part4 *p,
                             void (*progress)(void *, const char *), void *ctx, sl_error *err)
{
    memset(p, 0, sizeof *p);
    double mu[SL_MU_GRID_N];
    sl_mu_grid_default(mu);
    sl_status st = SL_OK;
    for (size_t g = 0; g < SL_STUDY_NGROUPS && st == SL_OK; g++) {
        size_t n = sl_study_groups[g].n;
        sl_set *sets = calloc(n, sizeof *sets);
        if (!sets)
            return sl_error_set(err, SL_ENOMEM, NULL, 0, "out of memory");
        for (size_t i = 0; i < n && st == SL_OK; i++)
            st = read_set(records, sl_study_groups[g].e[i].dir, &sets[i], err);
        if (st == SL_OK &&
            !(p->group[g] = sl_study_spectra_compute(sets, n, mu, SL_MU_GRID_N, NULL, err)))
            st = err ? err->code : SL_ENOMEM;
        for (size_t i = 0; i < n; i++)
            sl_set_free_motions(&sets[i]);
        free(sets);
        if (st == SL_OK) {
            best_below_mean(p, g);
            if (progress) {
                char msg[128];
                snprintf(msg, sizeof msg, "part 4: %s done", sl_study_groups[g].name);
                progress(ctx, msg);
            }
        }
    }
    return st;
}
