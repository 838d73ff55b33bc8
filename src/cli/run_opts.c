/* run_opts.c - the options of `seislide run` (run_opts.h): one cli_opt
 * table, parsed by cli_parse() and printed by --help, and the rules across
 * options. */
#include "run_opts.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core/standards.h"
#include "slide/model.h"
#include "method/scatter.h"
#include "plant/plant.h"
#include "report/plant_book.h"

static const char run_head[] =
    "usage: seislide run [FLOOR.ini|FLOOR.csv ... | DIR | PLANT] [options]\n\nThe main job: for every floor "
    "response spectrum file (default: every *.ini and *.csv in floors/),\nsynthesize motion sets, "
    "compute the peak vector sliding displacement of each by\nNLTHA over the friction grid "
    "and the ASCE/SEI 43-05 estimate, the design sliding\nspectra, every range where ASCE "
    "is below NLTHA, and the required clearance; write\nDIR/" SL_DELIVER_WORKBOOK " and "
    "the CSV files (docs/run.md).\n\nA PLANT is a folder of buildings, one sub-folder each with its floor files:\n"
    "DIR/<building>/ gets each building's outputs, DIR/" SL_PLANT_BOOK_CSV " and DIR/" SL_PLANT_BOOK_XLSX "\n"
    "the plant index. Every floor's result is kept in a cache and reused while its\n"
    "spectra and the settings are unchanged; an interrupted run resumes (docs/plant.md).\n"
    "\noptions:\n";
static const char run_tail[] =
    "\nExit status: 0 success, 1 bad input or failed run (the output folder unchanged),\n"
    "2 usage error.\n";

#define A(f) .off = offsetof(run_args, f)
enum { O_SETS = CLI_OPT_ID, O_SEED, O_MU_RANGE, O_MU, O_POLICY, O_ACC, O_SUB, O_MOTIONS,
       O_CREATED, O_FORCE, O_PROJECT, O_DOCUMENT, O_REVISION, O_PREPARED, O_CHECKED, O_DATE,
       O_REL_SE, O_ABS_SE, O_MAX_SETS, O_SCATTER, O_ACCEPT, O_SHARD, O_CACHE, O_NO_CACHE, O_COMPONENTS,
       O_ACCEPT_FLOOR, O_ROCKING_LOOKUP };
