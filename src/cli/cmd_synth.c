/* cmd_synth.c - `seislide synth`: spectrum-compatible three-component sets
 * (or recorded motions matched to a target), their files and a match report
 * with every acceptance check. Library: synth.h; method: docs/synthesis.md. */
#include <errno.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io/atomic.h"
#include "cli.h"
#include "io/floor.h"
#include "io/motion.h"
#include "signal/rg160.h"
#include "synth/synth.h"
#include "synth_opts.h"
#include "synth_output.h"

/* Most records --match takes (H1, H2, V). */
#define SYNTH_MAX_RECORDS SL_SYNTH_NCOMP
/* Most sets per run (a guard against typos). */
#define SYNTH_MAX_COUNT 1000
/* Longest accepted motion, s (a guard against typos). */
#define SYNTH_MAX_DURATION_S 3600.0
/* Relative slack when a duration must be a whole number of steps. */
#define SYNTH_STEP_SLACK 1e-9

typedef struct synth_run {
    sl_synth_params p;
    const char *floor_path, *outdir;
    const char *match[SYNTH_MAX_RECORDS];
    size_t nmatch;
    double rg_pga_g, damping, duration_s, dt_s;
    unsigned long count;
    unsigned long long seed;
    int have_count, have_seed, have_duration, csv, quiet;
    sl_unit units;
} synth_run;

static const char synth_help_head[] =
    "usage: seislide synth (--floor FILE | --rg160 PGA) --count N --seed S\n"
    "                      [--duration S] [--dt S] -o DIR [options]\n"
    "       seislide synth --match RECORD [--match H2 [--match V]]\n"
    "                      (--floor FILE | --rg160 PGA) -o DIR [options]\n"
    "\n"
    "Spectrum-compatible acceleration histories (docs/synthesis.md): a random sum\n"
    "of wave packets (Gabor wavelets) under an intensity envelope, then iterative\n"
    "correction of the Fourier amplitudes by the ratio target/computed spectrum\n"
    "with a soft, order-preserving compression of the largest half-cycles (no\n"
    "clipping, no pinning: the PGA comes out of matching the high-frequency end\n"
    "and PGA/ZPA is reported); baseline corrected so that velocity and\n"
    "displacement end at zero. Each set has three independent components H1, H2,\n"
    "V. --match modifies recorded motions instead (first to H1, then H2, then V),\n"
    "keeping their Fourier phases; the report gives the correlation with the\n"
    "record and both peak counts.\n"
    "Every motion is checked as in US NRC SRP 3.7.1; the report says pass or fail\n"
    "per check. A motion that misses a limit after the iterations is reported as\n"
    "failed and the exit status is 1.\n"
    "\n";

static const char synth_help_tail[] =
    "\n"
    "files: DIR/setNN_h1.AT2, setNN_h2.AT2, setNN_v.AT2 (or match_h1.AT2 ...),\n"
    "DIR/report.csv: one row per motion with every check (docs/synthesis.md).\n"
    "Exit status: 0 every check passed, 1 bad input, failed write or a motion that\n"
    "failed a check (files still written), 2 usage error.\n";

enum { OPT_FLOOR = CLI_OPT_ID, OPT_RG160, OPT_DAMPING, OPT_COUNT, OPT_SEED, OPT_DURATION, OPT_DT,
       OPT_MATCH, OPT_UNITS, OPT_FORMAT };
