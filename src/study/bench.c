/* bench.c - speed against error, as measurements (bench.h,
 * docs/performance.md). */
#include "study/bench.h"

#include <math.h>
#include <omp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis.h"
#include "io/floor.h"
#include "io/setdir.h"
#include "core/clock.h"
#include "signal/spectrum.h"
#include "synth/synth.h"

const double sl_bench_model_mu[SL_BENCH_N_MODEL_MU] = {0.05, 0.1, 0.2, 0.4};
const double sl_bench_targets[SL_BENCH_NTARGETS] = {1e-2, 1e-3, 1e-4};
const double sl_bench_spp[SL_BENCH_NSPP] = {5, 10, 20, 40, 80};
const char *const sl_bench_floors[SL_BENCH_NFLOORS] = {
    "floors/01-ground.ini", "floors/02-el12.ini", "floors/03-el24.ini", "floors/04-roof36.ini"};

static const char *const bench_dirs[SL_BENCH_MAX_SETS] = {
    "RSN1063_NORTHR_RRS", "RSN6_IMPVALL.I_I-ELC", "RSN77_SFERN_PUL"};

/* Deterministic broadband stand-in (sum of sines under an envelope). */
static sl_motion *standin(size_t n, double dt, double amp, unsigned seed)
{
    double *a = calloc(n, sizeof *a);
    if (!a)
        return NULL;
    unsigned s = seed;
    for (int k = 0; k < 40; k++) {
        s = s * 1103515245u + 12345u;
        double f = 0.3 + 15.0 * (double)((s >> 8) & 0xffff) / 65535.0;
        s = s * 1103515245u + 12345u;
        double ph = 2 * SL_PI * (double)((s >> 8) & 0xffff) / 65535.0;
        for (size_t i = 0; i < n; i++) {
            double t = (double)i * dt, T = (double)(n - 1) * dt;
            double env = sin(SL_PI * t / T);
            a[i] += amp / 8.0 * env * env * sin(2 * SL_PI * f * t + ph) / sqrt(1.0 + f);
        }
    }
    sl_motion *m = sl_motion_from_array(a, n, dt, "synthesized");
    free(a);
    return m;
}

static sl_status load_sets(const sl_bench_opts *o, sl_bench *b, sl_error *err)
{
    for (int r = 0; r < SL_BENCH_MAX_SETS; r++) {
        char dir[2048];
        snprintf(dir, sizeof dir, "%s/records/%s", o->shared, bench_dirs[r]);
        sl_error e;
        if (sl_set_read_dir(dir, &b->set[b->n_sets], &e) != SL_OK)
            continue;
        snprintf(b->name[b->n_sets], sizeof b->name[0], "%s", bench_dirs[r]);
        b->n_sets++;
    }
    for (int r = 0; b->n_sets == 0 && r < SL_BENCH_MAX_SETS; r++) {
        sl_set *s = &b->set[r];
        s->h1 = standin(4000, 0.01, 6.0, 17u * (unsigned)r);
        s->h2 = standin(4000, 0.01, 6.0, 17u * (unsigned)r + 1u);
        s->v = standin(4000, 0.01, 3.0, 17u * (unsigned)r + 2u);
        if (!s->h1 || !s->h2 || !s->v)
            return sl_error_set(err, SL_ENOMEM, NULL, 0, "out of memory");
        snprintf(b->name[r], sizeof b->name[0], "synthesized-%d", r + 1);
        if (r + 1 == SL_BENCH_MAX_SETS)
            b->n_sets = SL_BENCH_MAX_SETS;
    }
    for (int s = 0; s < b->n_sets; s++)
        b->mean_n += (double)b->set[s].h1->n / b->n_sets;
    return SL_OK;
}

