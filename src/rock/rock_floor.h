/*
 * rock_floor.h - rocking and overturning of slender items on one floor, by
 * NLTHA of the rocking block (rock.h) on the floor's own synthesized motion
 * sets, with the record-to-record intensity scatter the sliding uses
 * (method/scatter.h); docs/model.md, "Rocking", and docs/components.md.
 *
 * Per item and per level L (the floor motion, L = 1, and 1.5 x it, the two
 * levels of ASCE/SEI 43-05's target performance, section 1.3), over the
 * floor's sets s = 1..n:
 *
 *  - intensity: the horizontals of set s are scaled by L eps_j, the vertical
 *    by L, with eps_j = exp(sigma z_j - sigma^2/2) (scatter.h (R1): median
 *    below 1, mean 1) on the fixed grid z_j = SL_ROCKF_ZMIN, ... ,
 *    SL_ROCKF_ZMAX in steps SL_ROCKF_DZ, weights w_j proportional to
 *    phi(z_j) and summing to 1 (a trapezoid rule of the normal density; the
 *    mass beyond the ends is given to the end points);                (F1)
 *  - orientation: the weak axis at phi_k from H1 (a_h = cos phi h1 +
 *    sin phi h2), every SL_ROCKF_ORIENT_STEP_DEG over [0, 180) unless the
 *    item gives one; the worst orientation governs each (set, eps_j):
 *    peak theta/alpha and excursion are the largest over phi_k, and the
 *    (set, eps_j) uplifts / tips / overturns when some phi_k does;     (F2)
 *  - per set: P_s(tip) = sum_j w_j tip(s, j), likewise uplift and
 *    overturn; these are independent and identically distributed over
 *    sets, so
 *        p = (1/n) sum_s P_s,   SE(p) = sd_s(P_s) / sqrt(n)           (F3)
 *    (sd the sample standard deviation; 0 when every set agrees);
 *  - the peak theta/alpha and the excursion of realisation (s, j) carry
 *    weight w_j / n: their mean, and quantiles of that weighted sample
 *    (the smallest value x with cumulative weight >= q);              (F4)
 *  - the design excursion is the one exceeded with the target
 *    probabilities: the larger of the (1 - p_target[0]) quantile at L = 1
 *    and the (1 - p_target[1]) quantile at L = 1.5.                   (F5)
 *
 * Sets per item (the stopping rule of rocking, F6). An item takes the
 * floor's sets in order, a batch at a time, until its verdict on tipping is
 * decided: some level's p_tip above its target by more than
 * SL_ROCKF_SE_DECIDE standard errors (it overturns), or every level's below
 * it by more than that (it stands), a level where every set tips at every
 * intensity, or at none (p_tip 1 or 0), counting as decided; at least
 * min_sets sets, at most the floor's. An item near its limit so gets every
 * set the floor has; one far from it, the first batch only. Each item's
 * statistics are over its own sets (a prefix of the floor's).
 *
 * A realisation that cannot uplift is not integrated: uplift needs
 * L eps |a_h(t)| > (g + L a_v(t)) tan(alpha) at some t (rock.h (K3)), i.e.
 * eps > tan(alpha) c(phi, L) with c = min_t (g + L a_v) / (L |a_h|), a
 * minimum taken at the samples (a ratio of linear functions is monotone
 * between them); c is computed once per set, orientation and level for all
 * items.
 *
 * The result does not depend on the thread count: each set's values are
 * computed alone and reduced in set order.
 *
 * Units: SI inside (m, rad); probabilities as fractions.
 */
#ifndef SL_ROCK_FLOOR_H
#define SL_ROCK_FLOOR_H

#include <stddef.h>
#include <stdint.h>

#include "core/api.h"
#include "core/motion_type.h"
#include "core/status.h"
#include "rock/rock.h"

/* The intensity grid (F1), the orientations (F2), the levels and the target
 * probabilities of unacceptable performance at them (ASCE/SEI 43-05, 1.3:
 * about 1 % at the design basis earthquake, about 10 % at 1.5 x it). */
