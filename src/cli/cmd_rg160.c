/* cmd_rg160.c - `seislide rg160`: Regulatory Guide 1.60 design spectra. */
#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "signal/rg160.h"
#include "signal/spectrum.h"

/* Default damping ratio when --damping is not given. */
#define RG160_DEFAULT_DAMPING 0.05
/* Most dampings in one table. */
#define RG160_MAX_DAMPINGS 64

static const char rg160_help[] =
    "usage: seislide rg160 --pga G [--damping LIST] [--vertical]\n"
    "                      [--fmin HZ] [--fmax HZ] [--per-decade N | --freq LIST] [--csv]\n"
    "\n"
    "US NRC Regulatory Guide 1.60 design response spectrum (pseudo-spectral\n"
    "acceleration) scaled to a peak ground acceleration: straight lines in log-log\n"
    "through the control points A 33 Hz (= PGA), B 9 Hz, C 2.5 Hz (vertical 3.5 Hz)\n"
    "and D 0.25 Hz (a displacement, 36 in per g of PGA), constant displacement\n"
    "below D. Tabulated dampings 0.5, 2, 5, 7 and 10 %%; in between, the\n"
    "amplification factors are interpolated linearly in ln(damping).\n"
    "\n"
    "  --pga G                peak ground acceleration, g (required)\n"
    "  --damping LIST         damping ratios in [%g, %g] (default %g)\n"
    "  --vertical             the vertical spectrum (ZPA = PGA) instead of horizontal\n"
    "  --fmin HZ, --fmax HZ   frequency range (default %g to %g Hz)\n"
    "  --per-decade N         log-spaced points per decade (default %g)\n"
    "  --freq LIST            explicit frequencies, Hz, instead of the grid\n"
    "  --csv                  CSV instead of an aligned table (stdout)\n"
    "\n"
    "columns: f_hz, psa_g; with several dampings psa_g_z<damping>, e.g.\n"
    "psa_g_z0.05. The grid is the one of 'seislide spectrum', so the columns\n"
    "line up with computed spectra.\n"
    "Exit status: 0 success, 1 bad input, 2 usage error.\n";

enum { OPT_PGA = 256, OPT_DAMPING, OPT_VERTICAL, OPT_FMIN, OPT_FMAX, OPT_PER_DECADE,
       OPT_FREQ, OPT_CSV, OPT_HELP };

static const struct option rg160_opts[] = {
    {"pga", required_argument, 0, OPT_PGA},
    {"damping", required_argument, 0, OPT_DAMPING},
    {"vertical", no_argument, 0, OPT_VERTICAL},
    {"fmin", required_argument, 0, OPT_FMIN},
    {"fmax", required_argument, 0, OPT_FMAX},
    {"per-decade", required_argument, 0, OPT_PER_DECADE},
    {"freq", required_argument, 0, OPT_FREQ},
    {"csv", no_argument, 0, OPT_CSV},
    {"help", no_argument, 0, OPT_HELP},
    {0, 0, 0, 0}};