static const cli_opt opts[] = {
    {"output", 'o', "DIR", "output folder (default output/), swapped in whole (in place on a\n"
     "mount point): new (parents made), empty or one seislide wrote;\n"
     "files it did not write stay", .kind = CLI_STRING,
     A(out)},
    {"quiet", 'q', NULL, "no progress on stderr (warnings on the result and errors are\n"
     "still printed)",
     .kind = CLI_FLAG, A(quiet)},
    {"sets", O_SETS, "N", "a fixed number of motion sets per floor (ASCE 43-05: >= %g);\n"
     "default: sets are added until converged (docs/run.md, Convergence):",
     {SL_NLTHA_MIN_SETS}, .kind = CLI_COUNT1, A(sets)},
    {"rel-se", O_REL_SE, "R", "target standard error of the design value, relative (default %g),",
     {SL_ANALYSIS_REL_SE}, .kind = CLI_NONNEG, A(ao.rel_se)},
    {"abs-se", O_ABS_SE, "MM", "or absolute, mm (default %g), whichever is larger, at every mu",
     {1e3 * SL_ANALYSIS_ABS_SE_M}, .kind = CLI_NONNEG, A(abs_se_mm)},
    {"max-sets", O_MAX_SETS, "N", "stop there when not converged; the floor is flagged (default %g)",
     {SL_ANALYSIS_MAX_SETS}, .kind = CLI_COUNT1, A(max_sets)},
    {"scatter", O_SCATTER, "S", "record-to-record intensity scatter of the floor motions behind a\n"
     "spectrum, log standard deviation: 'floor' (default floor: each floor's\n"
     "from its spectrum), or S from 0 to %g for every floor (0: the sets as\n"
     "synthesized, each SRP 3.7.1-compatible; docs/run.md, Intensity scatter)",
     {SL_SCATTER_SIGMA_MAX}, .kind = CLI_CALL},
    {"seed", O_SEED, "S", "random seed (default 1); a floor's seed also depends on its\n"
     "spectra's numbers (or its 'seed ='), never on its name or the other floors",
     .kind = CLI_CALL},
    {"mu-range", O_MU_RANGE, "A:B:S", "friction grid (default " SL_MU_GRID_TEXT "); every value above 0\n"
     "and at most %g (static friction of equipment bases; docs/run.md)", {CLI_MU_MAX},
     .kind = CLI_MU_RANGE, A(mu)},
    {"mu", O_MU, "LIST", "explicit friction values, increasing, each above 0 and at most\n%g",
     {CLI_MU_MAX}, .kind = CLI_MU_LIST, A(mu)},
    {"policy", O_POLICY, "P", "required clearance: nltha (default), asce or envelope",
     .kind = CLI_CALL},
    {"accuracy", O_ACC, "E", "relative error of every NLTHA peak the 2-D engine aims at (its\n"
     "rtol, default %g, at most %g; docs/integrators.md)", {SL_SLIDE_DEFAULT_RTOL,
     SL_SLIDE_RTOL_MAX}, .kind = CLI_POSITIVE, A(ao.rtol)},
    {"substeps", O_SUB, "N", "expert: N fixed 2-D sub-steps per sample, no error control",
     .kind = CLI_COUNT1, A(substeps)},
    {"motions", O_MOTIONS, NULL, "also write every motion to DIR/motions/<floor id>/*.AT2",
     .kind = CLI_FLAG, A(dop.write_motions)},
    CLI_OPT_CREATED(O_CREATED),
    {"force", O_FORCE, NULL, "run a floor whose horizontal ZPA is outside %g-%g g (warning)",
     {SL_FLOOR_ZPA_MIN_G, SL_FLOOR_ZPA_MAX_G}, .kind = CLI_FLAG, A(force)},
    {"accept-floor", O_ACCEPT_FLOOR, "ID", "run a floor whose ZPA is out of line with its\n"
     "building's other floors (by default the run stops naming it: a units slip;\n"
     "docs/formats-floor.md); ID as in floors.csv, BUILDING/ID in a plant; once\n"
     "per floor; recorded in the outputs", .kind = CLI_CALL},
    {"accept-failed-checks", O_ACCEPT, NULL, "write the outputs although some motions failed\n"
     "their SRP 3.7.1 checks (default: the run stops, exit 1, no output\nwritten); the "
     "failures are listed on stderr, also with -q", .kind = CLI_FLAG, A(accept_failed)},
    {.head = "plant (docs/plant.md):"},
    {"shard", O_SHARD, "K/N", "compute shard K of N (a deterministic share of the floors, balanced\n"
     "by expected cost) into DIR for `seislide merge`", .kind = CLI_CALL},
    {"components", O_COMPONENTS, "FILE", "check the components listed in FILE against the floor\n"
     "tables: DIR/components.csv and components.xlsx (docs/components.md)",
     .kind = CLI_STRING, A(components)},
    {"rocking-lookup", O_ROCKING_LOOKUP, NULL, "also the rocking lookup of every floor: the\n"
     "probability that a slender item tips, over a grid of b/h and size, at the\n"
     "floor motion and 1.5 x it (DIR/rocking_lookup.csv, the Rocking sheet;\n"
     "docs/rocking.md; adds minutes)", .kind = CLI_FLAG, A(rocking_lookup)},
    {"cache", O_CACHE, "CDIR", "keep and reuse floor results in CDIR (default DIR/.seislide-cache);\n"
     "may be shared by runs at the same time", .kind = CLI_STRING, A(cache)},
    {"no-cache", O_NO_CACHE, NULL, "recompute every floor and keep no results", .kind = CLI_FLAG,
     A(no_cache)},
    {.head = "title block of the workbook (Lookup, Summary, page headers, CSV comments):"},
    {"project", O_PROJECT, "TEXT", "project", .kind = CLI_STRING, A(dop.project.project)},
    {"document", O_DOCUMENT, "TEXT", "document number", .kind = CLI_STRING,
     A(dop.project.document)},
    {"revision", O_REVISION, "TEXT", "revision", .kind = CLI_STRING, A(dop.project.revision)},
    {"prepared", O_PREPARED, "TEXT", "prepared by", .kind = CLI_STRING, A(dop.project.prepared)},
    {"checked", O_CHECKED, "TEXT", "checked by", .kind = CLI_STRING, A(dop.project.checked)},
    {"date", O_DATE, "TEXT", "date (default: the workbook date)", .kind = CLI_STRING,
     A(dop.project.date)}};

