/*
 * bench_rockf.h - the rocking check on a floor: its cost per item and the
 * cost of a floor's rocking lookup, against their statistical error
 * (`seislide bench`, docs/performance.md section 9; docs/rocking.md).
 *
 * The floor: SL_BENCH_ROCK_FLOOR (RG 1.60 at SL_BENCH_SYNTH_PGA_G when the
 * file is not found from the working folder), SL_BENCH_ROCKF_SETS sets made
 * as a run makes them (seed 1). Three items of the example list's kinds (a
 * cabinet, a ladder rack, a squat crate that rocks) and the lookup's grid
 * (rock/rock_lookup.h), each over every set (no stopping rule: the cost of
 * a set), with the default rocking options, on every thread; per item the
 * wall time and CPU time per set, the block runs integrated (after the
 * uplift screen) and p_tip with its standard error at 1.0 and 1.5 x.
 */
#ifndef SL_BENCH_ROCKF_H
#define SL_BENCH_ROCKF_H

#include <stddef.h>

#include "core/status.h"

#define SL_BENCH_ROCKF_SETS 16
#define SL_BENCH_ROCKF_NITEM 3

typedef struct sl_bench_rockf_item {
    const char *name;
    double bh, h_m;
    double s_per_set;          /* wall time per set, s */
    size_t runs;               /* block runs over every set */
    double p_tip[2], p_tip_se[2];
} sl_bench_rockf_item;

typedef struct sl_bench_rockf {
    char source[192];
    int threads;
    double synth_s_per_set;    /* wall time to make a set again, s */
    sl_bench_rockf_item item[SL_BENCH_ROCKF_NITEM];
    double lookup_s_per_set;   /* the 40 blocks of the lookup, wall time per set */
    size_t lookup_runs;
} sl_bench_rockf;

sl_status sl_bench_rockf_run(sl_bench_rockf *out, sl_error *err);

#endif
