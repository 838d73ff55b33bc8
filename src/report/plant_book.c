/* plant_book.c - plant.csv and plant.xlsx; see plant_book.h. */
#include "report/plant_book.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <xlsxwriter.h>

#include "core/units.h"
#include "io/atomic.h"
#include "report/sheets.h"

const double SL_PLANT_BOOK_MU[SL_PLANT_BOOK_NMU] = {0.05, 0.1, 0.2, 0.3, 0.4, 0.5};

/* The grid row of d at mu (within SL_PLANT_BOOK_MU_TOL), or NULL. */
static const sl_design_row *row_at(const sl_design *d, double mu)
{
    for (size_t k = 0; d && k < d->n; k++)
        if (fabs(d->rows[k].mu - mu) <= SL_PLANT_BOOK_MU_TOL)
            return &d->rows[k];
    return NULL; /* not a computed point: never interpolated between two */
}

double sl_plant_book_clearance(const sl_design *d, double mu)
{
    const sl_design_row *r = row_at(d, mu);
    return r ? r->clearance_m : NAN;
}

double sl_plant_book_asce(const sl_design *d, double mu)
{
    const sl_design_row *r = row_at(d, mu);
    return r ? r->asce_design_m : NAN;
}

const char *sl_plant_book_governing(const sl_design *d, char *buf, size_t n)
{
    int nl = 0, as = 0, cap = 0;
    for (size_t k = 0; k < d->n; k++) {
        const sl_design_row *r = &d->rows[k];
        if (!(r->clearance_m > 0))
            continue;
        int by_n = r->clearance_m == r->nltha_design_m, by_a = r->clearance_m == r->asce_design_m;
        nl |= by_n;
        as |= by_a && !by_n;
        cap |= r->clearance_m == r->cap_m;
    }
    if (!nl && !as) /* no sliding anywhere: the policy names the method */
        nl = d->policy != SL_CLEARANCE_ASCE, as = d->policy == SL_CLEARANCE_ASCE;
    snprintf(buf, n, "%s%s%s", nl && as ? "NLTHA and ASCE" : nl ? "NLTHA" : "ASCE",
             cap ? " (capped)" : "", "");
    return buf;
}

/* The floor's name as the Lookup lists it (its id when it has none), as the
 * building workbook's Lookup lists its floors. */
static const char *floor_name(const sl_plant_book_row *r)
{
    return r->name && *r->name ? r->name : r->id;
}

/* The motion checks of a row as text: "passed" or "FAILED n of m". */
static const char *checks_text(const sl_plant_book_row *r, char *buf, size_t n)
{
    if (!r->n_failed_motions)
        return "passed";
    snprintf(buf, n, "FAILED %zu of %zu", r->n_failed_motions, 3 * r->n_sets);
    return buf;
}

/* Decimals of a plant.csv clearance at mu: as many as summary.csv shows at
 * a grid mu (text.c: the place of the standard error's leading digit, 1 or
 * 0.1 mm); between grid rows, the more of the two rows around mu. */
static int csv_decimals(const sl_plant_book_row *r, double mu)
{
    const sl_report_floor fl = {.design = r->design, .design_se_m = r->design_se_m};
    size_t k1, k0 = sl_rpt_lookup_bracket(r->design, 1, mu, &k1);
    int d0 = sl_rpt_shown_decimals(&fl, k0), d1 = sl_rpt_shown_decimals(&fl, k1);
    return r->design->rows[k0].mu == mu || d0 > d1 ? d0 : d1;
}

/* The report the shared writers (csv.c, layout.c) read: the run's record
 * and title block, and one "floor" per row named BUILDING/ID for the
 * floor_file_crc32 lines (floors: NULL, none). */
static sl_status shared_report(const sl_plant_book *b, sl_report *r, sl_rpt_floors *floors,
                               const char *path, sl_error *err)
{
    sl_report_init(r);
    r->version = b->version;
    r->command_line = b->command_line;
    r->seed = b->seed;
    r->created = b->created;
    r->project = b->project;
    if (!floors)
        return SL_OK;
    if (sl_rpt_floors_alloc(floors, r, b->n, path, err))
        return err ? err->code : SL_ENOMEM;
    for (size_t i = 0; i < b->n; i++) {
        const sl_plant_book_row *w = &b->rows[i];
        sl_rpt_floors_set(floors, i, w->building, "/", w->id,
                          (sl_report_floor){.name = w->name, .path = w->path ? w->path : "-",
                                            .crc32 = w->crc32, .size_bytes = w->size_bytes});
    }
    return SL_OK;
}

