/*
 * report.h - the clearance tables for plant designers: one XLSX workbook
 * (libxlsxwriter, native Excel charts) and the same tables as CSV.
 *
 * Workbook:
 *  - "Lookup": choose a floor from a drop-down list, type mu; formulas return
 *    the required clearance in mm, interpolated linearly in mu (the same rule
 *    as sl_design_clearance_at()), with every intermediate cell visible;
 *  - "Summary": a chart of every floor; each floor's file, crossover,
 *    ranges and note; last, rows mu, one column per floor, required
 *    clearance in mm, and below it each floor's ZPA and sets;
 *  - one sheet per floor, named by its id (sl_report_floor_id; Excel's
 *    forbidden characters made '_', cut at 31 characters; "F1", "F2", ...
 *    when two such names collide), the full name in its title: what the
 *    floor is, a scatter chart of the design sliding spectra with the cap,
 *    then (last, from a new page) mu, mu g/ZPA, NLTHA mean and design with
 *    its standard error, ASCE best and design, cap, clearance (all mm),
 *    flags. A table is the last part of its sheet, so that its repeated
 *    header row prints over table pages only;
 *  - "Motion quality": the synthesized motions' checks, one row per set;
 *  - "Notes": assumptions and limits, every count given per floor;
 *  - "Inputs": what reproduces the run (version, command, floor files with
 *    size and CRC-32, seed, settings);
 *  - "Data" (hidden, not printed): the tables the charts and Lookup read.
 * One writer per sheet (sheet_*.c, csv.c; sheets.h); printed through
 * LibreOffice every page is A4 with no text cut or overprinted
 * (tests/cli/test_pdf.sh).
 * CSV (RFC 4180: CRLF line ends, fields quoted when needed; units in the
 * column names): floor_<id>.csv per floor, summary.csv, floors.csv (ZPA,
 * crossover, ranges, notes per floor), motion_quality.csv.
 *
 * Each CSV starts with comment lines that trace it to its run: program,
 * command, creation time, seed and the CRC-32 of every floor file it holds.
 * A floor whose motions failed their checks (n_failed_motions > 0) is named
 * in the first lines of every sheet and CSV that holds it.
 *
 * Every file is written atomically (atomic.h): a failure leaves no partial
 * file under its final name. The workbook's creation date is
 * sl_report.created, so equal inputs give byte-identical files.
 */
#ifndef SL_REPORT_H
#define SL_REPORT_H

#include <stddef.h>
#include <time.h>

#include "core/api.h"
#include "method/design.h"
#include "core/status.h"

