/* cmd_components.c - `seislide components RESULTS COMPONENTS.csv -o OUT`: each
 * component of a plant's list checked against the floor tables of a run
 * (report/components.h): OUT/components.csv and OUT/components.xlsx, the
 * folder written whole or not at all (outdir.h). */
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cli.h"
#include "components_out.h"
#include "plant/cache.h"
#include "outdir.h"
#include "report/components.h"

static const char comp_head[] =
    "usage: seislide components RESULTS COMPONENTS.csv -o OUT [options]\n"
    "\n"
    "Check a list of unanchored components against the floor tables of a run:\n"
    "RESULTS is the output folder of 'seislide run' (one building, or a plant\n"
    "with <building>/ folders and plant.csv). COMPONENTS.csv has the columns\n"
    "tag, building, floor, mu, base_m, cg_height_m, clearance_mm (any order,\n"
    "without case; other columns kept; ';' between fields and decimal commas\n"
    "read as a floor table); building may be empty for one building; floor is a\n"
    "floor id or name (names compared as the workbook does: ends trimmed, runs\n"
    "of blanks one, without case in any script). Per component: the required\n"
    "clearance at mu (linear interpolation on the floor's grid, as the\n"
    "workbook's Lookup), its standard error, the ASCE/SEI 43-05 value beside it,\n"
    "margin_mm = clearance_mm - required and the verdict: outside when mu is off\n"
    "the grid; short when the margin is < 0; marginal when it is below 2\n"
    "standard errors; ok otherwise.\n"
    "A slender item (mu >= b/h = base_m / (2 cg_height_m): it rocks before it\n"
    "slides) is checked for rocking instead, by NLTHA of the rocking block on\n"
    "the floor's own motion sets (made again from the floor files the run read;\n"
    "the results are kept in the cache): the probability that it tips at the\n"
    "floor motion and at 1.5 x it, against ASCE/SEI 43-05's targets of 1 % and\n"
    "10 %, and the excursion of its top against clearance_mm: stands, marginal,\n"
    "short or overturns. Optional columns: mu_max (upper bound of the friction:\n"
    "mu < b/h <= mu_max is checked both ways, the worse verdict governs),\n"
    "restitution (0-1, Housner's by default), orientation_deg (the rocking axis\n"
    "from H1; the worst of 12 by default).\n"
    "Writes OUT/" SL_COMP_CSV " and\n"
    "OUT/" SL_COMP_XLSX " (live formulas: rows typed in below get their verdict)\n"
    "(docs/components.md, docs/rocking.md).\n"
    "\n"
    "options:\n";
static const char comp_tail[] =
    "\nExit status: 0 every component computed (short is a result), 1 malformed\n"
    "rows (every problem named as file:line:column in one pass; nothing written)\n"
    "or unreadable results, 2 usage error.\n";

typedef struct comp_args {
    const char *out, *cache;
    int no_cache, quiet;
    double created;
} comp_args;

enum { O_CREATED = CLI_OPT_ID, O_CACHE, O_NO_CACHE };
#define A(f) .off = offsetof(comp_args, f)
static const cli_opt comp_opts[] = {
    {"output", 'o', "OUT", "output folder (required); written as a fresh folder swapped\n"
     "in: OUT must be new, empty or hold only these outputs", .kind = CLI_STRING, A(out)},
    {"cache", O_CACHE, "CDIR", "keep and reuse rocking results in CDIR (default\n"
     "RESULTS/" SL_CACHE_DIR_NAME " when it exists)", .kind = CLI_STRING, A(cache)},
    {"no-cache", O_NO_CACHE, NULL, "compute every rocking item and keep nothing",
     .kind = CLI_FLAG, A(no_cache)},
    {"quiet", 'q', NULL, "no progress on stderr (the summary line and errors stay)",
     .kind = CLI_FLAG, A(quiet)},
    CLI_OPT_CREATED(O_CREATED),
};

static int take(void *dst, int key, const char *v)
{
    comp_args *a = dst;
    (void)key;
    if (cli_parse_created(v, &a->created))
        return cli_usage("components", "bad value '%s' for --created", v);
    return CLI_EXIT_OK;
}

static int check(void *dst)
{
    const comp_args *a = dst;
    if (!a->out)
        return cli_usage("components", "name the output folder with -o OUT");
    if (a->cache && a->no_cache)
        return cli_usage("components", "--cache and --no-cache exclude each other");
    return CLI_EXIT_OK;
}

