/* cmd_asce.c - `seislide asce`: ASCE/SEI 43-05 approximate sliding
 * displacement (Appendix A.1) for many friction coefficients. */
#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "method/asce.h"
#include "cli.h"
#include "io/floor.h"
#include "io/motion.h"
#include "signal/rg160.h"
#include "signal/spectrum.h"

static const char asce_help[] =
    "usage: seislide asce (--rg160 PGA | --floor FILE | --h1 FILE --h2 FILE --v FILE)\n"
    "                     (--mu LIST | --mu-range A:B:S) [--fs F] [--pgd M] [--pgv V]\n"
    "                     [--units U] [--dt S] [--truncate] [--csv]\n"
    "\n"
    "Approximate peak sliding displacement of ASCE/SEI 43-05 Appendix A.1:\n"
    "  mu_e = mu (1 - 0.4 A_v/g);  c_s = 2 mu_e g;\n"
    "  SA_vH = sqrt(SA_H1^2 + 0.16 SA_H2^2) (10 %%-damped PSA, H1 the larger);\n"
    "  f_es = lowest frequency where SA_vH = c_s (scan upward, log-log interpolation);\n"
    "  delta_best = c_s/(2 pi f_es)^2;  delta_design = FS x delta_best, at most\n"
    "  1.5 x the peak input displacement (100-40 of the horizontals) when known.\n"
    "\n"
    "input (one of):\n"
    "  --rg160 PGA            both horizontals the RG 1.60 horizontal spectrum at PGA\n"
    "                         (g); A_v = PGA (the vertical ZPA); cap from 36 in per g\n"
    "                         per horizontal: 1.5 x 1.4 x 36 in x PGA\n"
    "  --floor FILE           a floor response spectrum file (docs/formats-floor.md):\n"
    "                         its sa_0.10 spectra of H1 and H2, A_v = the V zpa; no cap\n"
    "                         unless --pgd is given\n"
    "  --h1 F --h2 F --v F    three motions: their 10 %%-damped spectra (%g-%g Hz,\n"
    "                         %g per decade), A_v = peak |V|, cap from the 100-40\n"
    "                         peak displacement of H1 and H2\n"
    "  --units U, --dt S      units and sample interval for motion files that do not\n"
    "                         name them (as in 'seislide slide')\n"
    "  --truncate             cut motions of different length to the shortest\n"
    "friction:\n"
    "  --mu LIST              comma-separated coefficients, e.g. 0.05,0.1,0.2\n"
    "  --mu-range A:B:S       A, A+S, ... up to B\n"
    "options:\n"
    "  --fs F                 factor of safety on the best estimate (default %g)\n"
    "  --pgd M                peak input displacement (100-40), m, for the cap;\n"
    "                         replaces the one from the input\n"
    "  --pgv V                peak horizontal velocity, m/s, for Newmark's estimates\n"
    "                         (motions: the larger horizontal PGV by default)\n"
    "  --csv                  CSV instead of an aligned table (stdout)\n"
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

enum { OPT_RG160 = 256, OPT_FLOOR, OPT_H1, OPT_H2, OPT_V, OPT_UNITS, OPT_DT, OPT_TRUNCATE,
       OPT_MU, OPT_MU_RANGE, OPT_FS, OPT_PGD, OPT_PGV, OPT_CSV, OPT_HELP };

static const struct option asce_opts[] = {
    {"rg160", required_argument, 0, OPT_RG160},
    {"floor", required_argument, 0, OPT_FLOOR},
    {"h1", required_argument, 0, OPT_H1},
    {"h2", required_argument, 0, OPT_H2},
    {"v", required_argument, 0, OPT_V},
    {"units", required_argument, 0, OPT_UNITS},
    {"dt", required_argument, 0, OPT_DT},
    {"truncate", no_argument, 0, OPT_TRUNCATE},
    {"mu", required_argument, 0, OPT_MU},
    {"mu-range", required_argument, 0, OPT_MU_RANGE},
    {"fs", required_argument, 0, OPT_FS},
    {"pgd", required_argument, 0, OPT_PGD},
    {"pgv", required_argument, 0, OPT_PGV},
    {"csv", no_argument, 0, OPT_CSV},
    {"help", no_argument, 0, OPT_HELP},
    {0, 0, 0, 0}};