/* The options that need more than their kind. */
static int take(void *dst, int key, const char *v)
{
    run_args *a = dst;
    unsigned long ul = 0;
    if (key == O_ACCEPT_FLOOR) {
        if (a->n_accept == RUN_MAX_ACCEPT)
            return cli_usage("run", "--accept-floor given more than %d times", RUN_MAX_ACCEPT);
        a->accept_floor[a->n_accept++] = v;
        return CLI_EXIT_OK;
    }
    if (key == O_SHARD) {
        unsigned long k = 0, n = 0;
        char tail;
        if (sscanf(v, "%lu/%lu%c", &k, &n, &tail) != 2 || k < 1 || k > n || n > SL_PLANT_MAX_SHARDS)
            return cli_usage("run", "bad value '%s' for --shard: K/N with 1 <= K <= N <= %d", v,
                             SL_PLANT_MAX_SHARDS);
        a->shard_k = (unsigned)k;
        a->shard_n = (unsigned)n;
        return CLI_EXIT_OK;
    }
    if (key == O_SCATTER) { /* 'floor': (R4) per floor; else a number in [0, max] */
        double x = 0;
        if (strcmp(v, "floor") == 0)
            a->ao.scatter = SL_ANALYSIS_SCATTER_FLOOR;
        else if (cli_parse_double(v, &x) || !(x >= 0 && x <= SL_SCATTER_SIGMA_MAX))
            return cli_usage("run", "--scatter %s must be 'floor' or from 0 to %g", v,
                             SL_SCATTER_SIGMA_MAX);
        else
            a->ao.scatter = x;
        return CLI_EXIT_OK;
    }
    int p = key == O_POLICY ? sl_clearance_policy_parse(v) : 0;
    int bad = key == O_SEED ? cli_parse_ulong(v, &ul) : key == O_POLICY ? p < 0
              : cli_parse_created(v, &a->created);
    if (bad)
        return cli_usage("run", "bad value '%s' for --%s", v, key == O_SEED ? "seed"
                         : key == O_POLICY ? "policy (nltha, asce, envelope)" : "created");
    if (key == O_SEED)
        a->ao.seed = ul;
    if (key == O_POLICY)
        a->ao.policy = (sl_clearance_policy)p;
    return CLI_EXIT_OK;
}

/* The rules across options, every one checked here so that a bad value is a
 * usage error before any floor is read; the default friction grid. */
