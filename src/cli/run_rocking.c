/* run_rocking.c - the rocking lookup of every floor of a run (run_rocking.h). */
#include "run_rocking.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "core/clock.h"
#include "rock/rock_cache.h"
#include "rock/rock_lookup.h"

sl_status run_rocking_lookup(sl_plant *p, const unsigned char *mine, uint64_t seed,
                             const char *cache, int quiet, sl_error *err)
{
    sl_rockf_item items[SL_ROCKL_N];
    sl_rockl_items(items);
    sl_rockf_opts o;
    sl_rockf_opts_default(&o);
    for (size_t i = 0; i < p->n; i++) {
        sl_plant_floor *f = &p->floors[i];
        if (!mine[i] || !f->an || !f->floor)
            continue;
        sl_rockf_result *res = malloc(SL_ROCKL_N * sizeof *res);
        if (!res)
            return sl_error_set(err, SL_ENOMEM, NULL, 0, "out of memory");
        char lab[2 * SL_DELIVER_ID_MAX + 2];
        snprintf(lab, sizeof lab, "%s%s%s", p->is_plant ? p->building[f->building] : "",
                 p->is_plant ? "/" : "", f->id);
        sl_rockc_key key = {0};
        sl_status st = cache ? sl_rockc_key_make(f->floor, seed, f->an->n_sets, &o, items,
                                                 SL_ROCKL_N, &key, err)
                             : SL_OK;
        int hit = !st && cache && sl_rockc_read(cache, &key, res, SL_ROCKL_N);
        if (!st && !hit) {
            const sl_synth_set *sets =
                f->an->n_sets && f->an->sets && f->an->sets[0].set.h1 ? f->an->sets : NULL;
            double t0 = sl_clock_s();
            st = sl_rockf_floor_run(f->floor, seed, f->an->n_sets, sets, items, SL_ROCKL_N, &o,
                                    res, err);
            if (!st && !quiet)
                cli_msg("run: rocking lookup of floor '%s': %d blocks, %.1f s", lab, SL_ROCKL_N,
                        sl_clock_s() - t0);
            sl_error e;
            if (!st && cache && sl_rockc_write(cache, &key, res, SL_ROCKL_N, &e))
                cli_msg("run: warning: the rocking lookup of floor '%s' is not kept in the "
                        "cache: %s: %s", lab, e.file, e.msg);
        } else if (!st && !quiet) {
            cli_msg("run: rocking lookup of floor '%s' reused from the cache", lab);
        }
        sl_rockc_key_free(&key);
        if (st) {
            free(res);
            return st;
        }
        free(f->an->rock_lookup);
        f->an->rock_lookup = res;
    }
    return SL_OK;
}
