/*
 * sheets.h - the report's writers, one per sheet (sheet_*.c) and one for the
 * CSV files (csv.c), and what they share (layout.c: formats, row heights,
 * page setup, the title block, charts; text.c: the statements every sheet
 * and CSV makes about a floor). Internal to src/report: not installed, not
 * in seislide.h. report.c assembles the workbook from these.
 */
#ifndef SL_REPORT_SHEETS_H
#define SL_REPORT_SHEETS_H

#include <stddef.h>
#include <stdio.h>
#include <xlsxwriter.h>

#include "io/atomic.h"
#include "report/report.h"

#define SL_RPT_MM_PER_M 1000.0
#define SL_RPT_SHEET_NAME_MAX 31 /* Excel's limit */
#define SL_RPT_ID_MAX 64         /* longest floor id (sl_report_floor_id) */
#define SL_RPT_WORKBOOK "seislide-clearance.xlsx"
/* Print: the floor sheets' fixed scale, % (the PDF test checks >= 70 %). */
#define SL_RPT_FLOOR_PRINT_SCALE 72
/* Charts: log axis floor, mm (a log axis has no 0). */
#define SL_RPT_CHART_MIN_MM 0.1
/* Charts: the log axis ends at a power of ten at least this times the
 * largest value, so that the cap is never drawn on the top edge. */
#define SL_RPT_CHART_HEADROOM 2.0

typedef struct sl_rpt_fmts {
    lxw_format *bold, *title, *mm, *mm0, *mmbold, *ratio, *mu, *wrap, *result, *input, *header,
        *note, *label, *sci, *warn, *indent, *header_num;
    lxw_format *mm0bold;     /* a clearance shown to the whole mm, bold */
    lxw_format *dxf_mm0;     /* a conditional format: the number to the whole mm */
    lxw_format *header_ind;  /* a text heading after a number's heading: kept off it */
    lxw_format *text_right;  /* a text in a column of numbers: at their right, at the top */
    lxw_format *title_wrap;  /* a title merged over the printed columns, wrapped */
} sl_rpt_fmts;

/* Layout (0-based rows). */
enum {
    SL_RPT_TB_ROWS = 8,                  /* title + 7 fields */
    SL_RPT_WARN_ROW = SL_RPT_TB_ROWS,    /* failed checks, under the title block */
    SL_RPT_SUM_HEAD = SL_RPT_TB_ROWS + 1,/* Summary table header row */
    SL_RPT_DATA_HEAD = 3,                /* Data sheet header row */
};

/* Data sheet series per floor (chart columns). */
enum { SL_RPT_DS_NDESIGN, SL_RPT_DS_ADESIGN, SL_RPT_DS_MEAN, SL_RPT_DS_CAP, SL_RPT_DS_CLEAR,
       SL_RPT_DS_LO, SL_RPT_DS_HI, SL_RPT_DS_N };

/* The chart axes every chart shares: x = mu over the grid, y = log over
 * every floor, its top a decade above the largest value's so that no curve
 * (the cap above all) runs along the top edge. */
typedef struct sl_rpt_axes {
    double mu_min, mu_max, y_min, y_max;
} sl_rpt_axes;

/* report.c: SL_EINVAL naming the floor when a number to be written is not
 * finite (ASCE may be undefined: NAN, an empty cell), or the floors do not
 * share the friction grid. */
sl_status sl_rpt_check_finite(const sl_report *r, sl_error *err);

/* ---- text.c: statements about a floor ---------------------------------- */
double sl_rpt_design_se_m(const sl_report_floor *fl, size_t k);
int sl_rpt_shown_decimals(const sl_report_floor *fl, size_t k);
int sl_rpt_has_dampings(const sl_report_floor *fl);
char *sl_rpt_crossover_text(const sl_design *d, char *buf, size_t n);
char *sl_rpt_asce_shape_text(const sl_design *d, char *buf, size_t n);
/* "" when every motion of the floor passed its checks; else "CHECKS FAILED:
 * 12 of 204 motion components of this floor failed their SRP 3.7.1 checks
 * (below 5, run_below 7; ...)", counted from r->quality. */
