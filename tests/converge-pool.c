/* converge-pool.c - the stopping rule and the band in the bootstrap world of
 * a pool of real motion sets (docs/run.md, "Convergence"): cheaper than
 * tests/converge-bruteforce.sh (the sets are synthesized and analysed once),
 * for hundreds of simulated runs instead of 20. Not part of `make test`.
 *
 *   cc -std=c11 -O2 -fopenmp -D_XOPEN_SOURCE=700 -Isrc -o /tmp/converge-pool \
 *      tests/converge-pool.c build/libseislide.a -lgsl -lgslcblas -lm -lfftw3_threads -lfftw3 \
 *      -lxlsxwriter -linih -lz
 *   /tmp/converge-pool pool FLOOR.ini N SEED > pool.txt   (N sets, default mu grid:
 *                                                          a line per set: PGD, 76 peaks, m;
 *                                                          CROSS=1: a line per crossed block)
 *   /tmp/converge-pool sim pool.txt FIRST MARGIN GROWTH RUNS [B [FIXED]]
 *   /tmp/converge-pool vr FLOOR.ini N SEED [M]              (variance reduction, below)
 *
 * `sim` treats the pool as the population (its design value is the truth):
 * each run draws sets from it with replacement and applies the stopping rule
 * (default targets 5 %, 1 mm; sl_stats_plan_next with MARGIN and GROWTH;
 * FIXED > 0: that many sets instead; UNIT=3: each pool line is a crossed
 * block of three sets, the rule counting sets and adding whole blocks, as
 * the run does), then prints the mean sets per run, the
 * RMS stated SE over the scatter of the design value (range over mu and
 * mean), how often the actual SE (the pool's, at the run's count) misses
 * the target, and, with B > 0 resamples, how often the bootstrap-t and the
 * percentile bands hold the truth.
 *
 * `vr` (docs/run.md, "Variance reduction") synthesizes N sets and prints, at
 * every fifth mu of the grid, the correlation over the sets of the design
 * peak X (with the run's intensity scatter) with cheap per-set quantities a
 * control variate could use: the mean of the two 1-D runs (H1 with V, H2
 * with V, same scatter), the PGV and PGA sums, the Arias intensity, the PGD
 * of the set, and the largest |rho| with the set's 10 %-damped horizontal
 * spectral value (geometric mean of H1 and H2) over 24 frequencies
 * 0.5-50 Hz. Then it crosses the horizontals of the first M sets (default
 * 16): X(H1_i, H2_j, V_i) for all i, j, and splits the variance of X into
 * the H1 part, the H2 part and their interaction (two-way random-effects
 * ANOVA, one observation per cell: Var(row means) = s_a^2 + s_e^2 / M). */
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis.h"
#include "slide/slide.h"
#include "method/scatter.h"
#include "signal/spectrum.h"

#define K 76
#define NMAX 200
#define PMAX 2000

/* CROSS=1 (docs/run.md, "Variance reduction"): a block of three sets a, b,
 * c analysed also in a Latin square, each set's H1 with the other two
 * sets' H2 and V,
 *   square 1: (H1a, H2b, Vc), (H1b, H2c, Va), (H1c, H2a, Vb)
 *   square 2: (H1a, H2c, Vb), (H1b, H2a, Vc), (H1c, H2b, Va)
 * the first whose three combinations pass the SRP 3.7.1 independence check
 * (|rho| <= 0.16 for every pair), else none (led[i] = in[i]). Returns the
 * square, or 0. */
#define XBLOCK 3
static int cross_block(const sl_set in[XBLOCK], sl_set led[XBLOCK])
{
    for (int q = 1; q <= 2; q++) {
        sl_set c[XBLOCK];
        int pass = 1;
        for (int i = 0; i < XBLOCK; i++) {
            c[i] = (sl_set){in[i].h1, in[(i + q) % XBLOCK].h2, in[(i + 2 * q) % XBLOCK].v};
            const sl_motion *m[3] = {c[i].h1, c[i].h2, c[i].v};
            for (int p = 0; p < 3; p++)
                pass &= fabs(sl_synth_corr(m[p]->acc_ms2, m[(p + 1) % 3]->acc_ms2, m[p]->n)) <=
                        SL_SYNTH_MAX_CORR;
        }
        if (pass) {
            for (int i = 0; i < XBLOCK; i++)
                led[i] = c[i];
            return q;
        }
    }
    for (int i = 0; i < XBLOCK; i++)
        led[i] = in[i];
    return 0;
}

