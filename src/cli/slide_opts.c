/* slide_opts.c - the options of `seislide slide` (slide_opts.h): one cli_opt
 * table, parsed by cli_parse() and printed by --help, and the rules across
 * options. */
#include "slide_opts.h"

#include <math.h>
#include <stddef.h>

#include "slide/refmodel.h"

static const char slide_head[] =
    "usage: seislide slide --h1 FILE [--h2 FILE] [--v FILE] [--units g|m/s2|cm/s2]\n"
    "                      [--dt S] (--mu LIST | --mu-range A:B:S) [--scale-pga G]\n"
    "                      [--one-way | --up-ratio R] [--invert] [--history OUT.csv]\n"
    "                      [--csv] [--truncate] [--rtol R] [--model M ...]\n\n"
    "Peak sliding displacement of a rigid block on a level floor with Coulomb\n"
    "friction (static = kinetic) under the floor motion H1 [, H2] [, V]:\n"
    "  u'' = -a_g - mu (g + a_v) s,  s = u'/|u'| while sliding, |s| <= 1 stuck.\n"
    "H1 alone: 1-D, exact for piecewise-linear input. H1 + H2: 2-D, the two\n"
    "horizontals coupled through the circular friction limit. V changes the\n"
    "normal force; a_v <= -g is lift-off (no friction), counted.\n\n";
static const char slide_tail[] =
    "\nstatus: ok; no_sliding (mu g at or above the largest demand: not integrated);\n"
    "liftoff (some samples had a_v <= -g).\n"
    "Exit status: 0 success, 1 bad input or failed run, 2 usage error.\n";


enum { O_H1 = CLI_OPT_ID, O_H2, O_V, O_UNITS, O_DT, O_TRUNCATE, O_SCALE, O_INVERT, O_MU,
       O_MU_RANGE, O_ONE_WAY, O_UP_RATIO, O_MODEL, O_RTOL, O_ATOL, O_SUBSTEPS, O_ETA,
       O_UY, O_SOLVER, O_PUY, O_CSV, O_HISTORY };
