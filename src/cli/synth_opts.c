/* synth_opts.c - the limit and method options of `seislide synth`; see
 * synth_opts.h. */
#include "synth_opts.h"

#include <stdio.h>

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
} param_opt;

#define P_OFF(field) offsetof(sl_synth_params, field)
static const param_opt param_opts[] = {
    {"tol-below", P_OFF(tol_below), K_FRACTION_OPEN, NULL,
     "largest fraction a point is below target"},
    {"tol-above", P_OFF(tol_above), K_NONNEG, NULL,
     "largest fraction a point is above target"},
    {"max-run", P_OFF(max_run_below), K_COUNT, "points",
     "most consecutive points below target"},
    {"min-d575", P_OFF(min_d5_75_s), K_NONNEG, "s", "least D5-75 strong-motion duration"},
    {"min-duration", P_OFF(min_duration_s), K_NONNEG, "s", "least total duration"},
    {"max-corr", P_OFF(max_corr), K_FRACTION, NULL,
     "largest |correlation| of two components"},
    {"end-vel-frac", P_OFF(end_vel_frac), K_NONNEG, NULL, "largest |v(end)| as a fraction of PGV"},
    {"end-disp-frac", P_OFF(end_disp_frac), K_NONNEG, NULL,
     "largest |d(end)| as a fraction of PGD"},
    {"fmin", P_OFF(fmin_hz), K_POSITIVE, "Hz", "lowest frequency checked"},
    {"fmax", P_OFF(fmax_hz), K_POSITIVE, "Hz", "highest frequency checked"},
    {"per-decade", P_OFF(per_decade), K_POSITIVE, NULL, "grid points per decade"},
    {"max-iter", P_OFF(max_iter), K_UCOUNT, NULL, "correction iterations per attempt"},
    {"max-attempts", P_OFF(max_attempts), K_UCOUNT1, NULL,
     "phase sets tried per synthetic component"},
    {"aim", P_OFF(aim), K_POSITIVE, NULL,
     "the correction aims at aim x target (1.10: conservative)"},
    {"max-peaks", P_OFF(max_peaks), K_COUNT, NULL,
     "most peaks of |a| above 0.9 PGA (ground-like targets)"},
    {"pga-tol-below", P_OFF(pga_tol_below), K_FRACTION, NULL,
     "least PGA/ZPA is 1 - this (targets rigid at the end)"},
    {"psd-frac", P_OFF(psd_frac), K_NONNEG, NULL,
     "SRP App. B minimum PSD fraction (0: reported only)"},
    {"wavelet-rate", P_OFF(wavelet_rate), K_NONNEG, NULL,
     "wave packets per s per octave (0: random phases)"},
    {"wavelet-cycles", P_OFF(wavelet_cycles), K_POSITIVE, NULL, "cycles per wave packet"},
    {"rise-frac", P_OFF(rise_frac), K_POSITIVE, NULL, "envelope rise, fraction of the duration"},
    {"hold-frac", P_OFF(hold_frac), K_POSITIVE, NULL, "envelope end of hold, fraction"},
    {"end-amp", P_OFF(end_amp), K_POSITIVE, NULL, "envelope amplitude at the end"},
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