/* Worst relative error (reference peaks >= the floor) and absolute error. */
static void errors(const sl_slide_result *res, const sl_slide_result *ref, size_t n, double *rel,
                   double *abs_m)
{
    for (size_t k = 0; k < n; k++) {
        if (ref[k].peak_m >= SL_BENCH_PEAK_FLOOR_M)
            *rel = fmax(*rel, fabs(res[k].peak_m / ref[k].peak_m - 1));
        *abs_m = fmax(*abs_m, fabs(res[k].peak_m - ref[k].peak_m));
    }
}

/* Best of `repeat` runs of the engine: time into *best_s. */
static sl_status timed_run(const sl_set *set, const double *mu, size_t n, const sl_slide_opts *so,
                           unsigned long repeat, sl_slide_result *res, double *best_s,
                           sl_error *err)
{
    *best_s = INFINITY;
    for (unsigned long r = 0; r < repeat; r++) {
        double t0 = sl_clock_s();
        sl_status st = sl_slide_run(set, mu, n, so, res, err);
        if (st != SL_OK)
            return st;
        *best_s = fmin(*best_s, sl_clock_s() - t0);
    }
    return SL_OK;
}

/* 1. The engine over the default grid; the model references on the subset. */
static sl_status bench_engine(sl_bench *b, unsigned long repeat,
                              sl_slide_result mref[][SL_BENCH_N_MODEL_MU], sl_error *err)
{
    double mu[SL_MU_GRID_N];
    sl_mu_grid_default(mu);
    sl_slide_result ref[SL_MU_GRID_N], chk[SL_MU_GRID_N], res[SL_MU_GRID_N];
    sl_status st = SL_OK;
    for (int s = 0; s < b->n_sets && st == SL_OK; s++) {
        sl_bench_engine *e = &b->engine[s];
        const sl_set set1 = {b->set[s].h1, NULL, NULL};
        sl_slide_opts o;
        sl_slide_opts_default(&o);
        st = timed_run(&set1, mu, SL_MU_GRID_N, &o, repeat, res, &e->t1d_s, err);
        o.substeps = SL_BENCH_REF_SUBSTEPS;
        if (st == SL_OK)
            st = sl_slide_run(&b->set[s], mu, SL_MU_GRID_N, &o, ref, err);
        o.substeps = SL_BENCH_REF_CHECK_SUBSTEPS;
        if (st == SL_OK)
            st = sl_slide_run(&b->set[s], mu, SL_MU_GRID_N, &o, chk, err);
        e->conv_rel = e->conv_abs_m = 0;
        errors(chk, ref, SL_MU_GRID_N, &e->conv_rel, &e->conv_abs_m);
        for (unsigned q = 0; q < SL_BENCH_NSUB && st == SL_OK; q++) {
            o.substeps = 1u << q;
            st = timed_run(&b->set[s], mu, SL_MU_GRID_N, &o, repeat, res, &e->t_s[q], err);
            e->rel[q] = e->abs_m[q] = 0;
            errors(res, ref, SL_MU_GRID_N, &e->rel[q], &e->abs_m[q]);
        }
        o.substeps = SL_BENCH_REF_SUBSTEPS;
        if (st == SL_OK)
            st = sl_slide_run(&b->set[s], sl_bench_model_mu, SL_BENCH_N_MODEL_MU, &o, mref[s], err);
    }
    return st;
}

static sl_bench_setting *add_setting(sl_bench *b, const char *model)
{
    if (b->n_settings >= SL_BENCH_MAX_SETTINGS)
        return NULL;
    sl_bench_setting *x = &b->setting[b->n_settings++];
    sl_slide_opts_default(&x->o);
    snprintf(x->model, sizeof x->model, "%s", model);
    return x;
}

/* 2. The list of settings: engine sub-steps; smoothed model U_y, eta,
 * tolerance and solver; elastic-plastic U_y and sub-steps. */
