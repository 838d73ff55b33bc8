/*
 * bench_engine.c - work-precision data of the engine and its ratio to the
 * arithmetic floor (bench_engine.h).
 */
#include "study/bench_engine.h"

#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "io/setdir.h"
#include "core/clock.h"
#include "core/compare.h"
#include "slide/slide.h"

#if defined(__GNUC__) && !defined(__clang__)
#define VECTOR_LOOP __attribute__((optimize("no-trapping-math")))
#else
#define VECTOR_LOOP
#endif
/* The floor gets the engine's vector widths: AVX2 where the CPU has it
 * (the engine's vector passes, slide/kernel2d.c), else SSE2. target_clones
 * needs the C library's ifunc (glibc); elsewhere the floor is SSE2 only. */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__GLIBC__)
#define FLOOR_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define FLOOR_CLONES
#endif

const double sl_bench_wp_mu[SL_BENCH_WP_NMU] = {0.05, 0.075, 0.1, 0.15, 0.2, 0.3, 0.4};

/* The settings of part 1: rtol 1e-2 ... 1e-4, then fixed sub-steps. */
static const double wp_rtol[] = {1e-2, 3e-3, 1e-3, 3e-4, 1e-4};
static const unsigned wp_sub[] = {1, 4, 16, 64};

/* Part 2: these sets when present (a strong vertical, a far-field record,
 * a near-field pulse), else the first sets read. */
static const char *const floor_sets[SL_BENCH_WP_NFLOOR] = {"RSN1063_NORTHR_RRS",
                                                          "RSN6_IMPVALL.I_I-ELC", "RSN77_SFERN_PUL"};

/* The arithmetic floor: per sample one branch-free first-order projection
 * update of every block (the mean forcing of the sample, as the engine
 * uses), over contiguous arrays the compiler vectorises. Returns the share
 * of (sample, mu) updates in which the block moves. */
FLOOR_CLONES VECTOR_LOOP static double floor_run(const sl_set *set, const double *restrict mu, size_t m,
                                    double *restrict vx, double *restrict vy, double *restrict ux,
                                    double *restrict uy, double *restrict pk)
{
    const size_t n = set->h1->n;
    const double dt = set->h1->dt_s;
    const double *ax = set->h1->acc_ms2, *ay = set->h2->acc_ms2, *av = set->v ? set->v->acc_ms2 : NULL;
    for (size_t k = 0; k < m; k++)
        vx[k] = vy[k] = ux[k] = uy[k] = pk[k] = 0.0;
    double moving = 0.0;
    for (size_t i = 0; i + 1 < n; i++) {
        const double hax = 0.5 * dt * (ax[i] + ax[i + 1]), hay = 0.5 * dt * (ay[i] + ay[i + 1]);
        const double N = SL_G + (av ? 0.5 * (av[i] + av[i + 1]) : 0.0);
        const double hN = dt * (N > 0.0 ? N : 0.0);
        double mv = 0.0;
        for (size_t k = 0; k < m; k++) {
            const double wx = vx[k] - hax, wy = vy[k] - hay;
            const double wn = sqrt(wx * wx + wy * wy);
            const double s1 = 1.0 - mu[k] * hN / (wn > 1e-300 ? wn : 1e-300);
            const double s = s1 > 0.0 ? s1 : 0.0;
            vx[k] = wx * s;
            vy[k] = wy * s;
            ux[k] += dt * vx[k];
            uy[k] += dt * vy[k];
            const double r2 = ux[k] * ux[k] + uy[k] * uy[k];
            pk[k] = r2 > pk[k] ? r2 : pk[k];
            mv += s > 0.0 ? 1.0 : 0.0;
        }
        moving += mv;
    }
    return n > 1 && m > 0 ? moving / ((double)(n - 1) * (double)m) : 0.0;
}

void sl_bench_wp_free(sl_bench_wp *b)
{
    free(b);
}

