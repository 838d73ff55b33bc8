/*
 * deliver.h - the outputs of `seislide run` as one folder: the report
 * (report.h) assembled from the per-floor analyses (analysis.h), the CSV
 * files, the workbook and, on request, every synthesized motion, written
 * into a folder the caller made fresh (atomic.h: sl_atomic_dir_open) and
 * swaps in when this returns SL_OK.
 */
#ifndef SL_DELIVER_H
#define SL_DELIVER_H

#include <stddef.h>
#include <stdint.h>
#include <time.h>

#include "analysis.h"
#include "io/floor.h"
#include "report/report.h"

/* The workbook's file name in the output folder. */
#define SL_DELIVER_WORKBOOK "seislide-clearance.xlsx"

typedef struct sl_deliver_opts {
    const char *version, *command_line;
    time_t created;
    sl_report_project project;
    uint64_t seed;
    unsigned substeps;
    double accuracy;          /* the requested accuracy (for the record) */
    int write_motions;        /* also motions/<floor id>/setNN_{h1,h2,v}.AT2 */
} sl_deliver_opts;

/* Write everything for n floors (floors[i] analysed as an[i]; ids[i] from
 * sl_report_floor_id, already checked unique) into folder dir. Returns
 * SL_OK or the first error (err names the file). */
sl_status sl_deliver_write(const char *dir, size_t n, const sl_floor *const *floors,
                           const char *const *ids, const sl_analysis *const *an,
                           const sl_deliver_opts *o, sl_error *err);

#endif