static int pool(const char *path, size_t N, uint64_t seed)
{
    sl_error err;
    sl_floor *fl = sl_floor_load(path, &err);
    if (!fl)
        return 1;
    double mu[K];
    for (int k = 0; k < K; k++)
        mu[k] = 0.05 + 0.01 * k;
    sl_synth_params sp;
    sl_synth_params_default(&sp);
    sl_synth_target tgt[SL_SYNTH_NCOMP];
    if (sl_synth_targets_floor(fl, 0.0, tgt, &err))
        return 1;
    size_t n_t = (size_t)(SL_SYNTH_DURATION_S / SL_SYNTH_DT_S + 0.5) + 1;
    sl_synth *plan = sl_synth_alloc(n_t, SL_SYNTH_DT_S, &sp, &err);
    sl_synth_set *ss = calloc(N, sizeof *ss);
    sl_set *sets = calloc(N, sizeof *sets);
    sl_slide_result *res = calloc(N * K, sizeof *res);
    if (!plan || !ss || !sets || !res)
        return 1;
    sl_synth_make_sets(plan, tgt, sl_analysis_floor_seed(seed, fl), 0, N, ss, NULL, NULL, &err);
    for (size_t s = 0; s < N; s++)
        sets[s] = ss[s].set;
    sl_slide_opts so;
    sl_slide_opts_default(&so);
    /* the run's intensity scatter (method/scatter.h (R3), the floor's by (R4));
     * SCATTER=S: that sigma, 0: none */
    const char *sv = getenv("SCATTER");
    double sigma = sv ? atof(sv) : sl_scatter_sigma_of_floor(fl);
    sl_scatter *sc = sigma > 0 ? sl_scatter_alloc(sigma, mu, K, &err) : NULL;
    /* CROSS=1: the run's crossed blocks (method/cross.h): each block of three
     * sets also analysed in its Latin square, one line per block (the means
     * of its sets' values, each set's the mean of its two analyses) */
    const char *cv = getenv("CROSS");
    const size_t U = cv && atoi(cv) ? XBLOCK : 1, nb = N / U;
    size_t nr = N, crossed = 0;
    sl_set *runs = calloc(2 * N, sizeof *runs);
    size_t *led = calloc(N, sizeof *led);
    if (!runs || !led)
        return 1;
    for (size_t s = 0; s < N; s++) {
        runs[s] = sets[s];
        led[s] = s;
    }
    for (size_t b = 0; U > 1 && b < nb; b++) {
        sl_set comb[XBLOCK];
        int q = cross_block(sets + b * U, comb);
        crossed += q > 0;
        for (size_t i = 0; q > 0 && i < U; i++) {
            led[b * U + i] = nr;
            runs[nr++] = comb[i];
        }
    }
    if (U > 1)
        fprintf(stderr, "%zu of %zu blocks crossed\n", crossed, nb);
    res = realloc(res, nr * K * sizeof *res);
    double *y = malloc(nr * K * sizeof *y);
    if (!y || !res || (sc ? sl_scatter_slide_batch(sc, runs, nr, &so, y, NULL, &err)
                          : sl_slide_batch(runs, nr, mu, K, &so, res, &err)))
        return 1;
    for (size_t i = 0; !sc && i < nr * K; i++)
        y[i] = res[i].peak_m;
    for (size_t b = 0; b < nb; b++) {
        double g = 0, x[K] = {0};
        for (size_t i = b * U; i < (b + 1) * U; i++) {
            g += 0.5 * (sl_set_pgd_100_40(&runs[i]) + sl_set_pgd_100_40(&runs[led[i]])) / (double)U;
            for (int k = 0; k < K; k++)
                x[k] += 0.5 * (y[i * K + k] + y[led[i] * K + k]) / (double)U;
        }
        printf("%.9g", g);
        for (int k = 0; k < K; k++)
            printf(" %.9g", x[k]);
        printf("\n");
    }
    free(y);
    free(runs);
    free(led);
    sl_scatter_free(sc);
    return 0;
}

static double P[PMAX][K + 1];