/* Print a number in a table column of `width`, or "nan" (never "-nan"). */
static void put_num(const char *fmt, double v, int width)
{
    if (isnan(v))
        printf("%*s", width, "nan");
    else
        printf(fmt, width, v);
}

/* Print a CSV number: 8 significant digits, or "nan". */
static void put_csv(double v, int last)
{
    if (isnan(v))
        fputs("nan", stdout);
    else
        printf("%.8g", v);
    putchar(last ? '\n' : ',');
}

/* Everything the method needs, from whichever input. */
typedef struct source {
    sl_spectrum *own[2];      /* spectra this command made (freed at the end) */
    const sl_spectrum *h1, *h2;
    double av_ms2, zpa_h_ms2, pgd_m, pgv_ms;
    char what[1200];          /* description for the table header */
} source;

static int from_rg160(double pga_g, source *s, sl_error *err)
{
    size_t n;
    double *f = sl_rg160_grid(SL_RG160_HORIZONTAL, SL_SPECTRUM_FMIN_HZ, SL_SPECTRUM_FMAX_HZ,
                              SL_SPECTRUM_PER_DECADE, &n);
    sl_spectrum *sp = f ? sl_spectrum_alloc(n, SL_ASCE_DAMPING) : NULL;
    if (!sp) {
        free(f);
        sl_error_set(err, SL_ENOMEM, NULL, 0, "out of memory");
        return -1;
    }
    memcpy(sp->f_hz, f, n * sizeof *f);
    free(f);
    s->own[0] = sp;
    if (sl_rg160_psa(SL_RG160_HORIZONTAL, SL_ASCE_DAMPING, pga_g * SL_G, sp->f_hz, n,
                     sp->sa_ms2, err))
        return -1;
    s->h1 = s->h2 = sp;
    s->av_ms2 = pga_g * SL_G; /* vertical ZPA = horizontal PGA */
    s->zpa_h_ms2 = pga_g * SL_G;
    double pgd1 = SL_RG160_DISP_PER_G_M * pga_g; /* 36 in per g, each horizontal */
    s->pgd_m = pgd1 + SL_ASCE_COMB_100_40 * pgd1;
    s->pgv_ms = NAN;
    snprintf(s->what, sizeof s->what,
             "RG 1.60 horizontal at PGA %g g for H1 and H2, A_v = %g g, peak displacement "
             "%.4f m (1.4 x 36 in x PGA)",
             pga_g, pga_g, s->pgd_m);
    return 0;
}

static int from_floor(const char *path, source *s, sl_floor **flp, sl_error *err)
{
    sl_floor *fl = sl_floor_load(path, err);
    if (!fl)
        return -1;
    *flp = fl;
    for (int k = SL_FLOOR_H1; k <= SL_FLOOR_H2; k++) {
        if (!sl_floor_sa10(fl, (sl_floor_comp)k)) {
            const sl_floor_component *fc = &fl->comp[k];
            sl_error_set(err, SL_EUNSUPPORTED, path, fc->line,
                         "[%s] has no 10 %%-damped spectrum (sa_0.10), which the ASCE "
                         "method needs; this command has no fallback: add sa_0.10 or use "
                         "motions synthesized for the floor (--h1 --h2 --v)",
                         sl_floor_comp_name((sl_floor_comp)k));
            return -1;
        }
    }
    s->h1 = sl_floor_sa10(fl, SL_FLOOR_H1);
    s->h2 = sl_floor_sa10(fl, SL_FLOOR_H2);
    s->av_ms2 = fl->comp[SL_FLOOR_V].zpa_ms2;
    s->zpa_h_ms2 = fmax(fl->comp[SL_FLOOR_H1].zpa_ms2, fl->comp[SL_FLOOR_H2].zpa_ms2);
    s->pgd_m = NAN;
    s->pgv_ms = NAN;
    snprintf(s->what, sizeof s->what,
             "floor '%s' (%s)%s, horizontal ZPA %.4f g, A_v = %.4f g (V zpa%s)", fl->name,
             path, fl->h2_same_as_h1 ? ", H2 declared same as H1" : "",
             s->zpa_h_ms2 / SL_G, s->av_ms2 / SL_G,
             fl->comp[SL_FLOOR_V].zpa_given ? "" : " from the high-frequency end");
    return 0;
}

