/*
 * analysis.h - the per-floor study: floor response spectra in, design
 * sliding spectra out (the main job, `seislide run`, one floor at a time).
 *
 * For one floor:
 *  1. synthesize n_sets spectrum-compatible three-component motion sets
 *     from the floor's spectra (synth.h), with their quality checks;
 *  2. NLTHA of every set over the friction grid, both horizontals coupled,
 *     with the vertical (slide.h); friction values whose mu g is at or above
 *     what a set can ever demand are not integrated (exactly zero);
 *  3. the ASCE/SEI 43-05 method on the floor's 10 %-damped spectra (asce.h),
 *     or, when the file lacks them, on the mean 10 %-damped spectra of the
 *     synthesized motions (the documented fallback, stated in `note`);
 *  4. design spectra, cap, crossover and clearance (design.h).
 * The seed of a floor is seed XOR (CRC-32 of its name) << 32, so a floor's
 * results do not depend on which other floors are run with it.
 */
#ifndef SL_ANALYSIS_H
#define SL_ANALYSIS_H

#include <stddef.h>
#include <stdint.h>

#include "method/design.h"
#include "io/floor.h"
#include "core/status.h"
#include "synth/synth.h"

/* Default number of motion sets per floor (ASCE 43-05 needs at least 5). */
#define SL_ANALYSIS_DEFAULT_SETS 7

typedef struct sl_analysis_opts {
    size_t n_sets;               /* >= 1; < SL_NLTHA_MIN_SETS is flagged in the note */
    uint64_t seed;
    const double *mu;            /* friction grid, increasing */
    size_t n_mu;
    unsigned substeps;           /* 2-D sub-steps per sample: 0 = error-controlled by rtol */
    double rtol;                 /* 2-D: relative error of the peaks (SL_SLIDE_DEFAULT_RTOL) */
    sl_clearance_policy policy;
    double fs_nltha, fs_asce;
    /* progress: step is "synthesis", "nltha", "asce"; done of total */
    void (*progress)(void *ctx, const char *step, size_t done, size_t total);
    void *progress_ctx;
} sl_analysis_opts;

void sl_analysis_opts_default(sl_analysis_opts *o);

typedef struct sl_analysis {
    sl_design *design;
    double zpa_h_ms2;           /* larger horizontal ZPA of the floor */
    double av_ms2;              /* vertical ZPA (A_v of the ASCE method) */
    size_t n_sets;
    sl_synth_set *sets;         /* the synthesized motions and their checks */
    double *pgd_m;              /* 100-40 peak displacement per set */
    size_t n_failed_motions;    /* components that failed a quality check */
    size_t n_mu_skipped;        /* friction values not integrated for any set */
    int sa10_fallback;          /* 1: ASCE used the motions' mean 10 % spectra */
    double time_synth_s, time_nltha_s, time_asce_s; /* wall time of each step, s */
    char note[512];             /* what a reader must know ("" when nothing) */
} sl_analysis;

/* Run the study of one floor. Returns NULL and fills err on failure (bad
 * options, synthesis error, solver failure); quality-check failures of
 * individual motions are not errors: they are counted and kept. */
sl_analysis *sl_analysis_run(const sl_floor *fl, const sl_analysis_opts *o, sl_error *err);

void sl_analysis_free(sl_analysis *a);

/* The seed used for a floor (see above). */
uint64_t sl_analysis_floor_seed(uint64_t seed, const char *floor_name);

#endif
