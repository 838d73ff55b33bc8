/* run_deliver.h - the last step of `seislide run`, once every floor has its
 * result: the outputs written into the fresh output folder (a building's
 * workbook and CSV files, a plant's buildings and index, or a shard's
 * results and manifest; with --components, the components check), the
 * default cache carried into it, and the folder swapped in (outdir.h). */
#ifndef SL_CLI_RUN_DELIVER_H
#define SL_CLI_RUN_DELIVER_H

#include "io/atomic.h"
#include "plant/plant.h"
#include "run_opts.h"

/* Deliver plant (its floors of this run computed) into *out, the fresh
 * folder of a->out; default_cache (NULL: none) is the cache folder
 * DIR/.seislide-cache, moved into the fresh folder before the swap (and
 * back by any failure of the commit, or a signal: sl_atomic_dir_take). argc, argv: the recorded command
 * line. SL_OK (*out NULL: swapped in; "run: wrote ..." said unless -q), or
 * the first error (nothing swapped in). */
sl_status run_deliver(const run_args *a, const sl_plant *plant, const char *default_cache,
                      int argc, char **argv, sl_atomic_dir **out, sl_error *err);

#endif
