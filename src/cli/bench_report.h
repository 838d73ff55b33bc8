/* bench_report.h - the tables of `seislide bench` (internal to the command
 * line). */
#ifndef SL_BENCH_REPORT_H
#define SL_BENCH_REPORT_H

#include <stdio.h>

#include "study/bench.h"
#include "study/bench_engine.h"
#include "study/bench_rock.h"
#include "study/bench_rockf.h"

/* Print every section to stdout and to f (the report file). */
void bench_report(FILE *f, const sl_bench *b, unsigned long repeat);

/* Section 8: the rocking engine's cost per run against its error
 * (study/bench_rock.h). */
void bench_report_rock(FILE *f, const sl_bench_rock *r);
void bench_report_rockf(FILE *f, const sl_bench_rockf *r);

/* The engine's work-precision section (study/bench_engine.h; docs/integrators.md). */
void bench_report_engine_wp(FILE *f, const sl_bench_wp *w);

#endif
