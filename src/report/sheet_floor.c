/* sheet_floor.c - one sheet per floor: what the floor is, its table against
 * mu and its chart (sheets.h). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/units.h"
#include "report/sheets.h"

enum { FL_COLS = 10 }; /* table columns: mu, x, 7 values, flags */
enum { CHART_ROWS = 33 }; /* rows of 20 pixels the chart covers, and one */

/* Column widths (characters): mu, mu g/ZPA, the values; flags as wide as
 * its longest text, at most FLAGS_MAX (then wrapped, rows grown). */
#define W_MU 6.0
#define W_X 6.0
#define W_VAL 8.5
#define W_REQ 10.0 /* the required clearance: its heading's "clearance," on one line */
#define W_FLAGS_MIN 10.0
#define W_FLAGS_MAX 17.0 /* 90 units in all: a portrait A4 page at 72 % (about 8 points a unit) */
/* the sheet's title: 14 points against the 11 the heights are reckoned in */
#define TITLE_PT 14.0
#define BODY_PT 11.0

#define C_NLTHA 0x1F4E79
#define C_ASCE 0xC55A11
#define C_MEAN 0x5B9BD5
#define C_CAP LXW_COLOR_BLACK /* libxlsxwriter's black: a colour 0 is "automatic" */
#define C_BAND 0xFF0000

static lxw_chart *floor_chart(lxw_workbook *wb, const sl_report *r, size_t i,
                              const sl_rpt_axes *ax)
{
    const sl_report_floor *fl = &r->floors[i];
    const sl_design *d = fl->design;
    size_t nf = r->n_floors, n = d->n;
    lxw_row_t r0 = SL_RPT_DATA_HEAD + 1, r1 = (lxw_row_t)(SL_RPT_DATA_HEAD + n);
    lxw_chart *ch = workbook_add_chart(wb, LXW_CHART_SCATTER_STRAIGHT);
    char name[128], title[300];
    snprintf(name, sizeof name, "NLTHA design (%g x mean)", d->fs_nltha);
    sl_rpt_add_series(ch, "Data", 0, sl_rpt_data_col_series(nf, i, SL_RPT_DS_NDESIGN), r0, r1,
                      name, C_NLTHA, 2.25f, LXW_CHART_LINE_DASH_SOLID, 0);
    snprintf(name, sizeof name, "ASCE design (%g x best estimate)", d->fs_asce);
    sl_rpt_add_series(ch, "Data", 0, sl_rpt_data_col_series(nf, i, SL_RPT_DS_ADESIGN), r0, r1,
                      name, C_ASCE, 2.25f, LXW_CHART_LINE_DASH_SOLID, 0);
    sl_rpt_add_series(ch, "Data", 0, sl_rpt_data_col_series(nf, i, SL_RPT_DS_MEAN), r0, r1,
                      "NLTHA mean", C_MEAN, 1.25f, LXW_CHART_LINE_DASH_DASH, 0);
    /* the cap: black, dash-dot and heavier than the light gridlines (layout.c) */
    snprintf(name, sizeof name, "cap (%g x mean peak floor displacement)", d->cap_factor);
    sl_rpt_add_series(ch, "Data", 0, sl_rpt_data_col_series(nf, i, SL_RPT_DS_CAP), r0, r1, name,
                      C_CAP, 1.75f, LXW_CHART_LINE_DASH_LONG_DASH_DOT, 0);
    int extra = 0;
    if (fl->design_lo_m && fl->design_hi_m) { /* the convergence band, when computed */
        sl_rpt_add_series(ch, "Data", 0, sl_rpt_data_col_series(nf, i, SL_RPT_DS_LO), r0, r1,
                          "NLTHA design, 90 % band", C_NLTHA, 0.75f,
                          LXW_CHART_LINE_DASH_ROUND_DOT, 0);
        sl_rpt_add_series(ch, "Data", 0, sl_rpt_data_col_series(nf, i, SL_RPT_DS_HI), r0, r1, "",
                          C_NLTHA, 0.75f, LXW_CHART_LINE_DASH_ROUND_DOT, 0);
        extra = 2;
    }
    lxw_row_t b = sl_rpt_data_band_row(r, i);
    for (size_t q = 0; q < d->n_ranges; q++, b += 2)
        sl_rpt_add_series(ch, "Data", 1, 2, b, b + 1, q ? "" : "ASCE below NLTHA (band)", C_BAND,
                          9.0f, LXW_CHART_LINE_DASH_SOLID, 50);
    if (d->n_ranges > 1 || extra) {
        int16_t del[64];
        size_t k = 0;
        if (extra)
            del[k++] = 5; /* the band's second line */
        for (size_t q = 1; q < d->n_ranges && k + 1 < 64; q++)
            del[k++] = (int16_t)(4 + extra + (int)q);
        del[k] = -1;
        chart_legend_delete_series(ch, del);
    }
    snprintf(title, sizeof title, "%s: design sliding displacement", fl->name);
    chart_title_set_name(ch, title);
    sl_rpt_chart_axes(ch, ax, "design sliding displacement");
    return ch;
}