static int from_motions(const char *const path[3], const sl_read_opts *ro, int truncate,
                        source *s, sl_motion *m[3], sl_error *err)
{
    for (int q = 0; q < 3; q++) {
        m[q] = sl_motion_read(path[q], ro, err);
        if (!m[q])
            return -1;
    }
    sl_set set = {m[0], m[1], m[2]};
    if (sl_set_check(&set, truncate, err))
        return -1;
    size_t n;
    double *f = sl_spectrum_grid(SL_SPECTRUM_FMIN_HZ, SL_SPECTRUM_FMAX_HZ,
                                 SL_SPECTRUM_PER_DECADE, &n);
    if (!f) {
        sl_error_set(err, SL_ENOMEM, NULL, 0, "out of memory");
        return -1;
    }
    for (int q = 0; q < 2; q++) {
        s->own[q] = sl_spectrum_alloc(n, SL_ASCE_DAMPING);
        if (!s->own[q]) {
            free(f);
            sl_error_set(err, SL_ENOMEM, NULL, 0, "out of memory");
            return -1;
        }
        memcpy(s->own[q]->f_hz, f, n * sizeof *f);
    }
    double *psa = malloc(2 * n * sizeof *psa);
    const sl_motion *hm[2] = {m[0], m[1]};
    if (!psa || sl_spectrum_batch(hm, 2, f, n, SL_ASCE_DAMPING, NULL, psa, NULL, NULL, err)) {
        if (!psa)
            sl_error_set(err, SL_ENOMEM, NULL, 0, "out of memory");
        free(psa);
        free(f);
        return -1;
    }
    for (int q = 0; q < 2; q++)
        memcpy(s->own[q]->sa_ms2, psa + (size_t)q * n, n * sizeof *psa);
    free(psa);
    free(f);
    s->h1 = s->own[0];
    s->h2 = s->own[1];
    s->av_ms2 = sl_motion_pga(m[2]);
    s->zpa_h_ms2 = sl_set_pga_h(&set);
    s->pgd_m = sl_set_pgd_100_40(&set);
    s->pgv_ms = fmax(sl_motion_pgv(m[0]), sl_motion_pgv(m[1]));
    snprintf(s->what, sizeof s->what,
             "motions %s + %s + V %s, PGA %.4f g, A_v = %.4f g, peak displacement %.4f m "
             "(100-40)",
             path[0], path[1], path[2], s->zpa_h_ms2 / SL_G, s->av_ms2 / SL_G, s->pgd_m);
    return 0;
}

