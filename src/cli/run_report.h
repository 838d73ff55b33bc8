/* run_report.h - the messages of `seislide run` on stderr: progress within a
 * floor, the summary of each floor's analysis, and the verdict on its
 * motions' checks (a floor whose motions failed stops the run). */
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
/* The warnings and the verdict of floor i (1-based) of n after its analysis,
 * printed also with -q: a warning when the file has no 10 % table (ASCE on
 * the motions' mean spectrum); when some motions failed their SRP 3.7.1
 * checks, which checks, how many motions and where (component, sets, the
 * worst S/T). Returns CLI_EXIT_OK, or CLI_EXIT_ERROR when motions failed and
 * `accept` (--accept-failed-checks) is 0: the run must stop, writing
 * nothing. */
int run_report_checks(size_t i, size_t n, const sl_floor *fl, const sl_analysis *q, int accept);

#endif