char *sl_rpt_failed_text(const sl_report *r, const sl_report_floor *fl, char *buf, size_t n);
/* The ids of the floors whose motions failed ("" when none), ", "-separated. */
char *sl_rpt_failed_ids(const sl_report *r, char *buf, size_t n);
/* What every flag word means (the legend under the tables that show them). */
const char *sl_rpt_flags_legend(void);
/* The other-damping check explained for a page ("informational: ..."),
 * with the floor's text (sl_report_floor.dampings) after it. */
char *sl_rpt_dampings_text(const sl_report_floor *fl, char *buf, size_t n);
/* Where the ASCE estimate of d drops: to 0 from the first grid row where it
 * stays 0 (mu_e g reaches the ZPA), and every step between two grid rows
 * (f_es jumps past a peak of the spectrum): "" when none; brief: without
 * the why (said once around it, the Notes). */
char *sl_rpt_asce_drops_text(const sl_design *d, int brief, char *buf, size_t n);
/* "" when the floor file has a 10 % table; else what ASCE used instead. */
const char *sl_rpt_sa10_text(const sl_report_floor *fl);
/* "FLOOR: N sets; FLOOR: N sets; ..." (every floor's own count). */
char *sl_rpt_sets_text(const sl_report *r, const char *fmt, char *buf, size_t n);
const char *sl_rpt_or_dash(const char *s);
/* The floor's warnings (sl_report_floor.warnings; when NULL, the unusual-ZPA
 * warning worked out from its units and ZPA); "" when none. */
const char *sl_rpt_floor_warnings(const sl_report_floor *fl);
/* "WARNINGS (...): ID: text; ID: text" over every floor with a warning, cut
 * to n with "..."; "" when none. The Lookup and Summary sheets show it. */
char *sl_rpt_warnings_line(const sl_report *r, char *buf, size_t n);

/* ---- csv.c: what the plant index (plant_book.c) shares ------------------ */
/* The comment lines every CSV of the run starts with (report.h,
 * sl_report_write_csv): "# WARNING:" per floor whose motions failed, then
 * program, content (`what`), command, created, seed, "# floor_file_crc32:"
 * per floor of r, project, document, revision. */
void sl_rpt_csv_head(FILE *f, const sl_report *r, const char *what);
/* "# key: value" (line breaks in value made blanks), CRLF. */
void sl_rpt_csv_comment(FILE *f, const char *key, const char *value);
/* One RFC 4180 field, quoted when needed. */
void sl_rpt_csv_field(FILE *f, const char *s);
/* The floors of a report built from rows named BUILDING<sep>ID (the plant
 * index, the components CSV): the entries and their id texts, which
 * sl_rpt_floors_alloc allocates (at least one of each; SL_ENOMEM with path
 * on failure) and hangs on rep (floors, n_floors = n), and
 * sl_rpt_floors_free frees. */
#define SL_RPT_QID_MAX (2 * SL_RPT_ID_MAX + 2)
typedef struct sl_rpt_floors {
    sl_report_floor *floor;
    char (*id)[SL_RPT_QID_MAX];
} sl_rpt_floors;
sl_status sl_rpt_floors_alloc(sl_rpt_floors *fl, sl_report *rep, size_t n, const char *path,
                              sl_error *err);
/* Floor i: f, with the id "building sep id" written into fl. */
void sl_rpt_floors_set(sl_rpt_floors *fl, size_t i, const char *building, const char *sep,
                       const char *id, sl_report_floor f);
void sl_rpt_floors_free(sl_rpt_floors *fl);