sl_status sl_plant_book_write_csv(const sl_plant_book *b, const char *dir, sl_error *err)
{
    char path[4400], gov[64];
    snprintf(path, sizeof path, "%s/%s", dir, SL_PLANT_BOOK_CSV);
    for (size_t i = 0; i < b->n; i++)
        if (!isfinite(b->rows[i].zpa_h_ms2))
            return sl_error_set(err, SL_EINVAL, path, 0, "floor '%s/%s': ZPA not finite",
                                b->rows[i].building, b->rows[i].id);
    sl_report rep;
    sl_rpt_floors floors;
    if (shared_report(b, &rep, &floors, path, err))
        return err ? err->code : SL_ENOMEM;
    sl_atomic *a = sl_atomic_open(path, err);
    if (!a) {
        sl_rpt_floors_free(&floors);
        return err ? err->code : SL_EIO;
    }
    FILE *f = sl_atomic_file(a);
    char warn[600];
    for (size_t i = 0; i < b->n; i++) /* failed checks: the first lines, as in a building CSV */
        if (b->rows[i].n_failed_motions) {
            snprintf(warn, sizeof warn, "CHECKS FAILED: %zu of %zu motion components of floor "
                     "%s/%s failed their SRP 3.7.1 checks; its clearances were written only "
                     "because of --accept-failed-checks (%s/motion_quality.csv says which)",
                     b->rows[i].n_failed_motions, 3 * b->rows[i].n_sets, b->rows[i].building,
                     b->rows[i].id, b->rows[i].building);
            sl_rpt_csv_comment(f, "WARNING", warn);
        }
    sl_rpt_csv_head(f, &rep, "the plant index: one row per floor of every building; the "
                    "required clearance at six friction values, each where the run computed it "
                    "(empty where the friction grid does not hold it: never interpolated)");
    sl_rpt_floors_free(&floors);
    sl_rpt_csv_comment(f, "units", "elevation in m; ZPA in g; clearance in mm, shown to the "
                       "digit of its standard error (1 mm or 0.1 mm, as summary.csv); ASCE in "
                       "mm to 0.1 mm");
    sl_rpt_csv_comment(f, "asce_design_mm_mu_X", "the ASCE/SEI 43-05 design value at mu = X "
                       "(asce_design_mm of the floor's table), beside the clearance the "
                       "governing method gives (NLTHA under the default policy)");
    sl_rpt_csv_comment(f, "warnings", "every warning the run gave about the floor (its units, "
                       "the plausibility of its ZPA, a floor accepted with --accept-floor), as "
                       "the building's floors.csv; empty when none");
    fputs("building,floor,floor_name,elevation_m,zpa_g,sets,convergence", f);
    for (int k = 0; k < SL_PLANT_BOOK_NMU; k++)
        fprintf(f, ",clearance_mm_mu_%g", SL_PLANT_BOOK_MU[k]);
    fputs(",governing", f);
    for (int k = 0; k < SL_PLANT_BOOK_NMU; k++)
        fprintf(f, ",asce_design_mm_mu_%g", SL_PLANT_BOOK_MU[k]);
    fputs(",motion_checks,warnings\r\n", f);
    for (size_t i = 0; i < b->n; i++) {
        const sl_plant_book_row *r = &b->rows[i];
        sl_rpt_csv_field(f, r->building);
        fputc(',', f);
        sl_rpt_csv_field(f, r->id);
        fputc(',', f);
        sl_rpt_csv_field(f, r->name);
        fputc(',', f);
        if (isfinite(r->elevation_m))
            fprintf(f, "%.3f", r->elevation_m);
        fprintf(f, ",%.4f,%zu,%s", r->zpa_h_ms2 / SL_G, r->n_sets, r->stop);
        for (int k = 0; k < SL_PLANT_BOOK_NMU; k++) {
            double c = sl_plant_book_clearance(r->design, SL_PLANT_BOOK_MU[k]);
            fputc(',', f);
            if (isfinite(c))
                fprintf(f, "%.*f", csv_decimals(r, SL_PLANT_BOOK_MU[k]), 1e3 * c);
        }
        char chk[64];
        fprintf(f, ",%s", sl_plant_book_governing(r->design, gov, sizeof gov));
        for (int k = 0; k < SL_PLANT_BOOK_NMU; k++) {
            double asce = sl_plant_book_asce(r->design, SL_PLANT_BOOK_MU[k]);
            fputc(',', f);
            if (isfinite(asce))
                fprintf(f, "%.1f", SL_RPT_MM_PER_M * asce);
        }
        fprintf(f, ",%s,", checks_text(r, chk, sizeof chk));
        sl_rpt_csv_field(f, r->warnings ? r->warnings : "");
        fputs("\r\n", f);
    }
    return sl_atomic_commit(a, err);
}

/* Lookup cells (0-based rows; values in column B): the title block above
 * (rows 0-7, layout.c), the range of mu under its input. tests/test_plant.c
 * reads B14 (the clearance) and B15 (the input check). */
enum { LK_BUILDING = SL_RPT_TB_ROWS + 1, LK_FLOOR, LK_MU, LK_RANGE, LK_RESULT, LK_CHECK, LK_NOTE,
       LK_ZPA, LK_X, LK_SE, LK_FLAGS, LK_LEGEND, LK_SETS, LK_HOW, LK_ROW,
       LK_C1 = LK_ROW + 5 };
/* Lookup columns: labels, values; 64 units in all, a portrait A4 page at
 * 100 % (as the building Lookup, sheet_lookup.c). */
#define LK_W_A 36.0
#define LK_W_B 28.0

/* Plant sheet: the title, a note, two header rows (the clearance columns
 * under one heading), one row per floor. */
enum { PL_NOTE = 1, PL_HEAD = 3, PL_SUBHEAD, PL_FIRST, PL_CLEAR = 7,
       PL_GOV = PL_CLEAR + SL_PLANT_BOOK_NMU, PL_CHECKS, PL_COLS };
