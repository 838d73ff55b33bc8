/* synth_opts.c - the options of `seislide synth` and the records they
 * name; see synth_opts.h. */
#include "synth_opts.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "io/floor.h"
#include "io/motion.h"

typedef enum opt_kind {
    K_FRACTION_OPEN, /* [0, 1) */
    K_FRACTION,      /* [0, 1] */
    K_NONNEG,        /* >= 0 */
    K_POSITIVE,      /* > 0 */
    K_COUNT,         /* integer >= 0 (size_t field) */
    K_UCOUNT,        /* integer >= 0 (unsigned field) */
    K_UCOUNT1        /* integer >= 1 (unsigned field) */
} opt_kind;

typedef struct param_opt {
    const char *name;   /* long option */
    size_t offset;      /* field in sl_synth_params */
    opt_kind kind;
    const char *unit;   /* shown in help; NULL = dimensionless */
    const char *help;
    double max;         /* largest value accepted (a guard against typos); 0: none */
} param_opt;

#define P_OFF(field) offsetof(sl_synth_params, field)
static const param_opt param_opts[] = {
    {"tol-below", P_OFF(tol_below), K_FRACTION_OPEN, NULL,
     "largest fraction a point is below target", 0},
    {"tol-above", P_OFF(tol_above), K_NONNEG, NULL,
     "largest fraction a point is above target", 0},
    {"max-run", P_OFF(max_run_below), K_COUNT, "points",
     "most consecutive points below target", 0},
    {"min-d575", P_OFF(min_d5_75_s), K_NONNEG, "s", "least D5-75 strong-motion duration", 0},
    {"min-duration", P_OFF(min_duration_s), K_NONNEG, "s", "least total duration", 0},
    {"max-corr", P_OFF(max_corr), K_FRACTION, NULL,
     "largest |correlation| of two components", 0},
    {"end-vel-frac", P_OFF(end_vel_frac), K_NONNEG, NULL, "largest |v(end)| as a fraction of PGV", 0},
    {"end-disp-frac", P_OFF(end_disp_frac), K_NONNEG, NULL,
     "largest |d(end)| as a fraction of PGD", 0},
    {"fmin", P_OFF(fmin_hz), K_POSITIVE, "Hz", "lowest frequency checked", 0},
    {"fmax", P_OFF(fmax_hz), K_POSITIVE, "Hz", "highest frequency checked", 0},
    {"per-decade", P_OFF(per_decade), K_POSITIVE, NULL, "grid points per decade", 1000},
    {"max-iter", P_OFF(max_iter), K_UCOUNT, NULL, "correction iterations per attempt", 0},
    {"max-attempts", P_OFF(max_attempts), K_UCOUNT1, NULL,
     "phase sets tried per synthetic component", 0},
    {"aim", P_OFF(aim), K_POSITIVE, NULL,
     "the correction aims at aim x target (1.10: conservative)", 0},
    {"max-peaks", P_OFF(max_peaks), K_COUNT, NULL,
     "most peaks of |a| above 0.9 PGA (ground-like targets)", 0},
    {"pga-tol-below", P_OFF(pga_tol_below), K_FRACTION, NULL,
     "least PGA/ZPA is 1 - this (targets rigid at the end)", 0},
    {"psd-frac", P_OFF(psd_frac), K_NONNEG, NULL,
     "SRP App. B minimum PSD fraction (0: reported only)", 0},
    {"wavelet-rate", P_OFF(wavelet_rate), K_NONNEG, NULL,
     "wave packets per s per octave (0: random phases)", 100},
    {"wavelet-cycles", P_OFF(wavelet_cycles), K_POSITIVE, NULL, "cycles per wave packet within +-1 standard\n"
     "deviation of its window", 100},
    {"rise-frac", P_OFF(rise_frac), K_POSITIVE, NULL, "envelope rise, fraction of the duration", 0},
    {"hold-frac", P_OFF(hold_frac), K_POSITIVE, NULL, "envelope end of hold, fraction", 0},
    {"end-amp", P_OFF(end_amp), K_POSITIVE, NULL, "envelope amplitude at the end", 0},
    {"hp-frac", P_OFF(hp_frac), K_FRACTION_OPEN, NULL,
     "high-pass corner / lowest checked frequency (0: none)", 0},
    {"hp-order", P_OFF(hp_order), K_POSITIVE, NULL, "order of the Butterworth high-pass", 0},
    {"match-margin", P_OFF(match_margin), K_NONNEG, NULL,
     "records: no correction where S/T is in\n"
     "[1 + X, 1 + tol-above - X] (0: none; 0.01 keeps more)", 0},
};
#define N_PARAM_OPTS (sizeof param_opts / sizeof param_opts[0])

