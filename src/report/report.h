/*
 * report.h - the clearance tables for plant designers: one XLSX workbook
 * (libxlsxwriter, native Excel charts) and the same tables as CSV.
 *
 * Workbook:
 *  - "Lookup": choose a floor from a drop-down list, type mu; formulas return
 *    the required clearance in mm, interpolated linearly in mu (the same rule
 *    as sl_design_clearance_at()), with every intermediate cell visible;
 *  - "Summary": rows mu, one column per floor, required clearance in mm;
 *    below it each floor's horizontal ZPA and crossover;
 *  - one sheet per floor: mu, mu g/ZPA, NLTHA mean and sd, NLTHA design,
 *    ASCE best and design, cap, clearance (all mm), flags, and a scatter
 *    chart of the design sliding spectra with the cap and the crossover;
 *  - "Motion quality": every synthesized motion's checks;
 *  - "Inputs": what reproduces the run (version, command, floor files with
 *    size and CRC-32, seed, settings).
 * CSV (RFC 4180: CRLF line ends, fields quoted when needed; units in the
 * column names): floor_<name>.csv per floor, summary.csv, floors.csv (ZPA,
 * crossover, ranges, notes per floor), motion_quality.csv.
 *
 * Every file is written atomically (atomic.h): a failure leaves no partial
 * file under its final name. The workbook's creation date is
 * sl_report.created, so equal inputs give byte-identical files.
 */
#ifndef SL_REPORT_H
#define SL_REPORT_H

#include <stddef.h>
#include <time.h>

#include "method/design.h"
#include "method/stats.h"
#include "core/status.h"

typedef struct sl_report_floor {
    const char *name;        /* floor name (from its file) */
    const char *path;        /* floor file */
    unsigned long crc32;     /* CRC-32 of the file's bytes */
    long size_bytes;
    double zpa_h_ms2;        /* the horizontal ZPA used for mu g/ZPA */
    const sl_design *design;
    const char *note;        /* e.g. the 10 % fallback; "" when none */
    size_t n_mu_skipped;     /* friction values that needed no NLTHA for any motion */
    size_t n_sets;           /* motion sets used */
    const char *stop;        /* why it stopped adding sets: "converged", "max_sets", "fixed" */
    const sl_stats_conv *conv; /* per mu, as design->rows: sets, SE and band of the NLTHA
                                  design value (NULL: columns left blank) */
} sl_report_floor;

/* One synthesized motion component and its checks. */
typedef struct sl_report_quality {
    const char *floor;
    int set;                 /* 1-based */
    const char *component;   /* "H1", "H2", "V" */
    double pga_g;
    double d5_75_s;
    double min_ratio;        /* min over frequencies of computed/target */
    double max_ratio;
    int max_run_below;       /* longest run of points below the target */
    double max_corr;         /* largest |correlation| with the set's other components */
    double v_end_ms, d_end_m;
    int pass;
    const char *why;         /* failed checks, "" when passed */
} sl_report_quality;

typedef struct sl_report_setting {
    const char *name, *value;
} sl_report_setting;

typedef struct sl_report {
    const char *version;
    const char *command_line;
    time_t created;          /* workbook creation date (pin it for reproducible files) */
    size_t n_floors;
    const sl_report_floor *floors;
    size_t n_quality;
    const sl_report_quality *quality;
    size_t n_settings;
    const sl_report_setting *settings;
} sl_report;

/* Write the workbook to path. Returns SL_OK, or SL_EIO/SL_EINVAL with the
 * path and libxlsxwriter's message. All floors must share the mu grid. */
sl_status sl_report_write_xlsx(const sl_report *r, const char *path, sl_error *err);

/* Write floor_<name>.csv per floor, summary.csv, floors.csv and
 * motion_quality.csv into
 * dir (which must exist). Floor names are made safe for file names
 * (letters, digits, '-', '_'; others become '_'). */
sl_status sl_report_write_csv(const sl_report *r, const char *dir, sl_error *err);

/* The file-name form of a floor name (into buf of size n). */
char *sl_report_safe_name(const char *name, char *buf, size_t n);

/* Flags of a design row as text ("nltha_capped asce_unconservative ..."). */
char *sl_report_flags(unsigned flags, char *buf, size_t n);

#endif