/* Each floor takes two rows: its clearances, then (grey) the ASCE design
 * values at the same mu, labelled under Governing. */
#define PL_ROWS_PER_FLOOR 2

/* Data: A building, B floor name, C building|floor name, D.. clearance on the grid
 * (row 1: the grid); the building list in the column after the grid; then
 * each floor's horizontal ZPA (g) and motion sets, the standard error of
 * its NLTHA design value on the grid (mm) and its flags on the grid (what
 * the Lookup shows beside the clearance, as the building Lookup does).
 * Hidden: not printed (the Plant sheet and each building's workbook hold
 * the same numbers), as the building workbook's Data (sheet_data.c). */
static size_t data_col_zpa(size_t n) { return 3 + n + 2; }
static size_t data_col_sets(size_t n) { return 3 + n + 3; }
static size_t data_col_se(size_t n) { return 3 + n + 4; }
static size_t data_col_flags(size_t n) { return 3 + 2 * n + 4; }
static void data_sheet(lxw_workbook *wb, const sl_rpt_fmts *F, const sl_plant_book *b,
                       const sl_report *rep)
{
    lxw_worksheet *ws = workbook_add_worksheet(wb, "Data");
    const sl_design *d0 = b->rows[0].design;
    char key[400];
    worksheet_write_string(ws, 0, 0, "building", F->header);
    worksheet_write_string(ws, 0, 1, "floor", F->header);
    worksheet_write_string(ws, 0, 2, "building|floor", F->header);
    for (size_t k = 0; k < d0->n; k++)
        worksheet_write_number(ws, 0, (lxw_col_t)(3 + k), d0->rows[k].mu, F->ratio);
    size_t bcol = 3 + d0->n + 1, nb = 0;
    worksheet_write_string(ws, 0, (lxw_col_t)bcol, "buildings", F->header);
    for (size_t i = 0; i < b->n; i++) {
        const sl_plant_book_row *r = &b->rows[i];
        lxw_row_t row = (lxw_row_t)(i + 1);
        worksheet_write_string(ws, row, 0, r->building, NULL);
        worksheet_write_string(ws, row, 1, floor_name(r), NULL);
        snprintf(key, sizeof key, "%s|%s", r->building, floor_name(r));
        worksheet_write_string(ws, row, 2, key, NULL);
        for (size_t k = 0; k < r->design->n; k++)
            worksheet_write_number(ws, row, (lxw_col_t)(3 + k),
                                   SL_RPT_MM_PER_M * r->design->rows[k].clearance_m, F->mm);
        if (i == 0 || strcmp(r->building, b->rows[i - 1].building))
            worksheet_write_string(ws, (lxw_row_t)(1 + nb++), (lxw_col_t)bcol, r->building, NULL);
        worksheet_write_number(ws, row, (lxw_col_t)data_col_zpa(d0->n), r->zpa_h_ms2 / SL_G, NULL);
        worksheet_write_number(ws, row, (lxw_col_t)data_col_sets(d0->n), (double)r->n_sets, NULL);
        const sl_report_floor fl = {.design = r->design, .design_se_m = r->design_se_m};
        char flags[256];
        for (size_t k = 0; k < r->design->n; k++) {
            worksheet_write_number(ws, row, (lxw_col_t)(data_col_se(d0->n) + k),
                                   SL_RPT_MM_PER_M * sl_rpt_design_se_m(&fl, k), NULL);
            sl_report_flags(r->design->rows[k].flags, flags, sizeof flags);
            worksheet_write_string(ws, row, (lxw_col_t)(data_col_flags(d0->n) + k),
                                   flags[0] ? flags : "-", NULL);
        }
    }
    worksheet_write_string(ws, 0, (lxw_col_t)data_col_zpa(d0->n), "zpa_g", F->header);
    worksheet_write_string(ws, 0, (lxw_col_t)data_col_sets(d0->n), "sets", F->header);
    for (size_t k = 0; k < d0->n; k++) {
        worksheet_write_number(ws, 0, (lxw_col_t)(data_col_se(d0->n) + k), d0->rows[k].mu,
                               F->ratio);
        worksheet_write_number(ws, 0, (lxw_col_t)(data_col_flags(d0->n) + k), d0->rows[k].mu,
                               F->ratio);
    }
    char c0[8], c1[8], def[200];
    sl_rpt_col_name(3, c0);
    sl_rpt_col_name(3 + d0->n - 1, c1);
    snprintf(def, sizeof def, "=Data!$%s$1:$%s$1", c0, c1);
    workbook_define_name(wb, "plant_mu_grid", def);
    snprintf(def, sizeof def, "=Data!$%s$2:$%s$%zu", c0, c1, b->n + 1);
    workbook_define_name(wb, "plant_clearance_mm", def);
    snprintf(def, sizeof def, "=Data!$C$2:$C$%zu", b->n + 1);
    workbook_define_name(wb, "plant_floor_keys", def);
    snprintf(def, sizeof def, "=Data!$A$2:$A$%zu", b->n + 1);
    workbook_define_name(wb, "plant_floor_buildings", def);
    sl_rpt_col_name(bcol, c0);
    snprintf(def, sizeof def, "=Data!$%s$2:$%s$%zu", c0, c0, nb + 1);
    workbook_define_name(wb, "plant_buildings", def);
    const struct { const char *name; size_t c0, c1; } more[] = {
        {"plant_zpa_g", data_col_zpa(d0->n), data_col_zpa(d0->n)},
        {"plant_sets", data_col_sets(d0->n), data_col_sets(d0->n)},
        {"plant_se_mm", data_col_se(d0->n), data_col_se(d0->n) + d0->n - 1},
        {"plant_flags", data_col_flags(d0->n), data_col_flags(d0->n) + d0->n - 1}};
    for (size_t k = 0; k < sizeof more / sizeof more[0]; k++) {
        sl_rpt_col_name(more[k].c0, c0);
        sl_rpt_col_name(more[k].c1, c1);
        snprintf(def, sizeof def, "=Data!$%s$2:$%s$%zu", c0, c1, b->n + 1);
        workbook_define_name(wb, more[k].name, def);
    }
    worksheet_set_column(ws, 0, 2, 24, NULL);
    sl_rpt_page_setup(ws, rep, 1, "");
    worksheet_hide(ws); /* not printed: LibreOffice and Excel print visible sheets only */
    sl_rpt_protect(ws);
}

