/* cmd_run.c - `seislide run`: the main job. Floor response spectra in,
 * per-floor design sliding spectra and clearance tables out (XLSX + CSV). */
#include <errno.h>
#include <getopt.h>
#include <glob.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>
#include <zlib.h>

#include "analysis.h"
#include "method/asce.h"
#include "cli.h"
#include "io/floor.h"
#include "report/report.h"

#define RUN_DEFAULT_DIR "floors"
#define RUN_DEFAULT_OUT "output"
#define RUN_WORKBOOK "seislide-clearance.xlsx"
#define RUN_DEFAULT_MU_RANGE "0.05:0.80:0.01"
#define MAX_FLOORS 256

static const char run_help[] =
    "usage: seislide run [FLOOR.ini ... | DIR] [-o DIR] [-q] [--seed S]\n"
    "                    [--sets N | --rel-se R --abs-se MM --max-sets N]\n"
    "                    [--mu-range A:B:S | --mu LIST] [--policy nltha|asce|envelope]\n"
    "                    [--accuracy 0.01|0.001|0.0001 | --substeps N] [--created EPOCH]\n"
    "\n"
    "The main job: for every floor response spectrum file (default: every *.ini in\n"
    "floors/), synthesize spectrum-compatible three-component motion sets, compute\n"
    "the peak vector sliding displacement of each by NLTHA over the friction grid,\n"
    "the ASCE/SEI 43-05 estimate, the design sliding spectra (NLTHA 3.0 x mean, ASCE\n"
    "2.0 x best estimate, both capped at 1.5 x the mean peak floor displacement),\n"
    "the mu g/ZPA crossover and the required clearance, and write:\n"
    "  DIR/" RUN_WORKBOOK "   lookup (floor drop-down + mu -> clearance),\n"
    "      summary, one sheet and chart per floor, motion quality, inputs\n"
    "  DIR/floor_<name>.csv, DIR/summary.csv, DIR/floors.csv,\n"
    "      DIR/motion_quality.csv (RFC 4180, units in the column names)\n"
    "\n"
    "  -o, --output DIR     output folder (default output/; created if missing)\n"
    "  -q, --quiet          no progress on stderr\n"
    "  --sets N             a fixed number of motion sets per floor (ASCE 43-05: >= 5)\n"
    "                       instead of adding sets until converged (the default):\n"
    "  --rel-se R           target standard error of the design value, relative\n"
    "                       (default 0.05), or\n"
    "  --abs-se MM          absolute, mm (default 1), whichever is larger, at every mu\n"
    "  --max-sets N         stop there if not converged, flagged (default 200)\n"
    "  --seed S             random seed (default 1); a floor's seed also depends on its\n"
    "                       spectra's numbers (or its 'seed =' key), never on its name\n"
    "                       or on the other floors\n"
    "  --mu-range A:B:S     friction grid (default " RUN_DEFAULT_MU_RANGE ")\n"
    "  --mu LIST            explicit friction values, increasing\n"
    "  --policy P           required clearance: nltha (default: the NLTHA design value,\n"
    "                       which ASCE 43-05 permits everywhere), asce, or envelope\n"
    "  --accuracy E         relative accuracy of the 2-D integration: 0.01 -> 1 sub-step,\n"
    "                       0.001 (default) -> 8, 0.0001 -> 32 (docs/performance.md)\n"
    "  --substeps N         set the 2-D sub-steps directly\n"
    "  --motions            also write every synthesized motion (AT2, in g) to\n"
    "                       DIR/motions/<floor>/setNN_{h1,h2,v}.AT2, for audit\n"
    "  --created EPOCH      workbook creation time, s since 1970 (default: the\n"
    "                       SOURCE_DATE_EPOCH environment variable, else now)\n"
    "\n"
    "Work a floor does not need is not done: friction values with mu g at or above\n"
    "what a motion can demand are not integrated (reported as skipped).\n"
    "Exit status: 0 success, 1 bad input or failed run (no output file is left\n"
    "half-written), 2 usage error.\n";

