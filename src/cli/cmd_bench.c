/*
 * cmd_bench.c - `seislide bench`: speed against error of the sliding engine.
 *
 * For each test motion (three-component records from ../shared/records when
 * present, otherwise synthesized broadband motions) and the default friction
 * grid (mu 0.05..0.80 step 0.01), times the engine and measures the error of
 * the peak vector displacement against a converged reference: the 2-D
 * integrator at 1024 sub-steps, shown converged by its agreement with 2048
 * sub-steps (printed). Timing: best of several repeats, one thread.
 */
#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cli.h"
#include "motion.h"
#include "slide.h"

/* Relative errors are reported where the reference peak is at least this:
 * below a millimetre a clearance table rounds to zero anyway. */
#define PEAK_FLOOR_M 1e-3

static const char bench_help[] =
    "usage: seislide bench [--shared DIR] [--repeat N]\n"
    "\n"
    "Speed against error of the sliding engine: time per (motion, mu), throughput\n"
    "in samples x mu per second on one thread, and the worst relative error of the\n"
    "peak vector displacement against a converged reference (2-D: 1024 sub-steps,\n"
    "checked against 2048). Motions: three-component records from DIR/records\n"
    "(default ../shared), else synthesized ones.\n";

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
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
        double ph = 6.283185307179586 * (double)((s >> 8) & 0xffff) / 65535.0;
        for (size_t i = 0; i < n; i++) {
            double t = (double)i * dt, T = (double)(n - 1) * dt;
            double env = sin(3.141592653589793 * t / T);
            a[i] += amp / 8.0 * env * env * sin(6.283185307179586 * f * t + ph) / sqrt(1.0 + f);
        }
    }
    sl_motion *m = sl_motion_from_array(a, n, dt, "synthesized");
    free(a);
    return m;
}

typedef struct bench_set {
    char name[64];
    sl_motion *m[3];
} bench_set;

static int load_sets(const char *shared, bench_set *sets, int max)
{
    static const char *const names[][4] = {
        {"RSN1063_NORTHR_RRS", "Rinaldi228.AT2", "Rinaldi318.AT2", "RinaldiUP.AT2"},
        {"RSN6_IMPVALL.I_I-ELC", "RSN6_IMPVALL.I_I-ELC180.AT2",
         "RSN6_IMPVALL.I_I-ELC270-hor2.AT2", "RSN6_IMPVALL.I_I-ELC-UP.AT2"},
        {"RSN77_SFERN_PUL", "RSN77_SFERN_PUL164.AT2", "RSN77_SFERN_PUL254-hor2.AT2",
         "RSN77_SFERN_PULDWN-up.AT2"},
    };
    int n = 0;
    for (int r = 0; r < 3 && n < max; r++) {
        sl_read_opts ro = {SL_FORMAT_AUTO, SL_UNIT_NONE, 0};
        sl_error err;
        int ok = 1;
        for (int c = 0; c < 3; c++) {
            char p[2048];
            snprintf(p, sizeof p, "%s/records/%s/%s", shared, names[r][0], names[r][c + 1]);
            sets[n].m[c] = sl_motion_read(p, &ro, &err);
            ok &= sets[n].m[c] != NULL;
        }
        sl_set s = {sets[n].m[0], sets[n].m[1], sets[n].m[2]};
        if (ok && sl_set_check(&s, 1, &err) == SL_OK) {
            snprintf(sets[n].name, sizeof sets[n].name, "%s", names[r][0]);
            n++;
        } else {
            for (int c = 0; c < 3; c++)
                sl_motion_free(sets[n].m[c]);
        }
    }
    if (n == 0) {
        for (int r = 0; r < 3 && n < max; r++) {
            for (int c = 0; c < 3; c++)
                sets[n].m[c] = synth_component(4000, 0.01, c == 2 ? 3.0 : 6.0, 17u * (unsigned)r + (unsigned)c);
            snprintf(sets[n].name, sizeof sets[n].name, "synthesized-%d", r + 1);
            n++;
        }
    }
    return n;
}

