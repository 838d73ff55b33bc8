/* sheet_quality.c - the "Motion quality" sheet: the SRP 3.7.1 checks of the
 * synthesized motions, one row per three-component set with its verdict
 * (every component's values are in motion_quality.csv); each floor's count
 * of failures first (sheets.h). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "report/sheets.h"
#include "synth/synth.h"

enum { Q_COLS = 10 };
#define W_VERDICT 19.0

void sl_rpt_quality_sheet(lxw_workbook *wb, const sl_rpt_fmts *F, const sl_report *r)
{
    lxw_worksheet *ws = workbook_add_worksheet(wb, "Motion quality");
    size_t w_id = 8;
    for (size_t i = 0; i < r->n_floors; i++)
        w_id = strlen(r->floors[i].id) > w_id ? strlen(r->floors[i].id) : w_id;
    /* about 86 units: a portrait A4 page at 75 % */
    const double width[Q_COLS] = {(double)w_id * 0.9 + 1.5, 4, 6.5, 6.5, 6.5, 7.5, 7.5, 9.5, 10.5,
                                  W_VERDICT};
    double w_all = 0;
    for (lxw_col_t c = 0; c < Q_COLS; c++) {
        worksheet_set_column(ws, c, c, width[c], NULL);
        w_all += width[c];
    }
    char buf[1200], ids[400];
    lxw_row_t row = 0;
    worksheet_write_string(ws, row++, 0, "Motion quality: the SRP 3.7.1 checks, one row per set",
                           F->title);
    const char *intro = "Each row is one synthesized three-component set: the extremes over its "
                        "components H1, H2 and V. S/T: the ratio of the motion's 5 %-damped "
                        "spectrum S to the target T at each frequency point; a run: consecutive "
                        "frequency points below the target; correlation: the largest |correlation| "
                        "of two components of the set; each heading gives the SRP 3.7.1 limit. "
                        "Every component's values, and which check it failed, are in "
                        "motion_quality.csv.";
    worksheet_merge_range(ws, row, 0, row, Q_COLS - 1, intro, F->note);
    worksheet_set_row(ws, row++, sl_rpt_text_height(intro, w_all, 0), NULL);
    for (size_t i = 0; i < r->n_floors; i++) {
        const sl_report_floor *fl = &r->floors[i];
        sl_rpt_failed_text(r, fl, buf, sizeof buf);
        if (!buf[0])
            snprintf(buf, sizeof buf, "%s: %zu sets, every component passed every check", fl->id,
                     fl->design->n_sets);
        worksheet_merge_range(ws, row, 0, row, Q_COLS - 1, buf,
                              fl->n_failed_motions ? F->warn : F->note);
        worksheet_set_row(ws, row++, sl_rpt_text_height(buf, w_all, fl->n_failed_motions > 0),
                          NULL);
    }
    lxw_row_t head = ++row;
    /* each check's limit under its heading (synth.h: the SRP 3.7.1 defaults) */
    char h5[64], h6[64], h7[96], h8[96];
    /* no brackets to break; "limit 0.9" kept on one line (a no-break space) */
    snprintf(h5, sizeof h5, "lowest S/T, limit\xC2\xA0%g", 1 - SL_SYNTH_TOL_BELOW);
    snprintf(h6, sizeof h6, "highest S/T, limit\xC2\xA0%g", 1 + SL_SYNTH_TOL_ABOVE);
    snprintf(h7, sizeof h7, "run below target, points, limit\xC2\xA0%d",
             SL_SYNTH_MAX_RUN_BELOW);
    snprintf(h8, sizeof h8, "largest correlation, limit\xC2\xA0%g", SL_SYNTH_MAX_CORR);
    const char *const hd[Q_COLS] = {"floor id", "set", "PGA H1, g", "PGA H2, g", "PGA V, g", h5,
                                    h6, h7, h8, "verdict"};
    double hh = 0;
    for (lxw_col_t c = 0; c < Q_COLS; c++) { /* a heading over numbers at their right */
        char hb[200];
        sl_rpt_header_text(hd[c], width[c], hb, sizeof hb);
        worksheet_write_string(ws, head, c, hb, c == 0 ? F->header : c == Q_COLS - 1
                               ? F->header_ind : F->header_num);
        hh = fmax(hh, sl_rpt_text_height(hb, 1e3, 1)); /* its own lines */
    }
    worksheet_set_row(ws, head, hh, NULL);
    worksheet_freeze_panes(ws, head + 1, 0);
    row = head + 1;
    for (size_t q = 0; q < r->n_quality;) {
        const sl_report_quality *m = &r->quality[q];
        size_t e = q; /* the set's components: consecutive rows of one floor and set */
        while (e < r->n_quality && r->quality[e].set == m->set &&
               !strcmp(r->quality[e].floor, m->floor))
            e++;
        double lo = HUGE_VAL, hi = -HUGE_VAL, corr = 0, pga[3] = {NAN, NAN, NAN};
        int run = 0, pass = 1;
        size_t used = 0;
        buf[0] = '\0';
        for (size_t k = q; k < e; k++) {
            const sl_report_quality *c = &r->quality[k];
            int ci = !strcmp(c->component, "H1") ? 0 : !strcmp(c->component, "H2") ? 1 : 2;
            pga[ci] = c->pga_g;
            lo = fmin(lo, c->min_ratio);
            hi = fmax(hi, c->max_ratio);
            run = c->max_run_below > run ? c->max_run_below : run;
            corr = fmax(corr, c->max_corr);
            if (!c->pass) {
                int w = snprintf(buf + used, sizeof buf - used, "%s%s %s", pass ? "FAIL: " : "; ",
                                 c->component, c->why && *c->why ? c->why : "failed");
                used += w > 0 && (size_t)w < sizeof buf - used ? (size_t)w : 0;
                pass = 0;
            }
        }
        worksheet_write_string(ws, row, 0, m->floor, NULL);
        worksheet_write_number(ws, row, 1, m->set, NULL);
        for (lxw_col_t c = 0; c < 3; c++)
            sl_rpt_num_or_blank(ws, row, (lxw_col_t)(2 + c), pga[c], F->ratio);
        sl_rpt_num_or_blank(ws, row, 5, lo, F->ratio);
        sl_rpt_num_or_blank(ws, row, 6, hi, F->ratio);
        worksheet_write_number(ws, row, 7, run, NULL);
        sl_rpt_num_or_blank(ws, row, 8, corr, F->ratio);
        worksheet_write_string(ws, row, 9, pass ? "pass" : buf, pass ? F->indent : F->warn);
        if (!pass)
            worksheet_set_row(ws, row, sl_rpt_text_height(buf, W_VERDICT, 1), NULL);
        row++;
        q = e;
    }
    sl_rpt_page_setup(ws, r, 0, sl_rpt_failed_ids(r, ids, sizeof ids));
    worksheet_fit_to_pages(ws, 1, 0);
    worksheet_repeat_rows(ws, head, head);
    sl_rpt_protect(ws);
}
