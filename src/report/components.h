/*
 * components.h - the plant's list of unanchored components checked against
 * the floor tables of a `seislide run`: one verdict per component.
 *
 * Results: the output folder of `seislide run`, one building (floors.csv and
 * floor_<id>.csv) or a plant (plant.csv and one such folder per building,
 * named by the building id). sl_comp_results_load() reads every floor's
 * table from the CSV files: mu, clearance_mm and nltha_design_se_mm on the
 * run's friction grid, with each floor's id and name and the run's record
 * (the "# ..." lines every CSV of a run starts with).
 *
 * The components table (CSV, RFC 4180: quoted fields with commas, quotes
 * and line breaks; a UTF-8 byte-order mark and CRLF line ends tolerated;
 * lines starting with '#' outside a quoted field ignored). One header row,
 * names compared without case: tag, building, floor, mu, base_m,
 * cg_height_m, clearance_mm, in any order; any other column is kept as it
 * is, in its place. building may be empty when the results hold one
 * building; floor is a floor id or the floor's name (without case): the one
 * floor of its building whose id or name it is (results whose floors share
 * a reference are refused by sl_comp_results_load, so the workbook's MATCH
 * on ids, then names, finds the same floor). mu,
 * base_m (least base dimension) and cg_height_m (centre of mass above the
 * floor) must be > 0, clearance_mm (the available gap) >= 0; tags unique
 * (without case). Blank lines and rows of empty fields are skipped.
 *
 * Per component:
 *   required_clearance_mm  the floor's clearance at mu by linear
 *                          interpolation between the grid rows around it,
 *                          c0 + (mu - mu0) (c1 - c0) / (mu1 - mu0), the rows
 *                          found as the workbook's Lookup finds them (the
 *                          last at or below mu, and the next): the rule of
 *                          sl_design_clearance_at(); empty off the grid
 *   required_clearance_se_mm  the standard error of the NLTHA design value,
 *                          interpolated the same way (as the Lookup does)
 *   margin_mm              clearance_mm - required_clearance_mm
 *   b_over_h               base_m / (2 cg_height_m): half the base over the
 *                          height of the centre of mass
 *   verdict, in this order:
 *     rocking  mu >= b/h: a rigid block on a rigid floor rocks before it
 *              slides (Shenton 1996, "Criteria for initiation of slide,
 *              rock, and slide-rock rigid-body modes"); the sliding table
 *              does not apply: check rocking (ASCE/SEI 43-05)
 *     outside  mu off the computed grid [mu_first, mu_last]
 *     ok       margin >= 0
 *     short    margin < 0 (a result, not an error)
 *
 * Outputs (sl_comp_write): DIR/components.csv (the input columns in their
 * order, then the results, after the trace lines every CSV of the project
 * carries, csv.c) and DIR/components.xlsx (components_book.c): a
 * Components sheet whose results are live formulas over a hidden Floors
 * sheet (the floors' tables), with rows left for more components; a
 * Summary of counts per verdict and per floor; a chart of required against
 * available clearance. Each file written atomically.
 *
 * Memory: the loaders fill caller-owned structs that the matching _free
 * releases; the library prints nothing.
 */
#ifndef SL_REPORT_COMPONENTS_H
#define SL_REPORT_COMPONENTS_H

#include <stddef.h>
#include <time.h>

#include "core/status.h"
#include "report/report.h"

#define SL_COMP_CSV "components.csv"
#define SL_COMP_XLSX "components.xlsx"
/* Largest components file read, bytes; most columns; most rows. */
#define SL_COMP_MAX_BYTES (64L << 20)
#define SL_COMP_MAX_COLS 256
#define SL_COMP_MAX_ROWS 100000
/* The workbook keeps this many empty formula rows below the last component
 * for components typed in later. */
#define SL_COMP_SPARE_ROWS 200

/* The required columns, in the order the workbook shows them. */
typedef enum sl_comp_col {
    SL_COMP_TAG, SL_COMP_BUILDING, SL_COMP_FLOOR, SL_COMP_MU, SL_COMP_BASE, SL_COMP_CG,
    SL_COMP_CLEARANCE, SL_COMP_NCOLS
} sl_comp_col;
extern const char *const SL_COMP_COL_NAME[SL_COMP_NCOLS];

typedef enum sl_comp_verdict {
    SL_COMP_OK, SL_COMP_SHORT, SL_COMP_ROCKING, SL_COMP_OUTSIDE, SL_COMP_NVERDICTS
} sl_comp_verdict;
extern const char *const SL_COMP_VERDICT_NAME[SL_COMP_NVERDICTS]; /* "ok", "short", ... */

