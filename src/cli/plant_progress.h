/* plant_progress.h - progress of `seislide run` over the whole plant on
 * stderr: on a terminal one line updated in place (floors done of total,
 * motion sets, elapsed, ETA, and the step of the floor being computed),
 * otherwise one line per floor (beside the per-floor messages of
 * run_report.h); nothing with -q. The ETA assumes the floors left cost what
 * the floors computed so far did per unit of expected cost (plant.h, "Cost
 * model"); reused floors cost nothing. */
#ifndef SL_CLI_PLANT_PROGRESS_H
#define SL_CLI_PLANT_PROGRESS_H

#include <stddef.h>

#include "analysis.h"
#include "run_report.h"

typedef struct plant_progress {
    int quiet, tty;
    size_t total, done, reused, sets;
    double t0, cost_left, cost_done, time_done;
    double floor_t0, floor_cost;
    run_progress floor;         /* the per-floor messages when not on a terminal */
    const char *cache_dir, *lock_hash; /* the lock refreshed while a floor computes */
} plant_progress;

void plant_progress_start(plant_progress *pp, int quiet, size_t total, double cost_total);
/* Floor i (1-based) of the plant, `label` its name, starts computing. */
void plant_progress_floor(plant_progress *pp, size_t i, const char *label, double cost);
/* The sl_analysis_opts.progress callback; ctx is a plant_progress. */
void plant_progress_cb(void *ctx, const char *step, size_t done, size_t total);
/* Floor done (reused: read from the cache), with its result. */
void plant_progress_done(plant_progress *pp, size_t i, const char *label, const sl_analysis *a,
                         int reused, size_t n_mu);
/* A message that must not be overwritten by the updating line. */
void plant_progress_msg(plant_progress *pp, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* Clear the updating line. */
void plant_progress_end(plant_progress *pp);

#endif