static void make_settings(sl_bench *b, int quick)
{
    sl_bench_setting *x;
    for (unsigned sub = 1; sub <= 64; sub *= 2)
        if ((x = add_setting(b, "engine"))) {
            x->o.substeps = sub;
            snprintf(x->label, sizeof x->label, "%u sub-steps", sub);
        }
    static const double uys[] = {1e-4, 1e-5, 1e-6, 1e-7}, etas[] = {5, 20}, rtols[] = {1e-4, 1e-6};
    for (int iu = 0; iu < 4; iu++)
        for (int ie = 0; ie < 2; ie++)
            for (int ir = 0; ir < 2; ir++) {
                if ((quick && (iu == 3 || ie == 0 || ir == 1)) || !(x = add_setting(b, "smooth")))
                    continue;
                x->o.model = SL_MODEL_SMOOTH;
                x->o.smooth_uy_m = uys[iu];
                x->o.smooth_eta = etas[ie];
                x->o.smooth_rtol = rtols[ir];
                x->o.smooth_atol = uys[iu] * 1e-2;
                snprintf(x->label, sizeof x->label, "U_y %.0e, eta %.0f, rtol %.0e, msbdf",
                         uys[iu], etas[ie], rtols[ir]);
            }
    /* the other stiff solvers at the study's eta = 20 and the tight tolerance */
    static const char *const solver_names[] = {"msbdf", "rk4imp", "bsimp", "rkf45"};
    for (int iu = 0; iu < 4 && !quick; iu++)
        for (int sv = 1; sv <= 2; sv++) {
            /* rk4imp at U_y = 1e-7: seconds to minutes per run */
            if ((sv == 1 && iu >= 3) || !(x = add_setting(b, "smooth")))
                continue;
            x->o.model = SL_MODEL_SMOOTH;
            x->o.smooth_uy_m = uys[iu];
            x->o.smooth_eta = 20;
            x->o.smooth_rtol = 1e-6;
            x->o.smooth_atol = uys[iu] * 1e-2;
            x->o.smooth_solver = sv;
            snprintf(x->label, sizeof x->label, "U_y %.0e, eta 20, rtol 1e-06, %s", uys[iu],
                     solver_names[sv]);
        }
    for (int iu = 0; iu < 4; iu++)
        for (unsigned sub = 8; sub <= 512; sub *= 8)
            if ((x = add_setting(b, "plastic"))) {
                x->o.model = SL_MODEL_PLASTIC;
                x->o.plastic_uy_m = uys[iu];
                x->o.plastic_substeps = sub;
                snprintf(x->label, sizeof x->label, "U_y %.0e, %u sub-steps", uys[iu], sub);
            }
}

/* One setting over all motions (the slow reference models timed once). */
static void time_setting(sl_bench_setting *x, const sl_bench *b,
                         sl_slide_result ref[][SL_BENCH_N_MODEL_MU], unsigned long repeat)
{
    double total = 0;
    sl_slide_result res[SL_BENCH_N_MODEL_MU];
    x->rel = x->abs_m = 0;
    unsigned long reps = x->o.model == SL_MODEL_EXACT ? repeat : 1;
    for (int s = 0; s < b->n_sets; s++) {
        double best;
        sl_error e;
        if (timed_run(&b->set[s], sl_bench_model_mu, SL_BENCH_N_MODEL_MU, &x->o, reps, res, &best,
                      &e) != SL_OK) {
            x->failed = 1;
            return;
        }
        total += best;
        errors(res, ref[s], SL_BENCH_N_MODEL_MU, &x->rel, &x->abs_m);
    }
    x->us_per = 1e6 * total / ((double)b->n_sets * (double)SL_BENCH_N_MODEL_MU);
}

/* 3. The fastest setting of each model that reaches each target. */
static void pareto(sl_bench *b)
{
    static const char *const models[3] = {"engine", "smooth", "plastic"};
    for (int t = 0; t < SL_BENCH_NTARGETS; t++)
        for (int q = 0; q < 3; q++) {
            int best = -1;
            for (int i = 0; i < b->n_settings; i++) {
                const sl_bench_setting *x = &b->setting[i];
                if (!x->failed && x->rel <= sl_bench_targets[t] && !strcmp(x->model, models[q]) &&
                    (best < 0 || x->us_per < b->setting[best].us_per))
                    best = i;
            }
            b->pareto[t][q] = best;
        }
}

