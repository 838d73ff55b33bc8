/* components_out.h - the components check (report/components.h) from the
 * command line: `seislide components` and `seislide run --components`. */
#ifndef SL_CLI_COMPONENTS_OUT_H
#define SL_CLI_COMPONENTS_OUT_H

#include <time.h>

#include "core/status.h"
#include "plant/plant.h"
#include "report/components.h"

/* Read the run's results in `results` (named `shown` in the outputs), check
 * the components file `file` against them, rocking included
 * (components_rock), and write components.csv and components.xlsx into `dir`
 * (which exists); then print "N components: a ok, b marginal, ..." on
 * stderr. plant: the run's own floors (run --components), or NULL (the
 * floors read again from their files); cache: the folder rocking results
 * are kept in (NULL: none). SL_OK, or an error (nothing written): a list
 * with more than one problem has each printed here, and err says how many
 * rows were refused. */
sl_status components_write(const char *results, const char *shown, const char *file,
                           const char *dir, const char *cmdline, time_t created,
                           const sl_plant *plant, const char *cache, int quiet,
                           sl_error *err);

/* The rocking check of every row of t whose mode is rocking or both, per
 * floor: its items over the floor's motion sets (rock/rock_floor.h), taken
 * from the cache folder when it holds them, else computed and kept there;
 * each row given its result (sl_comp_set_rocking). The floor and its sets:
 * plant's (its floor, and its sets while they hold their motions), else the
 * floor file the results name, read again (its CRC-32 must be the run's)
 * and its sets made again (analysis.h, sl_analysis_make_sets). Prints a
 * line per floor unless quiet. */
sl_status components_rock(const sl_comp_results *r, sl_comp_table *t, const sl_plant *plant,
                          const char *cache, int quiet, sl_error *err);

#endif
