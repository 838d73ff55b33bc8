/* synth_opts.h - the options of `seislide synth`: one cli_opt table of the
 * command's settings, parsed by cli_parse() and printed by --help; the limit
 * and method options come from a table over sl_synth_params, turned into
 * entries of that table (help with the default of sl_synth_params_default)
 * and parsed with their ranges. */
#ifndef SL_CLI_SYNTH_OPTS_H
#define SL_CLI_SYNTH_OPTS_H

#include <stddef.h>

#include "cli.h"
#include "core/units.h"
#include "io/motion.h"
#include "synth/synth.h"

/* Most records --match takes (H1, H2, V). */
#define SYNTH_MAX_RECORDS SL_SYNTH_NCOMP
/* Most sets per run (a guard against typos). */
#define SYNTH_MAX_COUNT 1000
/* Longest accepted motion, s (a guard against typos). */
#define SYNTH_MAX_DURATION_S 3600.0
/* Fewest samples of a synthetic motion (the synthesis needs 16). */
#define SYNTH_MIN_SAMPLES 16
/* Relative slack when a duration must be a whole number of steps. */
#define SYNTH_STEP_SLACK 1e-9

/* The settings of one `synth` run. */
typedef struct synth_run {
    sl_synth_params p;
    const char *floor_path, *outdir;
    const char *match[SYNTH_MAX_RECORDS];
    size_t nmatch;
    double rg_pga_g, damping, duration_s, dt_s;
    unsigned long count;
    unsigned long long seed;
    int have_count, have_seed, have_duration, csv, quiet;
    sl_unit units;
} synth_run;

/* Parse the command line into o (defaults first). Returns CLI_EXIT_OK, an
 * exit code to return (usage error printed), or -1 after printing --help. */
int synth_parse(int argc, char **argv, synth_run *o);

#define SYNTH_OPT_PARAM0 (CLI_OPT_ID + 64) /* key of the first parameter option */
#define SYNTH_NPARAM 25                    /* number of parameter options */

/* Write the SYNTH_NPARAM option entries (kind CLI_CALL) to t; returns how many. */
size_t synth_param_opts(cli_opt *t);
/* Parse parameter option `key` into p. Returns CLI_EXIT_OK or (message
 * printed) CLI_EXIT_USAGE; 1 when key is not a parameter option. */
int synth_param_set(sl_synth_params *p, int key, const char *arg);

/* Read the --match records of o into rec (the caller frees), resampled to
 * a common step *dt_out (--dt, else from the first record). Returns
 * CLI_EXIT_OK or CLI_EXIT_ERROR (message printed). */
int synth_read_records(const synth_run *o, sl_motion *rec[SL_SYNTH_NCOMP], double *dt_out);

#endif
