/* cmd_slide.c - `seislide slide`: one motion set, many friction coefficients. */
#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "io/atomic.h"
#include "cli.h"
#include "io/motion.h"
#include "slide/slide.h"

static const char slide_help[] =
    "usage: seislide slide --h1 FILE [--h2 FILE] [--v FILE] [--units g|m/s2|cm/s2]\n"
    "                      [--dt S] (--mu LIST | --mu-range A:B:S) [--scale-pga G]\n"
    "                      [--one-way | --up-ratio R] [--invert] [--history OUT.csv]\n"
    "                      [--csv] [--truncate] [--rtol R] [--model M ...]\n"
    "\n"
    "Peak sliding displacement of a rigid block on a level floor with Coulomb\n"
    "friction (static = kinetic) under the floor motion H1 [, H2] [, V]:\n"
    "  u'' = -a_g - mu (g + a_v) s,  s = u'/|u'| while sliding, |s| <= 1 stuck.\n"
    "H1 alone: 1-D, exact for piecewise-linear input. H1 + H2: 2-D, the two\n"
    "horizontals coupled through the circular friction limit. V changes the\n"
    "normal force; a_v <= -g is lift-off (no friction), counted.\n"
    "\n"
    "input:\n"
    "  --h1 FILE, --h2 FILE, --v FILE   motions: PEER .AT2, one column (needs --dt),\n"
    "                         two columns time+acc, or CSV with a header\n"
    "  --units U              g, m/s2 or cm/s2 (= gal) for files that do not name\n"
    "                         their unit (AT2 headers do)\n"
    "  --dt S                 sample interval for one-column files, s\n"
    "  --truncate             cut components of different length to the shortest\n"
    "                         (default: pad the shorter ones with zeros, said on stderr)\n"
    "  --scale-pga G          scale the whole set so the larger horizontal peak\n"
    "                         acceleration is G (in g)\n"
    "  --invert               multiply the horizontal records by -1\n"
    "friction:\n"
    "  --mu LIST              comma-separated coefficients, e.g. 0.05,0.1,0.2\n"
    "  --mu-range A:B:S       A, A+S, ... up to B\n"
    "  --one-way              1-D: the block slides only toward -x (where a positive\n"
    "                         floor acceleration pushes it), as Newmark's asymmetric\n"
    "                         case and SLAMMER's rigid block (positive record =\n"
    "                         downslope pulse; --invert for the inverted polarity)\n"
    "  --up-ratio R           1-D: friction toward +x is R*mu (default 1)\n"
    "model:\n"
    "  --model M              exact (default), smooth or plastic (reference models)\n"
    "  --rtol R, --accuracy R exact model: relative error of every peak the 2-D engine\n"
    "                         aims at (default %g; 1-D is exact); smooth model: the\n"
    "                         solver's relative tolerance (1e-6)\n"
    "  --atol A               exact model: error not worth refining, m (default %g);\n"
    "                         smooth model: the solver's absolute tolerance (1e-9 m)\n"
    "  --substeps N           expert: N fixed 2-D sub-steps per sample, no error control\n"
    "  --eta E, --uy M        smooth model: exponent (5), yield displacement, m (1e-4)\n"
    "  --solver S             smooth model: msbdf, rk4imp, bsimp or rkf45\n"
    "  --plastic-uy M         plastic model: yield displacement, m (1e-4)\n"
    "output:\n"
    "  --csv                  one CSV row per mu on stdout: mu, peak_m, residual_m,\n"
    "                         peak_x_m, peak_y_m, t_peak_s, residual_x_m,\n"
    "                         residual_y_m, path_m, max_speed_m_s, t_rest_s,\n"
    "                         slide_time_s, episodes, liftoff_samples, err_est_m\n"
    "                         (estimated error of peak_m: 0 in 1-D, empty when not\n"
    "                         estimated), status\n"
    "  --history OUT.csv      time history of u, u' and F/W per axis (one mu only)\n"
    "\n"
    "status: ok; no_sliding (mu g at or above the largest demand: not integrated);\n"
    "never_stops (mu = 0); liftoff (some samples had a_v <= -g).\n"
    "Exit status: 0 success, 1 bad input or failed run, 2 usage error.\n";

enum { OPT_H1 = 256, OPT_H2, OPT_V, OPT_UNITS, OPT_DT, OPT_MU, OPT_MU_RANGE,
       OPT_SCALE, OPT_ONE_WAY, OPT_UP_RATIO, OPT_INVERT, OPT_HISTORY, OPT_CSV,
       OPT_TRUNCATE, OPT_SUBSTEPS, OPT_MODEL, OPT_ETA, OPT_UY, OPT_RTOL, OPT_ATOL,
       OPT_SOLVER, OPT_PUY, OPT_HELP };