/* Sub-steps for a requested accuracy, from the measured table in
 * docs/performance.md (worst relative error of the peak on real records). */
static unsigned substeps_for(double acc)
{
    if (acc >= 1e-2)
        return 1;
    if (acc >= 1e-3)
        return 8;
    if (acc >= 1e-4)
        return 32;
    return 128;
}

typedef struct progress_ctx {
    int quiet;
    size_t floor, n_floors;
    const char *name;
    int last_pct;
    const char *last_step;
} progress_ctx;

static void progress(void *ctx, const char *step, size_t done, size_t total)
{
    progress_ctx *p = ctx;
    if (p->quiet || total == 0)
        return;
    int pct = (int)(100.0 * (double)done / (double)total);
    if (p->last_step == step && pct < p->last_pct + 25 && done != total)
        return;
    p->last_step = step;
    p->last_pct = pct;
    fprintf(stderr, "seislide: run: floor %zu/%zu '%s': %s %zu/%zu (%d %%)\n", p->floor,
            p->n_floors, p->name, step, done, total, pct);
}

static int file_crc(const char *path, unsigned long *crc, long *size)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return -1;
    uLong c = crc32(0L, Z_NULL, 0);
    unsigned char buf[65536];
    size_t n;
    long total = 0;
    while ((n = fread(buf, 1, sizeof buf, f)) > 0) {
        c = crc32(c, buf, (uInt)n);
        total += (long)n;
    }
    int bad = ferror(f);
    fclose(f);
    *crc = c;
    *size = total;
    return bad ? -1 : 0;
}

static int add_inputs(const char *arg, char **paths, size_t *n)
{
    struct stat st;
    if (stat(arg, &st) != 0) {
        cli_msg("%s: %s", arg, strerror(errno));
        return -1;
    }
    if (S_ISDIR(st.st_mode)) {
        char pat[4096];
        snprintf(pat, sizeof pat, "%s/*.ini", arg);
        glob_t g;
        int rc = glob(pat, 0, NULL, &g); /* sorted */
        if (rc == GLOB_NOMATCH) {
            cli_msg("%s: no floor files (*.ini) in this folder", arg);
            return -1;
        }
        if (rc != 0) {
            cli_msg("%s: cannot list the folder", arg);
            return -1;
        }
        int full = 0;
        for (size_t i = 0; i < g.gl_pathc && !full; i++) {
            full = *n >= MAX_FLOORS;
            if (!full)
                paths[(*n)++] = strdup(g.gl_pathv[i]);
        }
        globfree(&g);
        if (full) {
            cli_msg("%s: more than %d floor files in one run", arg, MAX_FLOORS);
            return -1;
        }
    } else if (*n < MAX_FLOORS) {
        paths[(*n)++] = strdup(arg);
    } else {
        cli_msg("%s: more than %d floor files in one run", arg, MAX_FLOORS);
        return -1;
    }
    return 0;
}

