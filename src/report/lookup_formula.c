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

char *sl_rpt_interp_formula(char *buf, size_t n, const char *mu, const char *mu0, const char *mu1,
                            const char *c0, const char *c1)
{
    snprintf(buf, n, "IF(%s=%s,%s,%s+(%s-%s)*(%s-%s)/(%s-%s))", /* c0 + (mu-mu0)(c1-c0)/(mu1-mu0) */
             mu1, mu0, c0,
             c0, mu, mu0,
             c1, c0, mu1, mu0);
    return buf;
}

void sl_rpt_lookup_result(lxw_worksheet *ws, const sl_rpt_fmts *F, int zero_cache,
                          const sl_rpt_lookup_cells *c, double res, int ok)
{
    /* linear interpolation in mu between the grid rows around it, as
     * sl_design_clearance_at: C0 + (mu - mu0) (C1 - C0) / (mu1 - mu0) */
    char f[512], ip[300], r[5][16];
    worksheet_write_string(ws, c->result, 0, "Required clearance, mm", F->title);
    const int rows[5] = {c->mu, c->mu0, c->mu1, c->c0, c->c1};
    for (int k = 0; k < 5; k++)
        snprintf(r[k], sizeof r[k], "B%d", rows[k] + 1);
    snprintf(f, sizeof f, "=IF(B%d<>\"ok\",\"-\",%s)", c->check + 1,
             sl_rpt_interp_formula(ip, sizeof ip, r[0], r[1], r[2], r[3], r[4]));
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
