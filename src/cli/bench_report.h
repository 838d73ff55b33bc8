/* bench_report.h - the tables of `seislide bench` (internal to the command
 * line). */
#ifndef SL_BENCH_REPORT_H
#define SL_BENCH_REPORT_H

#include <stdio.h>

#include "study/bench.h"
#include "study/bench_engine.h"

/* Print every section to stdout and to f (the report file). */
void bench_report(FILE *f, const sl_bench *b, unsigned long repeat);

/* The engine's work-precision section (study/bench_engine.h; docs/integrators.md). */
void bench_report_engine_wp(FILE *f, const sl_bench_wp *w);

#endif