typedef struct sl_report_floor {
    const char *id;          /* short stable id: the file name's stem as written
                                (sl_report_floor_id); unique in a report, and so is
                                its file name (sl_report_file_name) */
    const char *name;        /* floor name (from its file); unique in a report */
    const char *path;        /* floor file */
    const char *description; /* free text from the file ("" when none) */
    double elevation_m;      /* NAN when not given */
    const char *units;       /* units of the file's spectral values */
    unsigned long crc32;     /* CRC-32 of the file's bytes */
    long size_bytes;
    double zpa_h_ms2;        /* the horizontal ZPA used for mu g/ZPA */
    const sl_design *design;
    const char *note;        /* e.g. the 10 % fallback; "" when none */
    size_t n_mu_skipped;     /* friction values that needed no NLTHA for any motion */
    /* Placeholders for the convergence statistics (analysis.c fills them
     * when it has them; NULL: the report shows the standard error sd/sqrt(N)
     * of the design rows only): per row of the design, the 90 % band of the
     * NLTHA design value, m. */
    const double *design_lo_m, *design_hi_m;
    /* Per row: the standard error of the NLTHA design value, m, as the
     * convergence statistics give it: FS SE(mean) below the cap, the cap's
     * own SE (1.5 SE of the mean PGD) where the cap governs. NULL: FS
     * sd/sqrt(N) of the design rows below the cap, 0 where it governs. */
    const double *design_se_m;
    /* Per row: the largest estimated integration error of any motion's peak
     * (the engine's err_est_m), m; NULL: not computed. */
    const double *err_est_m;
    const char *sets_stop;   /* why the floor stopped adding motion sets: "converged",
                                "max_sets" or "fixed" (NULL: not given) */
    double scatter;          /* the NLTHA's intensity scatter sigma_ln (analysis.h;
                                0: none, NAN: not given) */
    /* Every other damping of the file against the motions' own spectra
     * (sl_analysis_dampings_text; NULL or "none": the file gives one):
     * the text, the lowest and highest set-mean S/T over all of them
     * (NAN: none) and the verdict (1 all within the limits, 0 not). */
    const char *dampings;
    double dampings_min, dampings_max;
    int dampings_ok;
    /* Motion components of the floor that failed a quality check
     * (sl_analysis.n_failed_motions; kept only by --accept-failed-checks):
     * every sheet and CSV of the floor says so in its first lines. */
    size_t n_failed_motions;
    int sa10_fallback;       /* 1: the file had no 10 % table (sl_analysis.sa10_fallback):
                                a Notes entry and a line on the floor's sheet say so */
    /* Every warning the run gave about the floor (an unusual ZPA for its units,
     * a ZPA outside the plausible range run anyway with --force, a floor out of
     * line with its building accepted with --accept-floor), "; "-separated; ""
     * or NULL: none (NULL: the workbook's Notes work the ZPA warning out
     * itself). floors.csv's column warnings, a line on the Lookup and Summary
     * sheets, the Notes. */
    const char *warnings;
    int accepted;            /* 1: accepted in writing (--accept-floor; Inputs) */
    /* The floor's rocking lookup (rock/rock_lookup.h: SL_ROCKL_N results), NULL:
     * not computed (`run --rocking-lookup`): rocking_lookup.csv and the Rocking
     * sheet when some floor has it. */
    const struct sl_rockf_result *rock_lookup;
} sl_report_floor;

/* One synthesized motion component and its checks. */
typedef struct sl_report_quality {
    const char *floor;       /* floor id */
    int set;                 /* 1-based */
    const char *component;   /* "H1", "H2", "V" */
    double pga_g;
    double d5_75_s;
    double min_ratio;        /* min over frequencies of computed/target */
    double max_ratio;
    int max_run_below;       /* longest run of consecutive frequency points
                                below the target (SRP 3.7.1 limit: 9) */
    double max_corr;         /* largest |correlation| with the set's other components */
    double v_end_ms, d_end_m; /* 0 where round-off (sl_synth_end_residual) */
    int pass;
    const char *why;         /* failed checks, "" when passed */
} sl_report_quality;

typedef struct sl_report_setting {
    const char *name, *value;
} sl_report_setting;

/* The title block of the deliverable (any field NULL or "" prints "-"). */
typedef struct sl_report_project {
    const char *project, *document, *revision, *prepared, *checked, *date;
} sl_report_project;

typedef struct sl_report {
    const char *version;
    const char *command_line;
    const char *seed;        /* the run's seed as text, for the record (NULL: "-") */
    time_t created;          /* workbook creation date (pin it for reproducible files) */
    sl_report_project project;
    const char *building;    /* the building of a plant's workbook, as written (NULL: a
                                one-building run): named in every page's title and header */
    size_t n_floors;
    const sl_report_floor *floors;
    size_t n_quality;
    const sl_report_quality *quality;
    size_t n_settings;
    const sl_report_setting *settings;
    /* The Lookup sheet's initial inputs: a floor name (NULL: the first
     * floor; "" leaves the cell blank) and mu (NAN: blank; a value outside
     * the grid is kept, the sheet then says so). Tests set them. */
    const char *lookup_floor;
    double lookup_mu;
    const char *lookup_mu_text; /* non-NULL: the mu cell holds this text instead */
    /* Tests: write 0 as every Lookup formula's cached value, so that values
     * read back can only come from a recalculation (tests/test_lookup.c). */
    int lookup_zero_cache;
} sl_report;