/* Width of a column holding texts of at most `len` characters, in [lo, hi]
 * (wrapped beyond hi). */
static double text_width(size_t len, double lo, double hi)
{
    double w = 0.9 * (double)len + 1.5;
    return w < lo ? lo : w > hi ? hi : w;
}

/* A format for the Plant sheet's cells: numbers at the top of a row whose
 * wrapped texts make it taller (number format nf, NULL: general), aligned
 * right (a heading over numbers) when head. */
static lxw_format *top_format(lxw_workbook *wb, const char *nf, int head)
{
    lxw_format *f = workbook_add_format(wb);
    format_set_align(f, LXW_ALIGN_VERTICAL_TOP);
    if (nf)
        format_set_num_format(f, nf);
    if (head) {
        format_set_bold(f);
        format_set_align(f, LXW_ALIGN_RIGHT);
        format_set_bottom(f, LXW_BORDER_THIN);
    }
    return f;
}

static void plant_sheet(lxw_workbook *wb, const sl_rpt_fmts *F, const sl_plant_book *b,
                        const sl_report *rep)
{
    lxw_worksheet *ws = workbook_add_worksheet(wb, "Plant");
    lxw_format *num = top_format(wb, NULL, 0), *mm = top_format(wb, "0.0", 0),
               *mm0 = top_format(wb, "0", 0), /* shown as plant.csv shows it */
               *g = top_format(wb, "0.000", 0), *head_mu = top_format(wb, NULL, 1),
               *asce = top_format(wb, "0.0", 0), *asce_label = top_format(wb, NULL, 0);
    format_set_font_color(asce, 0x595959);
    format_set_font_color(asce_label, 0x595959);
    format_set_italic(asce_label);
    format_set_indent(asce_label, 1);
    size_t lb = 0, lf = 0, ln = 0;
    for (size_t i = 0; i < b->n; i++) {
        const sl_plant_book_row *r = &b->rows[i];
        lb = strlen(r->building) > lb ? strlen(r->building) : lb;
        lf = strlen(r->id) > lf ? strlen(r->id) : lf;
        ln = strlen(r->name) > ln ? strlen(r->name) : ln;
    }
    /* about 140 units: a landscape A4 page at about 70 %, the scale of the
     * building workbook's tables. Ids have no blanks: their columns grow
     * to 24 units (longer ids wrap inside); headings wrap between words. */
    double width[PL_COLS] = {text_width(lb, 9, 24), text_width(lf, 9, 24), text_width(ln, 12, 20),
                             11, 10, 6.5, 12}; /* "Elevation," and "Horizontal" on one line */
    for (int k = 0; k < SL_PLANT_BOOK_NMU; k++)
        width[PL_CLEAR + k] = 6;
    width[PL_GOV] = 13;
    width[PL_CHECKS] = 14;
    double w_all = 0;
    for (lxw_col_t c = 0; c < PL_COLS; c++) {
        worksheet_set_column(ws, c, c, width[c], NULL);
        w_all += width[c];
    }
    char h[64], gov[64], note[900];
    worksheet_write_string(ws, 0, 0, "Plant index: the required clearance of every floor",
                           F->title);
    snprintf(note, sizeof note, "One row per floor of every building. Clearance in mm at six "
             "friction values, each where the run computed it (empty where the friction grid does "
             "not hold it: never interpolated); Governing: the design curve that gives it "
             "(clearance policy %s), \"(capped)\" "
             "where the cap governs; under each floor, in grey, the ASCE/SEI 43-05 design value "
             "at the same friction values (ASCE design), beside it; Motion checks: FAILED where the floor's motions failed "
             "their SRP 3.7.1 checks and were accepted with --accept-failed-checks. Each building's workbook (<building>/"
             "seislide-clearance.xlsx) shows every floor's curves, standard errors and flags; "
             "the Lookup sheet interpolates at any mu.",
             sl_clearance_policy_name(b->rows[0].design->policy));
    worksheet_merge_range(ws, PL_NOTE, 0, PL_NOTE, PL_COLS - 1, note, F->note);
    worksheet_set_row(ws, PL_NOTE, sl_rpt_text_height(note, w_all, 0), NULL);
    static const char *const head[PL_CLEAR] = {"Building", "Floor", "Floor name",
                                               "Elevation, m", "Horizontal ZPA, g",
                                               "Motion sets", "Convergence"};
    double need = 0;
    for (lxw_col_t c = 0; c < PL_CLEAR; c++) { /* headings over numbers at their right */
        worksheet_merge_range(ws, PL_HEAD, c, PL_SUBHEAD, c, head[c],
                              c >= 3 && c <= 5 ? F->header_num : c == 6 ? F->header_ind
                              : F->header);
        need = fmax(need, sl_rpt_text_height(head[c], width[c], 1));
    }
    worksheet_merge_range(ws, PL_HEAD, PL_GOV, PL_SUBHEAD, PL_GOV, "Governing", F->header_ind);
    worksheet_merge_range(ws, PL_HEAD, PL_CHECKS, PL_SUBHEAD, PL_CHECKS, "Motion checks",
                          F->header_ind);
    worksheet_merge_range(ws, PL_HEAD, PL_CLEAR, PL_HEAD, PL_GOV - 1,
                          "Required clearance, mm, at mu =", F->header);
    for (int k = 0; k < SL_PLANT_BOOK_NMU; k++) {
        snprintf(h, sizeof h, "%g", SL_PLANT_BOOK_MU[k]);
        worksheet_write_string(ws, PL_SUBHEAD, (lxw_col_t)(PL_CLEAR + k), h, head_mu);
    }
    double h_head = sl_rpt_text_height("Required clearance, mm, at mu =",
                                       SL_PLANT_BOOK_NMU * width[PL_CLEAR], 1);
    worksheet_set_row(ws, PL_HEAD, h_head, NULL);
    worksheet_set_row(ws, PL_SUBHEAD, fmax(16, need - h_head), NULL);
    for (size_t i = 0; i < b->n; i++) {
        const sl_plant_book_row *r = &b->rows[i];
        lxw_row_t row = (lxw_row_t)(PL_FIRST + PL_ROWS_PER_FLOOR * i);
        sl_plant_book_governing(r->design, gov, sizeof gov);
        worksheet_write_string(ws, row, 0, r->building, F->wrap);
        worksheet_write_string(ws, row, 1, r->id, F->wrap);
        char name[600];
        worksheet_write_string(ws, row, 2, sl_rpt_keep_units(r->name, name, sizeof name),
                               F->wrap);
        sl_rpt_num_or_blank(ws, row, 3, r->elevation_m, num);
        worksheet_write_number(ws, row, 4, r->zpa_h_ms2 / SL_G, g);
        worksheet_write_number(ws, row, 5, (double)r->n_sets, num);
        worksheet_write_string(ws, row, 6, r->stop, F->indent);
        for (int k = 0; k < SL_PLANT_BOOK_NMU; k++)
            sl_rpt_num_or_blank(ws, row, (lxw_col_t)(PL_CLEAR + k),
                                SL_RPT_MM_PER_M * sl_plant_book_clearance(r->design,
                                                                          SL_PLANT_BOOK_MU[k]),
                                csv_decimals(r, SL_PLANT_BOOK_MU[k]) ? mm : mm0);
        worksheet_write_string(ws, row, PL_GOV, gov, F->indent);
        /* the ASCE design values beside it, on the row below */
        for (int k = 0; k < SL_PLANT_BOOK_NMU; k++)
            sl_rpt_num_or_blank(ws, row + 1, (lxw_col_t)(PL_CLEAR + k),
                                SL_RPT_MM_PER_M * sl_plant_book_asce(r->design,
                                                                     SL_PLANT_BOOK_MU[k]), asce);
        worksheet_write_string(ws, row + 1, PL_GOV, "ASCE design", asce_label);
        char chk_buf[64];
        const char *chk = checks_text(r, chk_buf, sizeof chk_buf);
        worksheet_write_string(ws, row, PL_CHECKS, chk, r->n_failed_motions ? F->warn : F->indent);
        double rh = fmax(sl_rpt_text_height(r->building, width[0], 0),
                         sl_rpt_text_height(r->id, width[1], 0));
        rh = fmax(rh, sl_rpt_text_height(r->name, width[2], 0));
        rh = fmax(rh, sl_rpt_text_height(gov, width[PL_GOV] - 1, 0)); /* indented */
        rh = fmax(rh, sl_rpt_text_height(chk, width[PL_CHECKS] - 1, r->n_failed_motions > 0));
        worksheet_set_row(ws, row, rh, NULL);
        worksheet_set_row(ws, row + 1, sl_rpt_text_height("ASCE design", width[PL_GOV] - 1, 0), NULL);
    }
    worksheet_freeze_panes(ws, PL_FIRST, 2);
    sl_rpt_page_setup(ws, rep, 1, "");
    worksheet_fit_to_pages(ws, 1, 0);
    worksheet_repeat_rows(ws, PL_HEAD, PL_SUBHEAD);
    sl_rpt_protect(ws);
}

