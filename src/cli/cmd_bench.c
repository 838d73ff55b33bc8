/*
 * cmd_bench.c - `seislide bench`: speed against error.
 *
 * Prints, and writes to docs/performance.md (--out), on real three-component
 * records from ../shared/records when present (otherwise synthesized ones):
 *  1. the engine over the default friction grid (76 mu): 1-D exact and 2-D
 *     at 1..64 sub-steps;
 *  2. every model and setting (engine sub-steps; smoothed model U_y, eta,
 *     tolerance; elastic-plastic U_y, sub-steps) on a friction subset, with
 *     the error of the peak vector displacement against the converged
 *     reference: the Coulomb solution by the engine at 1024 sub-steps,
 *     shown converged by its agreement with 2048 sub-steps;
 *  3. the Pareto table: for target errors 1 %, 0.1 %, 0.01 % the fastest
 *     setting of each model, and the engine's speed ratio to the smoothed
 *     model at equal error;
 *  4. response spectra: error of the sampled peak against steps per period
 *     and speed;
 *  5. motion synthesis: time to synthesize and verify one three-component
 *     set, 20 s at 200 samples/s, one core, and how well it matches;
 *  6. the arithmetic limit of the 2-D update on this machine, measured by a
 *     branch-free, vectorisable loop doing the update's arithmetic only, and
 *     how far the engine is from it.
 * Timing: best of --repeat runs, one thread (the engine's inner loops are
 * serial; OpenMP parallelism is over motions and is not what is measured).
 */
#include <getopt.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "io/atomic.h"
#include "cli.h"
#include "io/motion.h"
#include "slide/slide.h"
#include "io/setdir.h"
#include "analysis.h"
#include "io/floor.h"
#include "signal/spectrum.h"
#include "synth/synth.h"

#include <omp.h>

/* Relative errors are taken where the reference peak is at least this:
 * below a millimetre a clearance table rounds to zero anyway. */
#define PEAK_FLOOR_M 1e-3
/* Reference sub-steps of the 2-D integrator, and the check of it. */
#define REF_SUBSTEPS 1024u
#define REF_CHECK_SUBSTEPS 2048u
/* Friction subset for the model comparison (the reference models are slow). */
static const double model_mu[] = {0.05, 0.1, 0.2, 0.4};
#define N_MODEL_MU (sizeof model_mu / sizeof model_mu[0])
#define MAX_SETTINGS 64
#define MAX_SETS 3

static const char bench_help[] =
    "usage: seislide bench [--shared DIR] [--repeat N] [--out FILE] [--quick]\n"
    "\n"
    "Speed against error: the engine, the reference models (smoothed Park-Wen with\n"
    "GSL stiff solvers; elastic-plastic Newmark) and response spectra, on the\n"
    "three-component records in DIR/records (default ../shared; synthesized motions\n"
    "when absent). Errors of the peak vector sliding displacement are against the\n"
    "converged Coulomb solution (engine at 1024 sub-steps, checked against 2048).\n"
    "Prints the tables and writes them to FILE (default docs/performance.md).\n"
    "--quick skips the slowest reference-model settings.\n";

