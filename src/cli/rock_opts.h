/* rock_opts.h - the settings of `seislide rock` from its command line: one
 * option table (rock_opts.c) with the motion options of `slide`, --help
 * generated from it. */
#ifndef SL_CLI_ROCK_OPTS_H
#define SL_CLI_ROCK_OPTS_H

#include "cli.h"
#include "io/motion.h"
#include "rock/rock.h"

/* The orientations of the weak axis without --orientation: 0, 15, ..., 165
 * degrees from H1 (180 repeats 0: the block is symmetric). */
#define ROCK_N_ORIENT 12
#define ROCK_ORIENT_STEP_DEG 15.0

typedef struct rock_args {
    const char *path[3], *history;
    sl_read_opts ro;
    sl_rock_opts o;
    double base_m, cg_m, restitution, orientation_deg, scale_g, rtol;
    int csv, truncate, has_orientation, has_restitution;
} rock_args;

/* Parse the command line into a (defaults first) and check it. Returns
 * CLI_EXIT_OK, CLI_OPT_HELP after printing the help, or CLI_EXIT_USAGE
 * (message printed). */
int rock_parse(int argc, char **argv, rock_args *a);

#endif