#define SL_ROCKF_ZMIN (-2.5)
#define SL_ROCKF_ZMAX 3.0
#define SL_ROCKF_DZ 0.5
#define SL_ROCKF_ORIENT_STEP_DEG 15.0
#define SL_ROCKF_NLEVELS 2
#define SL_ROCKF_LEVEL_1 1.0
#define SL_ROCKF_LEVEL_2 1.5
#define SL_ROCKF_P_TARGET_1 0.01
#define SL_ROCKF_P_TARGET_2 0.10
/* The intensity scatter of rocking (F1): sigma_ln of the horizontals'
 * factor. Tipping depends on the floor motion's intensity at high
 * frequencies (uplift: PGA, whose scatter over physical floor motions is
 * 0.2-0.4) and at low ones (the long pulse that carries the block over: SA
 * below 2 Hz, 0.5-0.8 for records scaled to one PGA); 0.50 makes p_tip of
 * synthesized sets agree with the fraction of physical floor motions that
 * tip on three buildings (5 %, stiff 3 %, soft 2 %) and on three held out
 * (docs/rocking.md, "Against physical floor motions"; `make rockfloors`). */
#define SL_ROCKF_SCATTER 0.50
/* The stopping rule (F6): fewest sets per item, and the distance from the
 * target, in standard errors, that decides. */
#define SL_ROCKF_MIN_SETS 16
#define SL_ROCKF_SE_DECIDE 2.0
/* The quantile of theta/alpha reported beside its mean. */
#define SL_ROCKF_THETA_Q 0.84

/* One item: its block and, optionally, its orientation. */
typedef struct sl_rockf_item {
    sl_rock_block block;     /* b = base / 2, h = centre of mass height, r (rock.h) */
    double orientation_deg;  /* weak axis from H1, degrees; NAN: the worst of every
                                SL_ROCKF_ORIENT_STEP_DEG (F2) */
} sl_rockf_item;

typedef struct sl_rockf_opts {
    double sigma_ln;         /* intensity scatter (scatter.h); 0: each set as synthesized */
    double level[SL_ROCKF_NLEVELS];    /* SL_ROCKF_LEVEL_1, _2 */
    double p_target[SL_ROCKF_NLEVELS]; /* SL_ROCKF_P_TARGET_1, _2 */
    double zmin, zmax, dz;   /* the grid of (F1) */
    double orient_step_deg;  /* (F2) */
    size_t min_sets;         /* (F6) SL_ROCKF_MIN_SETS */
    int no_screen;           /* 1: integrate every realisation, the uplift screen off
                                (the same results, slower: a check of the screen) */
    sl_rock_opts engine;     /* rock.h */
} sl_rockf_opts;

SL_API void sl_rockf_opts_default(sl_rockf_opts *o);

/* The statistics at one level. */
typedef struct sl_rockf_level {
    double p_uplift, p_uplift_se;     /* (F3) */
    double p_tip, p_tip_se;
    double p_overturn, p_overturn_se;
    double theta_ratio_mean;          /* (F4): peak theta / alpha */
    double theta_ratio_q;             /* its SL_ROCKF_THETA_Q quantile */
    double excursion_mean_m;          /* (F4) */
    double excursion_q_m;             /* the (1 - p_target) quantile (F5) */
} sl_rockf_level;

/* Verdict of a rocking item against its targets (sl_rockf_verdict_of), in
 * this order:
 *   overturns  p_tip above its target at some level (the point estimate)
 *   short      the design excursion (F5) exceeds the available clearance
 *   marginal   p_tip at or below its target at every level, but not
 *              decided at some level by the rule of (F6) (within
 *              SL_ROCKF_SE_DECIDE standard errors of its target, or an SE of
 *              0 at a p_tip between 0 and 1): the floor's sets ran out
 *              first
 *   stands     p_tip below its target by more than that at every level (or
 *              every set agrees), and the excursion fits */
