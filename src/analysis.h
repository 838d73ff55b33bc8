/*
 * analysis.h - the per-floor study: floor response spectra in, design
 * sliding spectra out (the main job, `seislide run`, one floor at a time).
 *
 * For one floor:
 *  1. synthesize spectrum-compatible three-component motion sets from the
 *     floor's spectra (synth.h), with their quality checks;
 *  2. NLTHA of every set over the friction grid, both horizontals coupled,
 *     with the vertical (slide.h); friction values whose mu g is at or above
 *     what a set can ever demand are not integrated (exactly zero); with
 *     an intensity scatter (opts.scatter; by default derived from the
 *     floor's spectrum, method/scatter.h (R4)) a set's peak at mu is its
 *     expected peak over a log-normal intensity factor of its horizontals
 *     (method/scatter.h (R3)), from one NLTHA on a log friction grid;
 *     steps 1-2 run in batches of sets until the NLTHA design value is
 *     converged at every mu (below), or a fixed number of sets when
 *     opts.n_sets > 0;
 *  3. the ASCE/SEI 43-05 method on the floor's 10 %-damped spectra (asce.h),
 *     or, when the file lacks them, on the mean 10 %-damped spectra of the
 *     synthesized motions (the documented fallback, stated in `note`);
 *     every damping of the file other than the one matched (its 10 % table
 *     among them) is checked against the motions' own spectra, the set mean
 *     over all the floor's sets (dampings[]; reported, not a pass condition);
 *  4. design spectra, cap, crossover and clearance (design.h).
 *
 * Convergence (docs/run.md, "Convergence"). The NLTHA design value at mu is
 * D = min(FS m, cap) with m the sample mean of the sets' peaks (stats.h)
 * and cap = 1.5 x the mean 100-40 floor displacement. Its standard error is
 * FS SE(m) (uncapped) or 1.5 SE(mean PGD) (capped), SE(m) = s / sqrt(n) the
 * sample standard error (stats.h; the log-normal fit is reported only). After each
 * batch: stop when SE(D) <= max(rel_se D, abs_se_m) at every mu
 * (SL_ANALYSIS_STOP_CONVERGED), else when max_sets are done
 * (SL_ANALYSIS_STOP_MAX_SETS, the floor is flagged). The next batch aims at the
 * count the worst mu needs with a margin, n (SE / target)^2 margin^2, at
 * least min_batch more sets and at most growth x n (stats.h (4)). Set i is always the same motions (synth seeds per
 * set index) and the statistics are sums in set order, so the result does
 * not depend on batch sizes or threads. The 90 % band of D is a
 * bootstrap-t band over sets (stats.h (3); peaks and PGD resampled
 * together).
 *
 * Seed. A floor's seed is splitmix64(base) XOR the run's seed, where base
 * is the floor file's `seed =` when given, else a 64-bit FNV-1a hash of the
 * floor's numbers (per component: every damping, frequency and value in
 * m/s^2, and the ZPA). It is made by the same walk over the floor as its
 * cache key (plant/identity.h). A floor's motions therefore change neither
 * with its name nor with the other floors of the run.
 */
#ifndef SL_ANALYSIS_H
#define SL_ANALYSIS_H

#include <stddef.h>
#include <stdint.h>

#include "core/api.h"
#include "method/design.h"
#include "io/floor.h"
#include "core/status.h"
#include "synth/synth.h"
#include "method/stats.h"

/* Convergence defaults (docs/run.md): target standard error of the design
 * value, relative and absolute (m); most sets per floor; the first batch
 * (enough for a first estimate of the scatter; ASCE 43-05 needs >= 5) and
 * the smallest further batch. */
#define SL_ANALYSIS_REL_SE 0.05
#define SL_ANALYSIS_ABS_SE_M 0.001
#define SL_ANALYSIS_MAX_SETS 200
#define SL_ANALYSIS_FIRST_BATCH 10
#define SL_ANALYSIS_MIN_BATCH 4
/* The next batch aims at a SE of target / margin, and at most growth x the
 * sets so far (stats.h (4); docs/run.md, "Stopping rule"). */
#define SL_ANALYSIS_PLAN_MARGIN 1.1
#define SL_ANALYSIS_PLAN_GROWTH 2.0
/* Record-to-record intensity scatter of the floor motions behind a floor
 * spectrum: log standard deviation of the sets' horizontal intensity,
 * averaged exactly over each set (method/scatter.h (R1)-(R3); docs/run.md,
 * "Intensity scatter"). The default, SL_ANALYSIS_SCATTER_FLOOR (any value
 * < 0), derives it from each floor's spectrum (method/scatter.h (R4):
 * sl_scatter_sigma_of_floor; 0.35-0.46 on the buildings of
 * docs/synthesis.md 11); a value >= 0 is that sigma for
 * every floor (0: the sets as synthesized). */
#define SL_ANALYSIS_SCATTER_FLOOR (-1.0)
#define SL_ANALYSIS_SCATTER SL_ANALYSIS_SCATTER_FLOOR