int cmd_bench(int argc, char **argv)
{
    const char *shared = "../shared";
    unsigned long repeat = 3;
    static const struct option lo[] = {{"shared", required_argument, 0, 's'},
                                       {"repeat", required_argument, 0, 'r'},
                                       {"help", no_argument, 0, 'h'},
                                       {0, 0, 0, 0}};
    optind = 1;
    opterr = 0;
    int c;
    while ((c = getopt_long(argc, argv, ":", lo, NULL)) != -1) {
        switch (c) {
        case 's': shared = optarg; break;
        case 'r':
            if (cli_parse_ulong(optarg, &repeat) || repeat < 1)
                return cli_usage("bench", "--repeat '%s' must be an integer >= 1", optarg);
            break;
        case 'h': fputs(bench_help, stdout); return CLI_EXIT_OK;
        default: return cli_usage("bench", "unknown option '%s'", argv[optind - 1]);
        }
    }
    bench_set sets[3];
    int ns = load_sets(shared, sets, 3);
    const size_t nm = 76;
    double mu[76];
    for (size_t k = 0; k < nm; k++)
        mu[k] = 0.05 + 0.01 * (double)k;
    sl_slide_result *ref = calloc(nm, sizeof *ref), *chk = calloc(nm, sizeof *chk),
                    *res = calloc(nm, sizeof *res);
    if (!ref || !chk || !res) {
        cli_msg("out of memory");
        return CLI_EXIT_ERROR;
    }
    printf("# seislide bench: sliding engine, speed against error (one thread)\n");
    printf("# mu grid 0.05:0.80:0.01 (%zu values); time per (motion, mu) is for the whole\n"
           "# record; throughput counts input samples x mu per second.\n", nm);
    printf("# max_rel_err: over mu whose reference peak is >= 1 mm; max_abs_err_mm: all mu\n");
    printf("%-22s %-10s %8s %12s %14s %12s %12s\n", "motion", "setting", "samples",
           "us/(mot,mu)", "Msamples*mu/s", "max_rel_err", "max_abs_mm");
    for (int s = 0; s < ns; s++) {
        sl_set set2 = {sets[s].m[0], sets[s].m[1], sets[s].m[2]};
        sl_set set1 = {sets[s].m[0], NULL, NULL};
        size_t n = sets[s].m[0]->n;
        sl_slide_opts o;
        sl_slide_opts_default(&o);
        /* 1-D exact: error against itself is zero by construction; report
         * its agreement with the 2-D integrator at 1024 sub-steps on H1 alone */
        double best = INFINITY;
        for (unsigned long r = 0; r < repeat; r++) {
            double t0 = now_s();
            sl_slide_run(&set1, mu, nm, &o, res, NULL);
            best = fmin(best, now_s() - t0);
        }
        printf("%-22s %-10s %8zu %12.2f %14.1f %12s %12s\n", sets[s].name, "1-D exact", n,
               1e6 * best / (double)nm, (double)n * (double)nm / best / 1e6, "exact", "exact");
        o.substeps = 1024;
        sl_slide_run(&set2, mu, nm, &o, ref, NULL);
        o.substeps = 2048;
        sl_slide_run(&set2, mu, nm, &o, chk, NULL);
        double conv = 0;
        for (size_t k = 0; k < nm; k++)
            if (ref[k].peak_m >= PEAK_FLOOR_M)
                conv = fmax(conv, fabs(chk[k].peak_m / ref[k].peak_m - 1));
        for (unsigned sub = 1; sub <= 64; sub *= 2) {
            o.substeps = sub;
            best = INFINITY;
            for (unsigned long r = 0; r < repeat; r++) {
                double t0 = now_s();
                sl_slide_run(&set2, mu, nm, &o, res, NULL);
                best = fmin(best, now_s() - t0);
            }
            double err = 0, aerr = 0;
            for (size_t k = 0; k < nm; k++) {
                /* relative error where the peak is at least 1 mm; absolute everywhere */
                if (ref[k].peak_m >= PEAK_FLOOR_M)
                    err = fmax(err, fabs(res[k].peak_m / ref[k].peak_m - 1));
                aerr = fmax(aerr, fabs(res[k].peak_m - ref[k].peak_m));
            }
            char label[32];
            snprintf(label, sizeof label, "2-D sub %u", sub);
            printf("%-22s %-10s %8zu %12.2f %14.1f %12.2e %12.2e\n", sets[s].name, label, n,
                   1e6 * best / (double)nm, (double)n * (double)nm / best / 1e6, err, 1e3 * aerr);
        }
        printf("%-22s reference 1024 vs 2048 sub-steps: max rel. difference %.1e\n",
               sets[s].name, conv);
    }
    for (int s = 0; s < ns; s++)
        for (int q = 0; q < 3; q++)
            sl_motion_free(sets[s].m[q]);
    free(ref);
    free(chk);
    free(res);
    return CLI_EXIT_OK;
}
