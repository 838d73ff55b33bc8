/* sheet_rocking.c - the rocking lookup of every floor (run --rocking-lookup;
 * rock/rock_lookup.h, docs/rocking.md): the "Rocking" sheet, a table of the
 * probability of tipping over b/h and h per floor at the floor motion and at
 * 1.5 x it, coloured against the targets, with a chart; and
 * rocking_lookup.csv (sheets.h). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "report/sheets.h"
#include "core/units.h"
#include "rock/rock_lookup.h"

/* Columns: A b/h, B-F h at 1.0 x, G gap, H-L h at 1.5 x. */
#define C_BH 0
#define C_L1 1
#define C_L2 (C_L1 + SL_ROCKL_NH + 1)
#define N_COLS (C_L2 + SL_ROCKL_NH)
#define W_BH 9.0
#define W_P 8.0
#define W_GAP 3.0
/* Rows a floor's block takes: heading, level headings, h row, the grid, a
 * blank, then its chart (CHART_ROWS), a blank. */
#define CHART_ROWS 17
/* Page breaks between floors: at most this many (libxlsxwriter's limit is 1023). */
#define SL_RPT_ROCK_MAX_BREAKS 1000

int sl_rpt_has_rocking(const sl_report *r)
{
    for (size_t i = 0; i < r->n_floors; i++)
        if (r->floors[i].rock_lookup)
            return 1;
    return 0;
}

/* The verdict of one level: 0 below its target and decided, 1 below but not
 * decided (marginal), 2 above (rock_floor.h, the verdict and F6). */
static int level_state(const sl_rockf_level *v, double target)
{
    if (v->p_tip > target)
        return 2;
    int decided = v->p_tip == 0 || v->p_tip == 1 ||
                  (v->p_tip_se > 0 && target - v->p_tip > SL_ROCKF_SE_DECIDE * v->p_tip_se);
    return decided ? 0 : 1;
}