/* ---- workbook.c -------------------------------------------------------- */
/* A new workbook at `path`, written through sl_atomic (*a), with its
 * document properties (subject may be NULL; created <= 0 is written as one
 * second after the epoch: libxlsxwriter reads 0 as "now"). NULL on error,
 * err set and nothing left behind. */
lxw_workbook *sl_rpt_workbook_open(const char *path, const char *title, const char *subject,
                                   const sl_report_project *project, time_t created,
                                   sl_atomic **a, sl_error *err);
/* Close wb and rename it over `path` (or remove it on error). */
sl_status sl_rpt_workbook_close(lxw_workbook *wb, sl_atomic *a, const char *path, sl_error *err);
/* Close a workbook not wanted (an error before it was complete) and abort a. */
void sl_rpt_workbook_discard(lxw_workbook *wb, sl_atomic *a);

/* ---- lookup_formula.c: the Lookup chain of both workbooks ----------------- */
/* The rows (0-based) of a Lookup's cells in column B: the mu input, the
 * result, the input check, the note, and the six visible steps from row
 * `steps` on (where the floor is, where mu is, the grid mu at or below and
 * above, their clearances), under a heading in row steps - 1. */
typedef struct sl_rpt_lookup_cells {
    int mu, result, check, note, steps;
    /* the rows of the standard error of the result (mm) and of the floor's
     * number of motion sets, 0 when the sheet has none: the result and the
     * clearances of the steps are shown to the digit of the standard error
     * (whole mm from 1 mm, as the tables), and the note says when the sets
     * are fewer than the standard's minimum (SL_NLTHA_MIN_SETS) */
    int se, sets;
} sl_rpt_lookup_cells;
/* Where a Lookup's table lies: named ranges of the friction grid and the
 * clearances in mm; floors_down: 1 when the table has a row per floor and
 * the grid is a row (plant), 0 when it has a row per grid mu and a column
 * per floor (building); the formula that gives the floor's index in the
 * table (MATCH(...)); the labels of the first two steps; the width of
 * columns A:B. */
typedef struct sl_rpt_lookup_table {
    const char *grid, *table, *floor_match, *floor_step, *mu_step;
    int floors_down;
    double width;
} sl_rpt_lookup_table;
/* One test of a Lookup's inputs: its Excel condition, the message shown
 * when it holds, and whether it holds for the initial inputs. */
typedef struct sl_rpt_lookup_test {
    const char *formula, *message;
    int holds;
} sl_rpt_lookup_test;
#define SL_RPT_LOOKUP_NO_SLIDING \
    "no sliding predicted: mu g is at or above what every motion demands"
/* A formula in column B with its cached value (a number v, or the text s
 * when given); zero_cache: 0 (tests/test_lookup.c, tests/test_plant.c). */
void sl_rpt_lookup_formula(lxw_worksheet *ws, int zero_cache, lxw_row_t row, const char *f,
                           double v, const char *s, lxw_format *fmt);
/* The grid rows of d around mu, as the formulas find them (MATCH(mu,
 * grid,1) and the next): returns k0, the last row whose mu is at or below
 * mu (0 when !ok), and sets *k1 to the row after it (k0 at the grid's end). */
size_t sl_rpt_lookup_bracket(const sl_design *d, int ok, double mu, size_t *k1);
/* The interpolation of the Lookups and of the Components sheet as formula
 * text (no '='), over the cells named: IF(mu1=mu0,c0,c0+(mu-mu0)*(c1-c0)/
 * (mu1-mu0)), the rule of sl_design_clearance_at (sl_comp_interp is its C
 * twin, operation for operation). Into buf of size n; returns buf. */
char *sl_rpt_interp_formula(char *buf, size_t n, const char *mu, const char *mu0, const char *mu1,
                            const char *c0, const char *c1);
/* "Input check": the message of the first of tests[] that holds, else of
 * the mu tests every Lookup shares (mu blank or typed as text `mu_text`:
 * "type mu" / "mu must be a number"; outside [mu_min, mu_max]), else "ok";
 * formula and cached value alike. Returns 1 when the check is "ok". */
