/* lookup_formula.c - what the building Lookup (sheet_lookup.c) and the
 * plant Lookup (plant_book.c) compute alike: the formula cells of column B
 * with their cached values, the interpolated clearance, the no-sliding note
 * and the heading of the visible steps. Each sheet places the cells
 * (sl_rpt_lookup_cells) and writes its own input check and steps. */
#include <stdio.h>

#include "report/sheets.h"

void sl_rpt_lookup_formula(lxw_worksheet *ws, int zero_cache, lxw_row_t row, const char *f,
                           double v, const char *s, lxw_format *fmt)
{
    if (zero_cache)
        worksheet_write_formula_num(ws, row, 1, f, fmt, 0);
    else if (s)
        worksheet_write_formula_str(ws, row, 1, f, fmt, s);
    else
        worksheet_write_formula_num(ws, row, 1, f, fmt, v);
}

size_t sl_rpt_lookup_bracket(const sl_design *d, int ok, double mu, size_t *k1)
{
    size_t k0 = 0;
    while (ok && k0 + 1 < d->n && d->rows[k0 + 1].mu <= mu)
        k0++;
    *k1 = k0 + 1 < d->n ? k0 + 1 : k0;
    return k0;
}

void sl_rpt_lookup_result_text(char *f, size_t n, const sl_rpt_lookup_cells *c)
{
    /* linear interpolation in mu between the grid rows around it, as
     * sl_design_clearance_at: C0 + (mu - mu0) (C1 - C0) / (mu1 - mu0) */
    snprintf(f, n, "=IF(B%d<>\"ok\",\"-\",IF(B%d=B%d,B%d,B%d+(B%d-B%d)*(B%d-B%d)/(B%d-B%d)))",
             c->check + 1, c->mu1 + 1, c->mu0 + 1, c->c0 + 1, c->c0 + 1, c->mu + 1, c->mu0 + 1,
             c->c1 + 1, c->c0 + 1, c->mu1 + 1, c->mu0 + 1);
}

void sl_rpt_lookup_result(lxw_worksheet *ws, const sl_rpt_fmts *F, int zero_cache,
                          const sl_rpt_lookup_cells *c, double res, int ok)
{
    char f[SL_RPT_LOOKUP_RESULT_LEN];
    worksheet_write_string(ws, c->result, 0, "Required clearance, mm", F->title);
    sl_rpt_lookup_result_text(f, sizeof f, c);
    sl_rpt_lookup_formula(ws, zero_cache, c->result, f, res, ok ? NULL : "-", F->result);
}

void sl_rpt_lookup_note(lxw_worksheet *ws, const sl_rpt_fmts *F, int zero_cache,
                        const sl_rpt_lookup_cells *c, double res, int ok)
{
    char f[256];
    worksheet_write_string(ws, c->note, 0, "Note", F->bold);
    snprintf(f, sizeof f, "=IF(B%d<>\"ok\",\"\",IF(B%d=0,\"%s\",\"\"))", c->check + 1,
             c->result + 1, SL_RPT_LOOKUP_NO_SLIDING);
    sl_rpt_lookup_formula(ws, zero_cache, c->note, f, 0,
                          ok && res == 0 ? SL_RPT_LOOKUP_NO_SLIDING : "", F->wrap);
}

void sl_rpt_lookup_how(lxw_worksheet *ws, const sl_rpt_fmts *F, lxw_row_t row, double width)
{
    const char *how = "How it is computed (linear interpolation in mu, as "
                      "sl_design_clearance_at in the program):";
    worksheet_merge_range(ws, row, 0, row, 1, how, F->bold);
    worksheet_set_row(ws, row, sl_rpt_text_height(how, width, 1), NULL);
}