sl_status components_write(const char *results, const char *shown, const char *file,
                           const char *dir, const char *cmdline, time_t created,
                           const sl_plant *plant, const char *cache, int quiet,
                           sl_error *err)
{
    sl_comp_results r;
    sl_comp_table t;
    sl_status st = sl_comp_results_load(results, &r, err);
    if (!st && strcmp(shown, results) && (st = sl_comp_results_shown(&r, shown, err)))
        sl_comp_results_free(&r);
    if (st)
        return st;
    sl_comp_problems *p = malloc(sizeof *p);
    if (!p) {
        sl_comp_results_free(&r);
        return sl_error_set(err, SL_ENOMEM, file, 0, "out of memory");
    }
    if ((st = sl_comp_table_read(file, &r, &t, p, err))) {
        /* every bad row, each named; then how many (the caller prints err) */
        for (size_t i = 0; p->n > 1 && i < p->n; i++)
            cli_print_error(&p->e[i]);
        if (p->n_more)
            cli_msg("... and %zu more problems in %s", p->n_more, file);
        if (p->n > 1) {
            size_t len = strlen(err->msg);
            snprintf(err->msg + len, sizeof err->msg - len, "; nothing written");
        }
        free(p);
        sl_comp_results_free(&r);
        return st;
    }
    free(p);
    if ((st = components_rock(&r, &t, plant, cache, quiet, err))) {
        sl_comp_table_free(&t);
        sl_comp_results_free(&r);
        return st;
    }
    char date[32] = "";
    struct tm tm;
    if (gmtime_r(&created, &tm))
        strftime(date, sizeof date, "%Y-%m-%d", &tm);
    sl_comp_opts o = {sl_build_id(), cmdline, created, date[0] ? date : NULL};
    st = sl_comp_write(&r, &t, dir, &o, err);
    if (!st)
        cli_msg("%zu components: %zu ok, %zu stands, %zu marginal, %zu short, %zu overturns, "
                "%zu outside", t.n, t.count[SL_COMP_OK], t.count[SL_COMP_STANDS],
                t.count[SL_COMP_MARGINAL], t.count[SL_COMP_SHORT], t.count[SL_COMP_OVERTURNS],
                t.count[SL_COMP_OUTSIDE]);
    sl_comp_table_free(&t);
    sl_comp_results_free(&r);
    return st;
}

int cmd_components(int argc, char **argv)
{
    static const cli_command cmd = {"components", comp_head, comp_tail, comp_opts,
                                    CLI_NOPTS(comp_opts), 22, take, check, 1};
    comp_args a = {.created = cli_created_default()};
    int rc = cli_command_parse(&cmd, argc, argv, &a);
    if (rc)
        return rc == CLI_OPT_HELP ? CLI_EXIT_OK : rc;
    if (argc - optind != 2)
        return cli_usage("components", "give RESULTS (a run's output folder) and "
                         "COMPONENTS.csv");
    /* the output folder apart from the run's folder and the list (exit 2) */
    const char *inputs[2] = {argv[optind], argv[optind + 1]};
    if ((rc = cli_outdir_apart("components", "output folder", a.out, inputs, 2)))
        return rc;
    char cmdline[8192];
    cli_command_line(cmdline, sizeof cmdline, argc, argv);
    sl_error err;
    sl_error_clear(&err);
    sl_atomic_dir *out = cli_outdir_open(a.out, sl_build_id(), NULL, &err);
    rc = CLI_EXIT_ERROR;
    if (!out)
        goto fail;
    cli_outdir_writing();
    char cache[4400];
    snprintf(cache, sizeof cache, "%s/%s", argv[optind], SL_CACHE_DIR_NAME);
    const char *cdir = a.no_cache ? NULL : a.cache ? a.cache : cache;
    if (components_write(argv[optind], argv[optind], argv[optind + 1], sl_atomic_dir_path(out),
                         cmdline, (time_t)a.created, NULL, cdir, a.quiet, &err) ||
        cli_outdir_commit(&out, &err))
        goto fail;
    rc = CLI_EXIT_OK;
    goto done;
fail:
    cli_outdir_error(&err);
done:
    cli_outdir_finish(out);
    return rc;
}