static int sim(int argc, char **argv)
{
    FILE *f = fopen(argv[2], "r");
    size_t np = 0;
    while (f && np < PMAX && fscanf(f, "%lf", &P[np][0]) == 1) {
        for (int k = 1; k <= K; k++)
            if (fscanf(f, "%lf", &P[np][k]) != 1)
                return 1;
        np++;
    }
    if (f)
        fclose(f);
    if (np < 2)
        return 1;
    size_t first = (size_t)atoi(argv[3]), R = (size_t)atoi(argv[6]);
    double margin = atof(argv[4]), growth = atof(argv[5]);
    size_t B = argc > 7 ? (size_t)atoi(argv[7]) : 0, fixed = argc > 8 ? (size_t)atoi(argv[8]) : 0;
    static double pk[PMAX * K], pg[PMAX];
    double truth[K];
    for (size_t i = 0; i < np; i++) {
        pg[i] = P[i][0];
        for (int k = 0; k < K; k++)
            pk[i * K + k] = P[i][k + 1];
    }
    double se_pop[K]; /* the SE of a run of n sets is se_pop sqrt(np / n) */
    sl_stats_design_value(pk, np, K, pg, SL_NLTHA_FS, SL_DESIGN_CAP_FACTOR, truth, se_pop);
    const char *uv = getenv("UNIT");
    const size_t unit = uv && atoi(uv) > 0 ? (size_t)atoi(uv) : 1;
    size_t miss_any = 0, miss_mu = 0;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, 11);
    double sd[K] = {0}, sdd[K] = {0}, sse2[K] = {0}, ns = 0;
    size_t cov_t[K] = {0}, cov_p[K] = {0};
    for (size_t r = 0; r < R; r++) {
        size_t n = 0, want = fixed ? fixed : first;
        double D[K], SE[K];
        for (;;) {
            for (; n < want; n++) {
                size_t j = gsl_rng_uniform_int(rng, np);
                pg[n] = P[j][0];
                for (int k = 0; k < K; k++)
                    pk[n * K + k] = P[j][k + 1];
            }
            sl_stats_design_value(pk, n, K, pg, SL_NLTHA_FS, SL_DESIGN_CAP_FACTOR, D, SE);
            double worst = 0;
            for (int k = 0; k < K; k++) {
                double t = fmax(SL_ANALYSIS_REL_SE * D[k], SL_ANALYSIS_ABS_SE_M);
                worst = fmax(worst, SE[k] / t);
            }
            /* the rule counts sets: a unit (pool line) is UNIT sets (3: a crossed
             * block), the next count rounded up to whole units */
            size_t next = n;
            if (!fixed) {
                size_t ns_ = sl_stats_plan_next(n * unit, worst, margin, SL_ANALYSIS_MIN_BATCH,
                                                growth, NMAX / unit * unit);
                next = (ns_ + unit - 1) / unit;
            }
            if (next == n)
                break;
            want = next;
        }
        ns += (double)(n * unit);
        /* does the actual SE (of the population, at n sets) meet the target of the truth? */
        size_t miss = 0;
        for (int k = 0; k < K; k++)
            miss += se_pop[k] * sqrt((double)np / (double)n) >
                    fmax(SL_ANALYSIS_REL_SE * truth[k], SL_ANALYSIS_ABS_SE_M);
        miss_any += miss > 0;
        miss_mu += miss;
        if (B) {
            double lo[K], hi[K], lp[K], hp[K];
            sl_stats_design_band(pk, n, K, pg, SL_NLTHA_FS, SL_DESIGN_CAP_FACTOR, B, 0.9, 100 + r,
                                 SL_STATS_BAND_STUDENT, lo, hi, NULL);
            sl_stats_design_band(pk, n, K, pg, SL_NLTHA_FS, SL_DESIGN_CAP_FACTOR, B, 0.9, 100 + r,
                                 SL_STATS_BAND_PERCENTILE, lp, hp, NULL);
            for (int k = 0; k < K; k++) {
                cov_t[k] += lo[k] <= truth[k] && truth[k] <= hi[k];
                cov_p[k] += lp[k] <= truth[k] && truth[k] <= hp[k];
            }
        }
        for (int k = 0; k < K; k++) {
            sd[k] += D[k];
            sdd[k] += D[k] * D[k];
            sse2[k] += SE[k] * SE[k];
        }
    }
    double rs = 0, rmin = 1e9, rmax = 0, ct = 0, cp = 0, bsum = 0, bmin = 1e9, bmax = -1e9;
    int nk = 0, nc = 0, nb = 0;
    for (int k = 0; k < K; k++) {
        double m = sd[k] / (double)R, v = (sdd[k] - (double)R * m * m) / (double)(R - 1);
        if (truth[k] >= 1e-3) { /* bias of the design value: mean over runs / truth - 1 */
            double b = m / truth[k] - 1;
            bsum += b;
            bmin = fmin(bmin, b);
            bmax = fmax(bmax, b);
            nb++;
        }
        if (!(v > 0))
            continue;
        double q = sqrt(sse2[k] / (double)R) / sqrt(v);
        rs += q;
        nk++;
        rmin = fmin(rmin, q);
        rmax = fmax(rmax, q);
        if (truth[k] >= 1e-3) { /* as converge-bruteforce.sh: design >= 1 mm */
            ct += (double)cov_t[k] / (double)R;
            cp += (double)cov_p[k] / (double)R;
            nc++;
        }
        if (getenv("VERBOSE"))
            printf("mu %.2f: truth %.4f m, stated SE / scatter %.3f, bootstrap-t %.3f, "
                   "percentile %.3f\n", 0.05 + 0.01 * k, truth[k], q,
                   (double)cov_t[k] / (double)R, (double)cov_p[k] / (double)R);
    }
    printf("first %zu, margin %.2f, growth %.1f, fixed %zu, %zu runs from %zu units of %zu "
           "set(s): %.1f sets per run; stated SE / scatter %.3f to %.3f, mean %.3f", first,
           margin, growth, fixed, R, np, unit, ns / (double)R, rmin, rmax, rs / nk);
    printf("; bias (design >= 1 mm) %+.4f to %+.4f, mean %+.4f", bmin, bmax, bsum / nb);
    printf("; actual SE above the target: in %.2f of the runs, at %.3f of the mu",
           (double)miss_any / (double)R, (double)miss_mu / (double)(R * K));
    if (B)
        printf("; band holds the truth (mu with design >= 1 mm): bootstrap-t %.3f, percentile "
               "%.3f", ct / nc, cp / nc);
    printf("\n");
    gsl_rng_free(rng);
    return 0;
}

