/* components_out.h - the components check (report/components.h) from the
 * command line: `seislide components` and `seislide run --components`. */
#ifndef SL_CLI_COMPONENTS_OUT_H
#define SL_CLI_COMPONENTS_OUT_H

#include <time.h>

#include "core/status.h"

/* Read the run's results in `results` (named `shown` in the outputs), check
 * the components file `file` against them and write components.csv and
 * components.xlsx into `dir` (which exists); then print "N components: a ok,
 * b marginal, c short, d rocking, e outside" on stderr. SL_OK, or an error
 * (nothing written): a list with more than one problem has each printed
 * here, and err says how many rows were refused. */
sl_status components_write(const char *results, const char *shown, const char *file,
                           const char *dir, const char *cmdline, time_t created, sl_error *err);

#endif