static int check(void *dst)
{
    run_args *a = dst;
    const char *r = "run";
    if (!(a->ao.rel_se < 1))
        return cli_usage(r, "--rel-se %g must be below 1", a->ao.rel_se);
    if (!(a->ao.rel_se > 0 || a->abs_se_mm > 0))
        return cli_usage(r, "--rel-se and --abs-se must not both be 0");
    if (a->max_sets < 2 || a->max_sets > RUN_MAX_SETS)
        return cli_usage(r, "--max-sets %lu must be from 2 to %d", a->max_sets, RUN_MAX_SETS);
    if (a->sets > RUN_MAX_SETS)
        return cli_usage(r, "--sets %lu must be from 1 to %d", a->sets, RUN_MAX_SETS);
    if (a->sets && (a->ao.rel_se != SL_ANALYSIS_REL_SE || a->abs_se_mm != 1e3 *
                    SL_ANALYSIS_ABS_SE_M || a->max_sets != SL_ANALYSIS_MAX_SETS))
        return cli_usage(r, "--sets fixes the number of sets; --rel-se, --abs-se and --max-sets "
                         "apply only without it");
    if (!isfinite(a->abs_se_mm))
        return cli_usage(r, "--abs-se must be a finite number of mm");
    if (a->shard_n && a->dop.write_motions)
        return cli_usage(r, "--motions cannot be combined with --shard (a shard writes results, "
                         "not outputs)");
    if (a->shard_n && a->rocking_lookup)
        return cli_usage(r, "--rocking-lookup cannot be combined with --shard (a shard writes "
                         "results, not outputs)");
    if (a->shard_n && a->components)
        return cli_usage(r, "--components applies to a whole run, not to a shard (give it to "
                         "merge's results: seislide components)");
    if (a->cache && a->no_cache)
        return cli_usage(r, "--cache and --no-cache exclude each other");
    if (!(a->ao.rtol >= SL_SLIDE_RTOL_MIN && a->ao.rtol <= SL_SLIDE_RTOL_MAX))
        return cli_usage(r, "--accuracy %g must be from %g to %g", a->ao.rtol,
                         SL_SLIDE_RTOL_MIN, SL_SLIDE_RTOL_MAX);
    if (a->substeps > RUN_MAX_SUBSTEPS)
        return cli_usage(r, "--substeps %lu must be from 1 to %d", a->substeps,
                         RUN_MAX_SUBSTEPS);
    if (a->substeps && a->ao.rtol != SL_SLIDE_DEFAULT_RTOL)
        return cli_usage(r, "--substeps replaces the error control that --accuracy sets: "
                         "give one of them");
    if (!a->mu.v && cli_parse_range(SL_MU_GRID_TEXT, &a->mu.v, &a->mu.n)) {
        cli_msg("out of memory");
        return CLI_EXIT_ERROR;
    }
    if (a->mu.n > RUN_MAX_MU)
        return cli_usage(r, "%zu friction values; at most %d", a->mu.n, RUN_MAX_MU);
    return cli_mu_check(r, &a->mu);
}

/* The options the table cannot put into the analysis options directly
 * (units, types, the friction grid), converted into them. */
static void settings(run_args *a)
{
    sl_analysis_opts *ao = &a->ao; /* rel_se, rtol, seed, policy: set by the options */
    ao->substeps = (unsigned)a->substeps; /* 0: error-controlled by rtol (docs/integrators.md) */
    ao->n_sets = a->sets; /* 0: adaptive */
    ao->abs_se_m = 1e-3 * a->abs_se_mm;
    ao->max_sets = a->max_sets;
    ao->mu = a->mu.v;
    ao->n_mu = a->mu.n;
}

int run_parse(int argc, char **argv, run_args *a)
{
    static const cli_command cmd = {"run", run_head, run_tail, opts, CLI_NOPTS(opts), 22, take,
                                    check, 1};
    *a = (run_args){.out = "output", .abs_se_mm = 1e3 * SL_ANALYSIS_ABS_SE_M,
                    .max_sets = SL_ANALYSIS_MAX_SETS,
                    .created = cli_created_default(),
                    .dop = {.version = sl_build_id()}};
    sl_analysis_opts_default(&a->ao);
    int rc = cli_command_parse(&cmd, argc, argv, a);
    if (rc == CLI_EXIT_OK)
        settings(a);
    return rc;
}
