/* slide_opts.h - the settings of `seislide slide` from its command line:
 * one option table (slide_opts.c), --help generated from it, the model
 * tolerances mapped by sl_slide_opts_set_tol(). */
#ifndef SL_CLI_SLIDE_OPTS_H
#define SL_CLI_SLIDE_OPTS_H

#include "cli.h"
#include "io/motion.h"
#include "slide/slide.h"

typedef struct slide_args {
    const char *path[3], *history;
    sl_read_opts ro;
    sl_slide_opts so;
    cli_mu mu;
    double scale_g, ratio, rtol, atol;
    int csv, truncate, one_way;
    unsigned given; /* the model options given: 1 << (key - O_SUBSTEPS) (slide_opts.c) */
} slide_args;

/* Parse the command line into a (defaults first) and check it. Returns
 * CLI_EXIT_OK, CLI_OPT_HELP after printing the help, or CLI_EXIT_USAGE
 * (message printed). a->mu.v is owned by the caller either way. */
int slide_parse(int argc, char **argv, slide_args *a);

#endif