static double param_get(const sl_synth_params *p, const param_opt *o)
{
    const char *base = (const char *)p + o->offset;
    switch (o->kind) {
    case K_COUNT: return (double)*(const size_t *)(const void *)base;
    case K_UCOUNT:
    case K_UCOUNT1: return (double)*(const unsigned *)(const void *)base;
    default: return *(const double *)(const void *)base;
    }
}

int synth_param_set(sl_synth_params *p, int key, const char *arg)
{
    if (key < SYNTH_OPT_PARAM0 || key >= SYNTH_OPT_PARAM0 + (int)N_PARAM_OPTS)
        return 1;
    const param_opt *o = &param_opts[key - SYNTH_OPT_PARAM0];
    char *base = (char *)p + o->offset;
    if (o->kind == K_COUNT || o->kind == K_UCOUNT || o->kind == K_UCOUNT1) {
        unsigned long v;
        if (cli_parse_ulong(arg, &v) || v > 1000000UL || (o->kind == K_UCOUNT1 && v < 1))
            return cli_usage("synth", "--%s '%s' must be a whole number %s", o->name, arg,
                             o->kind == K_UCOUNT1 ? ">= 1" : ">= 0");
        if (o->kind == K_COUNT)
            *(size_t *)(void *)base = (size_t)v;
        else
            *(unsigned *)(void *)base = (unsigned)v;
        return CLI_EXIT_OK;
    }
    double v;
    int bad = cli_parse_double(arg, &v);
    const char *want = "";
    switch (o->kind) {
    case K_FRACTION_OPEN: bad = bad || !(v >= 0 && v < 1); want = "in [0, 1)"; break;
    case K_FRACTION: bad = bad || !(v >= 0 && v <= 1); want = "in [0, 1]"; break;
    case K_NONNEG: bad = bad || !(v >= 0); want = ">= 0"; break;
    default: bad = bad || !(v > 0); want = "> 0"; break;
    }
    if (bad)
        return cli_usage("synth", "--%s '%s' must be a number %s", o->name, arg, want);
    if (o->max > 0 && v > o->max)
        return cli_usage("synth", "--%s %g above %g", o->name, v, o->max);
    *(double *)(void *)base = v;
    return CLI_EXIT_OK;
}

_Static_assert(N_PARAM_OPTS == SYNTH_NPARAM, "SYNTH_NPARAM counts param_opts");

size_t synth_param_opts(cli_opt *t)
{
    static char help[N_PARAM_OPTS][160];
    sl_synth_params d;
    sl_synth_params_default(&d);
    for (size_t i = 0; i < N_PARAM_OPTS; i++) {
        const param_opt *o = &param_opts[i];
        snprintf(help[i], sizeof help[i], "%s (default %%g%s%s)", o->help, o->unit ? " " : "",
                 o->unit ? o->unit : "");
        t[i] = (cli_opt){o->name, SYNTH_OPT_PARAM0 + (int)i, o->kind >= K_COUNT ? "N" : "X",
                         help[i], {param_get(&d, o)}, .kind = CLI_CALL};
    }
    return N_PARAM_OPTS;
}

/* ---- The command's table and --help. */

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
    "DIR/report.csv: one row per motion with every check (docs/synthesis.md); an\n"
    "empty field does not apply (corr_record of a synthetic motion), never nan.\n"
    "Exit status: 0 every check passed, 1 bad input, failed write or a motion that\n"
    "failed a check (files still written), 2 usage error.\n";

enum { OPT_FLOOR = CLI_OPT_ID, OPT_RG160, OPT_DAMPING, OPT_COUNT, OPT_SEED, OPT_DURATION, OPT_DT,
       OPT_MATCH, OPT_UNITS, OPT_FORMAT };