#define A(f) .off = offsetof(slide_args, f)
static const cli_opt opts[] = {
    {.head = "input:"},
    {"h1", O_H1, "FILE", "motions: PEER .AT2, one column (needs --dt),\ntwo columns time+acc, "
     "or CSV with a header", .show = "--h1 FILE, --h2 FILE, --v FILE", .kind = CLI_STRING,
     A(path[0])},
    {"h2", O_H2, "FILE", NULL, .kind = CLI_STRING, A(path[1])},
    {"v", O_V, "FILE", NULL, .kind = CLI_STRING, A(path[2])},
    {"units", O_UNITS, "U", "g, m/s2 or cm/s2 (= gal) for files that do not name\ntheir unit "
     "(AT2 headers do)", .kind = CLI_UNITS, A(ro.units)},
    {"dt", O_DT, "S", "sample interval for one-column files, s", .kind = CLI_POSITIVE, A(ro.dt_s)},
    {"truncate", O_TRUNCATE, NULL, "cut components of different length to the shortest\n"
     "(default: pad the shorter ones with zeros, said on stderr)", .kind = CLI_FLAG, A(truncate)},
    {"scale-pga", O_SCALE, "G", "scale the whole set so the larger horizontal peak\nacceleration "
     "is G (in g)", .kind = CLI_POSITIVE, A(scale_g), .unit = "g"},
    {"invert", O_INVERT, NULL, "multiply the horizontal records by -1", .kind = CLI_FLAG,
     A(so.invert)},
    {.head = "friction:"},
    {"mu", O_MU, "LIST", "comma-separated coefficients, increasing, each above 0\n"
     "and at most %g, e.g. 0.05,0.1,0.2", {CLI_MU_MAX}, .kind = CLI_MU_LIST,
     A(mu)},
    {"mu-range", O_MU_RANGE, "A:B:S", "A, A+S, ... up to B", .kind = CLI_MU_RANGE, A(mu)},
    {"one-way", O_ONE_WAY, NULL, "1-D: the block slides only toward -x (where a positive\nfloor "
     "acceleration pushes it), as Newmark's asymmetric\ncase and SLAMMER's rigid block (positive "
     "record =\ndownslope pulse; --invert for the inverted polarity)", .kind = CLI_FLAG,
     A(one_way)},
    {"up-ratio", O_UP_RATIO, "R", "1-D: friction toward +x is R*mu (default 1)",
     .kind = CLI_POSITIVE, A(ratio)},
    {.head = "model:"},
    {"model", O_MODEL, "M", "exact (default), smooth or plastic (reference models)",
     .kind = CLI_CALL},
    {"rtol", O_RTOL, "R", "exact model: relative error of every peak the 2-D engine\naims at "
     "(default %g; 1-D is exact); smooth model: the\nsolver's relative tolerance (1e-6)",
     {SL_SLIDE_DEFAULT_RTOL}, .show = "--rtol R, --accuracy R", .kind = CLI_POSITIVE, A(rtol)},
    {"accuracy", O_RTOL, "R", NULL, .kind = CLI_POSITIVE, A(rtol)},
    {"atol", O_ATOL, "A", "exact model: error not worth refining, m (default %g);\nsmooth model: "
     "the solver's absolute tolerance (1e-9 m)", {SL_SLIDE_DEFAULT_ATOL_M},
     .kind = CLI_POSITIVE, A(atol), .unit = "m"},
    {"substeps", O_SUBSTEPS, "N", "expert: N fixed 2-D sub-steps per sample, no error control",
     .kind = CLI_CALL},
    {"eta", O_ETA, "E", "smooth model: exponent (5), yield displacement, m (1e-4)",
     .show = "--eta E, --uy M", .kind = CLI_CALL},
    {"uy", O_UY, "M", NULL, .kind = CLI_CALL},
    {"solver", O_SOLVER, "S", "smooth model: msbdf, rk4imp, bsimp or rkf45", .kind = CLI_CALL},
    {"plastic-uy", O_PUY, "M", "plastic model: yield displacement, m (1e-4)", .kind = CLI_CALL},
    {.head = "output:"},
    {"csv", O_CSV, NULL, "one CSV row per mu on stdout: mu, peak_m, residual_m,\npeak_x_m, "
     "peak_y_m, t_peak_s, residual_x_m,\nresidual_y_m, path_m, max_speed_m_s, t_rest_s,\n"
     "slide_time_s, episodes, liftoff_samples, err_est_m\n(estimated error of peak_m: 0 in 1-D, "
     "empty when not\nestimated), status", .kind = CLI_FLAG, A(csv)},
    {"history", O_HISTORY, "OUT.csv", "time history of u, u' and F/W per axis (one mu only)",
     .kind = CLI_STRING, A(history)},
};

/* The options that need more than a kind: names and bounded numbers. */
static int take(void *dst, int key, const char *arg)
{
    slide_args *a = dst;
    sl_slide_opts *so = &a->so;
    unsigned long ul;
    int q;
    if (key >= O_SUBSTEPS && key <= O_PUY)
        a->given |= 1u << (key - O_SUBSTEPS);
    if (key == O_UY || key == O_PUY)
        return cli_positive("slide", key == O_UY ? "--uy" : "--plastic-uy", arg, "m",
                            key == O_UY ? &so->smooth_uy_m : &so->plastic_uy_m);
    if (key == O_SUBSTEPS) {
        if (cli_parse_ulong(arg, &ul) || ul < 1 || ul > 1000000)
            return cli_usage("slide", "--substeps '%s' must be an integer >= 1", arg);
        so->substeps = (unsigned)ul;
    } else if (key == O_ETA) {
        if (cli_parse_double(arg, &so->smooth_eta) || so->smooth_eta < 1)
            return cli_usage("slide", "--eta '%s' must be a number >= 1", arg);
    } else if (key == O_MODEL) {
        if ((q = sl_model_parse(arg)) < 0)
            return cli_usage("slide", "unknown model '%s' (exact, smooth, plastic)", arg);
        so->model = (sl_model)q;
    } else { /* O_SOLVER */
        if ((q = sl_smooth_solver_parse(arg)) < 0)
            return cli_usage("slide", "unknown solver '%s' (msbdf, rk4imp, bsimp, rkf45)", arg);
        so->smooth_solver = q;
    }
    return CLI_EXIT_OK;
}