void sl_rpt_rocking_sheet(lxw_workbook *wb, const sl_rpt_fmts *F, const sl_report *r)
{
    lxw_worksheet *ws = workbook_add_worksheet(wb, "Rocking");
    double w_all = W_BH + 2 * SL_ROCKL_NH * W_P + W_GAP;
    worksheet_set_column(ws, C_BH, C_BH, W_BH, NULL);
    worksheet_set_column(ws, C_L1, C_L1 + SL_ROCKL_NH - 1, W_P, NULL);
    worksheet_set_column(ws, C_L1 + SL_ROCKL_NH, C_L1 + SL_ROCKL_NH, W_GAP, NULL);
    worksheet_set_column(ws, C_L2, C_L2 + SL_ROCKL_NH - 1, W_P, NULL);
    sl_rpt_title_block(ws, F, r, "Rocking: the probability that a slender item tips", 0,
                       N_COLS - 1, w_all);
    /* the colours of the three states */
    static const lxw_color_t bg[3] = {0xC6EFCE, 0xF8CBAD, 0xFFC7CE};
    static const lxw_color_t fg[3] = {0x006100, 0x833C0B, 0x9C0006};
    lxw_format *cell[3];
    for (int k = 0; k < 3; k++) {
        cell[k] = workbook_add_format(wb);
        format_set_num_format(cell[k], "0.0");
        format_set_bg_color(cell[k], bg[k]);
        format_set_font_color(cell[k], fg[k]);
        format_set_border(cell[k], LXW_BORDER_THIN);
        format_set_border_color(cell[k], 0xFFFFFF);
    }
    char note[1600];
    snprintf(note, sizeof note,
             "P(tip), %%: the probability that a rigid rectangular block tips (its rotation "
             "reaches alpha = atan(b/h)) on this floor, by NLTHA of the rocking block on the "
             "floor's own motion sets with the record-to-record intensity scatter of rocking "
             "(log standard deviation %.2f), its rocking axis the worst of every %g degrees, "
             "Housner's restitution; at the floor motion (1.0 x) and at 1.5 x it. b/h: half the "
             "base over the height of the centre of mass h. An item rocks (rather than slides) "
             "when its friction mu >= b/h. Green: below ASCE/SEI 43-05's target (%g %% at "
             "1.0 x, %g %% at 1.5 x) by more than %g standard errors; amber: below it but "
             "within the noise of the sets; red: above it. Between grid points read the next "
             "more slender row (larger P). An item on a components list gets its own NLTHA "
             "(seislide components; docs/rocking.md).",
             SL_ROCKF_SCATTER, SL_ROCKF_ORIENT_STEP_DEG, 100 * SL_ROCKF_P_TARGET_1,
             100 * SL_ROCKF_P_TARGET_2, SL_ROCKF_SE_DECIDE);
    lxw_row_t row = SL_RPT_TB_ROWS + 1;
    worksheet_merge_range(ws, row, 0, row, N_COLS - 1, note, F->note);
    worksheet_set_row(ws, row, sl_rpt_text_height(note, w_all, 0), NULL);
    row += 2;
    const double target[2] = {SL_ROCKF_P_TARGET_1, SL_ROCKF_P_TARGET_2};
    lxw_row_t breaks[SL_RPT_ROCK_MAX_BREAKS + 1] = {0};
    size_t n_breaks = 0;
    for (size_t i = 0; i < r->n_floors; i++) {
        const sl_report_floor *fl = &r->floors[i];
        if (!fl->rock_lookup)
            continue;
        char buf[600];
        snprintf(buf, sizeof buf, "%s (%s): ZPA %.2f g", fl->name, fl->id,
                 fl->zpa_h_ms2 / SL_G);
        worksheet_merge_range(ws, row, 0, row, N_COLS - 1, buf, F->bold);
        row++;
        worksheet_merge_range(ws, row, C_L1, row, C_L1 + SL_ROCKL_NH - 1,
                              "P(tip), % at 1.0 x (target 1 %)", F->header);
        worksheet_merge_range(ws, row, C_L2, row, C_L2 + SL_ROCKL_NH - 1,
                              "P(tip), % at 1.5 x (target 10 %)", F->header);
        row++;
        worksheet_write_string(ws, row, C_BH, "b/h \\ h, m", F->header);
        for (int j = 0; j < SL_ROCKL_NH; j++) {
            worksheet_write_number(ws, row, (lxw_col_t)(C_L1 + j), sl_rockl_h_m(j),
                                   F->header_num);
            worksheet_write_number(ws, row, (lxw_col_t)(C_L2 + j), sl_rockl_h_m(j),
                                   F->header_num);
        }
        const lxw_row_t r0 = row + 1;
        for (int b = 0; b < SL_ROCKL_NBH; b++) {
            row++;
            worksheet_write_number(ws, row, C_BH, sl_rockl_bh(b), F->ratio);
            for (int j = 0; j < SL_ROCKL_NH; j++) {
                const sl_rockf_result *x = &fl->rock_lookup[b * SL_ROCKL_NH + j];
                for (int l = 0; l < 2; l++)
                    worksheet_write_number(ws, row, (lxw_col_t)((l ? C_L2 : C_L1) + j),
                                           100 * x->level[l].p_tip,
                                           cell[level_state(&x->level[l], target[l])]);
            }
        }
        const lxw_row_t r1 = row;
        /* the chart: P(tip) against b/h, a line per h, both levels */
        lxw_chart *ch = workbook_add_chart(wb, LXW_CHART_SCATTER_STRAIGHT_WITH_MARKERS);
        static const lxw_color_t col[SL_ROCKL_NH] = {0x1F4E79, 0x2E75B6, 0x548235, 0xC55A11,
                                                     0x7030A0};
        for (int l = 0; l < 2; l++)
            for (int j = 0; j < SL_ROCKL_NH; j++) {
                char name[64];
                snprintf(name, sizeof name, "h %g m, %s", sl_rockl_h_m(j), l ? "1.5 x" : "1.0 x");
                sl_rpt_add_series(ch, "Rocking", C_BH, (lxw_col_t)((l ? C_L2 : C_L1) + j), r0, r1,
                                  name, col[j], l ? 1.0f : 2.0f,
                                  l ? LXW_CHART_LINE_DASH_DASH : LXW_CHART_LINE_DASH_SOLID, 0);
            }
        snprintf(buf, sizeof buf, "%s: P(tip) against b/h (solid 1.0 x, dashed 1.5 x)", fl->id);
        chart_title_set_name(ch, buf);
        chart_axis_set_name(ch->x_axis, "b/h (half the base over the height of the centre of mass)");
        chart_axis_set_name(ch->y_axis, "P(tip), %");
        chart_axis_set_min(ch->y_axis, 0);
        chart_axis_set_max(ch->y_axis, 100);
        chart_axis_set_min(ch->x_axis, sl_rockl_bh(0));
        chart_axis_set_max(ch->x_axis, sl_rockl_bh(SL_ROCKL_NBH - 1));
        chart_legend_set_position(ch, LXW_CHART_LEGEND_RIGHT);
        row += 2;
        lxw_chart_options co = {.x_scale = 1.55, .y_scale = 1.15};
        worksheet_insert_chart_opt(ws, row, 0, ch, &co);
        row += CHART_ROWS + 1;
        if (n_breaks < sizeof breaks / sizeof *breaks - 1)
            breaks[n_breaks++] = row; /* the next floor on a page of its own */
    }
    if (n_breaks > 1) {
        breaks[n_breaks - 1] = 0; /* the last floor's end is no break */
        worksheet_set_h_pagebreaks(ws, breaks);
    }
    sl_rpt_page_setup(ws, r, 0, "");
    worksheet_fit_to_pages(ws, 1, 0);
    sl_rpt_protect(ws);
}

