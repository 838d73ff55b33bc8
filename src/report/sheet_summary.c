/* sheet_summary.c - the "Summary" sheet: the clearance of every floor
 * against mu, each floor's numbers and statements, and one chart of every
 * floor; the named ranges the Lookup reads (sheets.h). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/units.h"
#include "report/sheets.h"

#define W_LABEL 16.0 /* column A: mu, and the labels below the table */
#define W_FLOOR 12.0 /* one column per floor: 4 floors fill a portrait A4 page */
/* A portrait A4 page inside the margins (layout.c): about 65 units wide
 * (8 points a unit) and 727 points high at 100 %; a floor's record that
 * would cross the page's end starts the next page (with a little room for
 * LibreOffice's own rounding of the row heights). */
#define PAGE_W_UNITS 65.0
#define PAGE_H_PT 700.0
#define ROW_PT 15.0 /* a row whose height is not set */
#define MAX_BREAKS 1000 /* page breaks of a sheet (Excel: 1,026) */

/* A label in A and its value merged over B..last, the row as tall as both
 * (its height added to *used, points). */
static lxw_row_t record_row(lxw_worksheet *ws, const sl_rpt_fmts *F, lxw_row_t row,
                            lxw_col_t last, const char *label, const char *value,
                            lxw_format *vf, double *used)
{
    char kept[2800];
    sl_rpt_keep_units(value, kept, sizeof kept);
    worksheet_write_string(ws, row, 0, label, F->label);
    if (last > 1)
        worksheet_merge_range(ws, row, 1, row, last, kept, vf);
    else
        worksheet_write_string(ws, row, 1, kept, vf);
    double h = fmax(sl_rpt_text_height(label, W_LABEL, 1),
                    sl_rpt_text_height(value, W_FLOOR * (double)last, vf == F->warn));
    worksheet_set_row(ws, row, h, NULL);
    *used += h;
    return row + 1;
}

/* Rows a chart of y_scale covers (288 pixels high at scale 1, rows of 20
 * pixels) and one. */
static lxw_row_t chart_rows(double y_scale) { return (lxw_row_t)ceil(288.0 * y_scale / 20.0) + 1; }