static void lookup_sheet(lxw_workbook *wb, const sl_rpt_fmts *F, const sl_plant_book *b,
                         const sl_report *rep, size_t nb)
{
    lxw_worksheet *ws = workbook_add_worksheet(wb, "Lookup");
    const sl_design *d0 = b->rows[0].design;
    size_t n = d0->n;
    double mu_min = d0->rows[0].mu, mu_max = d0->rows[n - 1].mu;
    char f[1600], msg[160];
    int z = b->lookup_zero_cache;
    worksheet_set_column(ws, 0, 0, LK_W_A, NULL);
    worksheet_set_column(ws, 1, 1, LK_W_B, NULL);
    sl_rpt_title_block(ws, F, rep, "Required clearance around a component: whole plant", 0, 1,
                       LK_W_B);
    char failed[600] = "", wl[1200] = "";
    size_t used = 0, wused = 0;
    for (size_t i = 0; i < b->n && used + 1 < sizeof failed; i++)
        if (b->rows[i].n_failed_motions) {
            int w = snprintf(failed + used, sizeof failed - used, "%s%s/%s", used ? ", " : "",
                             b->rows[i].building, b->rows[i].id);
            used = w > 0 && used + (size_t)w < sizeof failed ? used + (size_t)w : sizeof failed - 1;
        }
    for (size_t i = 0; i < b->n && wused + 1 < sizeof wl; i++) /* the run's warnings, also here */
        if (b->rows[i].warnings && b->rows[i].warnings[0]) {
            int w = snprintf(wl + wused, sizeof wl - wused, "%s%s/%s: %s",
                             wused ? "; " : "WARNINGS (plant.csv column warnings; each "
                             "building's Notes): ", b->rows[i].building, b->rows[i].id,
                             b->rows[i].warnings);
            wused = w > 0 && wused + (size_t)w < sizeof wl ? wused + (size_t)w : sizeof wl - 1;
        }
    sl_rpt_warn_row(ws, F, failed, "sheet Plant, column Motion checks; each building's Motion "
                    "quality sheet", wl, 1, LK_W_A + LK_W_B);
    const char *b0 = b->lookup_building ? b->lookup_building : b->rows[0].building;
    const char *f0 = b->lookup_floor ? b->lookup_floor : floor_name(&b->rows[0]);
    double mu0 = b->lookup_mu;
    static const char *const in_label[3] = {"Building (choose from the list)",
                                            "Floor (choose from the list)",
                                            "Friction coefficient mu (type it)"};
    for (int k = 0; k < 3; k++) {
        worksheet_write_string(ws, (lxw_row_t)(LK_BUILDING + k), 0, in_label[k], F->bold);
        worksheet_set_row(ws, (lxw_row_t)(LK_BUILDING + k),
                          sl_rpt_text_height(in_label[k], LK_W_A, 1), NULL);
    }
    if (*b0)
        worksheet_write_string(ws, LK_BUILDING, 1, b0, F->input);
    else
        worksheet_write_blank(ws, LK_BUILDING, 1, F->input);
    if (*f0)
        worksheet_write_string(ws, LK_FLOOR, 1, f0, F->input);
    else
        worksheet_write_blank(ws, LK_FLOOR, 1, F->input);
    if (isfinite(mu0))
        worksheet_write_number(ws, LK_MU, 1, mu0, F->input);
    else
        worksheet_write_blank(ws, LK_MU, 1, F->input);
    snprintf(msg, sizeof msg, "the table covers mu %.2f to %.2f", mu_min, mu_max);
    worksheet_write_string(ws, LK_RANGE, 1, msg, F->note);
    lxw_data_validation dv;
    memset(&dv, 0, sizeof dv);
    dv.validate = LXW_VALIDATION_TYPE_LIST_FORMULA;
    dv.value_formula = "=plant_buildings";
    dv.input_title = "Building";
    dv.input_message = "Choose the building.";
    dv.error_title = "Unknown building";
    dv.error_message = "Choose a building from the list.";
    worksheet_data_validation_cell(ws, LK_BUILDING, 1, &dv);
    lxw_data_validation dfl;
    memset(&dfl, 0, sizeof dfl);
    dfl.validate = LXW_VALIDATION_TYPE_LIST_FORMULA;
    char lf[200];
    snprintf(lf, sizeof lf, "=OFFSET(Data!$B$1,MATCH($B$%d,plant_floor_buildings,0),0,"
             "COUNTIF(plant_floor_buildings,$B$%d),1)", LK_BUILDING + 1, LK_BUILDING + 1);
    dfl.value_formula = lf;
    dfl.input_title = "Floor";
    dfl.input_message = "Choose the floor the component stands on (the building's floors).";
    dfl.error_title = "Unknown floor";
    dfl.error_message = "Choose a floor of the chosen building from the list.";
    worksheet_data_validation_cell(ws, LK_FLOOR, 1, &dfl);
    lxw_data_validation dm;
    memset(&dm, 0, sizeof dm);
    dm.validate = LXW_VALIDATION_TYPE_DECIMAL;
    dm.criteria = LXW_VALIDATION_CRITERIA_BETWEEN;
    dm.minimum_number = mu_min;
    dm.maximum_number = mu_max;
    snprintf(msg, sizeof msg, "A number from %.2f to %.2f (static = kinetic friction).", mu_min,
             mu_max);
    dm.input_title = "Friction coefficient";
    dm.input_message = msg;
    dm.error_title = "mu outside the table";
    dm.error_message = msg;
    worksheet_data_validation_cell(ws, LK_MU, 1, &dm);

    /* the input check and the chain (lookup_formula.c), formulas and values */
    size_t fi = b->n;
    int bknown = 0;
    for (size_t i = 0; i < b->n; i++) {
        bknown |= !strcasecmp(b0, b->rows[i].building);
        if (fi == b->n && !strcasecmp(b0, b->rows[i].building) &&
            !strcasecmp(f0, floor_name(&b->rows[i])))
            fi = i;
    }
    char t_b[40], t_bu[80], t_f[40], t_fu[140], match[120];
    snprintf(t_b, sizeof t_b, "B%d=\"\"", LK_BUILDING + 1);
    snprintf(t_bu, sizeof t_bu, "ISNA(MATCH(B%d,plant_buildings,0))", LK_BUILDING + 1);
    snprintf(t_f, sizeof t_f, "B%d=\"\"", LK_FLOOR + 1);
    snprintf(match, sizeof match, "MATCH(B%d&\"|\"&B%d,plant_floor_keys,0)", LK_BUILDING + 1,
             LK_FLOOR + 1);
    snprintf(t_fu, sizeof t_fu, "ISNA(%s)", match);
    const sl_rpt_lookup_test tests[] = {
        {t_b, "choose a building from the list", !*b0},
        {t_bu, "unknown building: choose one from the list", !bknown},
        {t_f, "choose a floor from the list", !*f0},
        {t_fu, "unknown floor in this building: choose one from the list", fi == b->n}};
    const sl_rpt_lookup_cells cells = {.mu = LK_MU, .result = LK_RESULT, .check = LK_CHECK,
                                       .note = LK_NOTE, .steps = LK_ROW, .se = LK_SE,
                                       .sets = LK_SETS};
    int ok = sl_rpt_lookup_check(ws, F, z, &cells, tests, 4, NULL, mu0, mu_min, mu_max);
    /* the longest check text wraps to two lines in column B */
    worksheet_set_row(ws, LK_CHECK, sl_rpt_text_height(tests[3].message, LK_W_B, 1), NULL);
    const sl_rpt_lookup_table table = {.grid = "plant_mu_grid", .table = "plant_clearance_mm",
                                       .floor_match = match,
                                       .floor_step = "row of the floor in Data",
                                       .mu_step = "column of the mu at or below",
                                       .floors_down = 1, .width = LK_W_A + LK_W_B};
    sl_rpt_lookup_chain(ws, F, z, &cells, &table, ok ? b->rows[fi].design : d0, ok ? fi : 0,
                        mu0, ok);
    char longest[400]; /* room for both notes at once */
    snprintf(longest, sizeof longest, "only 9 motion sets (ASCE/SEI 43-05: at least 5). %s",
             SL_RPT_LOOKUP_NO_SLIDING);
    worksheet_set_row(ws, LK_NOTE, sl_rpt_text_height(longest, LK_W_B, 0), NULL);
    /* what the building Lookup shows beside the clearance (sheet_lookup.c): the
     * floor's ZPA, mu g/ZPA, the standard error interpolated as the clearance
     * is, the flags of the grid rows around mu, the floor's motion sets */
    const sl_plant_book_row *fr = ok ? &b->rows[fi] : NULL;
    const int CHK = LK_CHECK + 1, FR = LK_ROW + 1, KR = LK_ROW + 2, M0 = LK_ROW + 3,
              M1 = LK_ROW + 4;
    size_t k1, k0 = sl_rpt_lookup_bracket(d0, ok, mu0, &k1);
    worksheet_write_string(ws, LK_ZPA, 0, "Floor's horizontal ZPA, g", F->bold);
    snprintf(f, sizeof f, "=IF(B%d<>\"ok\",\"\",INDEX(plant_zpa_g,B%d))", CHK, FR);
    sl_rpt_lookup_formula(ws, z, LK_ZPA, f, ok ? fr->zpa_h_ms2 / SL_G : 0, ok ? NULL : "",
                          F->ratio);
    worksheet_write_string(ws, LK_X, 0, "mu g / ZPA", F->bold);
    snprintf(f, sizeof f, "=IF(B%d<>\"ok\",\"\",B%d/B%d)", CHK, LK_MU + 1, LK_ZPA + 1);
    sl_rpt_lookup_formula(ws, z, LK_X, f, ok ? mu0 * SL_G / fr->zpa_h_ms2 : 0, ok ? NULL : "",
                          F->ratio);
    worksheet_write_string(ws, LK_SE, 0, "Standard error of the NLTHA design value, mm", F->bold);
    worksheet_set_row(ws, LK_SE, sl_rpt_text_height("Standard error of the NLTHA design value, "
                                                    "mm", LK_W_A, 1), NULL);
    snprintf(f, sizeof f, "=IF(B%d<>\"ok\",\"\",INDEX(plant_se_mm,B%d,B%d)+IF(B%d=B%d,0,"
             "(B%d-B%d)*(INDEX(plant_se_mm,B%d,MIN(B%d+1,%zu))-INDEX(plant_se_mm,B%d,B%d))/"
             "(B%d-B%d)))", CHK, FR, KR, M1, M0, LK_MU + 1, M0, FR, KR, d0->n, FR, KR, M1, M0);
    double se = 0;
    if (ok) {
        const sl_report_floor rf = {.design = fr->design, .design_se_m = fr->design_se_m};
        double s0 = sl_rpt_design_se_m(&rf, k0), s1 = sl_rpt_design_se_m(&rf, k1);
        double m0 = fr->design->rows[k0].mu, m1 = fr->design->rows[k1].mu;
        se = SL_RPT_MM_PER_M * (s0 + (m1 == m0 ? 0 : (mu0 - m0) * (s1 - s0) / (m1 - m0)));
    }
    sl_rpt_lookup_formula(ws, z, LK_SE, f, se, ok ? NULL : "", F->mm);
    worksheet_write_string(ws, LK_FLAGS, 0, "Flags at the grid rows around mu", F->bold);
    snprintf(f, sizeof f, "=IF(B%d<>\"ok\",\"\",INDEX(plant_flags,B%d,B%d)&\" | \"&"
             "INDEX(plant_flags,B%d,MIN(B%d+1,%zu)))", CHK, FR, KR, FR, KR, d0->n);
    char fl0[256], fl1[256], flc[600] = "";
    if (ok) {
        sl_report_flags(fr->design->rows[k0].flags, fl0, sizeof fl0);
        sl_report_flags(fr->design->rows[k1].flags, fl1, sizeof fl1);
        snprintf(flc, sizeof flc, "%s | %s", fl0[0] ? fl0 : "-", fl1[0] ? fl1 : "-");
    }
    sl_rpt_lookup_formula(ws, z, LK_FLAGS, f, 0, flc, F->wrap);
    worksheet_set_row(ws, LK_FLAGS, sl_rpt_text_height("nltha_capped asce_capped "
                      "asce_below_nltha | nltha_capped asce_capped asce_below_nltha", LK_W_B, 0),
                      NULL);
    worksheet_merge_range(ws, LK_LEGEND, 0, LK_LEGEND, 1, sl_rpt_flags_legend(), F->note);
    worksheet_set_row(ws, LK_LEGEND, sl_rpt_text_height(sl_rpt_flags_legend(), LK_W_A + LK_W_B,
                                                        0), NULL);
    worksheet_write_string(ws, LK_SETS, 0, "Motion sets of the floor", F->bold);
    snprintf(f, sizeof f, "=IF(B%d<>\"ok\",\"\",INDEX(plant_sets,B%d))", CHK, FR);
    sl_rpt_lookup_formula(ws, z, LK_SETS, f, ok ? (double)fr->n_sets : 0, ok ? NULL : "", NULL);
    snprintf(f, sizeof f, "%zu buildings, %zu floors; clearance policy %s. Each building's "
             "workbook (<building>/seislide-clearance.xlsx) shows every floor's curves and the "
             "assumptions; the Plant sheet lists every floor.",
             nb, b->n, sl_clearance_policy_name(d0->policy));
    worksheet_merge_range(ws, LK_C1 + 2, 0, LK_C1 + 2, 1, f, F->note);
    worksheet_set_row(ws, LK_C1 + 2, sl_rpt_text_height(f, LK_W_A + LK_W_B, 0), NULL);
    sl_rpt_page_setup(ws, rep, 0, "");
    worksheet_fit_to_pages(ws, 1, 1); /* 64 units fit: 100 % */
    worksheet_activate(ws);
    sl_rpt_protect(ws);
}