#define A(f) offsetof(synth_run, f)
static const cli_opt base_opts[] = {
    {.head = "target (one of):"},
    {"rg160", OPT_RG160, "PGA", "Regulatory Guide 1.60, horizontal (H1, H2) and vertical\n"
     "(V) spectra at PGA (g); ZPA = PGA", .kind = CLI_POSITIVE, .off = A(rg_pga_g), .unit = "g"},
    {"floor", OPT_FLOOR, "FILE", "a floor response spectrum file (docs/formats-floor.md):\n"
     "each component at 5 %% damping when given, else its\nlowest damping; ZPA from the file",
     .kind = CLI_STRING, .off = A(floor_path)},
    {"damping", OPT_DAMPING, "Z", "match at damping Z instead (RG 1.60 default %g; with\n"
     "--floor every component must give Z)", {SL_SYNTH_DAMPING}, .kind = CLI_CALL},
    {.head = "motions:"},
    {"count", OPT_COUNT, "N", "sets to make (1-%g)", {SYNTH_MAX_COUNT}, .kind = CLI_CALL},
    {"seed", OPT_SEED, "S", "seed of the random phases (a whole number); each\n"
     "motion's stream comes from (S, set, component)", .kind = CLI_CALL},
    {"duration", OPT_DURATION, "S", "duration of each motion, s (default %g)",
     {SL_SYNTH_DURATION_S}, .kind = CLI_CALL},
    {"dt", OPT_DT, "S", "time step, s (default %g; at most %g s: Nyquist\n"
     ">= 50 Hz); with --match the records are resampled to\n"
     "it (default: the record's step divided by the smallest\n"
     "whole number that makes it <= %g s)", {SL_SYNTH_DT_S, SL_SYNTH_MAX_DT_S, SL_SYNTH_MAX_DT_S}, .kind = CLI_CALL},
    {"match", OPT_MATCH, "FILE", "a recorded motion (AT2, or any format of 'seislide\n"
     "slide'); up to three", .kind = CLI_CALL},
    {"units", OPT_UNITS, "U", "units of --match files that do not name them", .kind = CLI_UNITS,
     .off = A(units)},
    {.head = "output:"},
    {"output", 'o', "DIR", "folder for the files (created if missing)", .kind = CLI_STRING,
     .off = A(outdir)},
    {"format", OPT_FORMAT, "at2|csv", "motion files: PEER-style AT2 in g (default), or CSV\n"
     "with columns time_s,acc_g", .kind = CLI_CALL},
    {"quiet", 'q', NULL, "no progress on stderr", .kind = CLI_FLAG, .off = A(quiet)},
    {.head = "limits and method (defaults: SRP 3.7.1, docs/synthesis.md):"},
};
#define N_BASE_OPTS CLI_NOPTS(base_opts)

/* ---- Progress --------------------------------------------------------- */

static void progress_cb(void *ctx, size_t done, size_t total)
{
    (void)ctx;
    fprintf(stderr, "\rseislide: synth: %zu/%zu motions", done, total);
    if (done >= total)
        fputc('\n', stderr);
    fflush(stderr);
}

/* ---- The command ------------------------------------------------------ */

/* Describe each component's target for the report and the AT2 title. */
static void describe_targets(const synth_run *o, const sl_floor *fl,
                             const sl_synth_target tgt[SL_SYNTH_NCOMP],
                             char desc[SL_SYNTH_NCOMP][512])
{
    for (int c = 0; c < SL_SYNTH_NCOMP; c++) {
        if (fl)
            snprintf(desc[c], sizeof desc[c], "floor %s [%s] at %g damping; ZPA %.4g g",
                     fl->path, sl_synth_comp_name((sl_synth_comp)c), tgt[c].spec->damping,
                     tgt[c].zpa_ms2 / SL_G);
        else
            snprintf(desc[c], sizeof desc[c], "RG 1.60 %s at %g damping; PGA %g g",
                     c == SL_SYNTH_V ? "vertical" : "horizontal", tgt[c].spec->damping,
                     o->rg_pga_g);
    }
}

/* Read the --match records, resampled to a common step; sets *dt_out. */
static int read_records(const synth_run *o, sl_motion *rec[SL_SYNTH_NCOMP], double *dt_out)
{
    sl_error err;
    sl_error_clear(&err);
    sl_read_opts ro;
    memset(&ro, 0, sizeof ro);
    ro.units = o->units;
    double dt = o->dt_s;
    for (size_t i = 0; i < o->nmatch; i++) {
        rec[i] = sl_motion_read(o->match[i], &ro, &err);
        if (!rec[i]) {
            cli_print_error(&err);
            return CLI_EXIT_ERROR;
        }
        if (i == 0 && !(dt > 0))
            dt = sl_synth_match_dt(rec[0]->dt_s);
    }
    for (size_t i = 0; i < o->nmatch; i++) {
        if (fabs(rec[i]->dt_s - dt) <= SYNTH_STEP_SLACK * dt)
            continue;
        sl_motion *r2 = sl_synth_resample_motion(rec[i], dt);
        if (!r2) {
            cli_msg("%s: cannot resample to dt %g s", o->match[i], dt);
            return CLI_EXIT_ERROR;
        }
        sl_motion_free(rec[i]);
        rec[i] = r2;
        if (!o->quiet)
            cli_msg("%s: resampled to dt %g s (linear interpolation)", o->match[i], dt);
    }
    *dt_out = dt;
    return CLI_EXIT_OK;
}