void sl_rpt_summary_sheet(lxw_workbook *wb, const sl_rpt_fmts *F, const sl_report *r,
                          const sl_rpt_axes *ax)
{
    lxw_worksheet *ws = workbook_add_worksheet(wb, "Summary");
    size_t n = r->floors[0].design->n, nf = r->n_floors;
    lxw_col_t last = (lxw_col_t)(nf > 3 ? nf : 3); /* the printed columns: B..last */
    char buf[2400], ids[400];
    worksheet_set_column(ws, 0, 0, W_LABEL, NULL);
    worksheet_set_column(ws, 1, last, W_FLOOR, NULL);
    sl_rpt_title_block(ws, F, r, "Required clearance per floor, mm", 0, last,
                       W_FLOOR * (double)last);
    sl_rpt_failed_ids(r, ids, sizeof ids);
    char wl[1200];
    sl_rpt_warnings_line(r, wl, sizeof wl); /* the run's warnings, also here */
    sl_rpt_warn_row(ws, F, ids, "below and Motion quality", wl, last,
                    W_LABEL + W_FLOOR * (double)last);
    /* Printed in this order, each part from a new page: the title block and
     * the chart of every floor; each floor's statements; the table, last,
     * so that its repeated header row is printed over table pages only
     * (LibreOffice repeats it from the page after the one it is on). */
    lxw_row_t chart_row = SL_RPT_SUM_HEAD + 1;
    lxw_chart *ch = workbook_add_chart(wb, LXW_CHART_SCATTER_STRAIGHT);
    static const lxw_color_t pal[] = {0x1F4E79, 0xC55A11, 0x548235, 0x7030A0, 0xBF9000, 0x2E75B6,
                                      0xFF0000, LXW_COLOR_BLACK /* 0 would be "automatic" */};
    for (size_t i = 0; i < nf; i++)
        sl_rpt_add_series(ch, "Data", 0, sl_rpt_data_col_series(nf, i, SL_RPT_DS_CLEAR),
                          SL_RPT_DATA_HEAD + 1, (lxw_row_t)(SL_RPT_DATA_HEAD + n),
                          r->floors[i].name, pal[i % 8], 2.0f,
                          (uint8_t)(i / 8 % 3 ? LXW_CHART_LINE_DASH_DASH
                                              : LXW_CHART_LINE_DASH_SOLID), 0);
    snprintf(buf, sizeof buf, "Required clearance (%s), every floor",
             sl_clearance_policy_name(r->floors[0].design->policy));
    chart_title_set_name(ch, buf);
    sl_rpt_chart_axes(ch, ax, "required clearance");
    /* as wide as the printed columns */
    double widths[64] = {W_LABEL};
    size_t nw = 1;
    for (; nw <= last && nw < 64; nw++)
        widths[nw] = W_FLOOR;
    double xs = sl_rpt_chart_scale(widths, nw);
    lxw_chart_options co = {.x_offset = 0, .y_offset = 0, .x_scale = xs, .y_scale = 1.6 * xs};
    worksheet_insert_chart_opt(ws, chart_row, 0, ch, &co);

    /* each floor's statements, one record per floor, a record never split
     * across two pages: the page's height in the sheet's points at the
     * scale the page's width sets */
    lxw_row_t row = chart_row + chart_rows(co.y_scale), statements = row;
    double scale = fmin(1.0, PAGE_W_UNITS / (W_LABEL + W_FLOOR * (double)last));
    double page_pt = PAGE_H_PT / scale, on_page = 0;
    lxw_row_t breaks[MAX_BREAKS + 3];
    size_t nb = 0;
    breaks[nb++] = statements;
    char path[1100];
    for (size_t i = 0; i < nf; i++) {
        const sl_report_floor *fl = &r->floors[i];
        lxw_row_t first = row;
        double used = 0;
        snprintf(buf, sizeof buf, "%s: %s", fl->id, fl->name);
        worksheet_merge_range(ws, row, 0, row, last, buf, F->header);
        double h = sl_rpt_text_height(buf, W_LABEL + W_FLOOR * (double)last, 1);
        worksheet_set_row(ws, row, h, NULL);
        used += h;
        row++;
        sl_rpt_failed_text(r, fl, buf, sizeof buf);
        if (buf[0])
            row = record_row(ws, F, row, last, "motion checks", buf, F->warn, &used);
        sl_rpt_shown_path(fl->path, path, sizeof path);
        if (isfinite(fl->elevation_m))
            snprintf(buf, sizeof buf, "%s; elevation %g m; %s", path, fl->elevation_m,
                     sl_rpt_or_dash(fl->description));
        else
            snprintf(buf, sizeof buf, "%s; %s", path, sl_rpt_or_dash(fl->description));
        row = record_row(ws, F, row, last, "file; description", buf, F->note, &used);
        row = record_row(ws, F, row, last, "crossover (docs/run.md)",
                         sl_rpt_crossover_text(fl->design, buf, sizeof buf), F->note, &used);
        row = record_row(ws, F, row, last, "ASCE below NLTHA for mu in",
                         sl_report_ranges_text(fl->design, buf, sizeof buf), F->note, &used);
        if (*sl_rpt_asce_drops_text(fl->design, 1, buf, sizeof buf))
            row = record_row(ws, F, row, last, "ASCE drops", buf, F->note, &used);
        if (fl->sa10_fallback)
            row = record_row(ws, F, row, last, "ASCE spectrum", sl_rpt_sa10_text(fl), F->note,
                             &used);
        char damp[1400] = "";
        if (sl_rpt_has_dampings(fl))
            sl_rpt_dampings_text(fl, damp, sizeof damp);
        snprintf(buf, sizeof buf, "%s%s%s", fl->note && *fl->note ? fl->note : damp[0] ? "" : "-",
                 fl->note && *fl->note && damp[0] ? "\n" : "", damp);
        row = record_row(ws, F, row, last, "note", buf, F->note, &used);
        row++;
        used += ROW_PT;
        if (on_page > 0 && on_page + used > page_pt && nb < MAX_BREAKS) {
            breaks[nb++] = first; /* the record starts a page */
            on_page = 0;
        }
        on_page += used;
    }

    /* the table: a row per mu, a column per floor, headed by what it holds
     * and the floor names, both printed over every table page */
    snprintf(buf, sizeof buf, "Required clearance, mm (policy %s), at each friction coefficient "
             "mu", sl_clearance_policy_name(r->floors[0].design->policy));
    lxw_row_t caption = row;
    worksheet_merge_range(ws, caption, 0, caption, last, buf, F->bold);
    worksheet_set_row(ws, caption, sl_rpt_text_height(buf, W_LABEL + W_FLOOR * (double)last, 1),
                      NULL);
    lxw_row_t head = caption + 1;
    worksheet_write_string(ws, head, 0, "mu", F->header_num);
    double hh = 15;
    for (size_t i = 0; i < nf; i++) {
        char name[600];
        sl_rpt_header_text(r->floors[i].name, W_FLOOR, name, sizeof name);
        worksheet_write_string(ws, head, (lxw_col_t)(i + 1), name, F->header_num);
        hh = fmax(hh, sl_rpt_text_height(name, 1e3, 1)); /* its own lines */
    }
    for (lxw_col_t c = (lxw_col_t)nf + 1; c <= last; c++)
        worksheet_write_blank(ws, head, c, F->header);
    worksheet_set_row(ws, head, hh, NULL);
    for (size_t k = 0; k < n; k++) {
        lxw_row_t rr = (lxw_row_t)(head + 1 + k);
        worksheet_write_number(ws, rr, 0, r->floors[0].design->rows[k].mu, F->mu);
        for (size_t i = 0; i < nf; i++)
            sl_rpt_num_or_blank(ws, rr, (lxw_col_t)(i + 1),
                                SL_RPT_MM_PER_M * r->floors[i].design->rows[k].clearance_m,
                                sl_rpt_shown_decimals(&r->floors[i], k) ? F->mm : F->mm0);
    }
    /* under it, short values, one column per floor (the Lookup reads ZPA and sets) */
    lxw_row_t b = (lxw_row_t)(head + n + 2);
    static const char *const lab[] = {"floor id", "horizontal ZPA, g", "motion sets",
                                      "sets stopped because"};
    for (lxw_row_t q = 0; q < 4; q++) {
        worksheet_write_string(ws, b + q, 0, lab[q], F->label);
        worksheet_set_row(ws, b + q, sl_rpt_text_height(lab[q], W_LABEL, 1), NULL);
    }
    double h_id = 15;
    for (size_t i = 0; i < nf; i++) {
        const sl_report_floor *fl = &r->floors[i];
        lxw_col_t c = (lxw_col_t)(i + 1);
        /* under the table's columns: at their right and at the top, as the numbers */
        worksheet_write_string(ws, b, c, fl->id, F->text_right);
        h_id = fmax(h_id, sl_rpt_text_height(fl->id, W_FLOOR, 0));
        worksheet_write_number(ws, b + 1, c, fl->zpa_h_ms2 / SL_G, F->ratio);
        worksheet_write_number(ws, b + 2, c, (double)fl->design->n_sets, F->mm0);
        worksheet_write_string(ws, b + 3, c, sl_rpt_or_dash(fl->sets_stop), F->text_right);
    }
    worksheet_set_row(ws, b, fmax(h_id, sl_rpt_text_height(lab[0], W_LABEL, 1)), NULL);

    /* named ranges the Lookup formulas read (floor_names: the Data sheet, the
     * names whole where the headings above break them into lines) */
    char last_col[8], def[160];
    sl_rpt_col_name(nf, last_col);
    snprintf(def, sizeof def, "=Summary!$A$%u:$A$%zu", (unsigned)head + 2, head + 1 + n);
    workbook_define_name(wb, "mu_grid", def);
    snprintf(def, sizeof def, "=Summary!$B$%u:$%s$%zu", (unsigned)head + 2, last_col,
             head + 1 + n);
    workbook_define_name(wb, "clearance_mm", def);
    snprintf(def, sizeof def, "=Summary!$B$%u:$%s$%u", (unsigned)b + 2, last_col, (unsigned)b + 2);
    workbook_define_name(wb, "floor_zpa_g", def);
    snprintf(def, sizeof def, "=Summary!$B$%u:$%s$%u", (unsigned)b + 3, last_col, (unsigned)b + 3);
    workbook_define_name(wb, "floor_sets", def);

    breaks[nb++] = caption;
    breaks[nb] = 0;
    worksheet_set_h_pagebreaks(ws, breaks);
    sl_rpt_page_setup(ws, r, 0, ids);
    worksheet_fit_to_pages(ws, 1, 0);
    worksheet_repeat_rows(ws, caption, head);
    worksheet_print_area(ws, 0, 0, b + 3, last);
    sl_rpt_protect(ws);
}