static const struct option slide_opts[] = {
    {"h1", required_argument, 0, OPT_H1},
    {"h2", required_argument, 0, OPT_H2},
    {"v", required_argument, 0, OPT_V},
    {"units", required_argument, 0, OPT_UNITS},
    {"dt", required_argument, 0, OPT_DT},
    {"mu", required_argument, 0, OPT_MU},
    {"mu-range", required_argument, 0, OPT_MU_RANGE},
    {"scale-pga", required_argument, 0, OPT_SCALE},
    {"one-way", no_argument, 0, OPT_ONE_WAY},
    {"up-ratio", required_argument, 0, OPT_UP_RATIO},
    {"invert", no_argument, 0, OPT_INVERT},
    {"history", required_argument, 0, OPT_HISTORY},
    {"csv", no_argument, 0, OPT_CSV},
    {"truncate", no_argument, 0, OPT_TRUNCATE},
    {"substeps", required_argument, 0, OPT_SUBSTEPS},
    {"model", required_argument, 0, OPT_MODEL},
    {"eta", required_argument, 0, OPT_ETA},
    {"uy", required_argument, 0, OPT_UY},
    {"rtol", required_argument, 0, OPT_RTOL},
    {"accuracy", required_argument, 0, OPT_RTOL},
    {"atol", required_argument, 0, OPT_ATOL},
    {"solver", required_argument, 0, OPT_SOLVER},
    {"plastic-uy", required_argument, 0, OPT_PUY},
    {"help", no_argument, 0, OPT_HELP},
    {0, 0, 0, 0}};

static const char *status_word(const sl_slide_result *r)
{
    if (r->flags & SL_SLIDE_SKIPPED)
        return "no_sliding";
    if (r->flags & SL_SLIDE_NEVER_STOPS)
        return "never_stops";
    if (r->flags & SL_SLIDE_LIFTOFF)
        return "liftoff";
    return "ok";
}

static int write_history(const char *path, const sl_history *h)
{
    sl_error err;
    sl_error_clear(&err);
    sl_atomic *a = sl_atomic_open(path, &err);
    if (!a) {
        cli_print_error(&err);
        return CLI_EXIT_ERROR;
    }
    FILE *f = sl_atomic_file(a);
    fprintf(f, "t_s,ux_m,uy_m,vx_m_s,vy_m_s,fx_over_w,fy_over_w\n");
    for (size_t i = 0; i < h->n; i++)
        fprintf(f, "%.6f,%.9g,%.9g,%.9g,%.9g,%.6g,%.6g\n", h->t_s[i], h->ux_m[i], h->uy_m[i],
                h->vx_ms[i], h->vy_ms[i], h->fx_w[i], h->fy_w[i]);
    if (sl_atomic_commit(a, &err)) {
        cli_print_error(&err);
        return CLI_EXIT_ERROR;
    }
    return CLI_EXIT_OK;
}