int sl_rpt_lookup_check(lxw_worksheet *ws, const sl_rpt_fmts *F, int zero_cache,
                        const sl_rpt_lookup_cells *c, const sl_rpt_lookup_test *tests,
                        size_t n_tests, const char *mu_text, double mu, double mu_min,
                        double mu_max);
/* The heading and the six steps over table t, the "Required clearance, mm"
 * result (linear interpolation in mu) and the no-sliding note: formulas,
 * and cached values from d (the chosen floor's design when ok, any floor's
 * otherwise) at floor_index (0-based) and mu. Returns the result in mm (NAN
 * when !ok). */
double sl_rpt_lookup_chain(lxw_worksheet *ws, const sl_rpt_fmts *F, int zero_cache,
                           const sl_rpt_lookup_cells *c, const sl_rpt_lookup_table *t,
                           const sl_design *d, size_t floor_index, double mu, int ok);
/* The text of the interpolation formula of the result cell (into f, size n;
 * SL_RPT_LOOKUP_RESULT_LEN is enough): "=IF(B<check><>"ok","-",...)" over
 * the steps' cells (mu0, mu1, c0, c1 at rows steps + 2 ... steps + 5). */
#define SL_RPT_LOOKUP_RESULT_LEN 512
void sl_rpt_lookup_result_text(char *f, size_t n, const sl_rpt_lookup_cells *c);

/* ---- layout.c ---------------------------------------------------------- */
void sl_rpt_formats(lxw_workbook *wb, sl_rpt_fmts *F);
/* Row height, points, that shows `s` whole when wrapped in a column (or
 * merged range) `width` characters wide (LibreOffice does not grow a row
 * whose height a file sets, nor one it reads without one). */
double sl_rpt_text_height(const char *s, double width, int bold);
/* A column heading broken into lines ('\n', at blanks) two characters
 * shorter than a column `width` wide holds in bold, so that no heading
 * runs into the next one (into buf of size n). */
char *sl_rpt_header_text(const char *s, double width, char *buf, size_t n);
/* The x_scale of a chart as wide as n columns of these widths. */
double sl_rpt_chart_scale(const double *width, size_t n);
/* Page setup shared by every sheet: A4, margins, a two-line header with the
 * title block's identity on the left and the sheet on the right (and the
 * floors whose checks failed), footer with program, file and page x of y. */
void sl_rpt_page_setup(lxw_worksheet *ws, const sl_report *r, int landscape,
                       const char *failed_ids);
void sl_rpt_protect(lxw_worksheet *ws);
/* The title block: rows 0-7 from column c, values merged over columns
 * c+1..c_last (together `width` characters wide); row heights fit. */
void sl_rpt_title_block(lxw_worksheet *ws, const sl_rpt_fmts *F, const sl_report *r,
                        const char *title, lxw_col_t c, lxw_col_t c_last, double width);
/* The warning row under the title block (SL_RPT_WARN_ROW, merged over
 * columns 0..c_last, `width` characters wide): "CHECKS FAILED: motions of
 * floor(s) IDS failed their SRP 3.7.1 checks; ... (WHERE)" when ids is not
 * empty, then the run's warnings wl; no row when both are empty. */
void sl_rpt_warn_row(lxw_worksheet *ws, const sl_rpt_fmts *F, const char *ids,
                     const char *where, const char *wl, lxw_col_t c_last, double width);
void sl_rpt_col_name(size_t c, char *buf);
void sl_rpt_num_or_blank(lxw_worksheet *ws, lxw_row_t row, lxw_col_t col, double v,
                         lxw_format *f);