static double corr(const double *x, size_t sx, const double *y, size_t sy, size_t n)
{
    double mx = 0, my = 0, sxy = 0, sxx = 0, syy = 0;
    for (size_t i = 0; i < n; i++) {
        mx += x[i * sx] / (double)n;
        my += y[i * sy] / (double)n;
    }
    for (size_t i = 0; i < n; i++) {
        sxy += (x[i * sx] - mx) * (y[i * sy] - my);
        sxx += (x[i * sx] - mx) * (x[i * sx] - mx);
        syy += (y[i * sy] - my) * (y[i * sy] - my);
    }
    return sxx > 0 && syy > 0 ? sxy / sqrt(sxx * syy) : NAN;
}

#define NFV 24
static int vr(const char *path, size_t N, uint64_t seed, size_t M)
{
    sl_error err;
    sl_floor *fl = sl_floor_load(path, &err);
    if (!fl || N < 3)
        return 1;
    if (M > N)
        M = N;
    double mu[K];
    for (int k = 0; k < K; k++)
        mu[k] = 0.05 + 0.01 * k;
    sl_synth_params sp;
    sl_synth_params_default(&sp);
    sl_synth_target tgt[SL_SYNTH_NCOMP];
    if (sl_synth_targets_floor(fl, 0.0, tgt, &err))
        return 1;
    size_t n_t = (size_t)(SL_SYNTH_DURATION_S / SL_SYNTH_DT_S + 0.5) + 1;
    sl_synth *plan = sl_synth_alloc(n_t, SL_SYNTH_DT_S, &sp, &err);
    sl_synth_set *ss = calloc(N, sizeof *ss);
    sl_set *sets = calloc(N, sizeof *sets), *one = calloc(2 * N, sizeof *one);
    sl_set *cross = calloc(M * M, sizeof *cross);
    double *x = malloc(N * K * sizeof *x), *x1 = malloc(2 * N * K * sizeof *x1);
    double *xc = malloc(M * M * K * sizeof *xc), *y = malloc(N * (6 + NFV) * sizeof *y);
    sl_scatter *sc = sl_scatter_alloc(sl_scatter_sigma_of_floor(fl), mu, K, &err);
    if (!plan || !ss || !sets || !one || !cross || !x || !x1 || !xc || !y || !sc)
        return 1;
    sl_synth_make_sets(plan, tgt, sl_analysis_floor_seed(seed, fl), 0, N, ss, NULL, NULL, &err);
    double f[NFV];
    for (int j = 0; j < NFV; j++)
        f[j] = 0.5 * pow(10.0, j / 12.0);
    for (size_t s = 0; s < N; s++) {
        sets[s] = ss[s].set;
        one[2 * s] = (sl_set){ss[s].set.h1, NULL, ss[s].set.v};
        one[2 * s + 1] = (sl_set){ss[s].set.h2, NULL, ss[s].set.v};
        double *ys = y + s * (6 + NFV), psa[2][NFV], ai = 0;
        const sl_synth_check *c1 = &ss[s].check[SL_SYNTH_H1], *c2 = &ss[s].check[SL_SYNTH_H2];
        for (int c = 0; c < 2; c++) {
            const sl_motion *m = c ? sets[s].h2 : sets[s].h1;
            if (sl_spectrum_compute(m->acc_ms2, m->n, m->dt_s, f, NFV, 0.10, psa[c], NULL, NULL,
                                    &err))
                return 1;
            for (size_t i = 0; i < m->n; i++)
                ai += m->acc_ms2[i] * m->acc_ms2[i] * m->dt_s;
        }
        ys[1] = c1->pgv_ms + c2->pgv_ms;
        ys[2] = c1->pga_ms2 + c2->pga_ms2;
        ys[3] = ai;
        ys[4] = sl_set_pgd_100_40(&sets[s]);
        for (int j = 0; j < NFV; j++)
            ys[6 + j] = sqrt(psa[0][j] * psa[1][j]);
    }
    for (size_t i = 0; i < M; i++)
        for (size_t j = 0; j < M; j++)
            cross[i * M + j] = (sl_set){ss[i].set.h1, ss[j].set.h2, ss[i].set.v};
    sl_slide_opts so;
    sl_slide_opts_default(&so);
    if (sl_scatter_slide_batch(sc, sets, N, &so, x, NULL, &err) ||
        sl_scatter_slide_batch(sc, one, 2 * N, &so, x1, NULL, &err) ||
        sl_scatter_slide_batch(sc, cross, M * M, &so, xc, NULL, &err))
        return 1;
    printf("%s, %zu sets (seed %llu): correlation over sets of the design peak X with\n", path, N,
           (unsigned long long)seed);
    printf("%5s %9s %7s %6s %6s %6s %6s %13s | crossed %zu x %zu: share of Var X\n", "mu",
           "mean X", "1-D", "PGV", "PGA", "Arias", "PGD", "SA best (Hz)", M, M);
    for (int k = 0; k < K; k += 5) {
        for (size_t s = 0; s < N; s++)
            y[s * (6 + NFV)] = 0.5 * (x1[2 * s * K + k] + x1[(2 * s + 1) * K + k]);
        double r[5], rb = 0, fb = 0, mx = 0;
        for (int q = 0; q < 5; q++)
            r[q] = corr(x + k, K, y + q, 6 + NFV, N);
        for (int j = 0; j < NFV; j++) {
            double rj = corr(x + k, K, y + 6 + j, 6 + NFV, N);
            if (fabs(rj) > fabs(rb)) {
                rb = rj;
                fb = f[j];
            }
        }
        for (size_t s = 0; s < N; s++)
            mx += x[s * K + k] / (double)N;
        /* two-way ANOVA of X(H1_i, H2_j) */
        double g = 0, va = 0, vb = 0, ve = 0, a[64], b[64];
        size_t m = M < 64 ? M : 64;
        for (size_t i = 0; i < m; i++)
            for (size_t j = 0; j < m; j++)
                g += xc[(i * M + j) * K + k] / (double)(m * m);
        for (size_t i = 0; i < m; i++) {
            a[i] = b[i] = -g;
            for (size_t j = 0; j < m; j++) {
                a[i] += xc[(i * M + j) * K + k] / (double)m;
                b[i] += xc[(j * M + i) * K + k] / (double)m;
            }
        }
        for (size_t i = 0; i < m; i++) {
            va += a[i] * a[i] / (double)(m - 1);
            vb += b[i] * b[i] / (double)(m - 1);
            for (size_t j = 0; j < m; j++) {
                double e = xc[(i * M + j) * K + k] - g - a[i] - b[j];
                ve += e * e / (double)((m - 1) * (m - 1));
            }
        }
        double sa = va - ve / (double)m, sb = vb - ve / (double)m, tot = sa + sb + ve;
        printf("%5.2f %9.4f %+7.2f %+6.2f %+6.2f %+6.2f %+6.2f %+6.2f (%5.2f) | H1 %.2f, H2 %.2f, "
               "interaction %.2f\n", mu[k], mx, r[0], r[1], r[2], r[3], r[4], rb, fb, sa / tot,
               sb / tot, ve / tot);
    }
    return 0;
}

int main(int argc, char **argv)
{
    if (argc >= 5 && !strcmp(argv[1], "pool"))
        return pool(argv[2], (size_t)atoi(argv[3]), (uint64_t)atoll(argv[4]));
    if (argc >= 5 && !strcmp(argv[1], "vr"))
        return vr(argv[2], (size_t)atoi(argv[3]), (uint64_t)atoll(argv[4]),
                  argc > 5 ? (size_t)atoi(argv[5]) : 16);
    if (argc >= 7 && !strcmp(argv[1], "sim"))
        return sim(argc, argv);
    fprintf(stderr, "usage: see the comment at the top of tests/converge-pool.c\n");
    return 2;
}
