/* rock_run.c - the rocking check of a floor's items over its sets, the
 * sets given or made again (rock_floor.h, sl_rockf_floor_run). */
#include <stdlib.h>

#include "analysis.h"
#include "io/floor.h"
#include "rock/rock_floor.h"
#include "synth/synth.h"

sl_status sl_rockf_floor_run(const sl_floor *fl, uint64_t run_seed, size_t n_sets,
                             const sl_synth_set *sets, const sl_rockf_item *items,
                             size_t n_items, const sl_rockf_opts *o, sl_rockf_result *out,
                             sl_error *err)
{
    sl_rockf_acc *acc = sl_rockf_acc_alloc(items, n_items, n_sets, o, err);
    if (!acc)
        return err ? err->code : SL_EINVAL;
    const size_t chunk = o->min_sets > SL_ROCKF_CHUNK ? o->min_sets : SL_ROCKF_CHUNK;
    sl_set *view = calloc(chunk, sizeof *view);
    sl_synth_set *made = sets ? NULL : calloc(chunk, sizeof *made);
    sl_status st = view && (sets || made) ? SL_OK
                                          : sl_error_set(err, SL_ENOMEM, NULL, 0,
                                                         "rocking: out of memory");
    sl_analysis_opts ao;
    sl_analysis_opts_default(&ao);
    ao.seed = run_seed; /* the only option the motions depend on (analysis.h, "Seed") */
    for (size_t first = 0, count; !st && first < n_sets; first += count) {
        /* the first batch: min_sets; then SL_ROCKF_CHUNK, while items are undecided */
        count = first ? SL_ROCKF_CHUNK : (o->min_sets ? o->min_sets : SL_ROCKF_CHUNK);
        count = n_sets - first < count ? n_sets - first : count;
        const sl_synth_set *from = sets ? sets + first : made;
        if (!sets && (st = sl_analysis_make_sets(fl, &ao, first, count, made, err)))
            break;
        for (size_t k = 0; k < count; k++)
            view[k] = from[k].set;
        st = sl_rockf_acc_add(acc, view, count, err);
        for (size_t k = 0; made && k < count; k++)
            sl_synth_set_clear(&made[k]);
        if (!st && sl_rockf_acc_update(acc) == 0)
            break;
    }
    if (!st)
        st = sl_rockf_acc_result(acc, out, err);
    free(made);
    free(view);
    sl_rockf_acc_free(acc);
    return st;
}