/* The options that need more than their kind: ranges, flags of presence. */
static int take(void *dst, int key, const char *arg)
{
    synth_run *o = dst;
    int rc;
    switch (key) {
    case OPT_DAMPING:
        if (cli_parse_double(arg, &o->damping) || !(o->damping > 0 && o->damping < 1))
            return cli_usage("synth", "--damping '%s' must be a number in (0, 1)", arg);
        return CLI_EXIT_OK;
    case OPT_COUNT:
        if (cli_parse_ulong(arg, &o->count) || o->count < 1 || o->count > SYNTH_MAX_COUNT)
            return cli_usage("synth", "--count '%s' must be a whole number in [1, %d]", arg,
                             SYNTH_MAX_COUNT);
        o->have_count = 1;
        return CLI_EXIT_OK;
    case OPT_SEED: {
        unsigned long v;
        if (cli_parse_ulong(arg, &v))
            return cli_usage("synth", "--seed '%s' must be a whole number >= 0", arg);
        o->seed = v;
        o->have_seed = 1;
        return CLI_EXIT_OK;
    }
    case OPT_DURATION:
        if ((rc = cli_positive("synth", "--duration", arg, "s", &o->duration_s)))
            return rc;
        if (o->duration_s > SYNTH_MAX_DURATION_S)
            return cli_usage("synth", "--duration %g above %g s", o->duration_s,
                             SYNTH_MAX_DURATION_S);
        o->have_duration = 1;
        return CLI_EXIT_OK;
    case OPT_DT:
        if ((rc = cli_positive("synth", "--dt", arg, "s", &o->dt_s)))
            return rc;
        if (o->dt_s > SL_SYNTH_MAX_DT_S * (1 + SYNTH_STEP_SLACK))
            return cli_usage("synth", "--dt %g above %g s (SRP 3.7.1: Nyquist frequency >= 50 Hz)",
                             o->dt_s, SL_SYNTH_MAX_DT_S);
        return CLI_EXIT_OK;
    case OPT_MATCH:
        if (o->nmatch == SYNTH_MAX_RECORDS)
            return cli_usage("synth", "at most %d --match records (H1, H2, V)", SYNTH_MAX_RECORDS);
        o->match[o->nmatch++] = arg;
        return CLI_EXIT_OK;
    case OPT_FORMAT:
        if (strcmp(arg, "csv") && strcmp(arg, "at2") && strcmp(arg, "AT2"))
            return cli_usage("synth", "--format '%s' must be at2 or csv", arg);
        o->csv = !strcmp(arg, "csv");
        return CLI_EXIT_OK;
    default: return synth_param_set(&o->p, key, arg) ? CLI_EXIT_USAGE : CLI_EXIT_OK;
    }
}

/* Parse the options into o. Returns CLI_EXIT_OK, or an exit code to return
 * (-1 for --help done). */