/* 4. Response spectra: sampled-peak error against steps per period. */
static sl_status bench_spectra(sl_bench *b, unsigned long repeat, sl_error *err)
{
    size_t nf = 0;
    double *f = sl_spectrum_grid(SL_SPECTRUM_FMIN_HZ, SL_SPECTRUM_FMAX_HZ, SL_SPECTRUM_PER_DECADE,
                                 &nf);
    double *pref = f ? malloc(nf * sizeof *pref) : NULL, *p = f ? malloc(nf * sizeof *p) : NULL;
    sl_status st = pref && p ? SL_OK : sl_error_set(err, SL_ENOMEM, NULL, 0, "out of memory");
    b->spec_nf = nf;
    for (int s = 0; s < b->n_sets && st == SL_OK; s++) {
        const sl_motion *m = b->set[s].h1;
        sl_spectrum_opts so;
        sl_spectrum_opts_default(&so);
        so.steps_per_period = SL_BENCH_SPP_REF;
        st = sl_spectrum_compute_opts(m->acc_ms2, m->n, m->dt_s, f, nf, SL_BENCH_SPEC_DAMPING, &so,
                                      pref, NULL, NULL, err);
        for (int q = 0; q < SL_BENCH_NSPP && st == SL_OK; q++) {
            so.steps_per_period = sl_bench_spp[q];
            double best = INFINITY;
            for (unsigned long r = 0; r < repeat && st == SL_OK; r++) {
                double t0 = sl_clock_s();
                st = sl_spectrum_compute_opts(m->acc_ms2, m->n, m->dt_s, f, nf,
                                              SL_BENCH_SPEC_DAMPING, &so, p, NULL, NULL, err);
                best = fmin(best, sl_clock_s() - t0);
            }
            double e = 0;
            for (size_t j = 0; j < nf; j++)
                e = fmax(e, fabs(p[j] / pref[j] - 1));
            b->spec_ms[s][q] = 1e3 * best;
            b->spec_err[s][q] = e;
        }
    }
    free(f);
    free(pref);
    free(p);
    return st;
}

/* 5. Synthesis of RG 1.60 sets on one thread, several seeds. */
static void bench_synth(sl_bench *b)
{
    sl_synth_params sp;
    sl_synth_params_default(&sp);
    sl_spectrum *spec[SL_SYNTH_NCOMP] = {NULL};
    sl_synth_target tgt[SL_SYNTH_NCOMP];
    sl_synth *sy = NULL;
    sl_error err;
    sl_error_clear(&err);
    size_t n = (size_t)(SL_SYNTH_DURATION_S / SL_SYNTH_DT_S + 0.5) + 1;
    if (sl_synth_targets_rg160(SL_BENCH_SYNTH_PGA_G * SL_G, SL_SYNTH_DAMPING, &sp, spec, tgt,
                               &err) == SL_OK)
        sy = sl_synth_alloc(n, SL_SYNTH_DT_S, &sp, &err);
    if (!sy) {
        snprintf(b->synth_error, sizeof b->synth_error, "%.200s", err.msg);
    } else {
        int saved = omp_get_max_threads();
        omp_set_num_threads(1);
        b->synth_lo = INFINITY;
        for (int q = 0; q < SL_BENCH_SYNTH_SEEDS; q++) {
            sl_synth_set set;
            double t0 = sl_clock_s();
            sl_status sst = sl_synth_make_set(sy, tgt, 1000u + (uint64_t)q, 0, &set, NULL);
            double t = sl_clock_s() - t0;
            b->synth_mean_s += t / SL_BENCH_SYNTH_SEEDS;
            b->synth_max_s = fmax(b->synth_max_s, t);
            b->synth_passed += (sst == SL_OK && set.pass);
            for (int c = 0; c < SL_SYNTH_NCOMP; c++) {
                b->synth_lo = fmin(b->synth_lo, set.check[c].min_ratio);
                b->synth_hi = fmax(b->synth_hi, set.check[c].max_ratio);
            }
            for (int c = 0; c < SL_SYNTH_NPAIR; c++)
                if (isfinite(set.corr[c]))
                    b->synth_corr = fmax(b->synth_corr, fabs(set.corr[c]));
            sl_synth_set_clear(&set);
        }
        omp_set_num_threads(saved);
        b->synth_ok = 1;
        sl_synth_free(sy);
    }
    for (int c = 0; c < SL_SYNTH_NCOMP; c++)
        sl_spectrum_free(spec[c]);
}