int cmd_slide(int argc, char **argv)
{
    const char *path[3] = {NULL, NULL, NULL}, *history = NULL;
    sl_read_opts ro = {SL_FORMAT_AUTO, SL_UNIT_NONE, 0.0};
    sl_slide_opts so;
    sl_slide_opts_default(&so);
    double *mu = NULL, scale_g = 0.0, rtol = 0.0, atol = 0.0;
    size_t n_mu = 0;
    int csv = 0, truncate = 0, one_way = 0, have_ratio = 0, rc = CLI_EXIT_ERROR;
    unsigned long ul;
    sl_motion *m[3] = {NULL, NULL, NULL};
    sl_slide_result *res = NULL;
    sl_history *hist = NULL;
    sl_error err;
    sl_error_clear(&err);

    optind = 1;
    opterr = 0;
    int c;
    while ((c = getopt_long(argc, argv, ":", slide_opts, NULL)) != -1) {
        const char *arg = optarg;
        switch (c) {
        case OPT_H1: path[0] = arg; break;
        case OPT_H2: path[1] = arg; break;
        case OPT_V: path[2] = arg; break;
        case OPT_UNITS:
            if (cli_units("slide", arg, &ro.units)) {
                rc = CLI_EXIT_USAGE;
                goto done;
            }
            break;
        case OPT_DT:
            if (cli_positive("slide", "--dt", arg, NULL, &ro.dt_s)) {
                rc = CLI_EXIT_USAGE;
                goto done;
            }
            break;
        case OPT_MU:
        case OPT_MU_RANGE:
            if (cli_friction("slide", c != OPT_MU, arg, &mu, &n_mu)) {
                rc = CLI_EXIT_USAGE;
                goto done;
            }
            break;
        case OPT_SCALE:
            if (cli_positive("slide", "--scale-pga", arg, "g", &scale_g)) {
                rc = CLI_EXIT_USAGE;
                goto done;
            }
            break;
        case OPT_ONE_WAY: one_way = 1; break;
        case OPT_UP_RATIO:
            if (cli_positive("slide", "--up-ratio", arg, NULL, &so.up_ratio)) {
                rc = CLI_EXIT_USAGE;
                goto done;
            }
            have_ratio = 1;
            break;
        case OPT_INVERT: so.invert = 1; break;
        case OPT_HISTORY: history = arg; break;
        case OPT_CSV: csv = 1; break;
        case OPT_TRUNCATE: truncate = 1; break;
        case OPT_SUBSTEPS:
            if (cli_parse_ulong(arg, &ul) || ul < 1 || ul > 1000000) {
                rc = cli_usage("slide", "--substeps '%s' must be an integer >= 1", arg);
                goto done;
            }
            so.substeps = (unsigned)ul;
            break;
        case OPT_MODEL:
            if (!strcmp(arg, "exact"))
                so.model = SL_MODEL_EXACT;
            else if (!strcmp(arg, "smooth"))
                so.model = SL_MODEL_SMOOTH;
            else if (!strcmp(arg, "plastic"))
                so.model = SL_MODEL_PLASTIC;
            else {
                rc = cli_usage("slide", "unknown model '%s' (exact, smooth, plastic)", arg);
                goto done;
            }
            break;
        case OPT_ETA:
            if (cli_parse_double(arg, &so.smooth_eta) || so.smooth_eta < 1) {
                rc = cli_usage("slide", "--eta '%s' must be a number >= 1", arg);
                goto done;
            }
            break;
        case OPT_UY:
            if (cli_positive("slide", "--uy", arg, "m", &so.smooth_uy_m)) {
                rc = CLI_EXIT_USAGE;
                goto done;
            }
            break;
        case OPT_RTOL:
            if (cli_positive("slide", "--rtol", arg, NULL, &rtol)) {
                rc = CLI_EXIT_USAGE;
                goto done;
            }
            break;
        case OPT_ATOL:
            if (cli_positive("slide", "--atol", arg, "m", &atol)) {
                rc = CLI_EXIT_USAGE;
                goto done;
            }
            break;
        case OPT_SOLVER: {
            static const char *names[] = {"msbdf", "rk4imp", "bsimp", "rkf45"};
            int found = -1;
            for (int q = 0; q < 4; q++)
                if (!strcmp(arg, names[q]))
                    found = q;
            if (found < 0) {
                rc = cli_usage("slide", "unknown solver '%s' (msbdf, rk4imp, bsimp, rkf45)", arg);
                goto done;
            }
            so.smooth_solver = found;
            break;
        }
        case OPT_PUY:
            if (cli_positive("slide", "--plastic-uy", arg, "m", &so.plastic_uy_m)) {
                rc = CLI_EXIT_USAGE;
                goto done;
            }
            break;
        case OPT_HELP:
            printf(slide_help, SL_SLIDE_DEFAULT_RTOL, SL_SLIDE_DEFAULT_ATOL_M);
            rc = CLI_EXIT_OK;
            goto done;
        case ':':
            rc = cli_usage("slide", "option '%s' needs a value", argv[optind - 1]);
            goto done;
        default:
            rc = cli_usage("slide", "unknown option '%s'", argv[optind - 1]);
            goto done;
        }
    }
    if (optind < argc) {
        rc = cli_usage("slide", "unexpected argument '%s'", argv[optind]);
        goto done;
    }
    /* --rtol/--atol: the engine's accuracy, or the smooth model's solver tolerances */
    if (rtol > 0 && so.model == SL_MODEL_SMOOTH)
        so.smooth_rtol = rtol;
    else if (rtol > 0 && !(rtol >= 1e-9 && rtol <= 0.1)) {
        rc = cli_usage("slide", "--rtol %g must be in [1e-9, 0.1]", rtol);
        goto done;
    } else if (rtol > 0)
        so.rtol = rtol;
    if (atol > 0 && so.model == SL_MODEL_SMOOTH)
        so.smooth_atol = atol;
    else if (atol > 0)
        so.atol_m = atol;
    if (!path[0]) {
        rc = cli_usage("slide", "--h1 FILE is required");
        goto done;
    }
    if (!mu) {
        rc = cli_usage("slide", "give the friction coefficients with --mu or --mu-range");
        goto done;
    }
    if (one_way && have_ratio) {
        rc = cli_usage("slide", "--one-way and --up-ratio exclude each other");
        goto done;
    }
    if (one_way)
        so.up_ratio = INFINITY;
    if (so.up_ratio != 1.0 && path[1]) {
        rc = cli_usage("slide", "--one-way and --up-ratio are 1-D: drop --h2");
        goto done;
    }
    if (history && n_mu != 1) {
        rc = cli_usage("slide", "--history needs exactly one mu (got %zu)", n_mu);
        goto done;
    }
    for (size_t k = 0; k < n_mu; k++)
        if (!(mu[k] >= 0)) {
            rc = cli_usage("slide", "friction coefficient %g must be >= 0", mu[k]);
            goto done;
        }

    for (int q = 0; q < 3; q++) {
        if (!path[q])
            continue;
        m[q] = sl_motion_read(path[q], &ro, &err);
        if (!m[q]) {
            cli_print_error(&err);
            goto done;
        }
    }
    sl_set set = {m[0], m[1], m[2]};
    sl_set_fit fit;
    if (sl_set_check_fit(&set, truncate, &fit, &err)) {
        cli_print_error(&err);
        goto done;
    }
    if (fit.changed) {
        static const char *const tag[3] = {"H1", "H2", "V"};
        for (int q = 0; q < 3; q++)
            if (m[q] && fit.n_in[q] != fit.n)
                cli_msg("%s %s: %zu samples (to %.6g s) %s to %zu (to %.6g s)", tag[q], path[q],
                        fit.n_in[q], (double)(fit.n_in[q] - 1) * set.h1->dt_s,
                        fit.truncated ? "cut" : "padded with zeros", fit.n,
                        (double)(fit.n - 1) * set.h1->dt_s);
    }
    double pga = sl_set_pga_h(&set);
    if (scale_g > 0) {
        if (!(pga > 0)) {
            cli_msg("%s: cannot scale an all-zero motion to %g g", path[0], scale_g);
            goto done;
        }
        double s = scale_g * SL_G / pga;
        for (int q = 0; q < 3; q++)
            if (m[q])
                sl_motion_scale(m[q], s);
        pga = sl_set_pga_h(&set);
    }
    res = calloc(n_mu, sizeof *res);
    if (!res) {
        cli_msg("out of memory");
        goto done;
    }
    sl_status st = history ? sl_slide_history(&set, mu[0], &so, res, &hist, &err)
                           : sl_slide_batch(&set, 1, mu, n_mu, &so, res, &err);
    if (st) {
        cli_print_error(&err);
        goto done;
    }
    if (history && write_history(history, hist) != CLI_EXIT_OK)
        goto done;

    if (csv) {
        printf("mu,peak_m,residual_m,peak_x_m,peak_y_m,t_peak_s,residual_x_m,residual_y_m,"
               "path_m,max_speed_m_s,t_rest_s,slide_time_s,episodes,liftoff_samples,err_est_m,"
               "status\n");
        for (size_t k = 0; k < n_mu; k++) {
            const sl_slide_result *r = &res[k];
            char est[32] = "";
            if (!isnan(r->err_est_m))
                snprintf(est, sizeof est, "%.3g", r->err_est_m);
            printf("%.6g,%.9g,%.9g,%.9g,%.9g,%.4f,%.9g,%.9g,%.9g,%.9g,%.4f,%.4f,%ld,%ld,%s,%s\n",
                   r->mu, r->peak_m, r->residual_m, r->peak_x_m, r->peak_y_m, r->t_peak_s,
                   r->residual_x_m, r->residual_y_m, r->path_m, r->max_speed_ms, r->t_rest_s,
                   r->slide_time_s, r->episodes, r->liftoff_samples, est, status_word(r));
        }
    } else {
        printf("# seislide slide: %s%s%s%s%s, %zu samples at dt = %g s\n", path[0],
               path[1] ? " + " : "", path[1] ? path[1] : "", path[2] ? " + V " : "",
               path[2] ? path[2] : "", m[0]->n, m[0]->dt_s);
        printf("# %s, peak horizontal acceleration %.4f g, no sliding for mu >= %.4f\n",
               path[1] ? "2-D coupled" : (so.up_ratio != 1.0 ? "1-D asymmetric" : "1-D exact"),
               pga / SL_G, sl_slide_mu_threshold(&set, &so));
        printf("%8s %12s %12s %10s %9s %8s  %s\n", "mu", "peak_mm", "residual_mm", "t_peak_s",
               "path_mm", "episodes", "status");
        for (size_t k = 0; k < n_mu; k++) {
            const sl_slide_result *r = &res[k];
            printf("%8.4f %12.3f %12.3f %10.3f %9.1f %8ld  %s\n", r->mu, 1e3 * r->peak_m,
                   1e3 * r->residual_m, r->t_peak_s, 1e3 * r->path_m, r->episodes,
                   status_word(r));
        }
    }
    rc = CLI_EXIT_OK;
done:
    free(mu);
    free(res);
    sl_history_free(hist);
    for (int q = 0; q < 3; q++)
        sl_motion_free(m[q]);
    return rc;
}
