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
 * building; floor is a floor id or the floor's name: the one floor of its
 * building whose id or name it is (results whose floors share a reference
 * are refused by sl_comp_results_load, so the workbook's MATCH on ids, then
 * names, finds the same floor). Names (column names,
 * buildings, floors, tags) are compared by one rule, sl_comp_same_name():
 * blanks at either end dropped, runs inside read as one, without case for
 * every script a plant writes names in (io/casefold.h), as the workbook's
 * MATCH over TRIM compares them. mu, base_m (least base dimension) and
 * cg_height_m (centre of mass above the floor) must be > 0, clearance_mm
 * (the available gap) >= 0; tags unique. Blank lines and rows of empty
 * fields are skipped. A header row holding ';' and no ',' (outside quotes)
 * makes a list separated by ';' whose numbers may carry a decimal comma
 * ("0,35"), as a European spreadsheet saves it: the rule of the floor
 * tables (io/floor_csv.c, sl_text_decimal_comma).
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
 *   asce_design_mm         the ASCE/SEI 43-05 design value at mu,
 *                          interpolated the same way: beside the required
 *                          clearance, which the run's clearance policy
 *                          takes from NLTHA by default
 *   margin_mm              clearance_mm - required_clearance_mm
 *   b_over_h               base_m / (2 cg_height_m): half the base over the
 *                          height of the centre of mass
 *   verdict of the sliding check, in this order:
 *     rocking  mu >= b/h: a rigid block on a rigid floor rocks before it
 *              slides (Shenton 1996, "Criteria for initiation of slide,
 *              rock, and slide-rock rigid-body modes"); the sliding table
 *              does not apply: the rocking check decides (mode below,
 *              sl_comp_set_rocking; docs/rocking.md)
 *     outside  mu off the computed grid [mu_first, mu_last]
 *     short    margin < 0 (a result, not an error)
 *     marginal 0 <= margin < SL_COMP_MARGIN_SE x the required clearance's
 *              standard error: the margin is inside the noise of the
 *              motion sets (an SE left empty counts as 0)
 *     ok       margin >= SL_COMP_MARGIN_SE x SE
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
#include "rock/rock_floor.h"

#define SL_COMP_CSV "components.csv"
#define SL_COMP_XLSX "components.xlsx"
/* Largest components file read, bytes; most columns; most rows. */
#define SL_COMP_MAX_BYTES (64L << 20)
#define SL_COMP_MAX_COLS 256
#define SL_COMP_MAX_ROWS 100000
/* The workbook keeps this many empty formula rows below the last component
 * for components typed in later; they are printed with the sheet (an empty
 * one as a blank row of the form), so that a row typed in prints. */
#define SL_COMP_SPARE_ROWS 40
/* A margin below this many standard errors of the required clearance is
 * "marginal", not "ok" (two standard errors: about the 95 % two-sided
 * band of the mean of the motion sets). */
#define SL_COMP_MARGIN_SE 2.0
/* Most problems of a refused list kept for the messages (every bad row is
 * counted). */
#define SL_COMP_MAX_PROBLEMS 50

/* The required columns, in the order the workbook shows them. */
typedef enum sl_comp_col {
    SL_COMP_TAG, SL_COMP_BUILDING, SL_COMP_FLOOR, SL_COMP_MU, SL_COMP_BASE, SL_COMP_CG,
    SL_COMP_CLEARANCE, SL_COMP_NCOLS
} sl_comp_col;
extern const char *const SL_COMP_COL_NAME[SL_COMP_NCOLS];

/* Optional columns (names compared by the one rule; empty field: not given):
 *   mu_max           upper bound of the friction (>= mu): an item with
 *                    mu < b/h <= mu_max may slide or rock, both are checked
 *   restitution      r of the rocking impacts, in [0, 1] (Housner's by default)
 *   orientation_deg  the rocking axis from H1, degrees (the worst of 12 by
 *                    default) */
typedef enum sl_comp_opt_col {
    SL_COMP_MU_MAX, SL_COMP_RESTITUTION, SL_COMP_ORIENTATION, SL_COMP_NOPT
} sl_comp_opt_col;
extern const char *const SL_COMP_OPT_NAME[SL_COMP_NOPT];

/* Verdicts. ok, marginal, short, outside: the sliding check; stands,
 * marginal, short, overturns: the rocking check (rock/rock_floor.h); rocking:
 * a slender item whose rocking was not computed (a row typed into the
 * workbook, or a table read but not yet given its rocking results,
 * sl_comp_set_rocking). */
typedef enum sl_comp_verdict {
    SL_COMP_OK, SL_COMP_MARGINAL, SL_COMP_SHORT, SL_COMP_ROCKING, SL_COMP_OUTSIDE,
    SL_COMP_STANDS, SL_COMP_OVERTURNS, SL_COMP_NVERDICTS
} sl_comp_verdict;
extern const char *const SL_COMP_VERDICT_NAME[SL_COMP_NVERDICTS]; /* "ok", "marginal", ... */

/* Which check a row gets (Shenton 1996: a rigid block slides first when
 * mu < b/h and rocks first when mu >= b/h): sliding when mu_max (or, not
 * given, mu) < b/h; rocking when mu >= b/h; both when mu < b/h <= mu_max.
 * A row checked both ways takes the worse verdict, in the order overturns,
 * short, outside, marginal, ok (= stands). */
typedef enum sl_comp_mode {
    SL_COMP_MODE_SLIDING, SL_COMP_MODE_ROCKING, SL_COMP_MODE_BOTH, SL_COMP_NMODES
} sl_comp_mode;
extern const char *const SL_COMP_MODE_NAME[SL_COMP_NMODES]; /* "sliding", "rocking", "both" */

/* The one rule by which names are compared: a row's building and floor
 * with the results' (building, floor id, floor name), tags with each
 * other, column names with the required ones. Ends trimmed, runs of blanks
 * inside read as one, without case (io/casefold.h: sl_casefold_same). 1
 * when a and b are the same name. */
int sl_comp_same_name(const char *a, const char *b);

/* One floor of the results: its table on the run's grid (mm). */
typedef struct sl_comp_floor {
    char *building;          /* building id ("" in a one-building folder) */
    char *id, *name;         /* floors.csv: floor_id, floor */
    char *file;              /* the floor file the run read (its floor_file_crc32 line) */
    unsigned long crc32;
    long size_bytes;
    double *clearance_mm, *se_mm; /* n_mu each; se NAN when the table leaves it empty */
    double *asce_mm;         /* n_mu: the ASCE design value (NAN: empty in the table) */
    char **flags;            /* n_mu: the flags of each grid row ("" when none) */
    size_t n_flags;          /* of them allocated */
    double zpa_g;            /* the horizontal ZPA (horizontal_zpa_g line; NAN: absent) */
    long n_sets;             /* floors.csv n_sets (-1: absent) */
    char *sets_stop;         /* floors.csv sets_stop ("" when absent) */
    char *note;              /* floors.csv note ("" when none) */
    char *warnings;          /* floors.csv warnings, when the table has the column ("") */
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
    char *policy;            /* the clearance policy (clearance_policy line; "-" when absent) */
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
    double b_over_h, required_mm, se_mm, asce_mm, margin_mm; /* NAN off the grid */
    double mu_max, restitution, orientation_deg; /* optional columns (NAN: not given) */
    sl_comp_mode mode;
    sl_comp_verdict slide_verdict; /* the sliding check (rocking: mu >= b/h) */
    sl_comp_verdict rock_verdict;  /* the rocking check; rocking until it is given */
    int has_rock;                  /* rock holds the rocking check's result */
    sl_rockf_result rock;
    sl_comp_verdict verdict;       /* the governing one */
} sl_comp_row;

typedef struct sl_comp_table {
    char *path;
    unsigned long crc32;
    long size_bytes;
    size_t n_cols;
    char **header;           /* as written */
    int col[SL_COMP_NCOLS];  /* the file's column of each required column */
    int opt[SL_COMP_NOPT];   /* the file's column of each optional column (-1: absent) */
    char sep;                /* the field separator: ',' or ';' (decimal commas) */
    size_t n;
    sl_comp_row *rows;
    size_t count[SL_COMP_NVERDICTS];
} sl_comp_table;

/* The problems of a refused list: the first SL_COMP_MAX_PROBLEMS messages
 * in file order (each file, line, column, the value), and the counts. */
typedef struct sl_comp_problems {
    size_t n;                /* messages in e */
    size_t n_more;           /* problems beyond the cap (counted, not kept) */
    size_t n_bad_rows;       /* rows with at least one problem */
    size_t n_rows;           /* component rows read */
    sl_error e[SL_COMP_MAX_PROBLEMS];
} sl_comp_problems;

/* Read and check the components file `path` against the results r and
 * compute every row. A malformed field is SL_EPARSE or SL_EINVAL with
 * file, line and column (the field's number) and the value; an unknown
 * building or floor lists the known ones; a repeated tag names both lines.
 * With p NULL the first problem stops the reading and is err. With p, every
 * field of every row is checked in one pass and each problem kept in p
 * (up to the cap); err is the only problem when there is one, else
 * "N of M rows refused (K problems)" naming the file, with the first
 * problem's code. A header that is not a components header, a quoted field
 * left open, text after a closing quote and too many rows stop the reading
 * at once (kept in p as well). On failure t is empty. */
sl_status sl_comp_table_read(const char *path, const sl_comp_results *r, sl_comp_table *t,
                             sl_comp_problems *p, sl_error *err);
void sl_comp_table_free(sl_comp_table *t);

/* The rocking block of row w (b = base_m / 2, h = cg_height_m, its
 * restitution and orientation, NAN: the defaults). */
sl_rockf_item sl_comp_rock_item(const sl_comp_row *w);
/* Give row i of t (mode rocking or both) its rocking result res: its
 * rocking verdict (sl_rockf_verdict_of at the row's clearance, targets
 * SL_ROCKF_P_TARGET_1, _2), the governing verdict, and t's counts. */
void sl_comp_set_rocking(sl_comp_table *t, size_t i, const sl_rockf_result *res);

/* The interpolation at mu on the grid mu[0..n) of the values c (the
 * Lookup's rule above): NAN when mu is off the grid or NAN. */
double sl_comp_interp(const double *mu, const double *c, size_t n, double mu_at);

/* The floor a building and a floor id or name give, resolved as a
 * components row is (the name rule; building "" or NULL: the only one, or
 * the folder's own name for one building). SL_EINVAL naming the known
 * buildings or the building's floors (err has no file: the caller says
 * where the names came from). */
sl_status sl_comp_find(const sl_comp_results *r, const char *building, const char *floor,
                       size_t *fi, sl_error *err);

/* One floor's numbers at mu, as a components row gets them: the required
 * clearance, its standard error and the ASCE value interpolated on the grid
 * (NAN off it), and the grid rows around mu (the last at or below, and the
 * next: their flags are the Lookup's). Returns 1 when mu is on the grid. */
typedef struct sl_comp_at {
    double required_mm, se_mm, asce_mm;
    size_t k0, k1;
} sl_comp_at;
int sl_comp_floor_at(const sl_comp_results *r, size_t fi, double mu, sl_comp_at *a);

/* The verdict's reason in words into buf ("required 59.3 mm (SE 6.4) >
 * available 50.0 mm: 9.3 mm short"; a rocking row: sl_comp_rock_prefix and
 * the excursion; a row checked both ways: "slides: ...; rocks: ..."); the
 * workbook's formula writes the same text. */
char *sl_comp_reason(const sl_comp_results *r, const sl_comp_row *w, char *buf, size_t n);
/* The part of a rocking row's reason that its clearance does not change
 * ("P(tip) 0.4 % (SE 0.2) at 1.0 x, ... (targets 1 %, 10 %)", then ": above
 * its target" or ": within 2 SE of its target after N sets"); the rest is
 * "; excursion E mm > available C mm: D mm short" or "... <= available C
 * mm" (none for overturns). Returns buf. */
char *sl_comp_rock_prefix(const sl_comp_row *w, char *buf, size_t n);

/* What the outputs record. */
typedef struct sl_comp_opts {
    const char *version;      /* "seislide 0.1.0" */
    const char *command_line; /* this command's */
    time_t created;
    const char *date;         /* the title block's Date (NULL: "-"): the CLI gives the
                                 created date, as `run` does */
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
