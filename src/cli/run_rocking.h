/* run_rocking.h - the rocking lookup of every floor of a run (`seislide run
 * --rocking-lookup`; rock/rock_lookup.h, docs/rocking.md). */
#ifndef SL_CLI_RUN_ROCKING_H
#define SL_CLI_RUN_ROCKING_H

#include "core/status.h"
#include "plant/plant.h"

/* For every floor i of p with mine[i]: the rocking lookup over its sets (its
 * analysis' sets when they hold their motions, else made again), from the
 * cache folder when it holds it, else computed and kept there (cache NULL:
 * none); attached to the floor's analysis (an->rock_lookup). A line per
 * floor on stderr unless quiet. */
sl_status run_rocking_lookup(sl_plant *p, const unsigned char *mine, uint64_t seed,
                             const char *cache, int quiet, sl_error *err);

#endif