/* Lookup default mu (when inside the grid). */
#define SL_REPORT_LOOKUP_MU 0.30

/* Initialise a report: zeros, lookup_mu = SL_REPORT_LOOKUP_MU. */
SL_API void sl_report_init(sl_report *r);

/* The id of a floor file (or of a building's folder): its file name without
 * folders and the ".ini" or ".csv" ending, as written (UTF-8), control bytes
 * and bytes that are not UTF-8 made '_', cut at whole characters to 64
 * bytes (into buf of size n). "floors/04-roof36.ini" -> "04-roof36",
 * "Niveau −3 m.ini" -> "Niveau −3 m". */
SL_API char *sl_report_floor_id(const char *path, char *buf, size_t n);
/* The part of an output file (or folder) name made from an id: ASCII
 * letters, digits, '-', '_' and every character beyond ASCII kept, any other
 * character made '_' (into buf of size n; 4 x the id's length suffices).
 * "Niveau −3 m" -> "Niveau_−3_m"; "Bâtiment réacteur" -> "Bâtiment_réacteur". */
SL_API char *sl_report_file_name(const char *id, char *buf, size_t n);
/* Bytes of the UTF-8 character at s (1 for ASCII), 0 when s holds no valid
 * one (or is at its end). */
SL_API size_t sl_report_utf8_len(const char *s);

/* Check that every floor reference is unique: no floor's id or name is
 * another floor's id or name, compared without case (as the workbook's
 * MATCH and a components list compare them; a floor's own id may be its
 * name), and no two ids give the same output file name. SL_EINVAL naming
 * both files. */
SL_API sl_status sl_report_check_floors(const sl_report *r, sl_error *err);
/* Do two floors (id and name each) share a reference, compared without case?
 * 0 no; 1 the ids; 2 the names; 3 b's id is a's name; 4 b's name is a's id.
 * The one rule of the run (sl_report_check_floors) and of a components list
 * (report/components.h). */
SL_API int sl_report_floor_refs_clash(const char *id_a, const char *name_a, const char *id_b,
                                      const char *name_b);

/* Write the workbook to path. Returns SL_OK, or SL_EIO/SL_EINVAL with the
 * path and libxlsxwriter's message. All floors must share the mu grid. */
SL_API sl_status sl_report_write_xlsx(const sl_report *r, const char *path, sl_error *err);

/* Write floor_<id>.csv per floor, summary.csv, floors.csv,
 * asce_below_nltha.csv and motion_quality.csv into dir (which must exist).
 * Every file starts with '#' comment lines: "# WARNING: CHECKS FAILED ..."
 * per floor whose motions failed their checks, then "# program:",
 * "# content:", "# command:", "# created:" (UTC, ISO 8601), "# seed:",
 * "# floor_file_crc32: CRC ID (PATH, N bytes)" per floor it holds, the
 * title block, and the floor(s), ZPA and units; then one header line; one
 * value per field. Every number written is finite (a value that does not exist is an
 * empty field); a non-finite result is an error, not a file. */
SL_API sl_status sl_report_write_csv(const sl_report *r, const char *dir, sl_error *err);


/* Every range of mu where ASCE is below NLTHA as "a-b, c-d" (ends
 * interpolated; "<=a" or "b+" where the grid does not close the range),
 * or "none"; into buf of size n. The one text every sheet, CSV comment and
 * message uses. */
SL_API char *sl_report_ranges_text(const sl_design *d, char *buf, size_t n);

/* Flags of a design row as text ("nltha_capped asce_unconservative ..."). */
SL_API char *sl_report_flags(unsigned flags, char *buf, size_t n);

#endif
