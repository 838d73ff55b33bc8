/* run_opts.h - the settings of `seislide run` from its command line: one
 * option table (run_opts.c), --help generated from it, the rules across
 * options. The analysis options are complete after run_parse (ao: what the
 * table cannot fill is converted there); the workbook's record is filled
 * where the table can (dop), run_deliver.h adds the rest. */
#ifndef SL_CLI_RUN_OPTS_H
#define SL_CLI_RUN_OPTS_H

#include "analysis.h"
#include "cli.h"
#include "report/deliver.h"

/* Bounds of the options (guards against typos that would exhaust memory or
 * time: the default grid has 76 friction values, runs 60-160 sets). */
#define RUN_MAX_SETS 10000      /* --sets, --max-sets */
#define RUN_MAX_MU 1000         /* friction values */
#define RUN_MAX_SUBSTEPS 1000000 /* --substeps (as `seislide slide`) */
#define RUN_MAX_ACCEPT 256       /* --accept-floor, given again for each floor */

typedef struct run_args {
    const char *out;
    int quiet, force, accept_failed; /* -q, --force, --accept-failed-checks */
    unsigned long sets, substeps, max_sets; /* for ao: n_sets, substeps, max_sets */
    double abs_se_mm, created;              /* for ao.abs_se_m (m), dop.created */
    cli_mu mu;                              /* the friction grid (default SL_MU_GRID_TEXT) */
    sl_analysis_opts ao;                    /* --rel-se, --accuracy (rtol), --seed, --policy */
    sl_deliver_opts dop;                    /* --motions, the title block */
    /* the plant (docs/plant.md): --shard K/N, --cache DIR, --no-cache */
    unsigned shard_k, shard_n;              /* 0/0: not sharded */
    const char *cache;                      /* NULL: OUT/.seislide-cache */
    int no_cache;
    const char *components;                 /* --components FILE (docs/components.md) */
    int rocking_lookup;                     /* --rocking-lookup (docs/rocking.md) */
    const char *accept_floor[RUN_MAX_ACCEPT]; /* --accept-floor ID (plant/intensity.h) */
    size_t n_accept;
} run_args;

/* Parse the command line into a (defaults first), check it and complete
 * a->ao (with a->mu.v as its friction grid); operands
 * (floor files or folders) start at optind. Returns CLI_EXIT_OK,
 * CLI_OPT_HELP after printing the help, CLI_EXIT_USAGE (message printed)
 * or CLI_EXIT_ERROR (out of memory). a->mu.v is owned by the caller either
 * way. */
int run_parse(int argc, char **argv, run_args *a);

#endif
