/* cmd_lookup.c - `seislide lookup RESULTS [--building B] --floor F --mu X
 * [--csv]`: the required clearance of one floor at one friction value from a
 * run's outputs, read and resolved by the components check's loader
 * (report/components.h: the floor tables, the name rule, the interpolation
 * of the workbook's Lookup), so that a floor and a building resolve exactly
 * as a components row and the sheet resolve them. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "method/stats.h"
#include "report/components.h"

static const char lookup_head[] =
    "usage: seislide lookup RESULTS [--building B] --floor F --mu X [--csv]\n"
    "\n"
    "The required clearance around an unanchored component on one floor at one\n"
    "friction coefficient, from the outputs of 'seislide run' in RESULTS (one\n"
    "building, or a plant with plant.csv): the floor's clearance at mu by linear\n"
    "interpolation between the grid rows around it, as the workbook's Lookup and\n"
    "'seislide components' compute it, with its standard error, the ASCE/SEI\n"
    "43-05 design value at mu, the floor's ZPA and mu g/ZPA, the flags of the two\n"
    "grid rows, the floor's motion sets and its note. The building and the floor\n"
    "(its id or its name) are found as a components row finds them: ends trimmed,\n"
    "runs of blanks one, without case in any script (docs/components.md).\n"
    "The clearance is printed to the digit of its standard error (whole mm when\n"
    "it is 1 mm or more, else 0.1 mm), as the tables print it; --csv prints it\n"
    "to 0.1 mm, as components.csv.\n"
    "\n"
    "options:\n";
static const char lookup_tail[] =
    "\nExit status: 0 the clearance printed, 1 unreadable results, an unknown\n"
    "building or floor (the known ones listed) or mu off the computed grid,\n"
    "2 usage error.\n";

typedef struct lookup_args {
    const char *building, *floor;
    double mu;
    int csv;
} lookup_args;

#define A(f) .off = offsetof(lookup_args, f)
static const cli_opt lookup_opts[] = {
    {"building", CLI_OPT_ID, "B", "the building, as plant.csv names it (may be left out\n"
     "for one building)", .kind = CLI_STRING, A(building)},
    {"floor", CLI_OPT_ID + 1, "F", "the floor: its id (file name without .ini/.csv) or\n"
     "its name (required)", .kind = CLI_STRING, A(floor)},
    {"mu", CLI_OPT_ID + 2, "X", "the friction coefficient (required), on the run's grid",
     .kind = CLI_POSITIVE, A(mu)},
    {"csv", CLI_OPT_ID + 3, NULL, "one CSV header and row on stdout instead of the text",
     .kind = CLI_FLAG, A(csv)},
};

static int check(void *dst)
{
    const lookup_args *a = dst;
    if (!a->floor)
        return cli_usage("lookup", "name the floor with --floor F");
    if (isnan(a->mu))
        return cli_usage("lookup", "give the friction coefficient with --mu X");
    return CLI_EXIT_OK;
}

/* Clearances are shown to the place of their SE's leading digit, between
 * these steps, mm (report/text.c: the tables' rule). */
#define SHOWN_MIN_STEP_MM 0.1
#define SHOWN_MAX_STEP_MM 1.0

static void put_text(const sl_comp_results *r, const sl_comp_floor *fl, double mu,
                     const sl_comp_at *at)
{
    double se = isfinite(at->se_mm) ? at->se_mm : 0;
    int dec = sl_stats_step_decimals(sl_stats_step(se, SHOWN_MIN_STEP_MM, SHOWN_MAX_STEP_MM));
    const char *b = r->is_plant ? fl->building : r->single ? r->single : "";
    printf("building            %s%s\n", b, r->is_plant ? "" : " (one building)");
    printf("floor               %s (%s)\n", fl->id, fl->name);
    if (mu == r->mu[at->k0])
        printf("mu                  %g (a grid row)\n", mu);
    else
        printf("mu                  %g (between the grid rows %g and %g)\n", mu, r->mu[at->k0],
               r->mu[at->k1]);
    printf("required clearance  %.*f mm (SE %.1f mm; clearance policy %s)\n", dec,
           at->required_mm, se, r->policy);
    if (isfinite(at->asce_mm))
        printf("ASCE design value   %.1f mm (ASCE/SEI 43-05, for comparison)\n", at->asce_mm);
    else
        printf("ASCE design value   - (not defined at these grid rows)\n");
    if (isfinite(fl->zpa_g))
        printf("horizontal ZPA      %.3f g (mu g/ZPA %.3f)\n", fl->zpa_g, mu / fl->zpa_g);
    printf("flags               %s | %s\n", *fl->flags[at->k0] ? fl->flags[at->k0] : "-",
           *fl->flags[at->k1] ? fl->flags[at->k1] : "-");
    if (fl->n_sets >= 0)
        printf("motion sets         %ld (%s)\n", fl->n_sets, *fl->sets_stop ? fl->sets_stop : "-");
    printf("note                %s\n", *fl->note ? fl->note : "-");
    if (*fl->warnings)
        printf("warnings            %s\n", fl->warnings);
}