static int parse(int argc, char **argv, synth_run *o)
{
    cli_opt opts[N_BASE_OPTS + SYNTH_NPARAM];
    memcpy(opts, base_opts, sizeof base_opts);
    size_t n = N_BASE_OPTS + synth_param_opts(opts + N_BASE_OPTS);
    int rc = cli_parse("synth", opts, n, argc, argv, o, take);
    if (rc == CLI_OPT_HELP) {
        fputs(synth_help_head, stdout);
        cli_help_options(stdout, opts, n, 25);
        fputs(synth_help_tail, stdout);
        return -1;
    }
    if (rc || (rc = cli_no_operands("synth", argc, argv)))
        return rc;
    if (!o->floor_path == isnan(o->rg_pga_g))
        return cli_usage("synth", "give exactly one target: --floor FILE or --rg160 PGA");
    if (!o->outdir)
        return cli_usage("synth", "-o DIR is required");
    if (o->nmatch > 0) {
        if (o->have_count || o->have_seed || o->have_duration)
            return cli_usage("synth", "--match takes no --count, --seed or --duration");
    } else {
        if (!o->have_count)
            return cli_usage("synth", "--count N is required (or --match FILE)");
        if (!o->have_seed)
            return cli_usage("synth", "--seed S is required: it makes the motions reproducible");
        if (o->units != SL_UNIT_NONE)
            return cli_usage("synth", "--units applies to --match files only");
    }
    sl_error err;
    if (sl_synth_params_check(&o->p, &err))
        return cli_usage("synth", "%s", err.msg);
    return CLI_EXIT_OK;
}
int cmd_synth(int argc, char **argv)
{
    synth_run o;
    memset(&o, 0, sizeof o);
    sl_synth_params_default(&o.p);
    o.rg_pga_g = NAN;
    o.duration_s = SL_SYNTH_DURATION_S;
    o.dt_s = NAN;
    int rc = parse(argc, argv, &o);
    if (rc)
        return rc < 0 ? CLI_EXIT_OK : rc;

    sl_error err;
    sl_error_clear(&err);
    sl_floor *fl = NULL;
    sl_spectrum *own[SL_SYNTH_NCOMP] = {NULL, NULL, NULL};
    sl_motion *rec[SL_SYNTH_NCOMP] = {NULL, NULL, NULL};
    sl_synth *plan = NULL;
    sl_synth_set *sets = NULL;
    size_t nsets = 0;
    sl_synth_target tgt[SL_SYNTH_NCOMP];
    char desc[SL_SYNTH_NCOMP][512];
    rc = CLI_EXIT_ERROR;

    /* Targets. */
    if (o.floor_path) {
        fl = sl_floor_load(o.floor_path, &err);
        if (!fl || sl_synth_targets_floor(fl, o.damping, tgt, &err)) {
            cli_print_error(&err);
            goto done;
        }
    } else {
        double z = o.damping > 0 ? o.damping : SL_SYNTH_DAMPING;
        if (!(z >= SL_RG160_ZETA_MIN && z <= SL_RG160_ZETA_MAX)) {
            rc = cli_usage("synth", "--damping %g outside RG 1.60's range [%g, %g]", z,
                           SL_RG160_ZETA_MIN, SL_RG160_ZETA_MAX);
            goto done;
        }
        if (sl_synth_targets_rg160(o.rg_pga_g * SL_G, z, &o.p, own, tgt, &err)) {
            cli_print_error(&err);
            goto done;
        }
    }
    describe_targets(&o, fl, tgt, desc);

    /* Plan and motions. */
    double dt = o.dt_s > 0 ? o.dt_s : SL_SYNTH_DT_S;
    size_t n;
    if (o.nmatch > 0) {
        if ((rc = read_records(&o, rec, &dt)) != CLI_EXIT_OK)
            goto done;
        rc = CLI_EXIT_ERROR;
        n = 0;
        for (size_t i = 0; i < o.nmatch; i++)
            n = rec[i]->n > n ? rec[i]->n : n;
    } else {
        n = (size_t)llround(o.duration_s / dt) + 1;
    }
    plan = sl_synth_alloc(n, dt, &o.p, &err);
    if (!plan) {
        cli_print_error(&err);
        goto done;
    }
    if (synth_make_dirs(o.outdir) != 0) {
        cli_msg("%s: cannot create the output folder: %s", o.outdir, strerror(errno));
        goto done;
    }
    nsets = o.nmatch > 0 ? 1 : (size_t)o.count;
    sets = calloc(nsets, sizeof *sets);
    if (!sets) {
        cli_msg("out of memory");
        goto done;
    }
    int show = !o.quiet && isatty(STDERR_FILENO);
    sl_status st;
    if (o.nmatch > 0) {
        const sl_motion *r3[SL_SYNTH_NCOMP] = {rec[0], rec[1], rec[2]};
        st = sl_synth_match_set(plan, tgt, r3, sets, &err);
    } else {
        st = sl_synth_make_sets(plan, tgt, (uint64_t)o.seed, 0, nsets, sets,
                                show ? progress_cb : NULL, NULL, &err);
    }
    if (st && st != SL_ENOCONV) {
        cli_print_error(&err);
        goto done;
    }
    synth_output out = {o.outdir, o.csv, o.seed, o.nmatch > 0 ? o.match : NULL,
                        (const char(*)[512])desc, &o.p};
    if (synth_write_outputs(&out, sets, nsets) != CLI_EXIT_OK)
        goto done;
    size_t total = 0, failed = 0;
    for (size_t k = 0; k < nsets; k++)
        for (int c = 0; c < SL_SYNTH_NCOMP; c++)
            if (sl_synth_set_motion(&sets[k], (sl_synth_comp)c)) {
                total++;
                failed += !sets[k].check[c].pass;
            }
    if (failed) {
        cli_msg("synth: %zu of %zu motions failed a check (see %s/report.csv)", failed, total,
                o.outdir);
        goto done;
    }
    if (!o.quiet) {
        if (o.nmatch > 0)
            cli_msg("synth: %zu motions matched, every check passed; %s/report.csv", total,
                    o.outdir);
        else
            cli_msg("synth: %zu motions, every check passed (seed %llu); %s/report.csv", total,
                    o.seed, o.outdir);
    }
    rc = CLI_EXIT_OK;
done:
    for (size_t k = 0; sets && k < nsets; k++)
        sl_synth_set_clear(&sets[k]);
    free(sets);
    sl_synth_free(plan);
    for (int c = 0; c < SL_SYNTH_NCOMP; c++) {
        sl_spectrum_free(own[c]);
        sl_motion_free(rec[c]);
    }
    sl_floor_free(fl);
    return rc;
}
