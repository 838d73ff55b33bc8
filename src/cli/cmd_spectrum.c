/* cmd_spectrum.c - `seislide spectrum`: response spectra of motions. */
#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "io/motion.h"
#include "signal/spectrum.h"

/* Default damping ratio when --damping is not given. */
#define SPECTRUM_DEFAULT_DAMPING 0.05
/* Largest damping ratio accepted (the oscillator must be underdamped). */
#define SPECTRUM_MAX_DAMPING 1.0

static const char spectrum_help[] =
    "usage: seislide spectrum FILE... [--damping LIST] [--units U] [--dt S]\n"
    "                         [--fmin HZ] [--fmax HZ] [--per-decade N | --freq LIST]\n"
    "                         [--all] [--csv]\n"
    "\n"
    "Linear response spectra of acceleration records by the exact piecewise-linear\n"
    "recurrence (Nigam-Jennings 1969), sub-stepped so that dt <= T/20, oscillator\n"
    "from rest, free vibration after the record until the first extremum.\n"
    "PSA = (2 pi f)^2 max|u| (pseudo-spectral acceleration).\n"
    "\n"
    "input:\n"
    "  FILE...                motions: PEER .AT2, one column (needs --dt), two\n"
    "                         columns time+acc, or CSV with a header\n"
    "  --units U              g, m/s2 or cm/s2 (= gal) for files that do not name\n"
    "                         their unit (AT2 headers do)\n"
    "  --dt S                 sample interval for one-column files, s\n"
    "spectrum:\n"
    "  --damping LIST         damping ratios in [0, 1), e.g. 0.05,0.10 (default %g)\n"
    "  --fmin HZ, --fmax HZ   frequency range (default %g to %g Hz)\n"
    "  --per-decade N         log-spaced points per decade (default %g)\n"
    "  --freq LIST            explicit frequencies, Hz, instead of the grid\n"
    "output (stdout):\n"
    "  --csv                  CSV instead of an aligned table\n"
    "  --all                  also spectral displacement and absolute acceleration\n"
    "\n"
    "columns: f_hz, then per file and per damping psa_g (and with --all sd_m,\n"
    "sa_abs_g). With several dampings the names end in _z<damping>, e.g.\n"
    "psa_g_z0.05; with several files also in _<file name>, e.g.\n"
    "psa_g_z0.05_H1.AT2 (the path as given when two names coincide).\n"
    "Exit status: 0 success, 1 bad input or failed run, 2 usage error.\n";

enum { OPT_DAMPING = 256, OPT_UNITS, OPT_DT, OPT_FMIN, OPT_FMAX, OPT_PER_DECADE, OPT_FREQ,
       OPT_ALL, OPT_CSV, OPT_HELP };

static const struct option spectrum_opts[] = {
    {"damping", required_argument, 0, OPT_DAMPING},
    {"units", required_argument, 0, OPT_UNITS},
    {"dt", required_argument, 0, OPT_DT},
    {"fmin", required_argument, 0, OPT_FMIN},
    {"fmax", required_argument, 0, OPT_FMAX},
    {"per-decade", required_argument, 0, OPT_PER_DECADE},
    {"freq", required_argument, 0, OPT_FREQ},
    {"all", no_argument, 0, OPT_ALL},
    {"csv", no_argument, 0, OPT_CSV},
    {"help", no_argument, 0, OPT_HELP},
    {0, 0, 0, 0}};

static const char *base_name(const char *p)
{
    const char *s = strrchr(p, '/');
    return s ? s + 1 : p;
}

/* Write a CSV field, quoted when it holds a comma, quote or blank. */
static void put_field(const char *s)
{
    if (!strpbrk(s, ",\" \t\r\n")) {
        fputs(s, stdout);
        return;
    }
    putchar('"');
    for (; *s; s++) {
        if (*s == '"')
            putchar('"');
        putchar(*s);
    }
    putchar('"');
}

