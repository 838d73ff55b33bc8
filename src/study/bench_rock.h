/*
 * bench_rock.h - the rocking engine's cost per run against its error
 * (`seislide bench`, docs/performance.md section 8; docs/integrators.md,
 * "Rocking"), as measurements.
 *
 * The motion: one set synthesized for SL_BENCH_ROCK_FLOOR (seed
 * SL_BENCH_ROCK_SEED; RG 1.60 at SL_BENCH_SYNTH_PGA_G when the floor file is
 * not found from the working folder), H1 along the weak axis. Three blocks
 * sized against the set's peak horizontal acceleration A (b/h = tan(alpha)):
 * one that never uplifts (b/h = 1.5 A/g), one that rocks without tipping
 * and one that tips (the first of a few candidates that does; the case
 * names what it did). For each: the time per run (best of `repeat` batches
 * of runs, one thread), the integrator's steps and impacts, and the
 * relative error of the peak rotation against the engine at
 * SL_BENCH_ROCK_REF_RTOL, with the case's sensitivity (the peak's change
 * under inputs scaled by 1 +- 1e-6 and 1 +- 1e-5: above 1e-4 the case is
 * chaotic and its error is not the integrator's).
 *
 * Units: SI; times in seconds unless the name says otherwise.
 */
#ifndef SL_BENCH_ROCK_H
#define SL_BENCH_ROCK_H

#include <stddef.h>

#include "core/status.h"

#define SL_BENCH_ROCK_FLOOR "floors/03-el24.ini"
#define SL_BENCH_ROCK_SEED 1u
#define SL_BENCH_ROCK_REF_RTOL 1e-10
#define SL_BENCH_ROCK_NCASE 3
#define SL_BENCH_ROCK_CHAOS 1e-4 /* peak change under the perturbed inputs */

typedef struct sl_bench_rock_case {
    char name[48];             /* "never uplifts", "rocks", "tips" (what it did) */
    double b_m, h_m;           /* half base, centre of mass */
    double s_per_run;          /* best of repeat */
    size_t steps, impacts;
    int uplifted, tipped, overturned;
    double peak_over_alpha;
    double err_rel;            /* |peak - reference| / reference (0 when both are 0) */
    double sensitivity;        /* largest relative change of the reference's peak */
} sl_bench_rock_case;

typedef struct sl_bench_rock {
    char source[192];          /* what the motion is */
    size_t n;                  /* samples */
    double dt_s, pga_ms2;
    sl_bench_rock_case c[SL_BENCH_ROCK_NCASE];
} sl_bench_rock;

/* Measure. repeat >= 1. Returns SL_OK, or an error of the synthesis or of
 * a run. */
sl_status sl_bench_rock_run(unsigned long repeat, sl_bench_rock *out, sl_error *err);

#endif