#define A(f) offsetof(synth_run, f)
static const cli_opt base_opts[] = {
    {.head = "target (one of):"},
    {"rg160", OPT_RG160, "PGA", "Regulatory Guide 1.60, horizontal (H1, H2) and vertical\n"
     "(V) spectra at PGA (g, %g-%g); ZPA = PGA", {SL_FLOOR_ZPA_MIN_G, SL_FLOOR_ZPA_MAX_G},
     .kind = CLI_POSITIVE, .off = A(rg_pga_g), .unit = "g"},
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
     "whole number that makes it <= %g s)",
     {SL_SYNTH_DT_S, SL_SYNTH_MAX_DT_S, SL_SYNTH_MAX_DT_S}, .kind = CLI_CALL},
    {"match", OPT_MATCH, "FILE", "a recorded motion (AT2, or any format of 'seislide\n"
     "slide'); up to three", .kind = CLI_CALL},
    {"units", OPT_UNITS, "U", "units of --match files that do not name them", .kind = CLI_UNITS,
     .off = A(units)},
    {.head = "output:"},
    {"output", 'o', "DIR", "folder for the files, swapped in whole, as by run (parents made)", .kind = CLI_STRING,
     .off = A(outdir)},
    {"format", OPT_FORMAT, "at2|csv", "motion files: PEER-style AT2 in g (default), or CSV\n"
     "with columns time_s,acc_g", .kind = CLI_CALL},
    {"quiet", 'q', NULL, "no progress on stderr", .kind = CLI_FLAG, .off = A(quiet)},
    {.head = "limits and method (defaults: SRP 3.7.1, docs/synthesis.md):"},
};
#define N_BASE_OPTS CLI_NOPTS(base_opts)

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

int synth_parse(int argc, char **argv, synth_run *o)
{
    memset(o, 0, sizeof *o);
    sl_synth_params_default(&o->p);
    o->rg_pga_g = NAN;
    o->duration_s = SL_SYNTH_DURATION_S;
    o->dt_s = NAN;
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
    if ((o->floor_path != NULL) == !isnan(o->rg_pga_g)) /* both or neither */
        return cli_usage("synth", "give exactly one target: --floor FILE or --rg160 PGA");
    if (!o->outdir)
        return cli_usage("synth", "-o DIR is required");
    if (o->floor_path == NULL &&
        !(o->rg_pga_g >= SL_FLOOR_ZPA_MIN_G && o->rg_pga_g <= SL_FLOOR_ZPA_MAX_G))
        return cli_usage("synth", "--rg160 %g g must be from %g to %g g", o->rg_pga_g,
                         SL_FLOOR_ZPA_MIN_G, SL_FLOOR_ZPA_MAX_G);
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
        double dt = o->dt_s > 0 ? o->dt_s : SL_SYNTH_DT_S;
        if (o->duration_s / dt + 1 < SYNTH_MIN_SAMPLES)
            return cli_usage("synth", "--duration %g s is fewer than %d steps of %g s",
                             o->duration_s, SYNTH_MIN_SAMPLES, dt);
        if (o->duration_s < o->p.min_duration_s)
            return cli_usage("synth", "--duration %g s is below --min-duration %g s: every "
                             "motion would fail that check", o->duration_s,
                             o->p.min_duration_s);
    }
    if (!(o->p.aim >= 1 - o->p.tol_below && o->p.aim <= 1 + o->p.tol_above))
        return cli_usage("synth", "--aim %g must lie within the accepted band %g-%g "
                         "(1 - --tol-below to 1 + --tol-above)", o->p.aim, 1 - o->p.tol_below,
                         1 + o->p.tol_above);
    if (!(2 * o->p.match_margin < o->p.tol_above) && o->p.match_margin > 0)
        return cli_usage("synth", "--match-margin %g must be below half of --tol-above (%g)",
                         o->p.match_margin, o->p.tol_above);
    sl_error err;
    if (sl_synth_params_check(&o->p, &err))
        return cli_usage("synth", "%s", err.msg);
    return CLI_EXIT_OK;
}

int synth_read_records(const synth_run *o, sl_motion *rec[SL_SYNTH_NCOMP], double *dt_out)
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