sl_status sl_plant_book_write_xlsx(const sl_plant_book *b, const char *dir, sl_error *err)
{
    char path[4400];
    snprintf(path, sizeof path, "%s/%s", dir, SL_PLANT_BOOK_XLSX);
    if (b->n == 0)
        return sl_error_set(err, SL_EINVAL, path, 0, "no floors");
    for (size_t i = 1; i < b->n; i++) {
        const sl_design *d = b->rows[i].design, *d0 = b->rows[0].design;
        int same = d->n == d0->n;
        for (size_t k = 0; same && k < d->n; k++)
            same = d->rows[k].mu == d0->rows[k].mu;
        if (!same)
            return sl_error_set(err, SL_EINVAL, path, 0, "floor '%s/%s': another friction grid",
                                b->rows[i].building, b->rows[i].id);
    }
    sl_atomic *a;
    lxw_workbook *wb = sl_rpt_workbook_open(
        path, "Required clearance around unanchored components, whole plant", NULL, &b->project,
        b->created, &a, err);
    if (!wb)
        return err ? err->code : SL_EIO;
    sl_rpt_fmts F;
    sl_rpt_formats(wb, &F);
    sl_report rep; /* the title block and the record the page header and footer show */
    shared_report(b, &rep, NULL, path, err);
    size_t nb = 0;
    for (size_t i = 0; i < b->n; i++)
        nb += i == 0 || strcmp(b->rows[i].building, b->rows[i - 1].building) != 0;
    /* Lookup first (the sheet that opens), then the tables */
    lookup_sheet(wb, &F, b, &rep, nb);
    plant_sheet(wb, &F, b, &rep);
    data_sheet(wb, &F, b, &rep);
    return sl_rpt_workbook_close(wb, a, path, err);
}