/* One floor of the results: its table on the run's grid (mm). */
typedef struct sl_comp_floor {
    char *building;          /* building id ("" in a one-building folder) */
    char *id, *name;         /* floors.csv: floor_id, floor */
    char *file;              /* the floor file the run read (its floor_file_crc32 line) */
    unsigned long crc32;
    long size_bytes;
    double *clearance_mm, *se_mm; /* n_mu each; se NAN when the table leaves it empty */
} sl_comp_floor;

typedef struct sl_comp_results {
    char *dir;
    int is_plant;
    size_t n_buildings;
    char **buildings;        /* names as written (plant.csv), in plant order; one "" for a
                                building folder */
    char **folders;          /* each building's output folder under dir
                                (sl_report_file_name of its name); "" for a building folder */
    char *single;            /* a building folder's own name (its last path part) */
    size_t n_floors;
    sl_comp_floor *floors;   /* grouped by building */
    size_t n_mu;
    double *mu;              /* the grid every floor shares */
    /* the run's record, from its CSV comment lines ("-" when absent) */
    char *program, *command, *created, *seed, *project, *document, *revision;
} sl_comp_results;

/* Read the results folder dir. SL_EIO (missing files), SL_EPARSE (a table
 * that is not what run writes: file:line:col), SL_EINVAL (floors on
 * different grids), SL_ENOMEM. On failure r is empty. */
sl_status sl_comp_results_load(const char *dir, sl_comp_results *r, sl_error *err);
void sl_comp_results_free(sl_comp_results *r);
/* Name the results `shown` in the outputs and messages (a run that checks
 * its own fresh folder names the final one); a one-building folder's own
 * name, which a row may give as its building, becomes shown's last part. */
sl_status sl_comp_results_shown(sl_comp_results *r, const char *shown, sl_error *err);

/* One component: the input fields and the results. */
typedef struct sl_comp_row {
    long line;               /* the line its record starts on */
    char **field;            /* the input fields, in the file's column order */
    size_t floor;            /* index into the results' floors */
    double mu, base_m, cg_height_m, clearance_mm;
    double b_over_h, required_mm, se_mm, margin_mm; /* required, se, margin NAN off the grid */
    sl_comp_verdict verdict;
} sl_comp_row;

typedef struct sl_comp_table {
    char *path;
    unsigned long crc32;
    long size_bytes;
    size_t n_cols;
    char **header;           /* as written */
    int col[SL_COMP_NCOLS];  /* the file's column of each required column */
    size_t n;
    sl_comp_row *rows;
    size_t count[SL_COMP_NVERDICTS];
} sl_comp_table;

/* Read and check the components file `path` against the results r and
 * compute every row. The first malformed row stops it: SL_EPARSE or
 * SL_EINVAL with file, line and column (the field's number) and the value;
 * an unknown building or floor lists the known ones; a repeated tag names
 * both lines. On failure t is empty. */
sl_status sl_comp_table_read(const char *path, const sl_comp_results *r, sl_comp_table *t,
                             sl_error *err);
void sl_comp_table_free(sl_comp_table *t);

/* The interpolation at mu on the grid mu[0..n) of the values c (the
 * Lookup's rule above): NAN when mu is off the grid or NAN. */
double sl_comp_interp(const double *mu, const double *c, size_t n, double mu_at);

/* The verdict's reason in words into buf ("mu 0.45 >= b/h 0.36: rocks
 * before it slides, check rocking (ASCE 43-05)"); the workbook's formula
 * writes the same text. */
char *sl_comp_reason(const sl_comp_results *r, const sl_comp_row *w, char *buf, size_t n);

/* What the outputs record. */
typedef struct sl_comp_opts {
    const char *version;      /* "seislide 0.1.0" */
    const char *command_line; /* this command's */
    time_t created;
} sl_comp_opts;

/* The run's record and title block (version, command, seed, created,
 * project; "-" read as none) into rep, as the shared writers read them;
 * no floors. */
void sl_comp_report(const sl_comp_results *r, const sl_comp_opts *o, sl_report *rep);

/* Write dir/components.csv and dir/components.xlsx (dir exists). */
sl_status sl_comp_write(const sl_comp_results *r, const sl_comp_table *t, const char *dir,
                        const sl_comp_opts *o, sl_error *err);
sl_status sl_comp_write_xlsx(const sl_comp_results *r, const sl_comp_table *t, const char *path,
                             const sl_comp_opts *o, sl_error *err);

#endif
