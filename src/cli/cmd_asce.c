/* cmd_asce.c - `seislide asce`: ASCE/SEI 43-05 approximate sliding
 * displacement (Appendix A.1) for many friction coefficients. The input is
 * assembled by method/asce_input.h (asce_output.c); this file parses, calls, prints. */
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "asce_output.h"
#include "io/floor.h"

static const char asce_head[] =
    "usage: seislide asce (--rg160 PGA | --floor FILE | --h1 FILE --h2 FILE --v FILE)\n"
    "                     (--mu LIST | --mu-range A:B:S) [--fs F] [--pgd M] [--pgv V]\n"
    "                     [--units U] [--dt S] [--truncate] [--csv]\n"
    "\n"
    "Approximate peak sliding displacement of ASCE/SEI 43-05 Appendix A.1:\n"
    "  mu_e = mu (1 - 0.4 A_v/g);  c_s = 2 mu_e g;\n"
    "  SA_vH = sqrt(SA_H1^2 + 0.16 SA_H2^2) (10 %-damped PSA, H1 the larger);\n"
    "  f_es = lowest frequency where SA_vH = c_s (scan upward, log-log interpolation);\n"
    "  delta_best = c_s/(2 pi f_es)^2;  delta_design = FS x delta_best, at most\n"
    "  1.5 x the peak input displacement (100-40 of the horizontals) when known.\n"
    "\n";

static const char asce_tail[] =
    "\n"
    "CSV columns: mu, mu_e, cs_g, fes_hz, delta_best_m, delta_design_m, status,\n"
    "cap_m, newmark_sym_m, newmark_asym_m. Newmark (1965) with mu g and the\n"
    "horizontal ZPA A: U = V^2/(2 mu g)(1 - mu g/A) (symmetric) and\n"
    "U = 2 V^2/(mu g)(1 - mu g/A)^2 (asymmetric). 'nan' marks a value that\n"
    "does not exist or is not known.\n"
    "status: ok; no_sliding (mu_e g >= horizontal ZPA: delta = 0); below_fmin\n"
    "(c_s below SA_vH at the lowest frequency: constant-SD extension, delta = SD\n"
    "there); no_crossing (SA_vH never reaches c_s: no answer, nan); capped\n"
    "(design value cut to the cap); flags joined with '+'.\n"
    "Exit status: 0 success, 1 bad input or failed run, 2 usage error.\n";


enum { OPT_RG160 = CLI_OPT_ID, OPT_FLOOR, OPT_H1, OPT_H2, OPT_V, OPT_UNITS, OPT_DT, OPT_TRUNCATE,
       OPT_MU, OPT_MU_RANGE, OPT_FS, OPT_PGD, OPT_PGV, OPT_CSV };
#define A(f) .off = offsetof(asce_args, f)
static const cli_opt asce_opts[] = {
    {.head = "input (one of):"},
    {"rg160", OPT_RG160, "PGA", "both horizontals the RG 1.60 horizontal spectrum at PGA\n(g, %g-%g); A_v "
     "= PGA (the vertical ZPA); cap from 36 in per g\nper horizontal: 1.5 x 1.4 x 36 in x PGA",
     {SL_FLOOR_ZPA_MIN_G, SL_FLOOR_ZPA_MAX_G}, .kind = CLI_POSITIVE, A(rg_pga_g), .unit = "g"},
    {"floor", OPT_FLOOR, "FILE", "a floor response spectrum file (docs/formats-floor.md):\nits "
     "sa_0.10 spectra of H1 and H2, A_v = the V zpa; no cap\nunless --pgd is given",
     .kind = CLI_STRING, A(floor)},
    {"h1", OPT_H1, "F", "three motions: their 10 %%-damped spectra (%g-%g Hz,\n%g per decade), "
     "A_v = peak |V|, cap from the 100-40\npeak displacement of H1 and H2",
     {SL_SPECTRUM_FMIN_HZ, SL_SPECTRUM_FMAX_HZ, SL_SPECTRUM_PER_DECADE},
     .show = "--h1 F --h2 F --v F", .kind = CLI_STRING, A(h1)},
    {"h2", OPT_H2, "F", NULL, .kind = CLI_STRING, A(h2)},
    {"v", OPT_V, "F", NULL, .kind = CLI_STRING, A(v)},
    {"units", OPT_UNITS, "U", "units and sample interval for motion files that do not\nname them "
     "(as in 'seislide slide')", .show = "--units U, --dt S", .kind = CLI_UNITS, A(ro.units)},
    {"dt", OPT_DT, "S", NULL, .kind = CLI_POSITIVE, A(ro.dt_s)},
    {"truncate", OPT_TRUNCATE, NULL, "cut motions of different length to the shortest",
     .kind = CLI_FLAG, A(truncate)},
    {.head = "friction:"},
    {"mu", OPT_MU, "LIST", "comma-separated coefficients, increasing, each above 0\n"
     "and at most %g, e.g. 0.05,0.1,0.2", {CLI_MU_MAX}, .kind = CLI_MU_LIST,
     A(mu)},
    {"mu-range", OPT_MU_RANGE, "A:B:S", "A, A+S, ... up to B", .kind = CLI_MU_RANGE, A(mu)},
    {.head = "options:"},
    {"fs", OPT_FS, "F", "factor of safety on the best estimate (default %g)", {SL_ASCE_FS},
     .kind = CLI_POSITIVE, A(fs)},
    {"pgd", OPT_PGD, "M", "peak input displacement (100-40), m, for the cap;\nreplaces the one "
     "from the input", .kind = CLI_POSITIVE, A(pgd_m), .unit = "m"},
    {"pgv", OPT_PGV, "V", "peak horizontal velocity, m/s, for Newmark's estimates\n(motions: the "
     "larger horizontal PGV by default)", .kind = CLI_POSITIVE, A(pgv_ms), .unit = "m/s"},
    {"csv", OPT_CSV, NULL, "CSV instead of an aligned table (stdout)", .kind = CLI_FLAG, A(csv)},
};