/* Output to stdout and to the report file at once. */
static FILE *report;
static void out(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;
static void out(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vprintf(fmt, ap);
    va_end(ap);
    if (report) {
        va_start(ap, fmt);
        vfprintf(report, fmt, ap);
        va_end(ap);
    }
}

/* Deterministic broadband stand-in (sum of sines under an envelope). */
static sl_motion *synth_component(size_t n, double dt, double amp, unsigned seed)
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

static int load_sets(const char *shared, sl_set *sets, char names[][64], int max)
{
    static const char *const dirs[] = {"RSN1063_NORTHR_RRS", "RSN6_IMPVALL.I_I-ELC",
                                       "RSN77_SFERN_PUL"};
    int n = 0;
    for (int r = 0; r < 3 && n < max; r++) {
        char dir[2048];
        snprintf(dir, sizeof dir, "%s/records/%s", shared, dirs[r]);
        sl_error err;
        if (sl_set_read_dir(dir, &sets[n], &err) != SL_OK)
            continue;
        snprintf(names[n], 64, "%s", dirs[r]);
        n++;
    }
    if (n == 0) {
        for (int r = 0; r < 3 && n < max; r++) {
            sets[n].h1 = synth_component(4000, 0.01, 6.0, 17u * (unsigned)r);
            sets[n].h2 = synth_component(4000, 0.01, 6.0, 17u * (unsigned)r + 1u);
            sets[n].v = synth_component(4000, 0.01, 3.0, 17u * (unsigned)r + 2u);
            snprintf(names[n], 64, "synthesized-%d", r + 1);
            n++;
        }
    }
    return n;
}

/* Worst relative error (peaks >= PEAK_FLOOR_M) and absolute error. */
static void errors(const sl_slide_result *res, const sl_slide_result *ref, size_t n, double *rel,
                   double *abs_m)
{
    for (size_t k = 0; k < n; k++) {
        if (ref[k].peak_m >= PEAK_FLOOR_M)
            *rel = fmax(*rel, fabs(res[k].peak_m / ref[k].peak_m - 1));
        *abs_m = fmax(*abs_m, fabs(res[k].peak_m - ref[k].peak_m));
    }
}

/* One model setting measured over all sets on the friction subset. */
typedef struct setting {
    char model[16], label[48];
    sl_slide_opts o;
    double us_per, rel, abs_m; /* mean time per (motion, mu); worst errors */
    int failed;
} setting;

static void time_setting(setting *st, const sl_set *sets, int ns, sl_slide_result ref[][N_MODEL_MU],
                         unsigned long repeat)
{
    double total = 0;
    sl_slide_result res[N_MODEL_MU];
    st->rel = st->abs_m = 0;
    for (int s = 0; s < ns; s++) {
        double best = INFINITY;
        /* the slow reference models are timed once */
        unsigned long reps = st->o.model == SL_MODEL_EXACT ? repeat : 1;
        for (unsigned long r = 0; r < reps; r++) {
            sl_error e;
            double t0 = cli_now_s();
            if (sl_slide_run(&sets[s], model_mu, N_MODEL_MU, &st->o, res, &e) != SL_OK) {
                st->failed = 1;
                return;
            }
            best = fmin(best, cli_now_s() - t0);
        }
        total += best;
        errors(res, ref[s], N_MODEL_MU, &st->rel, &st->abs_m);
    }
    st->us_per = 1e6 * total / ((double)ns * (double)N_MODEL_MU);
}

/* ---- arithmetic limit ----------------------------------------------- */

/* The arithmetic of one 2-D sliding update (midpoint branch) over arrays,
 * branch-free: what the engine must at least compute per (sub-step, mu).
 * Returns the best time per update, s. */
static double limit_time_per_update(void)
{
    enum { M = 4096, ITERS = 200 };
    double *vx = malloc(M * sizeof *vx), *vy = malloc(M * sizeof *vy), *ux = calloc(M, sizeof *ux),
           *uy = calloc(M, sizeof *uy), *mu = malloc(M * sizeof *mu), *pk = calloc(M, sizeof *pk),
           *path = calloc(M, sizeof *path), *spd = malloc(M * sizeof *spd);
    if (!vx || !vy || !ux || !uy || !mu || !pk || !path || !spd) {
        free(vx); free(vy); free(ux); free(uy); free(mu); free(pk); free(path); free(spd);
        return NAN;
    }
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
        double t0 = cli_now_s();
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
        best = fmin(best, (cli_now_s() - t0) / ((double)M * ITERS));
    }
    double sink = 0;
    for (int k = 0; k < M; k++)
        sink += pk[k] + path[k];
    if (!(sink == sink)) /* keep the work observable */
        best = NAN;
    free(vx); free(vy); free(ux); free(uy); free(mu); free(pk); free(path); free(spd);
    return best;
}

