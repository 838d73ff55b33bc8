/* run_report.h - the messages of `seislide run` on stderr: progress within a
 * floor and the summary of each floor's analysis (formatting only). */
#ifndef SL_CLI_RUN_REPORT_H
#define SL_CLI_RUN_REPORT_H

#include <stddef.h>

#include "analysis.h"

/* Progress of floor `floor` of n (name): a line per step at most every 25 %. */
typedef struct run_progress {
    int quiet;
    size_t floor, n;
    const char *name, *step;
    int pct;
} run_progress;
/* The sl_analysis_opts.progress callback; ctx is a run_progress. */
void run_progress_cb(void *ctx, const char *step, size_t done, size_t total);
/* The summary of floor i (1-based) of n: ZPA, friction values skipped,
 * ranges where ASCE is below NLTHA, motion sets and convergence, wall times. */
void run_report_floor(size_t i, size_t n, const char *name, const sl_analysis *q, size_t n_mu);

#endif
