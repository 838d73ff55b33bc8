/* run_floors.h - the floors of one `seislide run`, each taken from the cache
 * (plant/cache.h) or computed (analysis.h) while holding its lock in the
 * cache; a floor another run is computing is left for later and then waited
 * for. Progress and messages on stderr go through plant_progress.h. */
#ifndef SL_CLI_RUN_FLOORS_H
#define SL_CLI_RUN_FLOORS_H

#include <stddef.h>

#include "analysis.h"
#include "plant/plant.h"
#include "plant_progress.h"

typedef struct runner {
    const sl_plant *p;
    sl_analysis_opts *ao;
    const char *cache;      /* NULL: no cache */
    int cache_ready, read_cache;
    const char *out;        /* the final output folder (made when the default cache needs it) */
    plant_progress pp;
    size_t n_mu;
} runner;

/* Open the cache once (first making r->out, when set): SL_OK, or why not. */
sl_status run_cache_ready(runner *r, sl_error *err);
/* Every floor i with mine[i] and no result yet: its result (floors[i].an)
 * from the cache, else computed and stored in the cache. SL_OK, or the
 * first error. */
sl_status run_floors(runner *r, const unsigned char *mine, sl_error *err);

#endif