typedef enum sl_rockf_verdict {
    SL_ROCKF_STANDS = 0,
    SL_ROCKF_MARGINAL,
    SL_ROCKF_SHORT,
    SL_ROCKF_OVERTURNS
} sl_rockf_verdict;

typedef struct sl_rockf_result {
    size_t n_sets;                    /* the sets it was run on (F6) */
    size_t n_orient;                  /* orientations per realisation */
    sl_rockf_level level[SL_ROCKF_NLEVELS];
    double excursion_m;               /* the design excursion (F5) */
    size_t n_runs;                    /* block runs integrated (after the uplift screen) */
} sl_rockf_result;

/* The accumulator of a floor's items over its sets: made for items[n_items]
 * (copied) and at most max_sets sets under options o (copied); sets are added
 * in order, chunk by chunk (sl_rockf_acc_add: the caller may synthesize and
 * drop sets a chunk at a time), each set's values computed alone (OpenMP
 * over the sets of a chunk) and kept, so the statistics are the same
 * whatever the chunks and threads. NULL with err on bad input or no
 * memory. */
typedef struct sl_rockf_acc sl_rockf_acc;
SL_API sl_rockf_acc *sl_rockf_acc_alloc(const sl_rockf_item *items, size_t n_items,
                                        size_t max_sets, const sl_rockf_opts *o, sl_error *err);
SL_API void sl_rockf_acc_free(sl_rockf_acc *acc);
/* Add sets[0..count) (each with h1; h2 and v may be NULL; one n and dt per
 * set) as the next sets. SL_EINVAL (more than max_sets in all, a set
 * without h1, a sample not finite), SL_ENOMEM. */
SL_API sl_status sl_rockf_acc_add(sl_rockf_acc *acc, const sl_set *sets, size_t count,
                                  sl_error *err);
/* Sets added so far. */
SL_API size_t sl_rockf_acc_n_sets(const sl_rockf_acc *acc);
/* Apply the stopping rule (F6) to every item still taking sets; the items
 * decided take no more. Returns the items still taking sets. Without it,
 * every item takes every set added. */
SL_API size_t sl_rockf_acc_update(sl_rockf_acc *acc);
/* The statistics of every item over the sets added so far (out[n_items]). */
SL_API sl_status sl_rockf_acc_result(const sl_rockf_acc *acc, sl_rockf_result *out,
                                     sl_error *err);

/* The verdict of result r (above) for an item with available clearance
 * clearance_m (>= 0; NAN: the excursion is not checked), targets
 * p_target[]. */
SL_API sl_rockf_verdict sl_rockf_verdict_of(const sl_rockf_result *r,
                                            const double p_target[SL_ROCKF_NLEVELS],
                                            double clearance_m);
/* "stands", "marginal", "short", "overturns". */
SL_API const char *sl_rockf_verdict_name(sl_rockf_verdict v);

/* Sets synthesized at a time by sl_rockf_floor_run when it makes them. */
#define SL_ROCKF_CHUNK 16

/* The rocking check of items[n_items] on floor fl of a run with seed
 * run_seed and n_sets sets per floor: over sets[0..n_sets) when given with
 * their motions (a floor just computed), else over the same sets made again
 * (sl_analysis_make_sets: a floor read from the cache); the sets taken in
 * batches of SL_ROCKF_CHUNK (the first: o->min_sets), the stopping rule
 * (F6) applied after each. out[n_items] filled. Errors as sl_rockf_acc_*,
 * and the synthesis'. */
struct sl_floor;
struct sl_synth_set;
SL_API sl_status sl_rockf_floor_run(const struct sl_floor *fl, uint64_t run_seed, size_t n_sets,
                                    const struct sl_synth_set *sets, const sl_rockf_item *items,
                                    size_t n_items, const sl_rockf_opts *o,
                                    sl_rockf_result *out, sl_error *err);

#endif