/* Why a floor stopped adding sets. */
typedef enum sl_analysis_stop {
    SL_ANALYSIS_STOP_FIXED = 0,   /* a fixed count was asked for (opts.n_sets > 0) */
    SL_ANALYSIS_STOP_CONVERGED,   /* the target SE was reached at every mu */
    SL_ANALYSIS_STOP_MAX_SETS     /* max_sets reached before that: flagged */
} sl_analysis_stop;

/* "fixed", "converged", "max_sets". */
SL_API const char *sl_analysis_stop_name(sl_analysis_stop s);

typedef struct sl_analysis_opts {
    size_t n_sets;               /* > 0: exactly this many sets (< SL_NLTHA_MIN_SETS is
                                    flagged in the note); 0 (default): adaptive */
    double rel_se;               /* adaptive: target SE / design value (SL_ANALYSIS_REL_SE) */
    double abs_se_m;             /* adaptive: target SE floor, m (SL_ANALYSIS_ABS_SE_M) */
    size_t max_sets;             /* adaptive: at most this many (SL_ANALYSIS_MAX_SETS) */
    size_t first_batch;          /* adaptive: sets of the first batch (SL_ANALYSIS_FIRST_BATCH) */
    size_t min_batch;            /* adaptive: smallest further batch (SL_ANALYSIS_MIN_BATCH) */
    double plan_margin;          /* adaptive: next batch aims at SE = target / margin
                                    (SL_ANALYSIS_PLAN_MARGIN, >= 1) */
    double plan_growth;          /* adaptive: next count at most growth x n
                                    (SL_ANALYSIS_PLAN_GROWTH, > 1) */
    size_t boot_resamples;       /* bootstrap resamples of the band (SL_STATS_BOOT_RESAMPLES) */
    double band_level;           /* level of the band (SL_STATS_BAND_LEVEL) */
    sl_stats_band_method band_method; /* bootstrap-t (default) or percentile (stats.h) */
    uint64_t seed;
    const double *mu;            /* friction grid, increasing */
    size_t n_mu;
    unsigned substeps;           /* 2-D sub-steps per sample: 0 = error-controlled by rtol */
    double rtol;                 /* 2-D: relative error of the peaks (SL_SLIDE_DEFAULT_RTOL) */
    double scatter;              /* intensity scatter sigma_ln of the sets: < 0 (the default,
                                    SL_ANALYSIS_SCATTER_FLOOR): derived from the floor's
                                    spectrum (sl_scatter_sigma_of_floor); >= 0: that value
                                    for every floor (0: the sets as synthesized) */
    sl_clearance_policy policy;
    double fs_nltha, fs_asce;
    /* progress: step is "synthesis", "nltha", "asce"; done of total */
    void (*progress)(void *ctx, const char *step, size_t done, size_t total);
    void *progress_ctx;
} sl_analysis_opts;

SL_API void sl_analysis_opts_default(sl_analysis_opts *o);

/* The statistics of the NLTHA design value at one mu: stats.h. */
typedef sl_stats_conv sl_analysis_conv;

/* One other damping of a floor file checked on the motions' own spectra
 * (sl_synth_check_dampings on all the floor's sets; docs/run.md, "Every
 * damping of a floor file"): the mean over the sets of S/T, S the motions'
 * spectrum at that damping, T the file's table, on the synthesis check grid
 * inside the table's range. Reported, not a pass condition. */
typedef struct sl_analysis_damping {
    sl_synth_comp comp;          /* H1, H2 or V */
    double damping;              /* the table's damping ratio */
    double set_min, set_max;     /* lowest and highest set-mean S/T over the grid */
    double f_min_hz, f_max_hz;   /* where */
    int ok;                      /* within [lim_lo, lim_hi] */
} sl_analysis_damping;
#define SL_ANALYSIS_MAX_DAMPINGS (SL_SYNTH_NCOMP * SL_SYNTH_MAX_OTHER)