static void put_csv_num(double v, const char *fmt)
{
    if (isfinite(v))
        printf(fmt, v);
    putchar(',');
}

static void put_csv(const sl_comp_results *r, const sl_comp_floor *fl, double mu,
                    const sl_comp_at *at)
{
    printf("building,floor_id,floor,mu,required_clearance_mm,required_clearance_se_mm,"
           "asce_design_mm,clearance_policy,zpa_h_g,mu_g_over_zpa,flags_below,flags_above,"
           "n_sets,sets_stop,note,warnings\n");
    cli_put_field(r->is_plant ? fl->building : "");
    putchar(',');
    cli_put_field(fl->id);
    putchar(',');
    cli_put_field(fl->name);
    printf(",%g,", mu);
    put_csv_num(at->required_mm, "%.1f");
    put_csv_num(at->se_mm, "%.1f");
    put_csv_num(at->asce_mm, "%.1f");
    cli_put_field(r->policy);
    putchar(',');
    put_csv_num(fl->zpa_g, "%.4f");
    put_csv_num(isfinite(fl->zpa_g) ? mu / fl->zpa_g : NAN, "%.4f");
    cli_put_field(fl->flags[at->k0]);
    putchar(',');
    cli_put_field(fl->flags[at->k1]);
    putchar(',');
    if (fl->n_sets >= 0)
        printf("%ld", fl->n_sets);
    putchar(',');
    cli_put_field(fl->sets_stop);
    putchar(',');
    cli_put_field(fl->note);
    putchar(',');
    cli_put_field(fl->warnings);
    putchar('\n');
}

int cmd_lookup(int argc, char **argv)
{
    static const cli_command cmd = {"lookup", lookup_head, lookup_tail, lookup_opts,
                                    CLI_NOPTS(lookup_opts), 18, NULL, check, 1};
    lookup_args a = {.mu = NAN};
    int rc = cli_command_parse(&cmd, argc, argv, &a);
    if (rc)
        return rc == CLI_OPT_HELP ? CLI_EXIT_OK : rc;
    if (argc - optind != 1)
        return cli_usage("lookup", "give RESULTS (a run's output folder)");
    const char *dir = argv[optind];
    sl_error err;
    sl_error_clear(&err);
    sl_comp_results r;
    if (sl_comp_results_load(dir, &r, &err)) {
        cli_print_error(&err);
        return CLI_EXIT_ERROR;
    }
    size_t fi;
    sl_comp_at at;
    rc = CLI_EXIT_ERROR;
    if (sl_comp_find(&r, a.building, a.floor, &fi, &err)) {
        snprintf(err.file, sizeof err.file, "%s", dir); /* where the names were looked for */
        cli_print_error(&err);
    } else if (!sl_comp_floor_at(&r, fi, a.mu, &at)) {
        cli_msg("mu %g outside the computed grid %g-%g of %s: no clearance computed (run again "
                "with a grid that covers it: --mu-range)", a.mu, r.mu[0], r.mu[r.n_mu - 1], dir);
    } else {
        if (a.csv)
            put_csv(&r, &r.floors[fi], a.mu, &at);
        else
            put_text(&r, &r.floors[fi], a.mu, &at);
        rc = fflush(stdout) || ferror(stdout) ? CLI_EXIT_ERROR : CLI_EXIT_OK;
        if (rc)
            cli_msg("cannot write to stdout");
    }
    sl_comp_results_free(&r);
    return rc;
}
