/* synth_opts.h - the limit and method options of `seislide synth`: one
 * table over sl_synth_params, turned into entries of the command's cli_opt
 * table (help text with the default from sl_synth_params_default) and
 * parsed with their ranges. */
#ifndef SL_CLI_SYNTH_OPTS_H
#define SL_CLI_SYNTH_OPTS_H

#include <stddef.h>

#include "cli.h"
#include "synth/synth.h"

#define SYNTH_OPT_PARAM0 (CLI_OPT_ID + 64) /* key of the first parameter option */
#define SYNTH_NPARAM 22                    /* number of parameter options */

/* Write the SYNTH_NPARAM option entries (kind CLI_CALL) to t; returns how many. */
size_t synth_param_opts(cli_opt *t);
/* Parse parameter option `key` into p. Returns CLI_EXIT_OK or (message
 * printed) CLI_EXIT_USAGE; 1 when key is not a parameter option. */
int synth_param_set(sl_synth_params *p, int key, const char *arg);

#endif