sl_status sl_rpt_rocking_csv(const sl_report *r, FILE *f)
{
    sl_rpt_csv_head(f, r, "the rocking lookup of every floor (run --rocking-lookup): the "
                    "probability that a rigid block tips, over b/h and h");
    char buf[800];
    snprintf(buf, sizeof buf, "NLTHA of the rocking block (Housner 1963) on the floor's own sets, "
             "the horizontals scaled by a log-normal intensity factor of log standard deviation "
             "%.2f, the worst of every %g degrees of the rocking axis, Housner's restitution; "
             "p_tip, p_uplift at the floor motion, _15 at 1.5 x it; each with its standard error "
             "over rocking_sets sets (docs/rocking.md)", SL_ROCKF_SCATTER,
             SL_ROCKF_ORIENT_STEP_DEG);
    sl_rpt_csv_comment(f, "rocking", buf);
    snprintf(buf, sizeof buf, "stands when p_tip <= %g and p_tip_15 <= %g, each decided (more than "
             "%g SE below, or every set alike); marginal when below but not decided; overturns "
             "when above (the excursion against a gap is checked per item by seislide "
             "components)", SL_ROCKF_P_TARGET_1, SL_ROCKF_P_TARGET_2, SL_ROCKF_SE_DECIDE);
    sl_rpt_csv_comment(f, "verdict", buf);
    sl_rpt_csv_comment(f, "units", "b_over_h dimensionless; cg_height_m and base_m in m; "
                       "probabilities as fractions; excursion_mm in mm");
    fputs("floor_id,b_over_h,cg_height_m,base_m,rocking_sets,p_uplift,p_tip,p_tip_se,p_tip_15,"
          "p_tip_15_se,p_overturn_15,theta_over_alpha_p84,excursion_mm,verdict\r\n", f);
    static const char *const vn[3] = {"stands", "marginal", "overturns"};
    const double target[2] = {SL_ROCKF_P_TARGET_1, SL_ROCKF_P_TARGET_2};
    for (size_t i = 0; i < r->n_floors; i++) {
        const sl_report_floor *fl = &r->floors[i];
        if (!fl->rock_lookup)
            continue;
        for (int b = 0; b < SL_ROCKL_NBH; b++)
            for (int j = 0; j < SL_ROCKL_NH; j++) {
                const sl_rockf_result *x = &fl->rock_lookup[b * SL_ROCKL_NH + j];
                int s0 = level_state(&x->level[0], target[0]);
                int s1 = level_state(&x->level[1], target[1]);
                int s = s0 > s1 ? s0 : s1;
                sl_rpt_csv_field(f, fl->id);
                fprintf(f, ",%.2f,%.2f,%.3f,%zu,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.3f,%.1f,%s\r\n",
                        sl_rockl_bh(b), sl_rockl_h_m(j), 2 * sl_rockl_bh(b) * sl_rockl_h_m(j),
                        x->n_sets, x->level[0].p_uplift, x->level[0].p_tip,
                        x->level[0].p_tip_se, x->level[1].p_tip, x->level[1].p_tip_se,
                        x->level[1].p_overturn, x->level[0].theta_ratio_q,
                        1000 * x->excursion_m, vn[s]);
            }
    }
    return ferror(f) ? SL_EIO : SL_OK;
}