int cmd_bench(int argc, char **argv)
{
    const char *shared = "../shared", *out_path = "docs/performance.md";
    unsigned long repeat = 3;
    int quick = 0;
    static const struct option lo[] = {{"shared", required_argument, 0, 's'},
                                       {"repeat", required_argument, 0, 'r'},
                                       {"out", required_argument, 0, 'o'},
                                       {"quick", no_argument, 0, 'q'},
                                       {"help", no_argument, 0, 'h'},
                                       {0, 0, 0, 0}};
    optind = 1;
    opterr = 0;
    int c;
    while ((c = getopt_long(argc, argv, ":", lo, NULL)) != -1) {
        switch (c) {
        case 's': shared = optarg; break;
        case 'o': out_path = optarg; break;
        case 'q': quick = 1; break;
        case 'r':
            if (cli_parse_ulong(optarg, &repeat) || repeat < 1)
                return cli_usage("bench", "--repeat '%s' must be an integer >= 1", optarg);
            break;
        case 'h': fputs(bench_help, stdout); return CLI_EXIT_OK;
        default: return cli_usage("bench", "unknown option '%s'", argv[optind - 1]);
        }
    }
    sl_error err;
    sl_error_clear(&err);
    sl_atomic *af = sl_atomic_open(out_path, &err);
    if (!af) {
        cli_print_error(&err);
        return CLI_EXIT_ERROR;
    }
    report = sl_atomic_file(af);

    sl_set sets[MAX_SETS];
    char names[MAX_SETS][64];
    int ns = load_sets(shared, sets, names, MAX_SETS);
    const size_t nm = 76;
    double mu[76];
    for (size_t k = 0; k < nm; k++)
        mu[k] = 0.05 + 0.01 * (double)k;
    sl_slide_result *ref = calloc(nm, sizeof *ref), *chk = calloc(nm, sizeof *chk),
                    *res = calloc(nm, sizeof *res);
    static sl_slide_result mref[MAX_SETS][N_MODEL_MU];
    if (!ref || !chk || !res) {
        sl_atomic_abort(af);
        cli_msg("out of memory");
        return CLI_EXIT_ERROR;
    }

    out("# Performance: speed against error\n\n");
    out("Generated by `make bench` (`seislide bench`); do not edit by hand. One thread;\n"
        "best of %lu runs for the engine, one run for the reference models. Motions:", repeat);
    for (int s = 0; s < ns; s++)
        out(" %s (%zu samples at %g s)%s", names[s], sets[s].h1->n, sets[s].h1->dt_s,
            s + 1 < ns ? "," : ".\n\n");
    out("Error: the worst relative error of the peak vector sliding displacement over the\n"
        "friction values whose reference peak is at least 1 mm, and the worst absolute\n"
        "error over all of them. Reference: the Coulomb solution by the engine's 2-D\n"
        "integrator at %u sub-steps per sample; its agreement with %u sub-steps is\n"
        "printed per motion (the reference's own error is below that).\n\n",
        REF_SUBSTEPS, REF_CHECK_SUBSTEPS);

    /* 1. the engine over the default friction grid */
    out("## 1. The engine over the default friction grid (mu 0.05:0.80:0.01, 76 values)\n\n");
    out("| motion | setting | us per (motion, mu) | Msamples x mu / s | max rel. error | max abs. error, mm |\n");
    out("|---|---|---|---|---|---|\n");
    for (int s = 0; s < ns; s++) {
        sl_set set2 = sets[s];
        sl_set set1 = {sets[s].h1, NULL, NULL};
        size_t n = sets[s].h1->n;
        sl_slide_opts o;
        sl_slide_opts_default(&o);
        double best = INFINITY;
        for (unsigned long r = 0; r < repeat; r++) {
            double t0 = cli_now_s();
            sl_slide_run(&set1, mu, nm, &o, res, NULL);
            best = fmin(best, cli_now_s() - t0);
        }
        out("| %s | 1-D exact (H1) | %.2f | %.1f | exact | exact |\n", names[s],
            1e6 * best / (double)nm, (double)n * (double)nm / best / 1e6);
        o.substeps = REF_SUBSTEPS;
        sl_slide_run(&set2, mu, nm, &o, ref, NULL);
        o.substeps = REF_CHECK_SUBSTEPS;
        sl_slide_run(&set2, mu, nm, &o, chk, NULL);
        double conv = 0, conv_abs = 0;
        errors(chk, ref, nm, &conv, &conv_abs);
        for (unsigned sub = 1; sub <= 64; sub *= 2) {
            o.substeps = sub;
            best = INFINITY;
            for (unsigned long r = 0; r < repeat; r++) {
                double t0 = cli_now_s();
                sl_slide_run(&set2, mu, nm, &o, res, NULL);
                best = fmin(best, cli_now_s() - t0);
            }
            double rel = 0, abs_m = 0;
            errors(res, ref, nm, &rel, &abs_m);
            out("| %s | 2-D, %u sub-steps | %.2f | %.1f | %.2e | %.3f |\n", names[s], sub,
                1e6 * best / (double)nm, (double)n * (double)nm / best / 1e6, rel, 1e3 * abs_m);
        }
        out("| %s | reference %u vs %u | | | %.1e | %.1e |\n", names[s], REF_SUBSTEPS,
            REF_CHECK_SUBSTEPS, conv, 1e3 * conv_abs);
        /* the model-comparison reference on the subset */
        o.substeps = REF_SUBSTEPS;
        sl_slide_run(&set2, model_mu, N_MODEL_MU, &o, mref[s], NULL);
    }

    /* 2. every model and setting on the friction subset */
    static setting st[MAX_SETTINGS];
    int nst = 0;
    for (unsigned sub = 1; sub <= 64 && nst < MAX_SETTINGS; sub *= 2) {
        setting *x = &st[nst++];
        sl_slide_opts_default(&x->o);
        x->o.substeps = sub;
        snprintf(x->model, sizeof x->model, "engine");
        snprintf(x->label, sizeof x->label, "%u sub-steps", sub);
    }
    const double uys[] = {1e-4, 1e-5, 1e-6, 1e-7};
    const double etas[] = {5, 20};
    const double rtols[] = {1e-4, 1e-6};
    for (int iu = 0; iu < 4; iu++)
        for (int ie = 0; ie < 2; ie++)
            for (int ir = 0; ir < 2; ir++) {
                if (quick && (iu == 3 || ie == 0 || ir == 1))
                    continue;
                setting *x = &st[nst++];
                sl_slide_opts_default(&x->o);
                x->o.model = SL_MODEL_SMOOTH;
                x->o.smooth_uy_m = uys[iu];
                x->o.smooth_eta = etas[ie];
                x->o.smooth_rtol = rtols[ir];
                x->o.smooth_atol = uys[iu] * 1e-2;
                snprintf(x->model, sizeof x->model, "smooth");
                snprintf(x->label, sizeof x->label, "U_y %.0e, eta %.0f, rtol %.0e, msbdf",
                         uys[iu], etas[ie], rtols[ir]);
            }
    /* the other stiff solvers at the study's eta = 20 and the tight tolerance */
    static const char *const solver_names[] = {"msbdf", "rk4imp", "bsimp", "rkf45"};
    for (int iu = 0; iu < 4 && !quick; iu++)
        for (int sv = 1; sv <= 2; sv++) {
            if (sv == 1 && iu >= 3)
                continue; /* rk4imp at U_y = 1e-7: seconds to minutes per run */
            setting *x = &st[nst++];
            sl_slide_opts_default(&x->o);
            x->o.model = SL_MODEL_SMOOTH;
            x->o.smooth_uy_m = uys[iu];
            x->o.smooth_eta = 20;
            x->o.smooth_rtol = 1e-6;
            x->o.smooth_atol = uys[iu] * 1e-2;
            x->o.smooth_solver = sv;
            snprintf(x->model, sizeof x->model, "smooth");
            snprintf(x->label, sizeof x->label, "U_y %.0e, eta 20, rtol 1e-06, %s", uys[iu],
                     solver_names[sv]);
        }
    for (int iu = 0; iu < 4; iu++)
        for (unsigned sub = 8; sub <= 512; sub *= 8) {
            setting *x = &st[nst++];
            sl_slide_opts_default(&x->o);
            x->o.model = SL_MODEL_PLASTIC;
            x->o.plastic_uy_m = uys[iu];
            x->o.plastic_substeps = sub;
            snprintf(x->model, sizeof x->model, "plastic");
            snprintf(x->label, sizeof x->label, "U_y %.0e, %u sub-steps", uys[iu], sub);
        }
    out("\n## 2. Every model and setting (mu = 0.05, 0.1, 0.2, 0.4; all motions)\n\n");
    double mean_n = 0;
    for (int s2 = 0; s2 < ns; s2++)
        mean_n += (double)sets[s2].h1->n / ns;
    out("| model | setting | ms per (motion, mu) | Msamples x mu / s | max rel. error | max abs. error, mm |\n");
    out("|---|---|---|---|---|---|\n");
    for (int i = 0; i < nst; i++) {
        fprintf(stderr, "seislide: bench: %s %s\n", st[i].model, st[i].label);
        time_setting(&st[i], sets, ns, mref, repeat);
        if (st[i].failed)
            out("| %s | %s | solver failed | | | |\n", st[i].model, st[i].label);
        else
            out("| %s | %s | %.3f | %.3g | %.2e | %.3f |\n", st[i].model, st[i].label,
                1e-3 * st[i].us_per, mean_n / st[i].us_per, st[i].rel, 1e3 * st[i].abs_m);
    }

    /* 3. Pareto */
    out("\n## 3. Fastest setting per model for a target error\n\n");
    out("| target | engine | smooth | plastic | engine speed-up over smooth |\n");
    out("|---|---|---|---|---|\n");
    const double targets[] = {1e-2, 1e-3, 1e-4};
    for (int t = 0; t < 3; t++) {
        int best[3] = {-1, -1, -1};
        const char *models[3] = {"engine", "smooth", "plastic"};
        for (int i = 0; i < nst; i++) {
            if (st[i].failed || !(st[i].rel <= targets[t]))
                continue;
            for (int q = 0; q < 3; q++)
                if (!strcmp(st[i].model, models[q]) &&
                    (best[q] < 0 || st[i].us_per < st[best[q]].us_per))
                    best[q] = i;
        }
        char cell[3][96];
        for (int q = 0; q < 3; q++) {
            if (best[q] < 0)
                snprintf(cell[q], sizeof cell[q], "not reached");
            else
                snprintf(cell[q], sizeof cell[q], "%s (%.3f ms)", st[best[q]].label,
                         1e-3 * st[best[q]].us_per);
        }
        char ratio[48] = "n/a (smooth does not reach it)";
        if (best[0] >= 0 && best[1] >= 0)
            snprintf(ratio, sizeof ratio, "%.0f x", st[best[1]].us_per / st[best[0]].us_per);
        out("| %.0e | %s | %s | %s | %s |\n", targets[t], cell[0], cell[1], cell[2], ratio);
    }

    /* 4. response spectra */
    out("\n## 4. Response spectra: sampled-peak error against steps per period\n\n");
    out("5 %% damping, 271 frequencies 0.1-50 Hz, H1 of each motion. Reference: 640 steps per\n"
        "period. Error: worst relative error of PSA over the frequencies.\n\n");
    out("| motion | steps per period | ms per spectrum | max rel. error |\n|---|---|---|---|\n");
    {
        size_t nf = 0;
        double *f = sl_spectrum_grid(SL_SPECTRUM_FMIN_HZ, SL_SPECTRUM_FMAX_HZ,
                                     SL_SPECTRUM_PER_DECADE, &nf);
        double *pref = malloc(nf * sizeof *pref), *p = malloc(nf * sizeof *p);
        for (int s = 0; f && pref && p && s < ns; s++) {
            const sl_motion *m = sets[s].h1;
            sl_spectrum_opts so;
            sl_spectrum_opts_default(&so);
            so.steps_per_period = 640;
            sl_spectrum_compute_opts(m->acc_ms2, m->n, m->dt_s, f, nf, 0.05, &so, pref, NULL,
                                     NULL, NULL);
            const double spp[] = {5, 10, 20, 40, 80};
            for (int q = 0; q < 5; q++) {
                so.steps_per_period = spp[q];
                double best = INFINITY;
                for (unsigned long r = 0; r < repeat; r++) {
                    double t0 = cli_now_s();
                    sl_spectrum_compute_opts(m->acc_ms2, m->n, m->dt_s, f, nf, 0.05, &so, p, NULL,
                                             NULL, NULL);
                    best = fmin(best, cli_now_s() - t0);
                }
                double e = 0;
                for (size_t j = 0; j < nf; j++)
                    e = fmax(e, fabs(p[j] / pref[j] - 1));
                out("| %s | %.0f | %.2f | %.2e |\n", names[s], spp[q], 1e3 * best, e);
            }
        }
        free(f);
        free(pref);
        free(p);
    }

    /* 5. synthesis */
    {
        const int nseeds = 10;
        out("\n## 5. Motion synthesis: one three-component set, 20 s at 200 samples/s\n\n");
        out("RG 1.60 at 0.3 g, 5 %% damping; each set synthesized and verified (every check of\n"
            "../shared/docs/REFERENCE.md section 5) on one thread; %d seeds.\n\n", nseeds);
        sl_synth_params sp;
        sl_synth_params_default(&sp);
        sl_spectrum *spec[SL_SYNTH_NCOMP] = {NULL};
        sl_synth_target tgt[SL_SYNTH_NCOMP];
        sl_synth *sy = NULL;
        size_t n = (size_t)(SL_SYNTH_DURATION_S / SL_SYNTH_DT_S + 0.5) + 1;
        if (sl_synth_targets_rg160(0.3 * SL_G, SL_SYNTH_DAMPING, &sp, spec, tgt, &err) == SL_OK)
            sy = sl_synth_alloc(n, SL_SYNTH_DT_S, &sp, &err);
        if (!sy) {
            out("synthesis unavailable: %s\n", err.msg);
        } else {
            int saved = omp_get_max_threads(), passed = 0;
            omp_set_num_threads(1);
            double tsum = 0, tmax = 0, worst_lo = INFINITY, worst_hi = 0, worst_corr = 0;
            for (int q = 0; q < nseeds; q++) {
                sl_synth_set set;
                double t0 = cli_now_s();
                sl_status sst = sl_synth_make_set(sy, tgt, 1000u + (uint64_t)q, 0, &set, NULL);
                double t = cli_now_s() - t0;
                tsum += t;
                tmax = fmax(tmax, t);
                passed += (sst == SL_OK && set.pass);
                for (int cc = 0; cc < SL_SYNTH_NCOMP; cc++) {
                    worst_lo = fmin(worst_lo, set.check[cc].min_ratio);
                    worst_hi = fmax(worst_hi, set.check[cc].max_ratio);
                }
                for (int cc = 0; cc < SL_SYNTH_NPAIR; cc++)
                    if (isfinite(set.corr[cc]))
                        worst_corr = fmax(worst_corr, fabs(set.corr[cc]));
                sl_synth_set_clear(&set);
            }
            omp_set_num_threads(saved);
            out("| sets passed | mean s per set | max s per set | spectrum / target (min, max) | max abs. correlation |\n");
            out("|---|---|---|---|---|\n");
            out("| %d / %d | %.3f | %.3f | %.3f, %.3f | %.3f |\n", passed, nseeds, tsum / nseeds,
                tmax, worst_lo, worst_hi, worst_corr);
            sl_synth_free(sy);
        }
        for (int cc = 0; cc < SL_SYNTH_NCOMP; cc++)
            sl_spectrum_free(spec[cc]);
    }

    /* 6. the example facility, the main job */
    {
        static const char *const fl_files[] = {"floors/01-ground.ini", "floors/02-el12.ini",
                                               "floors/03-el24.ini", "floors/04-roof36.ini"};
        out("\n## 6. The main job on the example facility (`seislide run` on floors/)\n\n");
        out("76 friction values, 8 sub-steps; all threads of this machine (%d); wall time.\n"
            "Two settings per floor: a fixed 7 motion sets (the former default) and the\n"
            "default since issue 13, sets added until the standard error of the design\n"
            "value is <= max(5 %%, 1 mm) at every mu (docs/run.md, \"Convergence\"). The\n"
            "time per set does not depend on the setting; the number of sets does.\n\n",
            omp_get_max_threads());
        out("| floor | setting | sets | stop | synthesis, s | NLTHA, s | statistics, s | ASCE + design, s | total, s | s per set | synthesis share | mu not integrated |\n");
        out("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
        double tot[2][4] = {{0}};
        size_t tsets[2] = {0, 0};
        for (int mode = 0; mode < 2; mode++)
            for (size_t i = 0; i < sizeof fl_files / sizeof fl_files[0]; i++) {
                sl_error fe;
                sl_floor *fl = sl_floor_load(fl_files[i], &fe);
                if (!fl) {
                    out("| %s | not found (run from the repository root) | | | | | | | | | | |\n",
                        fl_files[i]);
                    continue;
                }
                sl_analysis_opts ao;
                sl_analysis_opts_default(&ao);
                ao.mu = mu;
                ao.n_mu = nm;
                ao.n_sets = mode == 0 ? 7 : 0;
                sl_analysis *an = sl_analysis_run(fl, &ao, &fe);
                if (an) {
                    double t[4] = {an->time_synth_s, an->time_nltha_s, an->time_stats_s,
                                   an->time_asce_s};
                    double all = t[0] + t[1] + t[2] + t[3];
                    out("| %s | %s | %zu | %s | %.2f | %.2f | %.3f | %.3f | %.2f | %.3f | %.0f %% | %zu of %zu |\n",
                        fl->name, mode == 0 ? "7 sets" : "converged", an->n_sets,
                        sl_analysis_stop_name(an->stop), t[0], t[1], t[2], t[3], all,
                        all / (double)an->n_sets, 100 * t[0] / all, an->n_mu_skipped, nm);
                    for (int q = 0; q < 4; q++)
                        tot[mode][q] += t[q];
                    tsets[mode] += an->n_sets;
                }
                sl_analysis_free(an);
                sl_floor_free(fl);
            }
        for (int mode = 0; mode < 2; mode++) {
            double all = tot[mode][0] + tot[mode][1] + tot[mode][2] + tot[mode][3];
            out("| all floors | %s | %zu | | %.2f | %.2f | %.3f | %.3f | %.2f | %.3f | %.0f %% | |\n",
                mode == 0 ? "7 sets" : "converged", tsets[mode], tot[mode][0], tot[mode][1],
                tot[mode][2], tot[mode][3], all, tsets[mode] ? all / (double)tsets[mode] : 0.0,
                all > 0 ? 100 * tot[mode][0] / all : 0.0);
        }
    }

    /* 7. arithmetic limit */
    {
        double tl = limit_time_per_update();
        out("\n## 7. How close the engine comes to this machine's arithmetic limit\n\n");
        out("The limit is measured, not guessed: a branch-free loop over 4096 independent\n"
            "blocks doing only the arithmetic of one 2-D sliding update (midpoint friction\n"
            "direction: 2 square roots, 1 division, about 30 other flops; the compiler\n"
            "vectorises it) runs at %.2f ns per update on this machine (best of 5).\n"
            "A block at rest costs the engine one compare, so this is the ceiling for a\n"
            "block that slides all the time.\n\n", 1e9 * tl);
        out("| motion | engine at 16 sub-steps: ns per (sub-step, mu) | sliding share | ns per sliding update, at most | limit, ns | ratio |\n");
        out("|---|---|---|---|---|---|\n");
        for (int s = 0; s < ns; s++) {
            sl_set set2 = sets[s];
            sl_slide_opts o;
            sl_slide_opts_default(&o);
            o.substeps = 16;
            double best = INFINITY;
            for (unsigned long r = 0; r < repeat; r++) {
                double t0 = cli_now_s();
                sl_slide_run(&set2, mu, nm, &o, res, NULL);
                best = fmin(best, cli_now_s() - t0);
            }
            double per = best / ((double)sets[s].h1->n * 16.0 * (double)nm);
            /* sliding updates: time spent sliding within the record / h */
            double h = sets[s].h1->dt_s / 16.0, tend = (double)(sets[s].h1->n - 1) * sets[s].h1->dt_s;
            double nslide = 0;
            for (size_t k = 0; k < nm; k++)
                nslide += fmin(res[k].slide_time_s, tend) / h;
            double share = nslide / ((double)sets[s].h1->n * 16.0 * (double)nm);
            double per_slide = nslide > 0 ? best / nslide : NAN;
            out("| %s | %.2f | %.2f | %.2f | %.2f | %.2f |\n", names[s], 1e9 * per, share,
                1e9 * per_slide, 1e9 * tl, per_slide / tl);
        }
        out("\n'ns per sliding update, at most' charges all of the engine's time to the\n"
            "(sub-step, mu) pairs in which the block slides (its time sliding over h),\n"
            "ignoring the cost of the pairs at rest: the ratio to the limit is therefore an\n"
            "upper bound on how far the engine is from the arithmetic limit.\n");
    }

    for (int s = 0; s < ns; s++)
        sl_set_free_motions(&sets[s]);
    free(ref);
    free(chk);
    free(res);
    report = NULL;
    if (sl_atomic_commit(af, &err)) {
        cli_print_error(&err);
        return CLI_EXIT_ERROR;
    }
    fprintf(stderr, "seislide: bench: wrote %s\n", out_path);
    return CLI_EXIT_OK;
}
