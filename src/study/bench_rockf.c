/* bench_rockf.c - the rocking check on a floor, cost per item and of the
 * lookup (bench_rockf.h). */
#include "study/bench_rockf.h"

#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis.h"
#include "core/clock.h"
#include "core/units.h"
#include "io/floor.h"
#include "rock/rock_floor.h"
#include "rock/rock_lookup.h"
#include "study/bench.h"
#include "study/bench_rock.h"
#include "synth/synth.h"

/* The sets: the bench floor's, made as a run makes them, else RG 1.60's. */
static sl_status make_sets(sl_bench_rockf *b, sl_synth_set *ss, sl_error *err)
{
    sl_error fe;
    sl_floor *fl = sl_floor_load(SL_BENCH_ROCK_FLOOR, &fe);
    sl_status st;
    double t0 = sl_clock_s();
    if (fl) {
        sl_analysis_opts ao;
        sl_analysis_opts_default(&ao);
        st = sl_analysis_make_sets(fl, &ao, 0, SL_BENCH_ROCKF_SETS, ss, err);
        snprintf(b->source, sizeof b->source, "%d sets of %s (seed 1)", SL_BENCH_ROCKF_SETS,
                 SL_BENCH_ROCK_FLOOR);
    } else {
        sl_synth_params sp;
        sl_synth_params_default(&sp);
        sp.psd_report = 0;
        sl_spectrum *spec[SL_SYNTH_NCOMP] = {NULL};
        sl_synth_target tgt[SL_SYNTH_NCOMP];
        st = sl_synth_targets_rg160(SL_BENCH_SYNTH_PGA_G * SL_G, SL_SYNTH_DAMPING, &sp, spec,
                                    tgt, err);
        const size_t n = (size_t)(SL_SYNTH_DURATION_S / SL_SYNTH_DT_S + 0.5) + 1;
        sl_synth *sy = st ? NULL : sl_synth_alloc(n, SL_SYNTH_DT_S, &sp, err);
        if (sy)
            st = sl_synth_make_sets(sy, tgt, 1, 0, SL_BENCH_ROCKF_SETS, ss, NULL, NULL, err);
        st = st == SL_ENOCONV ? SL_OK : st;
        sl_synth_free(sy);
        for (int c = 0; c < SL_SYNTH_NCOMP; c++)
            sl_spectrum_free(spec[c]);
        snprintf(b->source, sizeof b->source, "%d sets for RG 1.60 at %.1f g (%s not found)",
                 SL_BENCH_ROCKF_SETS, SL_BENCH_SYNTH_PGA_G, SL_BENCH_ROCK_FLOOR);
    }
    b->synth_s_per_set = (sl_clock_s() - t0) / SL_BENCH_ROCKF_SETS;
    sl_floor_free(fl);
    return st;
}

/* items[n] over every set: wall time per set and the results. */
static sl_status timed(const sl_set *sets, const sl_rockf_item *items, size_t n,
                       sl_rockf_result *res, double *s_per_set, sl_error *err)
{
    sl_rockf_opts o;
    sl_rockf_opts_default(&o);
    o.min_sets = SL_BENCH_ROCKF_SETS;
    sl_rockf_acc *acc = sl_rockf_acc_alloc(items, n, SL_BENCH_ROCKF_SETS, &o, err);
    if (!acc)
        return err ? err->code : SL_ENOMEM;
    double t0 = sl_clock_s();
    sl_status st = sl_rockf_acc_add(acc, sets, SL_BENCH_ROCKF_SETS, err);
    *s_per_set = (sl_clock_s() - t0) / SL_BENCH_ROCKF_SETS;
    if (!st)
        st = sl_rockf_acc_result(acc, res, err);
    sl_rockf_acc_free(acc);
    return st;
}

sl_status sl_bench_rockf_run(sl_bench_rockf *b, sl_error *err)
{
    memset(b, 0, sizeof *b);
    b->threads = omp_get_max_threads();
    sl_synth_set ss[SL_BENCH_ROCKF_SETS];
    sl_set sets[SL_BENCH_ROCKF_SETS];
    memset(ss, 0, sizeof ss);
    sl_status st = make_sets(b, ss, err);
    for (int s = 0; s < SL_BENCH_ROCKF_SETS; s++)
        sets[s] = ss[s].set;
    static const struct { const char *name; double bh, h; } kinds[SL_BENCH_ROCKF_NITEM] = {
        {"cabinet", 0.278, 0.90}, {"ladder rack", 0.182, 1.10}, {"crate", 0.50, 0.50}};
    for (int k = 0; !st && k < SL_BENCH_ROCKF_NITEM; k++) {
        sl_bench_rockf_item *x = &b->item[k];
        x->name = kinds[k].name;
        x->bh = kinds[k].bh;
        x->h_m = kinds[k].h;
        sl_rockf_item it = {{kinds[k].bh * kinds[k].h, kinds[k].h, -1}, NAN};
        sl_rockf_result r;
        if ((st = timed(sets, &it, 1, &r, &x->s_per_set, err)))
            break;
        x->runs = r.n_runs;
        for (int l = 0; l < 2; l++) {
            x->p_tip[l] = r.level[l].p_tip;
            x->p_tip_se[l] = r.level[l].p_tip_se;
        }
    }
    if (!st) {
        sl_rockf_item items[SL_ROCKL_N];
        sl_rockf_result res[SL_ROCKL_N];
        sl_rockl_items(items);
        st = timed(sets, items, SL_ROCKL_N, res, &b->lookup_s_per_set, err);
        for (int i = 0; !st && i < SL_ROCKL_N; i++)
            b->lookup_runs += res[i].n_runs;
    }
    for (int s = 0; s < SL_BENCH_ROCKF_SETS; s++)
        sl_synth_set_clear(&ss[s]);
    return st;
}