/* A row spanning the table: label over columns A-C, value over D-J. */
static lxw_row_t info_row(lxw_worksheet *ws, const sl_rpt_fmts *F, lxw_row_t row,
                          const char *label, const char *value, double w_value)
{
    char kept[2400];
    worksheet_merge_range(ws, row, 0, row, 2, label, F->label);
    worksheet_merge_range(ws, row, 3, row, FL_COLS - 1,
                          sl_rpt_keep_units(value, kept, sizeof kept), F->note);
    double h = fmax(sl_rpt_text_height(label, W_MU + W_X + W_VAL, 1),
                    sl_rpt_text_height(value, w_value, 0));
    worksheet_set_row(ws, row, h, NULL);
    return row + 1;
}

void sl_rpt_floor_sheet(lxw_workbook *wb, const sl_rpt_fmts *F, const sl_report *r, size_t i,
                        const char *sheet_name, const sl_rpt_axes *ax)
{
    const sl_report_floor *fl = &r->floors[i];
    lxw_worksheet *ws = workbook_add_worksheet(wb, sheet_name);
    const sl_design *d = fl->design;
    char buf[1200], flags[256], path[1100];
    /* the flags column: as wide as its longest text */
    size_t longest = 0;
    for (size_t k = 0; k < d->n; k++) {
        size_t len = strlen(sl_report_flags(d->rows[k].flags, flags, sizeof flags));
        longest = len > longest ? len : longest;
    }
    double w_flags = fmin(W_FLAGS_MAX, fmax(W_FLAGS_MIN, (double)longest * 0.9 + 3));
    double w_all = W_MU + W_X + 6 * W_VAL + W_REQ + w_flags,
           w_value = 5 * W_VAL + W_REQ + w_flags;
    worksheet_set_column(ws, 0, 0, W_MU, NULL);
    worksheet_set_column(ws, 1, 1, W_X, NULL);
    worksheet_set_column(ws, 2, 7, W_VAL, NULL);
    worksheet_set_column(ws, 8, 8, W_REQ, NULL);
    worksheet_set_column(ws, 9, 9, w_flags, NULL);

    lxw_row_t row = 0;
    if (r->building && *r->building)
        snprintf(buf, sizeof buf, "Building %s, floor %s: %s", r->building, fl->id, fl->name);
    else
        snprintf(buf, sizeof buf, "Floor %s: %s", fl->id, fl->name);
    worksheet_merge_range(ws, row, 0, row, FL_COLS - 1, buf, F->title);
    worksheet_set_row(ws, row++, sl_rpt_text_height(buf, w_all * BODY_PT / TITLE_PT, 1) *
                                     TITLE_PT / BODY_PT, NULL);
    sl_rpt_failed_text(r, fl, buf, sizeof buf);
    if (buf[0]) { /* failed checks: the first thing the sheet says */
        worksheet_merge_range(ws, row, 0, row, FL_COLS - 1, buf, F->warn);
        worksheet_set_row(ws, row++, sl_rpt_text_height(buf, w_all, 1), NULL);
    }
    snprintf(buf, sizeof buf, "%s (%s, %s)", fl->id, sl_rpt_shown_path(fl->path, path, sizeof path),
             sl_rpt_or_dash(fl->units));
    row = info_row(ws, F, row, "id and file", buf, w_value);
    if (isfinite(fl->elevation_m))
        snprintf(buf, sizeof buf, "%g m; %s", fl->elevation_m, sl_rpt_or_dash(fl->description));
    else
        snprintf(buf, sizeof buf, "-; %s", sl_rpt_or_dash(fl->description));
    row = info_row(ws, F, row, "elevation; description", buf, w_value);
    snprintf(buf, sizeof buf, "%.3f g (mu g/ZPA = mu / %.3f)", fl->zpa_h_ms2 / SL_G,
             fl->zpa_h_ms2 / SL_G);
    row = info_row(ws, F, row, "horizontal ZPA", buf, w_value);
    row = info_row(ws, F, row, "ASCE < NLTHA for mu in", sl_report_ranges_text(d, buf, sizeof buf),
                   w_value);
    row = info_row(ws, F, row, "crossover", sl_rpt_crossover_text(d, buf, sizeof buf), w_value);
    snprintf(buf, sizeof buf,
             "policy %s; NLTHA design %g x mean of this floor's %zu sets, ASCE design %g x best "
             "estimate, both capped at %g x the mean peak floor displacement (the horizontals "
             "combined by the 100-40 rule)",
             sl_clearance_policy_name(d->policy), d->fs_nltha, d->n_sets, d->fs_asce,
             d->cap_factor);
    row = info_row(ws, F, row, "clearance; factors", buf, w_value);
    row = info_row(ws, F, row, "ASCE best estimate", sl_rpt_asce_shape_text(d, buf, sizeof buf),
                   w_value);
    if (*sl_rpt_asce_drops_text(d, 0, buf, sizeof buf))
        row = info_row(ws, F, row, "ASCE drops", buf, w_value);
    if (fl->sa10_fallback)
        row = info_row(ws, F, row, "ASCE spectrum", sl_rpt_sa10_text(fl), w_value);
    const char *note = fl->note ? fl->note : "";
    size_t ln = strlen(note); /* after a sentence, a blank; after a phrase, "; " */
    while (ln && note[ln - 1] == ' ')
        ln--;
    snprintf(buf, sizeof buf, "%.*s%s%zu friction values %s", (int)ln, note,
             !ln ? "" : note[ln - 1] == '.' ? " " : "; ", fl->n_mu_skipped,
             fl->scatter > 0 ? "with no sliding at any intensity of the scatter (mu g at or above "
                               "every motion's demand even at the strongest intensity)"
                             : "needed no NLTHA (mu g at or above every motion's demand)");
    row = info_row(ws, F, row, "note", buf, w_value);

    /* the chart under what the floor is, then the table from a new page,
     * last, so that its repeated header row is printed over table pages
     * only (LibreOffice repeats it from the page after the one it is on) */
    lxw_row_t chart_row = row + 1;
    /* as wide as the table and about as high (LibreOffice draws a column
     * half as wide again as libxlsxwriter's model, a row as high) */
    const double widths[FL_COLS] = {W_MU, W_X, W_VAL, W_VAL, W_VAL, W_VAL, W_VAL, W_VAL, W_REQ,
                                    w_flags};
    double xs = sl_rpt_chart_scale(widths, FL_COLS);
    lxw_chart_options co = {.x_offset = 0, .y_offset = 0, .x_scale = xs, .y_scale = 1.6 * xs};
    worksheet_insert_chart_opt(ws, chart_row, 0, floor_chart(wb, r, i, ax), &co);
    const char *band = "The red band along the bottom marks every range of mu where the ASCE "
                       "design value is below the NLTHA design value; the black dash-dot line "
                       "is the cap.";
    lxw_row_t band_row = chart_row + CHART_ROWS;
    worksheet_merge_range(ws, band_row, 0, band_row, FL_COLS - 1, band, F->note);
    worksheet_set_row(ws, band_row, sl_rpt_text_height(band, w_all, 0), NULL);

    /* what the columns hold, above the table (its headings stay short: no
     * factor in brackets broken across lines) */
    char legend[1600];
    snprintf(legend, sizeof legend, "Columns: NLTHA design = %g x NLTHA mean; ASCE design = %g x "
             "ASCE best estimate; cap = %g x the mean over the sets of the peak floor "
             "displacement (the horizontals combined by the 100-40 rule); each design value is "
             "at most the cap; required clearance by the policy (%s), shown to the digit of its "
             "standard error (whole mm from 1 mm). %s", d->fs_nltha, d->fs_asce, d->cap_factor,
             sl_clearance_policy_name(d->policy), sl_rpt_flags_legend());
    lxw_row_t legend_row = band_row + 2;
    worksheet_merge_range(ws, legend_row, 0, legend_row, FL_COLS - 1, legend, F->note);
    worksheet_set_row(ws, legend_row, sl_rpt_text_height(legend, w_all, 0), NULL);
    lxw_row_t head = legend_row + 1;
    char h[FL_COLS][96], hb[160];
    snprintf(h[0], sizeof h[0], "mu");
    snprintf(h[1], sizeof h[1], "mu g / ZPA");
    snprintf(h[2], sizeof h[2], "NLTHA mean, mm");
    snprintf(h[3], sizeof h[3], "NLTHA design, mm");
    snprintf(h[4], sizeof h[4], "its standard error, mm");
    snprintf(h[5], sizeof h[5], "ASCE best estimate, mm");
    snprintf(h[6], sizeof h[6], "ASCE design, mm");
    snprintf(h[7], sizeof h[7], "cap, mm");
    snprintf(h[8], sizeof h[8], "required clearance, mm");
    snprintf(h[9], sizeof h[9], "flags");
    double hh = 0;
    for (lxw_col_t c = 0; c < FL_COLS; c++) {
        double w = c == 0 ? W_MU : c == 1 ? W_X : c == 8 ? W_REQ : c == 9 ? w_flags : W_VAL;
        sl_rpt_header_text(h[c], w, hb, sizeof hb);
        worksheet_write_string(ws, head, c, hb, c == 9 ? F->header_ind : F->header_num);
        hh = fmax(hh, sl_rpt_text_height(hb, 1e3, 1)); /* its own lines */
    }
    worksheet_set_row(ws, head, hh, NULL);
    for (size_t k = 0; k < d->n; k++) {
        const sl_design_row *w = &d->rows[k];
        lxw_row_t rr = (lxw_row_t)(head + 1 + k);
        worksheet_write_number(ws, rr, 0, w->mu, F->mu);
        worksheet_write_number(ws, rr, 1, w->x, F->ratio);
        const double v[7] = {w->nltha_mean_m, w->nltha_design_m, sl_rpt_design_se_m(fl, k),
                             w->asce_best_m, w->asce_design_m, w->cap_m, w->clearance_m};
        int dec = sl_rpt_shown_decimals(fl, k); /* the clearance as summary.csv shows it */
        for (lxw_col_t c = 0; c < 7; c++)
            sl_rpt_num_or_blank(ws, rr, (lxw_col_t)(2 + c), SL_RPT_MM_PER_M * v[c],
                                c < 6 ? F->mm : dec ? F->mmbold : F->mm0bold);
        sl_report_flags(w->flags, flags, sizeof flags);
        worksheet_write_string(ws, rr, 9, flags[0] ? flags : "-", F->indent);
        double fh = sl_rpt_text_height(flags, w_flags - 1, 0); /* less the indent */
        if (fh > 20) /* more than a line */
            worksheet_set_row(ws, rr, fh, NULL);
    }
    lxw_row_t breaks[] = {head, 0}; /* the legend under the chart, the table from a new page */
    worksheet_set_h_pagebreaks(ws, breaks);
    sl_rpt_page_setup(ws, r, 0, fl->n_failed_motions ? fl->id : "");
    worksheet_set_print_scale(ws, SL_RPT_FLOOR_PRINT_SCALE);
    worksheet_repeat_rows(ws, head, head);
    worksheet_print_area(ws, 0, 0, (lxw_row_t)(head + d->n), FL_COLS - 1);
    sl_rpt_protect(ws);
}