int cmd_run(int argc, char **argv)
{
    enum { O_MOTIONS = 300 };
enum { O_SETS = 256, O_SEED, O_MU, O_MU_RANGE, O_POLICY, O_ACC, O_SUB, O_CREATED, O_HELP };
    enum { O_REL_SE = 320, O_ABS_SE, O_MAX_SETS };
    static const struct option lo[] = {{"output", required_argument, 0, 'o'},
                                       {"quiet", no_argument, 0, 'q'},
                                       {"sets", required_argument, 0, O_SETS},
                                       {"seed", required_argument, 0, O_SEED},
                                       {"mu", required_argument, 0, O_MU},
                                       {"mu-range", required_argument, 0, O_MU_RANGE},
                                       {"policy", required_argument, 0, O_POLICY},
                                       {"accuracy", required_argument, 0, O_ACC},
                                       {"substeps", required_argument, 0, O_SUB},
                                       {"created", required_argument, 0, O_CREATED},
                                       {"motions", no_argument, 0, O_MOTIONS},
                                       {"rel-se", required_argument, 0, O_REL_SE},
                                       {"abs-se", required_argument, 0, O_ABS_SE},
                                       {"max-sets", required_argument, 0, O_MAX_SETS},
                                       {"help", no_argument, 0, O_HELP},
                                       {0, 0, 0, 0}};
    const char *outdir = RUN_DEFAULT_OUT;
    int quiet = 0, rc = CLI_EXIT_ERROR, write_motions = 0;
    unsigned long ul, seed = 1, n_sets = 0, max_sets = SL_ANALYSIS_MAX_SETS;
    double rel_se = SL_ANALYSIS_REL_SE, abs_se_mm = 1e3 * SL_ANALYSIS_ABS_SE_M;
    unsigned substeps = 0;
    double acc = 1e-3, *mu = NULL;
    size_t n_mu = 0;
    int policy = SL_CLEARANCE_NLTHA;
    long long created = -1;
    char *paths[MAX_FLOORS];
    size_t np = 0;
    sl_floor *floors[MAX_FLOORS] = {NULL};
    sl_analysis *an[MAX_FLOORS] = {NULL};
    sl_report_floor *rf = NULL;
    sl_report_quality *rq = NULL;
    char (*why)[160] = NULL;
    char *cmdline = NULL;
    sl_error err;
    sl_error_clear(&err);

    optind = 1;
    opterr = 0;
    int c;
    while ((c = getopt_long(argc, argv, ":o:q", lo, NULL)) != -1) {
        const char *arg = optarg;
        switch (c) {
        case 'o': outdir = arg; break;
        case 'q': quiet = 1; break;
        case O_SETS:
            if (cli_parse_ulong(arg, &n_sets) || n_sets < 1 || n_sets > 1000) {
                rc = cli_usage("run", "--sets '%s' must be an integer from 1 to 1000", arg);
                goto done;
            }
            break;
        case O_SEED:
            if (cli_parse_ulong(arg, &seed)) {
                rc = cli_usage("run", "--seed '%s' must be a non-negative integer", arg);
                goto done;
            }
            break;
        case O_MU:
        case O_MU_RANGE:
            if (cli_friction("run", c != O_MU, arg, &mu, &n_mu)) {
                rc = CLI_EXIT_USAGE;
                goto done;
            }
            break;
        case O_POLICY:
            if ((policy = sl_clearance_policy_parse(arg)) < 0) {
                rc = cli_usage("run", "unknown policy '%s' (nltha, asce, envelope)", arg);
                goto done;
            }
            break;
        case O_ACC:
            if (cli_positive("run", "--accuracy", arg, NULL, &acc)) {
                rc = CLI_EXIT_USAGE;
                goto done;
            }
            break;
        case O_SUB:
            if (cli_parse_ulong(arg, &ul) || ul < 1 || ul > 100000) {
                rc = cli_usage("run", "--substeps '%s' must be an integer >= 1", arg);
                goto done;
            }
            substeps = (unsigned)ul;
            break;
        case O_CREATED: {
            double v;
            if (cli_parse_double(arg, &v) || v < 0) {
                rc = cli_usage("run", "--created '%s' must be seconds since 1970", arg);
                goto done;
            }
            created = (long long)v;
            break;
        }
        case O_MOTIONS: write_motions = 1; break;
        case O_REL_SE:
            if (cli_parse_double(arg, &rel_se) || !(rel_se >= 0 && rel_se < 1)) {
                rc = cli_usage("run", "--rel-se '%s' must be a number in [0, 1)", arg);
                goto done;
            }
            break;
        case O_ABS_SE:
            if (cli_parse_double(arg, &abs_se_mm) || !(abs_se_mm >= 0) || !isfinite(abs_se_mm)) {
                rc = cli_usage("run", "--abs-se '%s' must be a number >= 0 (mm)", arg);
                goto done;
            }
            break;
        case O_MAX_SETS:
            if (cli_parse_ulong(arg, &max_sets) || max_sets < 2 || max_sets > 10000) {
                rc = cli_usage("run", "--max-sets '%s' must be an integer from 2 to 10000", arg);
                goto done;
            }
            break;
        case O_HELP:
            fputs(run_help, stdout);
            rc = CLI_EXIT_OK;
            goto done;
        case ':':
            rc = cli_usage("run", "option '%s' needs a value", argv[optind - 1]);
            goto done;
        default:
            rc = cli_usage("run", "unknown option '%s'", argv[optind - 1]);
            goto done;
        }
    }
    if (!(rel_se > 0 || abs_se_mm > 0)) {
        rc = cli_usage("run", "--rel-se and --abs-se cannot both be 0");
        goto done;
    }
    if (!mu && cli_parse_range(RUN_DEFAULT_MU_RANGE, &mu, &n_mu)) {
        cli_msg("out of memory");
        goto done;
    }
    for (size_t k = 0; k < n_mu; k++)
        if (!(mu[k] > 0) || (k > 0 && !(mu[k] > mu[k - 1]))) {
            rc = cli_usage("run", "friction values must be > 0 and increasing (%g)", mu[k]);
            goto done;
        }
    if (substeps == 0)
        substeps = substeps_for(acc);
    if (created < 0) {
        const char *sde = getenv("SOURCE_DATE_EPOCH");
        double v;
        created = (sde && !cli_parse_double(sde, &v) && v >= 0) ? (long long)v : (long long)time(NULL);
    }
    if (optind == argc) {
        if (add_inputs(RUN_DEFAULT_DIR, paths, &np))
            goto done;
    }
    for (int i = optind; i < argc; i++)
        if (add_inputs(argv[i], paths, &np))
            goto done;

    /* read and check every floor before any long work */
    for (size_t i = 0; i < np; i++) {
        floors[i] = sl_floor_load(paths[i], &err);
        if (!floors[i]) {
            cli_print_error(&err);
            goto done;
        }
    }
    if (mkdir(outdir, 0777) != 0 && errno != EEXIST) {
        cli_msg("%s: cannot create the output folder: %s", outdir, strerror(errno));
        goto done;
    }

    sl_analysis_opts ao;
    sl_analysis_opts_default(&ao);
    ao.n_sets = n_sets;
    ao.rel_se = rel_se;
    ao.abs_se_m = 1e-3 * abs_se_mm;
    ao.max_sets = max_sets;
    ao.seed = seed;
    ao.mu = mu;
    ao.n_mu = n_mu;
    ao.substeps = substeps;
    ao.policy = (sl_clearance_policy)policy;
    ao.progress = progress;
    progress_ctx pc = {quiet, 0, np, "", -100, NULL};
    ao.progress_ctx = &pc;
    if (n_sets > 0 && n_sets < SL_NLTHA_MIN_SETS && !quiet)
        cli_msg("run: warning: %lu motion sets per floor; ASCE/SEI 43-05 asks for at least %d",
                n_sets, SL_NLTHA_MIN_SETS);
    for (size_t i = 0; i < np; i++) {
        pc.floor = i + 1;
        pc.name = floors[i]->name;
        pc.last_step = NULL;
        an[i] = sl_analysis_run(floors[i], &ao, &err);
        if (!an[i]) {
            cli_print_error(&err);
            goto done;
        }
        if (!quiet) {
            const sl_design *d = an[i]->design;
            cli_msg("run: floor %zu/%zu '%s': ZPA %.3f g; %zu of %zu friction values need no "
                    "NLTHA (mu g >= demand); crossover mu g/ZPA %s%.3f%s",
                    i + 1, np, floors[i]->name, an[i]->zpa_h_ms2 / SL_G, an[i]->n_mu_skipped, n_mu,
                    d->has_crossover ? "" : "(none", d->has_crossover ? d->crossover_x : 0.0,
                    d->has_crossover ? "" : ")");
            const sl_analysis *q = an[i];
            if (q->stop == SL_ANALYSIS_STOP_FIXED)
                cli_msg("run: floor '%s': %zu motion sets (fixed by --sets)", floors[i]->name,
                        q->n_sets);
            else
                cli_msg("run: floor '%s': %zu motion sets in %zu batches: %s (worst standard "
                        "error %.1f %% of the design value)", floors[i]->name, q->n_sets,
                        q->n_batches,
                        q->stop == SL_ANALYSIS_STOP_CONVERGED ? "converged"
                                                              : "NOT converged, --max-sets reached",
                        100 * q->worst_rel_se);
            cli_msg("run: floor '%s': wall time: synthesis %.2f s, NLTHA %.2f s, statistics "
                    "%.3f s, ASCE and design %.3f s (%.3f s per set)", floors[i]->name,
                    q->time_synth_s, q->time_nltha_s, q->time_stats_s, q->time_asce_s,
                    (q->time_synth_s + q->time_nltha_s + q->time_stats_s + q->time_asce_s) /
                        (double)q->n_sets);
            if (an[i]->note[0])
                cli_msg("run: floor '%s': note: %s", floors[i]->name, an[i]->note);
        }
    }

    /* the report */
    rf = calloc(np, sizeof *rf);
    size_t nq = 0;
    for (size_t i = 0; i < np; i++)
        nq += an[i]->n_sets * SL_SYNTH_NCOMP;
    rq = calloc(nq ? nq : 1, sizeof *rq);
    why = calloc(nq ? nq : 1, sizeof *why);
    if (!rf || !rq || !why) {
        cli_msg("out of memory");
        goto done;
    }
    static const char *const comp[SL_SYNTH_NCOMP] = {"H1", "H2", "V"};
    size_t q = 0;
    for (size_t i = 0; i < np; i++) {
        rf[i].name = floors[i]->name;
        rf[i].path = paths[i];
        if (file_crc(paths[i], &rf[i].crc32, &rf[i].size_bytes)) {
            cli_msg("%s: cannot read: %s", paths[i], strerror(errno));
            goto done;
        }
        rf[i].zpa_h_ms2 = an[i]->zpa_h_ms2;
        rf[i].design = an[i]->design;
        rf[i].note = an[i]->note;
        rf[i].n_mu_skipped = an[i]->n_mu_skipped;
        rf[i].n_sets = an[i]->n_sets;
        rf[i].stop = sl_analysis_stop_name(an[i]->stop);
        rf[i].conv = an[i]->conv;
        for (size_t s = 0; s < an[i]->n_sets; s++)
            for (int cc = 0; cc < SL_SYNTH_NCOMP; cc++) {
                const sl_synth_check *k = &an[i]->sets[s].check[cc];
                sl_report_quality *m = &rq[q];
                m->floor = floors[i]->name;
                m->set = (int)s + 1;
                m->component = comp[cc];
                m->pga_g = k->pga_ms2 / SL_G;
                m->d5_75_s = k->d5_75_s;
                m->min_ratio = k->min_ratio;
                m->max_ratio = k->max_ratio;
                m->max_run_below = (int)k->run_below;
                m->max_corr = k->max_corr;
                m->v_end_ms = k->v_end_ms;
                m->d_end_m = k->d_end_m;
                m->pass = k->pass;
                snprintf(why[q], sizeof why[q], "%s%s%s%s%s%s%s%s", k->ok_below ? "" : "below ",
                         k->ok_above ? "" : "above ", k->ok_run ? "" : "run_below ",
                         k->ok_d5_75 ? "" : "d5_75 ", k->ok_duration ? "" : "duration ",
                         k->ok_end ? "" : "end_v_d ", k->ok_pga ? "" : "pga ",
                         k->ok_corr ? "" : "correlation");
                m->why = why[q];
                q++;
            }
    }
    size_t len = 16;
    for (int i = 0; i < argc; i++)
        len += strlen(argv[i]) + 1;
    cmdline = malloc(len);
    if (!cmdline)
        goto done;
    strcpy(cmdline, "seislide");
    for (int i = 0; i < argc; i++) {
        strcat(cmdline, " ");
        strcat(cmdline, argv[i]);
    }
    char s_sets[96], s_seed[32], s_mu[96], s_sub[64], s_fs[64], s_synth[160];
    if (n_sets > 0)
        snprintf(s_sets, sizeof s_sets, "%lu (fixed)", n_sets);
    else
        snprintf(s_sets, sizeof s_sets, "until SE <= max(%g %%, %g mm), at most %lu",
                 100 * rel_se, abs_se_mm, max_sets);
    snprintf(s_seed, sizeof s_seed, "%lu", seed);
    snprintf(s_mu, sizeof s_mu, "%zu values, %g to %g", n_mu, mu[0], mu[n_mu - 1]);
    snprintf(s_sub, sizeof s_sub, "%u per sample (requested accuracy %g)", substeps, acc);
    snprintf(s_fs, sizeof s_fs, "NLTHA %.1f x mean; ASCE %.1f x best; cap %.1f x mean PGD",
             SL_NLTHA_FS, SL_ASCE_FS, SL_DESIGN_CAP_FACTOR);
    snprintf(s_synth, sizeof s_synth, "%g s at %g s, matched at %g %% damping (SRP 3.7.1 checks)",
             SL_SYNTH_DURATION_S, SL_SYNTH_DT_S, 100 * SL_SYNTH_DAMPING);
    const sl_report_setting settings[] = {
        {"motion sets per floor", s_sets}, {"seed", s_seed}, {"friction grid", s_mu},
        {"2-D sub-steps", s_sub}, {"factors", s_fs}, {"synthetic motions", s_synth},
        {"clearance policy", sl_clearance_policy_name((sl_clearance_policy)policy)},
        {"units", "displacements in mm; accelerations in g; SI inside"}};
    sl_report rep = {"seislide " SEISLIDE_VERSION, cmdline, (time_t)created, np, rf, q, rq,
                     sizeof settings / sizeof settings[0], settings};
    char wb[4096];
    snprintf(wb, sizeof wb, "%s/%s", outdir, RUN_WORKBOOK);
    if (sl_report_write_csv(&rep, outdir, &err) || sl_report_write_xlsx(&rep, wb, &err)) {
        cli_print_error(&err);
        goto done;
    }
    if (write_motions) {
        char dir[4096], safe[256], path[4400];
        static const char *const cn[SL_SYNTH_NCOMP] = {"h1", "h2", "v"};
        snprintf(dir, sizeof dir, "%s/motions", outdir);
        if (mkdir(dir, 0777) != 0 && errno != EEXIST) {
            cli_msg("%s: cannot create: %s", dir, strerror(errno));
            goto done;
        }
        for (size_t i = 0; i < np; i++) {
            snprintf(dir, sizeof dir, "%s/motions/%s", outdir,
                     sl_report_safe_name(floors[i]->name, safe, sizeof safe));
            if (mkdir(dir, 0777) != 0 && errno != EEXIST) {
                cli_msg("%s: cannot create: %s", dir, strerror(errno));
                goto done;
            }
            for (size_t s = 0; s < an[i]->n_sets; s++)
                for (int cc = 0; cc < SL_SYNTH_NCOMP; cc++) {
                    char title[512];
                    snprintf(path, sizeof path, "%s/set%02zu_%s.AT2", dir, s + 1, cn[cc]);
                    snprintf(title, sizeof title, "%s, set %zu, %s, seed %lu", floors[i]->name,
                             s + 1, cn[cc], seed);
                    if (sl_synth_write_at2(path, an[i]->sets[s].motion[cc], title, &err)) {
                        cli_print_error(&err);
                        goto done;
                    }
                }
        }
    }
    if (!quiet)
        cli_msg("run: wrote %s and %zu CSV files in %s", wb, np + 3, outdir);
    rc = CLI_EXIT_OK;
done:
    free(mu);
    free(rf);
    free(rq);
    free(why);
    free(cmdline);
    for (size_t i = 0; i < np; i++) {
        sl_analysis_free(an[i]);
        sl_floor_free(floors[i]);
        free(paths[i]);
    }
    return rc;
}
