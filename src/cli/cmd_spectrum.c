/* cmd_spectrum.c - `seislide spectrum`: response spectra of motions. Parses
 * (one option table), calls signal/spectrum.h, prints (spectrum_output.h). */
#include <math.h>
#include <stddef.h>
#include <stdlib.h>

#include "cli.h"
#include "io/motion.h"
#include "signal/spectrum.h"
#include "spectrum_output.h"

/* Default damping ratio when --damping is not given. */
#define SPECTRUM_DEFAULT_DAMPING 0.05
/* Largest damping ratio accepted (the oscillator must be underdamped). */
#define SPECTRUM_MAX_DAMPING 1.0

static const char spectrum_head[] =
    "usage: seislide spectrum FILE... [--damping LIST] [--units U] [--dt S]\n"
    "                         [--fmin HZ] [--fmax HZ] [--per-decade N | --freq LIST]\n"
    "                         [--all] [--csv]\n"
    "\n"
    "Linear response spectra of acceleration records by the exact piecewise-linear\n"
    "recurrence (Nigam-Jennings 1969), sub-stepped so that dt <= T/%g, oscillator\n"
    "from rest, free vibration after the record until the first extremum.\n"
    "PSA = (2 pi f)^2 max|u| (pseudo-spectral acceleration).\n"
    "\n";

static const char spectrum_tail[] =
    "\n"
    "columns: f_hz, then per file and per damping psa_g (and with --all sd_m,\n"
    "sa_abs_g). With several dampings the names end in _z<damping>, e.g.\n"
    "psa_g_z0.05; with several files also in _<file name>, e.g.\n"
    "psa_g_z0.05_H1.AT2 (the path as given when two names coincide).\n"
    "Exit status: 0 success, 1 bad input or failed run, 2 usage error.\n";

typedef struct spectrum_args {
    cli_list damp;
    sl_read_opts ro;
    cli_grid grid;
    int all, csv;
} spectrum_args;

#define A(f) .off = offsetof(spectrum_args, f)
static const cli_opt spectrum_opts[] = {
    {.head = "input:"},
    {.show = "FILE...", .help = "motions: PEER .AT2, one column (needs --dt), two\ncolumns "
     "time+acc, or CSV with a header"},
    {"units", CLI_OPT_ID, "U", "g, m/s2 or cm/s2 (= gal) for files that do not name\ntheir unit "
     "(AT2 headers do)", .kind = CLI_UNITS, A(ro.units)},
    {"dt", CLI_OPT_ID + 1, "S", "sample interval for one-column files, s", .kind = CLI_POSITIVE,
     A(ro.dt_s)},
    {.head = "spectrum:"},
    {"damping", CLI_OPT_ID + 2, "LIST", "damping ratios in [0, 1), e.g. 0.05,0.10 (default %g)",
     {SPECTRUM_DEFAULT_DAMPING}, .kind = CLI_LIST, A(damp)},
    CLI_GRID_OPTS(offsetof(spectrum_args, grid)),
    {.head = "output (stdout):"},
    {"csv", CLI_OPT_ID + 3, NULL, "CSV instead of an aligned table", .kind = CLI_FLAG, A(csv)},
    {"all", CLI_OPT_ID + 4, NULL, "also spectral displacement and absolute acceleration",
     .kind = CLI_FLAG, A(all)},
};

int cmd_spectrum(int argc, char **argv)
{
    spectrum_args a = {.ro = {SL_FORMAT_AUTO, SL_UNIT_NONE, 0.0}};
    cli_grid_init(&a.grid);
    double default_damping = SPECTRUM_DEFAULT_DAMPING, *f = NULL, *out[3] = {NULL, NULL, NULL};
    size_t nf = 0, nm = 0;
    sl_motion **m = NULL;
    char **label = NULL;
    sl_error err;
    sl_error_clear(&err);
    int rc = cli_parse("spectrum", spectrum_opts, CLI_NOPTS(spectrum_opts), argc, argv, &a, NULL);
    if (rc == CLI_OPT_HELP) {
        printf(spectrum_head, SL_SPECTRUM_STEPS_PER_PERIOD);
        cli_help_options(stdout, spectrum_opts, CLI_NOPTS(spectrum_opts), 25);
        fputs(spectrum_tail, stdout);
        rc = CLI_EXIT_OK;
        goto done;
    }
    if (rc)
        goto done;
    if (optind >= argc) {
        rc = cli_usage("spectrum", "give at least one motion FILE");
        goto done;
    }
    const double *damp = a.damp.v ? a.damp.v : &default_damping;
    size_t nd = a.damp.v ? a.damp.n : 1, nq = a.all ? 3 : 1;
    for (size_t k = 0; k < nd; k++)
        if (!(damp[k] >= 0 && damp[k] < SPECTRUM_MAX_DAMPING)) {
            rc = cli_usage("spectrum", "damping %g outside [0, 1)", damp[k]);
            goto done;
        }
    if ((rc = cli_grid_make("spectrum", &a.grid, &f, &nf)) != CLI_EXIT_OK)
        goto done;
    rc = CLI_EXIT_ERROR;
    nm = (size_t)(argc - optind);
    char **files = argv + optind;
    m = calloc(nm, sizeof *m);
    label = calloc(nm, sizeof *label);
    for (size_t q = 0; q < nq; q++)
        out[q] = malloc(nd * nm * nf * sizeof *out[q]);
    if (!m || !label || !out[0] || (a.all && (!out[1] || !out[2]))) {
        cli_msg("out of memory");
        goto done;
    }
    for (size_t i = 0; i < nm; i++)
        if (!(m[i] = sl_motion_read(files[i], &a.ro, &err))) {
            cli_print_error(&err);
            goto done;
        }
    spectrum_labels(files, nm, label);
    for (size_t k = 0; k < nd; k++) {
        size_t at = k * nm * nf;
        if (sl_spectrum_batch((const sl_motion *const *)m, nm, f, nf, damp[k], NULL, out[0] + at,
                              a.all ? out[1] + at : NULL, a.all ? out[2] + at : NULL, &err)) {
            cli_print_error(&err);
            goto done;
        }
    }
    if (spectrum_print(a.csv, files, m, nm, label, damp, nd, f, nf, out, nq)) {
        cli_msg("out of memory");
        goto done;
    }
    rc = cli_stdout_done();
done:
    free(a.damp.v);
    cli_grid_free(&a.grid);
    free(f);
    for (int q = 0; q < 3; q++)
        free(out[q]);
    free(label);
    for (size_t i = 0; m && i < nm; i++)
        sl_motion_free(m[i]);
    free(m);
    return rc;
}