/* 6. The main job on the example floors, default settings, all threads. */
static void bench_floors(sl_bench *b)
{
    double mu[SL_MU_GRID_N];
    sl_mu_grid_default(mu);
    b->threads = omp_get_max_threads();
    for (int i = 0; i < SL_BENCH_NFLOORS; i++) {
        sl_error fe;
        sl_floor *fl = sl_floor_load(sl_bench_floors[i], &fe);
        if (!fl)
            continue;
        snprintf(b->floor_name[i], sizeof b->floor_name[i], "%s", fl->name);
        b->floor_found[i] = 1;
        for (int mode = 0; mode < 2; mode++) {
            sl_analysis_opts ao;
            sl_analysis_opts_default(&ao);
            ao.mu = mu;
            ao.n_mu = SL_MU_GRID_N;
            ao.n_sets = mode == 0 ? SL_BENCH_FIXED_SETS : 0;
            sl_analysis *an = sl_analysis_run(fl, &ao, &fe);
            if (!an)
                b->floor_found[i] = -1;
            if (an) {
                double *t = b->floor_t[i][mode];
                t[0] = an->time_synth_s;
                t[1] = an->time_nltha_s;
                t[2] = an->time_stats_s;
                t[3] = an->time_asce_s;
                b->floor_sets[i][mode] = an->n_sets;
                b->floor_stop[i][mode] = (int)an->stop;
                b->floor_skipped[i] = an->n_mu_skipped;
            }
            sl_analysis_free(an);
        }
        sl_floor_free(fl);
    }
}

/* The arithmetic of one 2-D sliding update (midpoint branch) over arrays,
 * branch-free: what the engine must at least compute per (sub-step, mu).
 * Returns the best time per update, s (NAN without memory). */
static double limit_time_per_update(void)
{
    enum { M = 4096, ITERS = 200, NARR = 8 };
    double *buf = calloc((size_t)NARR * M, sizeof *buf);
    if (!buf)
        return NAN;
    double *vx = buf, *vy = buf + M, *ux = buf + 2 * M, *uy = buf + 3 * M, *mu = buf + 4 * M,
           *pk = buf + 5 * M, *path = buf + 6 * M, *spd = buf + 7 * M;
    for (int k = 0; k < M; k++) {
        vx[k] = 0.3 + 1e-4 * k;
        vy[k] = 0.2;
        mu[k] = 0.05 + 1e-5 * k;
        spd[k] = hypot(vx[k], vy[k]);
    }
    const double h = 0.01 / 8, hN = h * SL_G, h2 = 0.5 * h;
    double *restrict rvx = vx, *restrict rvy = vy, *restrict rux = ux, *restrict ruy = uy,
                     *restrict rpk = pk, *restrict rpath = path, *restrict rspd = spd;
    const double *restrict rmu = mu;
    double best = INFINITY;
    for (int rep = 0; rep < 5; rep++) {
        double t0 = sl_clock_s();
        for (int it = 0; it < ITERS; it++) {
            const double hax = 1e-4 * (it & 7), hay = -1e-4 * (it & 3);
            for (int k = 0; k < M; k++) {
                const double f = hN * rmu[k];
                const double yx = 2 * rvx[k] - hax, yy = 2 * rvy[k] - hay;
                const double yn = sqrt(yx * yx + yy * yy);
                const double sm = 1.0 - f / yn;
                const double nx = yx * sm - rvx[k], ny = yy * sm - rvy[k];
                rux[k] += h2 * (rvx[k] + nx);
                ruy[k] += h2 * (rvy[k] + ny);
                const double sp = sqrt(nx * nx + ny * ny);
                rpath[k] += h2 * (rspd[k] + sp);
                rspd[k] = sp;
                const double r2 = rux[k] * rux[k] + ruy[k] * ruy[k];
                rpk[k] = r2 > rpk[k] ? r2 : rpk[k];
                /* keep the state bounded so the loop stays in range */
                rvx[k] = nx + 1e-3 * f;
                rvy[k] = ny;
            }
        }
        best = fmin(best, (sl_clock_s() - t0) / ((double)M * ITERS));
    }
    double sink = 0;
    for (int k = 0; k < M; k++)
        sink += pk[k] + path[k];
    if (!(sink == sink)) /* keep the work observable */
        best = NAN;
    free(buf);
    return best;
}