typedef struct sl_analysis {
    sl_design *design;
    sl_analysis_conv *conv;     /* one per mu, as design->rows */
    double *design_lo_m, *design_hi_m; /* the band of conv[], as plain arrays (report.h) */
    double *design_se_m;        /* conv[].design_se_m as a plain array (report.h): the SE of
                                   the design value actually used, the cap's where it governs */
    double *err_est_m;          /* per mu: the largest estimated integration error of any
                                   set's peak (sl_slide_result.err_est_m), m */
    /* Variance reduction (docs/run.md, "Variance reduction"): per mu, how much of
     * the sets' scatter a control variate could remove, measured on the run's
     * own sets; not applied to the design value (no candidate has a known
     * mean). NAN where undefined (fewer than 3 sets, no f_es, or a constant). */
    double *vr_f_hz;            /* the ASCE f_es of that mu (asce.h step 4), Hz */
    double *vr_corr_sa;         /* Pearson correlation over sets of the peak with the
                                   set's own 10 %-damped horizontal spectral value at
                                   vr_f_hz (geometric mean of H1 and H2) */
    double *vr_corr_pgv;        /* the same with the set's PGV (H1 + H2) */
    double *vr_factor;          /* 1 - max(vr_corr_sa^2, vr_corr_pgv^2): the fraction of
                                   the sets a control variate on either would still need,
                                   were its mean known exactly */
    sl_analysis_stop stop;      /* why the floor stopped adding sets */
    size_t n_batches;           /* batches run */
    size_t n_unconverged;       /* mu where design_se_m > target_se_m */
    double worst_rel_se;        /* max over mu of design_se_m / max(design_m, abs_se_m / rel_se) */
    uint64_t floor_seed;        /* the seed the motions came from */
    double zpa_h_ms2;           /* larger horizontal ZPA of the floor */
    double av_ms2;              /* vertical ZPA (A_v of the ASCE method) */
    double scatter;             /* the intensity scatter sigma_ln used: opts.scatter, or
                                   the floor's (R4) when opts.scatter < 0 */
    size_t n_nltha_mu;          /* friction values each set was integrated at */
    size_t n_sets;
    sl_synth_set *sets;         /* the synthesized motions and their checks */
    double *pgd_m;              /* 100-40 peak displacement per set */
    size_t n_failed_motions;    /* components that failed a quality check */
    size_t n_mu_skipped;        /* friction values not integrated for any set */
    int sa10_fallback;          /* 1: ASCE used the motions' mean 10 % spectra */
    /* Times of the steps, s, as thread time: the time threads spend in the
     * step, summed over threads (on 1 thread, its wall time). A batch's
     * synthesis and NLTHA run as one flow of tasks and overlap: the NLTHA
     * is its tasks' time, the synthesis the rest of the flow's wall time x
     * threads (with the time threads wait at the flow's end); the steps
     * run by one thread (statistics, ASCE, design) are their wall time. */
    double time_synth_s, time_nltha_s, time_asce_s; /* thread time of each step, s */
    double time_stats_s;        /* time of the convergence statistics, the band and the
                                   variance-reduction diagnostic, s (each step timed once:
                                   time_asce_s is the ASCE method and the design only) */
    double time_checks_s;       /* the other dampings' checks: their wall time x threads, s
                                 * (part of time_synth_s, which also holds the checks made
                                 * while synthesizing) */
    size_t n_extra_attempts;    /* synthesis attempts beyond the first, summed over every
                                 * component of every set (sl_synth_check.attempt) */
    char note[512];             /* what a reader must know ("" when nothing) */
    /* every damping of the floor file other than the one matched, per
     * component in file order (n_dampings = 0: the file gives one) */
    size_t n_dampings;
    sl_analysis_damping dampings[SL_ANALYSIS_MAX_DAMPINGS];
    double damping_lim_lo, damping_lim_hi; /* the limits of the set mean (0.9, 1.3) */
    int dampings_ok;            /* 1: every one within the limits (or none) */
    /* The floor's rocking lookup (rock/rock_lookup.h: SL_ROCKL_N results), when the
     * caller computed it (`run --rocking-lookup`); NULL otherwise. Not part of a
     * cache entry (it has its own, rock/rock_cache.h); freed with the analysis. */
    struct sl_rockf_result *rock_lookup;
} sl_analysis;

/* Run the study of one floor. Returns NULL and fills err on failure (bad
 * options, synthesis error, solver failure); quality-check failures of
 * individual motions are not errors: they are counted and kept. Not
 * converging within max_sets is not an error either: stop says so. */
SL_API sl_analysis *sl_analysis_run(const sl_floor *fl, const sl_analysis_opts *o, sl_error *err);

SL_API void sl_analysis_free(sl_analysis *a);

/* Sets first .. first + count - 1 of floor fl under options o, synthesized
 * again: the same bits as the sets sl_analysis_run made (the same plan,
 * targets and floor seed; a set's motions depend only on its index), so a
 * result read from the cache, which keeps no motions, can be given its
 * motions back (the rocking check, rock/rock_floor.h). out[count] filled
 * (free each with sl_synth_set_clear); a motion that fails its checks is
 * kept, as the run keeps it. SL_OK, or SL_EINVAL, SL_ENOMEM, SL_ESOLVER
 * (out cleared). */
SL_API sl_status sl_analysis_make_sets(const sl_floor *fl, const sl_analysis_opts *o,
                                       size_t first, size_t count, sl_synth_set *out,
                                       sl_error *err);

/* The other-damping check of a as text into buf (size n): "none" when the
 * file gives one damping, else "H1 10 %: 0.931-1.118 ok; H1 2 %: ... OUTSIDE;
 * ..." (set-mean S/T lowest-highest, verdict). Returns buf. */
SL_API const char *sl_analysis_dampings_text(const sl_analysis *a, char *buf, size_t n);

/* The seed used for a floor (see "Seed" above). */
SL_API uint64_t sl_analysis_floor_seed(uint64_t seed, const sl_floor *fl);

#endif