int cmd_rg160(int argc, char **argv)
{
    double default_damping = RG160_DEFAULT_DAMPING;
    double *damp = NULL, *f = NULL, *psa = NULL;
    size_t nd = 0, nf = 0;
    double pga_g = NAN;
    cli_grid grid;
    cli_grid_init(&grid);
    int csv = 0, rc = CLI_EXIT_ERROR;
    sl_rg160_dir dir = SL_RG160_HORIZONTAL;
    sl_error err;
    sl_error_clear(&err);

    optind = 1;
    opterr = 0;
    int c;
    while ((c = getopt_long(argc, argv, ":", rg160_opts, NULL)) != -1) {
        const char *arg = optarg;
        switch (c) {
        case OPT_PGA:
            if (cli_parse_double(arg, &pga_g) || !(pga_g >= 0)) {
                rc = cli_usage("rg160", "--pga '%s' must be a number >= 0 (g)", arg);
                goto done;
            }
            break;
        case OPT_DAMPING:
            free(damp);
            if (cli_parse_list(arg, &damp, &nd)) {
                rc = cli_usage("rg160", "bad --damping '%s'", arg);
                goto done;
            }
            break;
        case OPT_VERTICAL: dir = SL_RG160_VERTICAL; break;
        case OPT_FMIN:
        case OPT_FMAX:
        case OPT_PER_DECADE:
        case OPT_FREQ:
            if (cli_grid_option("rg160", c == OPT_FMIN ? CLI_GRID_FMIN : c == OPT_FMAX ? CLI_GRID_FMAX
                                : c == OPT_PER_DECADE ? CLI_GRID_PER_DECADE : CLI_GRID_FREQ,
                                arg, &grid)) {
                rc = CLI_EXIT_USAGE;
                goto done;
            }
            break;
        case OPT_CSV: csv = 1; break;
        case OPT_HELP:
            printf(rg160_help, SL_RG160_ZETA_MIN, SL_RG160_ZETA_MAX, RG160_DEFAULT_DAMPING,
                   SL_SPECTRUM_FMIN_HZ, SL_SPECTRUM_FMAX_HZ, SL_SPECTRUM_PER_DECADE);
            rc = CLI_EXIT_OK;
            goto done;
        case ':':
            rc = cli_usage("rg160", "option '%s' needs a value", argv[optind - 1]);
            goto done;
        default:
            rc = cli_usage("rg160", "unknown option '%s'", argv[optind - 1]);
            goto done;
        }
    }
    if (optind < argc) {
        rc = cli_usage("rg160", "unexpected argument '%s'", argv[optind]);
        goto done;
    }
    if (isnan(pga_g)) {
        rc = cli_usage("rg160", "--pga G is required");
        goto done;
    }
    if (!damp) {
        damp = &default_damping;
        nd = 1;
    }
    if (nd > RG160_MAX_DAMPINGS) {
        rc = cli_usage("rg160", "at most %d dampings", RG160_MAX_DAMPINGS);
        goto done;
    }
    for (size_t k = 0; k < nd; k++)
        if (!(damp[k] >= SL_RG160_ZETA_MIN && damp[k] <= SL_RG160_ZETA_MAX)) {
            rc = cli_usage("rg160", "damping %g outside the guide's range [%g, %g]", damp[k],
                           SL_RG160_ZETA_MIN, SL_RG160_ZETA_MAX);
            goto done;
        }
    if ((rc = cli_grid_make("rg160", &grid, &f, &nf)) != CLI_EXIT_OK)
        goto done;
    rc = CLI_EXIT_ERROR;
    psa = malloc(nd * nf * sizeof *psa);
    if (!psa) {
        cli_msg("out of memory");
        goto done;
    }
    for (size_t k = 0; k < nd; k++)
        if (sl_rg160_psa(dir, damp[k], pga_g * SL_G, f, nf, psa + k * nf, &err)) {
            cli_print_error(&err);
            goto done;
        }
    if (!csv)
        printf("# seislide rg160: Regulatory Guide 1.60 %s design spectrum, PGA %g g\n",
               dir == SL_RG160_VERTICAL ? "vertical" : "horizontal", pga_g);
    char names[RG160_MAX_DAMPINGS][40];
    for (size_t k = 0; k < nd; k++) {
        if (nd > 1)
            snprintf(names[k], sizeof names[k], "psa_g_z%g", damp[k]);
        else
            snprintf(names[k], sizeof names[k], "psa_g");
    }
    if (csv) {
        fputs("f_hz", stdout);
        for (size_t k = 0; k < nd; k++)
            printf(",%s", names[k]);
    } else {
        printf("%10s", "f_hz");
        for (size_t k = 0; k < nd; k++)
            printf(" %12s", names[k]);
    }
    putchar('\n');
    for (size_t j = 0; j < nf; j++) {
        printf(csv ? "%.6g" : "%10.5g", f[j]);
        for (size_t k = 0; k < nd; k++)
            printf(csv ? ",%.8g" : " %12.6g", psa[k * nf + j] / SL_G);
        putchar('\n');
    }
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
    return rc;
}