/* 7. The engine at 16 sub-steps against the limit. */
static sl_status bench_limit(sl_bench *b, unsigned long repeat, sl_error *err)
{
    double mu[SL_MU_GRID_N];
    sl_mu_grid_default(mu);
    sl_slide_result res[SL_MU_GRID_N];
    const double nsub = SL_BENCH_LIMIT_SUBSTEPS, nm = SL_MU_GRID_N;
    b->limit_s = limit_time_per_update();
    for (int s = 0; s < b->n_sets; s++) {
        const sl_motion *h1 = b->set[s].h1;
        sl_slide_opts o;
        sl_slide_opts_default(&o);
        o.substeps = SL_BENCH_LIMIT_SUBSTEPS;
        double best;
        sl_status st = timed_run(&b->set[s], mu, SL_MU_GRID_N, &o, repeat, res, &best, err);
        if (st != SL_OK)
            return st;
        /* sliding updates: time spent sliding within the record / h */
        double h = h1->dt_s / nsub, tend = (double)(h1->n - 1) * h1->dt_s, nslide = 0;
        for (size_t k = 0; k < SL_MU_GRID_N; k++)
            nslide += fmin(res[k].slide_time_s, tend) / h;
        sl_bench_limit *l = &b->limit[s];
        l->per_s = best / ((double)h1->n * nsub * nm);
        l->share = nslide / ((double)h1->n * nsub * nm);
        l->per_slide_s = nslide > 0 ? best / nslide : NAN;
    }
    return SL_OK;
}

void sl_bench_free(sl_bench *b)
{
    if (!b)
        return;
    for (int s = 0; s < SL_BENCH_MAX_SETS; s++)
        sl_set_free_motions(&b->set[s]);
    free(b);
}

sl_bench *sl_bench_run(const sl_bench_opts *o, sl_error *err)
{
    sl_bench *b = calloc(1, sizeof *b);
    sl_slide_result mref[SL_BENCH_MAX_SETS][SL_BENCH_N_MODEL_MU];
    if (!b) {
        sl_error_set(err, SL_ENOMEM, NULL, 0, "out of memory");
        return NULL;
    }
    unsigned long repeat = o->repeat ? o->repeat : 1;
    if (load_sets(o, b, err) || bench_engine(b, repeat, mref, err))
        goto fail;
    make_settings(b, o->quick);
    for (int i = 0; i < b->n_settings; i++) {
        if (o->progress) {
            char msg[96];
            snprintf(msg, sizeof msg, "%s %s", b->setting[i].model, b->setting[i].label);
            o->progress(o->ctx, msg);
        }
        time_setting(&b->setting[i], b, mref, repeat);
    }
    pareto(b);
    if (bench_spectra(b, repeat, err))
        goto fail;
    bench_synth(b);
    bench_floors(b);
    if (bench_limit(b, repeat, err))
        goto fail;
    return b;
fail:
    sl_bench_free(b);
    return NULL;
}