/* The usage rules across options. Returns CLI_EXIT_OK or a usage error. */
static int check_args(void *dst)
{
    const asce_args *a = dst;
    int motion = a->h1 || a->h2 || a->v;
    if (!isnan(a->rg_pga_g) + (a->floor != NULL) + motion != 1)
        return cli_usage("asce", "give exactly one input: --rg160 PGA, --floor FILE or "
                                 "--h1 FILE --h2 FILE --v FILE");
    if (!isnan(a->rg_pga_g) && !(a->rg_pga_g >= SL_FLOOR_ZPA_MIN_G &&
                                 a->rg_pga_g <= SL_FLOOR_ZPA_MAX_G))
        return cli_usage("asce", "--rg160 %g g must be from %g to %g g", a->rg_pga_g,
                         SL_FLOOR_ZPA_MIN_G, SL_FLOOR_ZPA_MAX_G);
    if (motion && !(a->h1 && a->h2 && a->v))
        return cli_usage("asce", "motions need all three of --h1, --h2 and --v");
    if (!motion && (a->ro.units != SL_UNIT_NONE || a->ro.dt_s > 0 || a->truncate))
        return cli_usage("asce", "--units, --dt and --truncate apply to motion files only");
    if (!a->mu.v)
        return cli_usage("asce", "give the friction coefficients with --mu or --mu-range");
    return cli_mu_check("asce", &a->mu);
}

static const cli_command asce_cmd = {"asce", asce_head, asce_tail, asce_opts,
                                     CLI_NOPTS(asce_opts), 25, NULL, check_args, 0};

int cmd_asce(int argc, char **argv)
{
    asce_args a = {.rg_pga_g = NAN, .fs = SL_ASCE_FS, .pgd_m = NAN, .pgv_ms = NAN,
                   .ro = {SL_FORMAT_AUTO, SL_UNIT_NONE, 0.0}};
    sl_asce_source src = {0};
    sl_floor *fl = NULL;
    sl_motion *m[3] = {NULL, NULL, NULL};
    sl_asce *plan = NULL;
    sl_error err;
    sl_error_clear(&err);
    char what[1200];
    double pgv_ms;
    int rc = cli_command_parse(&asce_cmd, argc, argv, &a);
    if (rc)
        goto done;
    rc = CLI_EXIT_ERROR;
    if (asce_make_source(&a, &src, &fl, m, &pgv_ms, what, sizeof what, &err)) {
        cli_print_error(&err);
        goto done;
    }
    if (!isnan(a.pgd_m))
        src.in.pgd_m = a.pgd_m;
    if (!isnan(a.pgv_ms))
        pgv_ms = a.pgv_ms;
    src.in.fs = a.fs;
    if (!(plan = sl_asce_alloc(&src.in, &err))) {
        if (a.floor && !err.file[0])
            snprintf(err.file, sizeof err.file, "%s", a.floor);
        cli_print_error(&err);
        goto done;
    }
    asce_print_head(a.csv, a.fs, what, a.pgd_m, src.in.pgd_m > 0);
    for (size_t k = 0; k < a.mu.n; k++) {
        sl_asce_result r;
        if (sl_asce_eval(plan, a.mu.v[k], &r, &err)) {
            cli_print_error(&err);
            goto done;
        }
        double zpa = src.in.zpa_h_ms2;
        asce_print_row(&r, sl_asce_newmark_sym(pgv_ms, zpa, a.mu.v[k], SL_G),
                  sl_asce_newmark_asym(pgv_ms, zpa, a.mu.v[k], SL_G), a.csv);
    }
    rc = cli_stdout_done();
done:
    free(a.mu.v);
    sl_asce_free(plan);
    sl_asce_source_free(&src);
    sl_floor_free(fl);
    for (int q = 0; q < 3; q++)
        sl_motion_free(m[q]);
    return rc == CLI_OPT_HELP ? CLI_EXIT_OK : rc;
}