/* The options of one model that another would ignore: a usage error. */
static int model_options(const slide_args *a)
{
    static const char *const model[] = {"exact", "smooth", "plastic"};
    const sl_model m = a->so.model;
#define GIVEN(k) ((a->given >> ((k) - O_SUBSTEPS)) & 1u)
    const char *bad = m != SL_MODEL_SMOOTH && GIVEN(O_ETA)      ? "--eta"
                      : m != SL_MODEL_SMOOTH && GIVEN(O_UY)     ? "--uy"
                      : m != SL_MODEL_SMOOTH && GIVEN(O_SOLVER) ? "--solver"
                      : m != SL_MODEL_PLASTIC && GIVEN(O_PUY)   ? "--plastic-uy"
                      : m != SL_MODEL_EXACT && GIVEN(O_SUBSTEPS) ? "--substeps"
                      : m == SL_MODEL_PLASTIC && (a->rtol > 0 || a->atol > 0) ? "--rtol or --atol"
                                                                              : NULL;
    if (bad)
        return cli_usage("slide", "%s does not apply to --model %s", bad,
                         model[m <= SL_MODEL_PLASTIC ? m : 0]);
    if (m == SL_MODEL_EXACT && GIVEN(O_SUBSTEPS) && a->rtol > 0)
        return cli_usage("slide", "--substeps replaces the error control that --rtol sets: "
                         "give one of them");
#undef GIVEN
    return CLI_EXIT_OK;
}

/* The settings of a reference model, checked by the model itself on a
 * motion of two zero samples (its ranges are its own; nothing is read yet). */
static int model_settings(const slide_args *a)
{
    if (a->so.model == SL_MODEL_EXACT)
        return CLI_EXIT_OK;
    double zero[2] = {0, 0};
    sl_motion m = {"", "", 2, 0.01, zero};
    sl_set set = {&m, a->path[1] ? &m : NULL, NULL};
    sl_slide_result r;
    sl_error err;
    sl_error_clear(&err);
    if (sl_refmodel_run(&set, 1.0, &a->so, &r, NULL, &err))
        return cli_usage("slide", "%s", err.msg);
    return CLI_EXIT_OK;
}

/* The rules across options; fills so from rtol, atol, one_way, ratio. */
static int check_args(void *dst)
{
    slide_args *a = dst;
    sl_slide_opts *so = &a->so;
    int rc = model_options(a);
    if (rc)
        return rc;
    if (sl_slide_opts_set_tol(so, a->rtol, a->atol, NULL))
        return cli_usage("slide", "--rtol %g must be in [%g, %g]", a->rtol, SL_SLIDE_RTOL_MIN,
                         SL_SLIDE_RTOL_MAX);
    if (!a->path[0])
        return cli_usage("slide", "--h1 FILE is required");
    if (!a->mu.v)
        return cli_usage("slide", "give the friction coefficients with --mu or --mu-range");
    if (a->one_way && a->ratio > 0)
        return cli_usage("slide", "--one-way and --up-ratio exclude each other");
    so->up_ratio = a->one_way ? INFINITY : a->ratio > 0 ? a->ratio : so->up_ratio;
    if (so->up_ratio != 1.0 && a->path[1])
        return cli_usage("slide", "--one-way and --up-ratio are 1-D: drop --h2");
    if (a->history && a->mu.n != 1)
        return cli_usage("slide", "--history needs exactly one mu (got %zu)", a->mu.n);
    if ((rc = cli_mu_check("slide", &a->mu)))
        return rc;
    return model_settings(a);
}

int slide_parse(int argc, char **argv, slide_args *a)
{
    static const cli_command cmd = {"slide", slide_head, slide_tail, opts, CLI_NOPTS(opts), 25,
                                    take, check_args, 0};
    *a = (slide_args){.ro = {SL_FORMAT_AUTO, SL_UNIT_NONE, 0.0}};
    sl_slide_opts_default(&a->so);
    return cli_command_parse(&cmd, argc, argv, a);
}
