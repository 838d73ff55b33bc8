/* cmd_rg160.c - `seislide rg160`: Regulatory Guide 1.60 design spectra. */
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "signal/rg160.h"
#include "signal/spectrum.h"

/* Default damping ratio when --damping is not given. */
#define RG160_DEFAULT_DAMPING 0.05
/* Most dampings in one table. */
#define RG160_MAX_DAMPINGS 64

static const char rg160_head[] =
    "usage: seislide rg160 --pga G [--damping LIST] [--vertical]\n"
    "                      [--fmin HZ] [--fmax HZ] [--per-decade N | --freq LIST] [--csv]\n"
    "\n"
    "US NRC Regulatory Guide 1.60 design response spectrum (pseudo-spectral\n"
    "acceleration) scaled to a peak ground acceleration: straight lines in log-log\n"
    "through the control points A 33 Hz (= PGA), B 9 Hz, C 2.5 Hz (vertical 3.5 Hz)\n"
    "and D 0.25 Hz (a displacement, 36 in per g of PGA), constant displacement\n"
    "below D. Tabulated dampings 0.5, 2, 5, 7 and 10 %; in between, the\n"
    "amplification factors are interpolated linearly in ln(damping).\n"
    "\n";

static const char rg160_tail[] =
    "\n"
    "columns: f_hz, psa_g; with several dampings psa_g_z<damping>, e.g.\n"
    "psa_g_z0.05. The grid is the one of 'seislide spectrum', so the columns\n"
    "line up with computed spectra.\n"
    "Exit status: 0 success, 1 bad input, 2 usage error.\n";

typedef struct rg160_args {
    double pga_g;
    cli_list damp;
    int vertical, csv;
    cli_grid grid;
} rg160_args;

#define A(f) .off = offsetof(rg160_args, f)
static const cli_opt rg160_opts[] = {
    {"pga", CLI_OPT_ID, "G", "peak ground acceleration, g (required)", .kind = CLI_NONNEG,
     A(pga_g), .unit = "g"},
    {"damping", CLI_OPT_ID + 1, "LIST", "damping ratios in [%g, %g] (default %g)",
     {SL_RG160_ZETA_MIN, SL_RG160_ZETA_MAX, RG160_DEFAULT_DAMPING}, .kind = CLI_LIST, A(damp)},
    {"vertical", CLI_OPT_ID + 2, NULL, "the vertical spectrum (ZPA = PGA) instead of horizontal",
     .kind = CLI_FLAG, A(vertical)},
    CLI_GRID_OPTS(offsetof(rg160_args, grid)),
    {"csv", CLI_OPT_ID + 3, NULL, "CSV instead of an aligned table (stdout)", .kind = CLI_FLAG,
     A(csv)},
};

/* The usage rules across options. Returns CLI_EXIT_OK or a usage error. */
static int check_args(void *dst)
{
    const rg160_args *a = dst;
    if (isnan(a->pga_g))
        return cli_usage("rg160", "--pga G is required");
    if (a->damp.n > RG160_MAX_DAMPINGS)
        return cli_usage("rg160", "at most %d dampings", RG160_MAX_DAMPINGS);
    for (size_t k = 0; k < a->damp.n; k++)
        if (!(a->damp.v[k] >= SL_RG160_ZETA_MIN && a->damp.v[k] <= SL_RG160_ZETA_MAX))
            return cli_usage("rg160", "damping %g outside the guide's range [%g, %g]",
                             a->damp.v[k], SL_RG160_ZETA_MIN, SL_RG160_ZETA_MAX);
    return CLI_EXIT_OK;
}

static const cli_command rg160_cmd = {"rg160", rg160_head, rg160_tail, rg160_opts,
                                      CLI_NOPTS(rg160_opts), 25, NULL, check_args, 0};

int cmd_rg160(int argc, char **argv)
{
    rg160_args a = {.pga_g = NAN};
    cli_grid_init(&a.grid);
    double default_damping = RG160_DEFAULT_DAMPING, *f = NULL, *psa = NULL;
    size_t nf = 0;
    sl_error err;
    sl_error_clear(&err);
    int rc = cli_command_parse(&rg160_cmd, argc, argv, &a);
    if (rc || (rc = cli_grid_make("rg160", &a.grid, &f, &nf)))
        goto done;
    const double *damp = a.damp.v ? a.damp.v : &default_damping;
    size_t nd = a.damp.v ? a.damp.n : 1;
    rc = CLI_EXIT_ERROR;
    if (!(psa = malloc(nd * nf * sizeof *psa))) {
        cli_msg("out of memory");
        goto done;
    }
    sl_rg160_dir dir = a.vertical ? SL_RG160_VERTICAL : SL_RG160_HORIZONTAL;
    for (size_t k = 0; k < nd; k++)
        if (sl_rg160_psa(dir, damp[k], a.pga_g * SL_G, f, nf, psa + k * nf, &err)) {
            cli_print_error(&err);
            goto done;
        }
    if (!a.csv)
        printf("# seislide rg160: Regulatory Guide 1.60 %s design spectrum, PGA %g g\n",
               a.vertical ? "vertical" : "horizontal", a.pga_g);
    char names[RG160_MAX_DAMPINGS][320];
    for (size_t k = 0; k < nd; k++)
        if (nd > 1)
            snprintf(names[k], sizeof names[k], "psa_g_z%g", damp[k]);
        else
            snprintf(names[k], sizeof names[k], "psa_g");
    for (size_t i = 0; i < nd * nf; i++)
        psa[i] /= SL_G; /* in g */
    cli_print_table(a.csv, f, nf, names, nd, psa);
    rc = cli_stdout_done();
done:
    free(a.damp.v);
    cli_grid_free(&a.grid);
    free(f);
    free(psa);
    return rc == CLI_OPT_HELP ? CLI_EXIT_OK : rc;
}
