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
    const char *building;     /* a plant's building, named on every page of its workbook
                                 (NULL: a one-building run) */
} sl_deliver_opts;

/* Most floors in one run, and the longest floor id. */
#define SL_DELIVER_MAX_FLOORS 256
#define SL_DELIVER_ID_MAX 80

/* The floors of a run, read and checked before any long work. */
typedef struct sl_deliver_inputs {
    size_t n;
    char *paths[SL_DELIVER_MAX_FLOORS];
    sl_floor *floors[SL_DELIVER_MAX_FLOORS];
    char ids[SL_DELIVER_MAX_FLOORS][SL_DELIVER_ID_MAX];
    const char *idp[SL_DELIVER_MAX_FLOORS]; /* ids[i] */
    char *warn[SL_DELIVER_MAX_FLOORS];      /* each floor's warnings (below), NULL: none */
} sl_deliver_inputs;

/* Read every floor file named by args (files or folders of *.ini;
 * sl_floor_list), check each (sl_floor_check_plausible: an error, or with
 * `force` a line appended to `warnings`, size nw; an unusual ZPA,
 * sl_floor_zpa_warning, appends "file:line: text\n"; each floor's own
 * warnings, without the place, also in in->warn[i]) and the uniqueness of
 * their ids and names (sl_report_check_floors). in must be zeroed; free it
 * with sl_deliver_inputs_free() whatever the result. */
sl_status sl_deliver_inputs_load(sl_deliver_inputs *in, const char *const *args, size_t nargs,
                                 int force, char *warnings, size_t nw, sl_error *err);
void sl_deliver_inputs_free(sl_deliver_inputs *in);

/* What the outputs say about a floor file (beside its analysis): from the
 * floor read (sl_deliver_meta_of) or from a shard's record (merge). */
typedef struct sl_deliver_meta {
    const char *name, *path, *description, *units;
    double elevation_m;       /* NAN when not given */
    unsigned long crc32;      /* of the file's bytes */
    long size_bytes;
    const char *warnings;     /* the run's warnings about it (sl_report_floor.warnings) */
    int accepted;             /* accepted in writing (--accept-floor) */
} sl_deliver_meta;

/* CRC-32 (zlib) and size of the bytes of file `path` (recorded so that an
 * input can be recognised later). SL_EIO naming the file. */
sl_status sl_deliver_file_crc(const char *path, unsigned long *crc, long *size, sl_error *err);

/* The meta of floor fl (its strings borrowed from fl); reads the file for
 * its CRC-32 and size. */
sl_status sl_deliver_meta_of(const sl_floor *fl, sl_deliver_meta *m, sl_error *err);

/* sl_deliver_write from metas: the same outputs (write_motions needs the
 * analyses' motions). */
sl_status sl_deliver_write_meta(const char *dir, size_t n, const sl_deliver_meta *meta,
                                const char *const *ids, const sl_analysis *const *an,
                                const sl_deliver_opts *o, sl_error *err);

/* Write everything for n floors (floors[i] analysed as an[i]; ids[i] from
 * sl_report_floor_id, already checked unique) into folder dir. Returns
 * SL_OK or the first error (err names the file). */
sl_status sl_deliver_write(const char *dir, size_t n, const sl_floor *const *floors,
                           const char *const *ids, const sl_analysis *const *an,
                           const sl_deliver_opts *o, sl_error *err);

#endif