/* The names of the folders under root, sorted; *n of them. */
static char **list_dirs(const char *root, size_t *n)
{
    *n = 0;
    DIR *d = opendir(root);
    if (!d)
        return NULL;
    size_t cap = 0;
    char **v = NULL;
    struct dirent *e;
    while ((e = readdir(d))) {
        if (e->d_name[0] == '.')
            continue;
        if (*n == cap) {
            cap = cap ? 2 * cap : 64;
            char **p = realloc(v, cap * sizeof *p);
            if (!p)
                break;
            v = p;
        }
        v[*n] = strdup(e->d_name);
        if (v[*n])
            (*n)++;
    }
    closedir(d);
    if (v)
        qsort(v, *n, sizeof *v, sl_cmp_str);
    return v;
}

sl_bench_wp *sl_bench_wp_run(const char *shared, unsigned long repeat, sl_error *err)
{
    char root[1024];
    snprintf(root, sizeof root, "%s/records", shared);
    size_t nd = 0;
    char **names = list_dirs(root, &nd);
    sl_bench_wp *b = calloc(1, sizeof *b);
    sl_set *sets = calloc(nd ? nd : 1, sizeof *sets);
    char **set_name = calloc(nd ? nd : 1, sizeof *set_name);
    const size_t nmu = SL_BENCH_WP_NMU, nset = SL_BENCH_WP_NSET;
    double *ref = NULL, *res = NULL, *rel = NULL, *est = NULL;
    double *grid = NULL, *fl = NULL;
    sl_slide_result *rr = NULL;
    if (!names || !b || !sets || !set_name) {
        sl_error_set(err, names ? SL_ENOMEM : SL_EIO, root, 0,
                     names ? "out of memory" : "cannot read the records folder");
        goto fail;
    }
    for (size_t i = 0; i < nd; i++) {
        char dir[2048];
        struct stat st;
        snprintf(dir, sizeof dir, "%s/%s", root, names[i]);
        if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode))
            continue;
        sl_error e;
        sl_error_clear(&e);
        if (sl_set_read_dir(dir, &sets[b->n_sets], &e) != SL_OK) {
            b->n_unread++;
            continue;
        }
        set_name[b->n_sets++] = names[i];
    }
    if (b->n_sets == 0) {
        sl_error_set(err, SL_EIO, root, 0, "no three-component set (2 horizontals + 1 vertical)");
        goto fail;
    }
    const size_t rows = b->n_sets * nmu;
    b->n_rows = rows;
    ref = malloc(rows * sizeof *ref);
    res = malloc(rows * sizeof *res);
    est = malloc(rows * sizeof *est);
    rel = malloc(rows * sizeof *rel);
    rr = malloc(nmu * sizeof *rr);
    if (!ref || !res || !est || !rel || !rr) {
        sl_error_set(err, SL_ENOMEM, NULL, 0, "out of memory");
        goto fail;
    }
    /* part 1: the reference, then each setting */
    sl_slide_opts o;
    sl_slide_opts_default(&o);
    o.rtol = SL_BENCH_WP_REF_RTOL;
    o.atol_m = SL_BENCH_WP_REF_ATOL_M;
    double t0 = sl_clock_s();
    for (size_t s = 0; s < b->n_sets; s++) {
        if (sl_slide_run(&sets[s], sl_bench_wp_mu, nmu, &o, rr, err))
            goto fail;
        for (size_t k = 0; k < nmu; k++)
            ref[s * nmu + k] = rr[k].peak_m;
    }
    b->ref_time_s = sl_clock_s() - t0;
    for (size_t q = 0; q < nset; q++) {
        sl_bench_wp_setting *x = &b->set[q];
        const size_t nr = sizeof wp_rtol / sizeof wp_rtol[0];
        sl_slide_opts_default(&o);
        if (q < nr)
            o.rtol = x->rtol = wp_rtol[q];
        else
            o.substeps = x->substeps = wp_sub[q - nr];
        x->time_s = INFINITY;
        for (unsigned long r = 0; r < repeat; r++) {
            t0 = sl_clock_s();
            for (size_t s = 0; s < b->n_sets; s++) {
                if (sl_slide_run(&sets[s], sl_bench_wp_mu, nmu, &o, rr, err))
                    goto fail;
                for (size_t k = 0; k < nmu; k++) {
                    res[s * nmu + k] = rr[k].peak_m;
                    est[s * nmu + k] = rr[k].err_est_m;
                }
            }
            x->time_s = fmin(x->time_s, sl_clock_s() - t0);
        }
        size_t nrel = 0, nb = 0, nw = 0;
        x->worst_rel = 0.0;
        for (size_t j = 0; j < rows; j++) {
            const double e = fabs(res[j] - ref[j]);
            nb += (est[j] >= e);
            nw += (e <= fmax(o.rtol * ref[j], o.atol_m));
            if (ref[j] >= SL_BENCH_WP_PEAK_FLOOR_M) {
                rel[nrel++] = e / ref[j];
                x->worst_rel = fmax(x->worst_rel, e / ref[j]);
            }
        }
        qsort(rel, nrel, sizeof *rel, sl_cmp_double);
        x->median_rel = nrel ? rel[nrel / 2] : NAN;
        x->bounded = x->substeps ? NAN : (double)nb / (double)rows;
        x->within = x->substeps ? NAN : (double)nw / (double)rows;
    }
    /* part 2: the default engine and the floor on a fine grid */
    grid = malloc(SL_BENCH_WP_GRID_N * sizeof *grid);
    fl = malloc(5 * SL_BENCH_WP_GRID_N * sizeof *fl);
    sl_slide_result *rg = malloc(SL_BENCH_WP_GRID_N * sizeof *rg);
    if (!grid || !fl || !rg) {
        free(rg);
        sl_error_set(err, SL_ENOMEM, NULL, 0, "out of memory");
        goto fail;
    }
    for (size_t k = 0; k < SL_BENCH_WP_GRID_N; k++)
        grid[k] = 0.05 + 0.001 * (double)k;
    for (int f = 0; f < SL_BENCH_WP_NFLOOR && b->n_floor < SL_BENCH_WP_NFLOOR; f++) {
        size_t s = b->n_sets;
        for (size_t i = 0; i < b->n_sets; i++)
            if (!strcmp(set_name[i], floor_sets[f]))
                s = i;
        if (s == b->n_sets)
            s = (size_t)f < b->n_sets ? (size_t)f : 0;
        sl_bench_wp_floor *x = &b->floor[b->n_floor++];
        snprintf(x->name, sizeof x->name, "%s", set_name[s]);
        x->n = sets[s].h1->n;
        sl_slide_opts_default(&o);
        x->engine_s = x->floor_s = INFINITY;
        for (unsigned long r = 0; r < repeat; r++) {
            t0 = sl_clock_s();
            if (sl_slide_run(&sets[s], grid, SL_BENCH_WP_GRID_N, &o, rg, err)) {
                free(rg);
                goto fail;
            }
            x->engine_s = fmin(x->engine_s, sl_clock_s() - t0);
            t0 = sl_clock_s();
            x->sliding = floor_run(&sets[s], grid, SL_BENCH_WP_GRID_N, fl, fl + SL_BENCH_WP_GRID_N,
                                   fl + 2 * SL_BENCH_WP_GRID_N, fl + 3 * SL_BENCH_WP_GRID_N,
                                   fl + 4 * SL_BENCH_WP_GRID_N);
            x->floor_s = fmin(x->floor_s, sl_clock_s() - t0);
        }
        x->ratio = x->engine_s / x->floor_s;
    }
    free(rg);
    free(grid);
    free(fl);
    free(ref);
    free(res);
    free(est);
    free(rel);
    free(rr);
    for (size_t s = 0; s < b->n_sets; s++)
        sl_set_free_motions(&sets[s]);
    free(sets);
    free(set_name);
    for (size_t i = 0; i < nd; i++)
        free(names[i]);
    free(names);
    return b;
fail:
    free(grid);
    free(fl);
    free(ref);
    free(res);
    free(est);
    free(rel);
    free(rr);
    if (sets && b)
        for (size_t s = 0; s < b->n_sets; s++)
            sl_set_free_motions(&sets[s]);
    free(sets);
    free(set_name);
    if (names)
        for (size_t i = 0; i < nd; i++)
            free(names[i]);
    free(names);
    free(b);
    return NULL;
}