int cmd_asce(int argc, char **argv)
{
    const char *path[3] = {NULL, NULL, NULL}, *floor_path = NULL;
    double rg_pga_g = NAN, fs = SL_ASCE_FS, pgd_opt = NAN, pgv_opt = NAN;
    double *mu = NULL;
    size_t n_mu = 0;
    int csv = 0, truncate = 0, rc = CLI_EXIT_ERROR;
    sl_read_opts ro = {SL_FORMAT_AUTO, SL_UNIT_NONE, 0.0};
    source src;
    memset(&src, 0, sizeof src);
    sl_floor *fl = NULL;
    sl_motion *m[3] = {NULL, NULL, NULL};
    sl_asce *plan = NULL;
    sl_error err;
    sl_error_clear(&err);

    optind = 1;
    opterr = 0;
    int c;
    while ((c = getopt_long(argc, argv, ":", asce_opts, NULL)) != -1) {
        const char *arg = optarg;
        switch (c) {
        case OPT_RG160:
            if (cli_positive("asce", "--rg160", arg, "g", &rg_pga_g)) {
                rc = CLI_EXIT_USAGE;
                goto done;
            }
            break;
        case OPT_FLOOR: floor_path = arg; break;
        case OPT_H1: path[0] = arg; break;
        case OPT_H2: path[1] = arg; break;
        case OPT_V: path[2] = arg; break;
        case OPT_UNITS:
            if (cli_units("asce", arg, &ro.units)) {
                rc = CLI_EXIT_USAGE;
                goto done;
            }
            break;
        case OPT_DT:
            if (cli_positive("asce", "--dt", arg, NULL, &ro.dt_s)) {
                rc = CLI_EXIT_USAGE;
                goto done;
            }
            break;
        case OPT_TRUNCATE: truncate = 1; break;
        case OPT_MU:
        case OPT_MU_RANGE:
            if (cli_friction("asce", c != OPT_MU, arg, &mu, &n_mu)) {
                rc = CLI_EXIT_USAGE;
                goto done;
            }
            break;
        case OPT_FS:
            if (cli_positive("asce", "--fs", arg, NULL, &fs)) {
                rc = CLI_EXIT_USAGE;
                goto done;
            }
            break;
        case OPT_PGD:
            if (cli_positive("asce", "--pgd", arg, "m", &pgd_opt)) {
                rc = CLI_EXIT_USAGE;
                goto done;
            }
            break;
        case OPT_PGV:
            if (cli_positive("asce", "--pgv", arg, "m/s", &pgv_opt)) {
                rc = CLI_EXIT_USAGE;
                goto done;
            }
            break;
        case OPT_CSV: csv = 1; break;
        case OPT_HELP:
            printf(asce_help, SL_SPECTRUM_FMIN_HZ, SL_SPECTRUM_FMAX_HZ, SL_SPECTRUM_PER_DECADE,
                   SL_ASCE_FS);
            rc = CLI_EXIT_OK;
            goto done;
        case ':':
            rc = cli_usage("asce", "option '%s' needs a value", argv[optind - 1]);
            goto done;
        default:
            rc = cli_usage("asce", "unknown option '%s'", argv[optind - 1]);
            goto done;
        }
    }
    if (optind < argc) {
        rc = cli_usage("asce", "unexpected argument '%s'", argv[optind]);
        goto done;
    }
    int have_motion = path[0] || path[1] || path[2];
    int n_inputs = !isnan(rg_pga_g) + (floor_path != NULL) + have_motion;
    if (n_inputs != 1) {
        rc = cli_usage("asce", "give exactly one input: --rg160 PGA, --floor FILE or "
                               "--h1 FILE --h2 FILE --v FILE");
        goto done;
    }
    if (have_motion && !(path[0] && path[1] && path[2])) {
        rc = cli_usage("asce", "motions need all three of --h1, --h2 and --v");
        goto done;
    }
    if (!have_motion && (ro.units != SL_UNIT_NONE || ro.dt_s > 0 || truncate)) {
        rc = cli_usage("asce", "--units, --dt and --truncate apply to motion files only");
        goto done;
    }
    if (!mu) {
        rc = cli_usage("asce", "give the friction coefficients with --mu or --mu-range");
        goto done;
    }
    for (size_t k = 0; k < n_mu; k++)
        if (!(mu[k] >= 0)) {
            rc = cli_usage("asce", "friction coefficient %g must be >= 0", mu[k]);
            goto done;
        }

    int bad = !isnan(rg_pga_g) ? from_rg160(rg_pga_g, &src, &err)
              : floor_path     ? from_floor(floor_path, &src, &fl, &err)
                               : from_motions(path, &ro, truncate, &src, m, &err);
    if (bad) {
        cli_print_error(&err);
        goto done;
    }
    if (!isnan(pgd_opt))
        src.pgd_m = pgd_opt;
    if (!isnan(pgv_opt))
        src.pgv_ms = pgv_opt;

    sl_asce_input in;
    sl_asce_input_default(&in);
    in.h1 = src.h1;
    in.h2 = src.h2;
    in.av_ms2 = src.av_ms2;
    in.zpa_h_ms2 = src.zpa_h_ms2;
    in.pgd_m = src.pgd_m;
    in.fs = fs;
    plan = sl_asce_alloc(&in, &err);
    if (!plan) {
        if (floor_path && !err.file[0])
            snprintf(err.file, sizeof err.file, "%s", floor_path);
        cli_print_error(&err);
        goto done;
    }

    if (csv) {
        printf("mu,mu_e,cs_g,fes_hz,delta_best_m,delta_design_m,status,cap_m,"
               "newmark_sym_m,newmark_asym_m\n");
    } else {
        printf("# seislide asce: ASCE/SEI 43-05 A.1, FS = %g\n", fs);
        printf("# input: %s\n", src.what);
        if (!isnan(pgd_opt))
            printf("# peak input displacement %.4f m from --pgd\n", pgd_opt);
        printf("# cap: %s\n", src.pgd_m > 0 ? "1.5 x peak input displacement"
                                            : "none (peak input displacement unknown)");
        printf("%8s %8s %8s %9s %12s %14s %9s %13s %14s  %s\n", "mu", "mu_e", "cs_g",
               "fes_hz", "best_mm", "design_mm", "cap_mm", "newmark_s_mm", "newmark_a_mm",
               "status");
    }
    for (size_t k = 0; k < n_mu; k++) {
        sl_asce_result r;
        if (sl_asce_eval(plan, mu[k], &r, &err)) {
            cli_print_error(&err);
            goto done;
        }
        double nm1 = sl_asce_newmark_sym(src.pgv_ms, src.zpa_h_ms2, mu[k], SL_G);
        double nm2 = sl_asce_newmark_asym(src.pgv_ms, src.zpa_h_ms2, mu[k], SL_G);
        char st[80];
        sl_asce_status_name(r.flags, st, sizeof st);
        if (csv) {
            printf("%.6g,%.6g,", r.mu, r.mu_e);
            put_csv(r.cs_ms2 / SL_G, 0);
            put_csv(r.fes_hz, 0);
            put_csv(r.delta_best_m, 0);
            put_csv(r.delta_design_m, 0);
            printf("%s,", st);
            put_csv(r.cap_m, 0);
            put_csv(nm1, 0);
            put_csv(nm2, 1);
        } else {
            printf("%8.4f %8.4f %8.4f ", r.mu, r.mu_e, r.cs_ms2 / SL_G);
            put_num("%*.4f", r.fes_hz, 9);
            putchar(' ');
            put_num("%*.3f", 1e3 * r.delta_best_m, 12);
            putchar(' ');
            put_num("%*.3f", 1e3 * r.delta_design_m, 14);
            putchar(' ');
            put_num("%*.1f", 1e3 * r.cap_m, 9);
            putchar(' ');
            put_num("%*.3f", 1e3 * nm1, 13);
            putchar(' ');
            put_num("%*.3f", 1e3 * nm2, 14);
            printf("  %s\n", st);
        }
    }
    if (fflush(stdout) || ferror(stdout)) {
        cli_msg("error writing the output");
        goto done;
    }
    rc = CLI_EXIT_OK;
done:
    free(mu);
    sl_asce_free(plan);
    sl_spectrum_free(src.own[0]);
    sl_spectrum_free(src.own[1]);
    sl_floor_free(fl);
    for (int q = 0; q < 3; q++)
        sl_motion_free(m[q]);
    return rc;
}
