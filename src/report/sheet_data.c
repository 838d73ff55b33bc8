/* sheet_data.c - the "Data" sheet: the tables the Lookup formulas and the
 * charts read. Hidden (it is not part of the printed document; Inputs and
 * the floor sheets hold the same numbers) and protected (sheets.h). */
#include <math.h>
#include <stdio.h>

#include "report/sheets.h"

lxw_col_t sl_rpt_data_col_se(size_t nf, size_t i)
{
    (void)nf;
    return (lxw_col_t)(1 + i);
}

lxw_col_t sl_rpt_data_col_flags(size_t nf, size_t i) { return (lxw_col_t)(1 + nf + i); }

lxw_col_t sl_rpt_data_col_series(size_t nf, size_t i, int s)
{
    return (lxw_col_t)(1 + 2 * nf + SL_RPT_DS_N * i + (size_t)s);
}

lxw_row_t sl_rpt_data_band_row(const sl_report *r, size_t i)
{
    lxw_row_t row = (lxw_row_t)(SL_RPT_DATA_HEAD + r->floors[0].design->n + 3);
    for (size_t j = 0; j < i; j++)
        row += (lxw_row_t)(2 * r->floors[j].design->n_ranges);
    return row;
}

void sl_rpt_data_sheet(lxw_workbook *wb, const sl_rpt_fmts *F, const sl_report *r,
                       const sl_rpt_axes *ax)
{
    lxw_worksheet *ws = workbook_add_worksheet(wb, "Data");
    size_t nf = r->n_floors, n = r->floors[0].design->n;
    char buf[256], flags[256];
    worksheet_write_string(ws, 0, 0, "Tables the Lookup sheet and the charts read (do not edit)",
                           F->title);
    worksheet_write_string(ws, 1, 0,
                           "Chart columns leave a cell empty where the value is 0 or does not "
                           "exist: a log axis has no 0.", NULL);
    /* the floor names the Lookup lists and matches (floor_names), in the
     * order of the Summary's columns */
    worksheet_write_string(ws, SL_RPT_DATA_HEAD - 1, 0, "floor names", F->bold);
    for (size_t i = 0; i < nf; i++)
        worksheet_write_string(ws, SL_RPT_DATA_HEAD - 1, (lxw_col_t)(1 + i), r->floors[i].name,
                               NULL);
    char last[8], def[80];
    sl_rpt_col_name(nf, last);
    snprintf(def, sizeof def, "=Data!$B$%d:$%s$%d", SL_RPT_DATA_HEAD, last, SL_RPT_DATA_HEAD);
    workbook_define_name(wb, "floor_names", def);
    worksheet_write_string(ws, SL_RPT_DATA_HEAD, 0, "mu", F->header);
    static const char *const sname[SL_RPT_DS_N] = {"NLTHA design, mm", "ASCE design, mm",
                                                   "NLTHA mean, mm", "cap, mm", "clearance, mm",
                                                   "NLTHA design 90 % band low, mm",
                                                   "NLTHA design 90 % band high, mm"};
    for (size_t i = 0; i < nf; i++) {
        const sl_report_floor *fl = &r->floors[i];
        snprintf(buf, sizeof buf, "%s: standard error of the NLTHA design value, mm", fl->id);
        worksheet_write_string(ws, SL_RPT_DATA_HEAD, sl_rpt_data_col_se(nf, i), buf, F->header);
        snprintf(buf, sizeof buf, "%s: flags", fl->id);
        worksheet_write_string(ws, SL_RPT_DATA_HEAD, sl_rpt_data_col_flags(nf, i), buf, F->header);
        for (int s = 0; s < SL_RPT_DS_N; s++) {
            snprintf(buf, sizeof buf, "%s: %s", fl->id, sname[s]);
            worksheet_write_string(ws, SL_RPT_DATA_HEAD, sl_rpt_data_col_series(nf, i, s), buf,
                                   F->header);
        }
    }
    worksheet_set_row(ws, SL_RPT_DATA_HEAD, 60, NULL);
    worksheet_set_column(ws, 0, (lxw_col_t)(2 * nf + SL_RPT_DS_N * nf), 12, NULL);
    for (size_t k = 0; k < n; k++) {
        lxw_row_t row = (lxw_row_t)(SL_RPT_DATA_HEAD + 1 + k);
        worksheet_write_number(ws, row, 0, r->floors[0].design->rows[k].mu, F->mu);
        for (size_t i = 0; i < nf; i++) {
            const sl_report_floor *fl = &r->floors[i];
            const sl_design_row *w = &fl->design->rows[k];
            worksheet_write_number(ws, row, sl_rpt_data_col_se(nf, i),
                                   SL_RPT_MM_PER_M * sl_rpt_design_se_m(fl, k), F->mm);
            sl_report_flags(w->flags, flags, sizeof flags);
            worksheet_write_string(ws, row, sl_rpt_data_col_flags(nf, i), flags[0] ? flags : "-",
                                   NULL);
            const double v[SL_RPT_DS_N] = {w->nltha_design_m, w->asce_design_m, w->nltha_mean_m,
                                           w->cap_m, w->clearance_m,
                                           fl->design_lo_m ? fl->design_lo_m[k] : NAN,
                                           fl->design_hi_m ? fl->design_hi_m[k] : NAN};
            for (int s = 0; s < SL_RPT_DS_N; s++) {
                double mm = SL_RPT_MM_PER_M * v[s];
                if (isfinite(mm) && mm > 0)
                    worksheet_write_number(ws, row, sl_rpt_data_col_series(nf, i, s), mm, F->mm);
            }
        }
    }
    /* bands: the ASCE-below-NLTHA ranges drawn along the bottom of each chart */
    lxw_row_t b0 = sl_rpt_data_band_row(r, 0);
    worksheet_write_string(ws, b0 - 1, 0, "floor id", F->header);
    worksheet_write_string(ws, b0 - 1, 1, "ASCE below NLTHA: mu at the range's ends", F->header);
    worksheet_write_string(ws, b0 - 1, 2, "band height, mm", F->header);
    for (size_t i = 0; i < nf; i++) {
        const sl_design *d = r->floors[i].design;
        lxw_row_t row = sl_rpt_data_band_row(r, i);
        for (size_t q = 0; q < d->n_ranges; q++) {
            for (int end = 0; end < 2; end++, row++) {
                worksheet_write_string(ws, row, 0, r->floors[i].id, NULL);
                worksheet_write_number(ws, row, 1, end ? d->ranges[q].mu_hi : d->ranges[q].mu_lo,
                                       F->ratio);
                worksheet_write_number(ws, row, 2, ax->y_min * 1.15, NULL);
            }
        }
    }
    sl_rpt_page_setup(ws, r, 1, "");
    worksheet_hide(ws); /* not printed: LibreOffice and Excel print visible sheets only */
    sl_rpt_protect(ws);
}