sl_rpt_axes sl_rpt_shared_axes(const sl_report *r);
/* The shared axes (x mu, y log), y titled "<quantity>, mm (log scale)". */
void sl_rpt_chart_axes(lxw_chart *ch, const sl_rpt_axes *ax, const char *quantity);
/* s with the blank between a number and its unit ("0.3 g", "12 m", "5 %")
 * made a no-break space (U+00A0), so that a wrapped text never leaves a
 * number at a line's end and its unit on the next (into buf). */
char *sl_rpt_keep_units(const char *s, char *buf, size_t n);
/* A path as a printed page shows it: as written when relative; an absolute
 * one (a machine's own folders) as ".../<folder>/<file>", its last two
 * parts (the CSV files keep it whole, for the record). Into buf. */
char *sl_rpt_shown_path(const char *path, char *buf, size_t n);
/* A command line broken into lines of at most width characters at the
 * blanks between its words (a word in quotes is one word), each line but
 * the last ending in " \": the cell copies into a shell as one command.
 * Into buf; returns the lines. */
int sl_rpt_command_lines(const char *cmd, size_t width, char *buf, size_t n);
void sl_rpt_add_series(lxw_chart *ch, const char *sheet, lxw_col_t xc, lxw_col_t yc,
                       lxw_row_t r0, lxw_row_t r1, const char *name, lxw_color_t color,
                       float width, uint8_t dash, uint8_t transparency);
/* Sheet names of the floors (names[i], 4 SL_RPT_SHEET_NAME_MAX + 1 bytes
 * each: 31 characters of UTF-8): the floor ids as written, Excel's
 * forbidden characters []:*?/\ (and an apostrophe at either end) made '_',
 * cut at 31 characters, when they are unique without case and none is
 * another sheet's name; else "F1", "F2", ... */
void sl_rpt_sheet_names(const sl_report *r, char (*names)[SL_RPT_SHEET_NAME_MAX * 4 + 1]);

/* ---- the sheets -------------------------------------------------------- */
void sl_rpt_lookup_sheet(lxw_workbook *wb, const sl_rpt_fmts *F, const sl_report *r);
void sl_rpt_summary_sheet(lxw_workbook *wb, const sl_rpt_fmts *F, const sl_report *r,
                          const sl_rpt_axes *ax);
void sl_rpt_floor_sheet(lxw_workbook *wb, const sl_rpt_fmts *F, const sl_report *r, size_t i,
                        const char *sheet_name, const sl_rpt_axes *ax);
void sl_rpt_quality_sheet(lxw_workbook *wb, const sl_rpt_fmts *F, const sl_report *r);
/* sheet_rocking.c: 1 when some floor has its rocking lookup; the Rocking
 * sheet; rocking_lookup.csv's content into f (after its trace lines). */
int sl_rpt_has_rocking(const sl_report *r);
void sl_rpt_rocking_sheet(lxw_workbook *wb, const sl_rpt_fmts *F, const sl_report *r);
sl_status sl_rpt_rocking_csv(const sl_report *r, FILE *f);
void sl_rpt_notes_sheet(lxw_workbook *wb, const sl_rpt_fmts *F, const sl_report *r);
void sl_rpt_inputs_sheet(lxw_workbook *wb, const sl_rpt_fmts *F, const sl_report *r);
void sl_rpt_data_sheet(lxw_workbook *wb, const sl_rpt_fmts *F, const sl_report *r,
                       const sl_rpt_axes *ax);

/* Data sheet columns: A mu, then per floor i of nf: se (1 + i), flags
 * (1 + nf + i), chart series s (1 + 2 nf + SL_RPT_DS_N i + s); the band
 * block (two rows per ASCE-below-NLTHA range) of floor i from
 * sl_rpt_data_band_row. */
lxw_col_t sl_rpt_data_col_se(size_t nf, size_t i);
lxw_col_t sl_rpt_data_col_flags(size_t nf, size_t i);
lxw_col_t sl_rpt_data_col_series(size_t nf, size_t i, int s);
lxw_row_t sl_rpt_data_band_row(const sl_report *r, size_t i);

#endif