int cmd_spectrum(int argc, char **argv)
{
    double default_damping = SPECTRUM_DEFAULT_DAMPING;
    double *damp = NULL, *f = NULL;
    size_t nd = 0, nf = 0;
    cli_grid grid;
    cli_grid_init(&grid);
    int csv = 0, all = 0, rc = CLI_EXIT_ERROR;
    sl_read_opts ro = {SL_FORMAT_AUTO, SL_UNIT_NONE, 0.0};
    sl_motion **m = NULL;
    size_t nm = 0;
    double *psa = NULL, *sd = NULL, *sa = NULL;
    char **label = NULL;
    sl_error err;
    sl_error_clear(&err);

    optind = 1;
    opterr = 0;
    int c;
    while ((c = getopt_long(argc, argv, ":", spectrum_opts, NULL)) != -1) {
        const char *arg = optarg;
        switch (c) {
        case OPT_DAMPING:
            free(damp);
            if (cli_parse_list(arg, &damp, &nd)) {
                rc = cli_usage("spectrum", "bad --damping '%s'", arg);
                goto done;
            }
            break;
        case OPT_UNITS:
            if (cli_units("spectrum", arg, &ro.units)) {
                rc = CLI_EXIT_USAGE;
                goto done;
            }
            break;
        case OPT_DT:
            if (cli_positive("spectrum", "--dt", arg, NULL, &ro.dt_s)) {
                rc = CLI_EXIT_USAGE;
                goto done;
            }
            break;
        case OPT_FMIN:
        case OPT_FMAX:
        case OPT_PER_DECADE:
        case OPT_FREQ:
            if (cli_grid_option("spectrum", c == OPT_FMIN ? CLI_GRID_FMIN : c == OPT_FMAX ? CLI_GRID_FMAX
                                : c == OPT_PER_DECADE ? CLI_GRID_PER_DECADE : CLI_GRID_FREQ,
                                arg, &grid)) {
                rc = CLI_EXIT_USAGE;
                goto done;
            }
            break;
        case OPT_ALL: all = 1; break;
        case OPT_CSV: csv = 1; break;
        case OPT_HELP:
            printf(spectrum_help, SPECTRUM_DEFAULT_DAMPING, SL_SPECTRUM_FMIN_HZ,
                   SL_SPECTRUM_FMAX_HZ, SL_SPECTRUM_PER_DECADE);
            rc = CLI_EXIT_OK;
            goto done;
        case ':':
            rc = cli_usage("spectrum", "option '%s' needs a value", argv[optind - 1]);
            goto done;
        default:
            rc = cli_usage("spectrum", "unknown option '%s'", argv[optind - 1]);
            goto done;
        }
    }
    if (optind >= argc) {
        rc = cli_usage("spectrum", "give at least one motion FILE");
        goto done;
    }
    if (!damp) {
        damp = &default_damping;
        nd = 1;
    }
    for (size_t k = 0; k < nd; k++)
        if (!(damp[k] >= 0 && damp[k] < SPECTRUM_MAX_DAMPING)) {
            rc = cli_usage("spectrum", "damping %g outside [0, 1)", damp[k]);
            goto done;
        }
    if ((rc = cli_grid_make("spectrum", &grid, &f, &nf)) != CLI_EXIT_OK)
        goto done;
    rc = CLI_EXIT_ERROR;

    nm = (size_t)(argc - optind);
    m = calloc(nm, sizeof *m);
    label = calloc(nm, sizeof *label);
    if (!m || !label) {
        cli_msg("out of memory");
        goto done;
    }
    for (size_t i = 0; i < nm; i++) {
        m[i] = sl_motion_read(argv[optind + (int)i], &ro, &err);
        if (!m[i]) {
            cli_print_error(&err);
            goto done;
        }
    }
    /* file labels for column names: base names unless two coincide */
    int clash = 0;
    for (size_t i = 0; i < nm; i++)
        for (size_t j = i + 1; j < nm; j++)
            if (!strcmp(base_name(argv[optind + (int)i]), base_name(argv[optind + (int)j])))
                clash = 1;
    for (size_t i = 0; i < nm; i++)
        label[i] = clash ? argv[optind + (int)i] : (char *)base_name(argv[optind + (int)i]);

    size_t per = nm * nf;
    psa = malloc(nd * per * sizeof *psa);
    if (all) {
        sd = malloc(nd * per * sizeof *sd);
        sa = malloc(nd * per * sizeof *sa);
    }
    if (!psa || (all && (!sd || !sa))) {
        cli_msg("out of memory");
        goto done;
    }
    for (size_t k = 0; k < nd; k++) {
        if (sl_spectrum_batch((const sl_motion *const *)m, nm, f, nf, damp[k], NULL,
                              psa + k * per, all ? sd + k * per : NULL,
                              all ? sa + k * per : NULL, &err)) {
            cli_print_error(&err);
            goto done;
        }
    }

    /* columns: per file, per damping: psa_g [, sd_m, sa_abs_g] */
    size_t nq = all ? 3 : 1;
    static const char *const qname[3] = {"psa_g", "sd_m", "sa_abs_g"};
    size_t ncol = nm * nd * nq;
    char (*name)[320] = calloc(ncol, sizeof *name);
    if (!name) {
        cli_msg("out of memory");
        goto done;
    }
    size_t col = 0;
    for (size_t i = 0; i < nm; i++)
        for (size_t k = 0; k < nd; k++)
            for (size_t q = 0; q < nq; q++) {
                char zs[40] = "", fs[300] = "";
                if (nd > 1)
                    snprintf(zs, sizeof zs, "_z%g", damp[k]);
                if (nm > 1)
                    snprintf(fs, sizeof fs, "_%s", label[i]);
                snprintf(name[col++], sizeof name[0], "%s%s%s", qname[q], zs, fs);
            }

    if (!csv) {
        printf("# seislide spectrum: Nigam-Jennings, dt <= T/%g, %zu frequencies\n",
               SL_SPECTRUM_STEPS_PER_PERIOD, nf);
        for (size_t i = 0; i < nm; i++)
            printf("# %s: %zu samples at dt = %g s, PGA %.4f g\n", argv[optind + (int)i],
                   m[i]->n, m[i]->dt_s, sl_motion_pga(m[i]) / SL_G);
    }
    int w = 12;
    for (size_t j = 0; j < ncol; j++)
        if ((int)strlen(name[j]) > w)
            w = (int)strlen(name[j]);
    if (csv) {
        fputs("f_hz", stdout);
        for (size_t j = 0; j < ncol; j++) {
            putchar(',');
            put_field(name[j]);
        }
        putchar('\n');
    } else {
        printf("%10s", "f_hz");
        for (size_t j = 0; j < ncol; j++)
            printf(" %*s", w, name[j]);
        putchar('\n');
    }
    for (size_t p = 0; p < nf; p++) {
        if (csv)
            printf("%.6g", f[p]);
        else
            printf("%10.5g", f[p]);
        for (size_t i = 0; i < nm; i++)
            for (size_t k = 0; k < nd; k++)
                for (size_t q = 0; q < nq; q++) {
                    size_t at = k * per + i * nf + p;
                    double v = q == 0 ? psa[at] / SL_G : q == 1 ? sd[at] : sa[at] / SL_G;
                    if (csv)
                        printf(",%.8g", v);
                    else
                        printf(" %*.6g", w, v);
                }
        putchar('\n');
    }
    free(name);
    if (fflush(stdout) || ferror(stdout)) {
        cli_msg("error writing the output");
        goto done;
    }
    rc = CLI_EXIT_OK;
done:
    if (damp != &default_damping)
        free(damp);
    cli_grid_free(&grid);
    free(f);
    free(psa);
    free(sd);
    free(sa);
    free(label);
    if (m)
        for (size_t i = 0; i < nm; i++)
            sl_motion_free(m[i]);
    free(m);
    return rc;
}
