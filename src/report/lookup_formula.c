/* lookup_formula.c - the one generator of the Lookup chain that the building
 * Lookup (sheet_lookup.c) and the plant Lookup (plant_book.c) both write:
 * each cell's Excel formula and the value the program computes for it are
 * made side by side here, so that the two sheets cannot drift apart. A
 * sheet describes where its table lies (sl_rpt_lookup_table), passes its
 * own floor tests, and adds what only it shows (the building's ZPA, standard
 * error, flags and policy; the plant's building list). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "method/design.h"
#include "report/sheets.h"

/* A standard error of 1 mm or more shows the clearance to the whole mm
 * (text.c, sl_rpt_shown_decimals: the tables' rule). */
#define WHOLE_MM_SE 1.0

/* Cell B<row+1> shown to the whole mm while the standard error in B<se+1>
 * is WHOLE_MM_SE or more (a conditional number format: the value is not
 * rounded). */
static void whole_mm_when(lxw_worksheet *ws, const sl_rpt_fmts *F, int row, int se)
{
    char crit[64];
    snprintf(crit, sizeof crit, "=AND(ISNUMBER($B$%d),$B$%d>=%g)", se + 1, se + 1, WHOLE_MM_SE);
    lxw_conditional_format cf;
    memset(&cf, 0, sizeof cf);
    cf.type = LXW_CONDITIONAL_TYPE_FORMULA;
    cf.value_string = crit;
    cf.format = F->dxf_mm0;
    worksheet_conditional_format_cell(ws, (lxw_row_t)row, 1, &cf);
}

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

int sl_rpt_lookup_check(lxw_worksheet *ws, const sl_rpt_fmts *F, int zero_cache,
                        const sl_rpt_lookup_cells *c, const sl_rpt_lookup_test *tests,
                        size_t n_tests, const char *mu_text, double mu, double mu_min,
                        double mu_max)
{
    char f[2000];
    const char *check = NULL;
    size_t used = (size_t)snprintf(f, sizeof f, "=");
    for (size_t k = 0; k < n_tests; k++) {
        used += (size_t)snprintf(f + used, sizeof f - used, "IF(%s,\"%s\",", tests[k].formula,
                                 tests[k].message);
        if (!check && tests[k].holds)
            check = tests[k].message;
    }
    /* the mu tests, the same in every Lookup: blank, not a number, off the grid */
    used += (size_t)snprintf(f + used, sizeof f - used,
                             "IF(B%d=\"\",\"type mu\",IF(NOT(ISNUMBER(B%d)),\"mu must be a "
                             "number\",IF(OR(B%d<%.10g,B%d>%.10g),\"mu outside the table\","
                             "\"ok\")))",
                             c->mu + 1, c->mu + 1, c->mu + 1, mu_min, c->mu + 1, mu_max);
    for (size_t k = 0; k < n_tests && used + 1 < sizeof f; k++)
        f[used++] = ')';
    f[used] = '\0';
    if (!check)
        check = mu_text && *mu_text ? "mu must be a number"
                : !isfinite(mu) || mu_text ? "type mu"
                : mu < mu_min || mu > mu_max ? "mu outside the table"
                : "ok";
    worksheet_write_string(ws, c->check, 0, "Input check", F->bold);
    sl_rpt_lookup_formula(ws, zero_cache, c->check, f, 0, check, F->bold);
    return !strcmp(check, "ok");
}

void sl_rpt_lookup_result_text(char *f, size_t n, const sl_rpt_lookup_cells *c)
{
    /* linear interpolation in mu between the grid rows around it, as
     * sl_design_clearance_at: C0 + (mu - mu0) (C1 - C0) / (mu1 - mu0) */
    char ip[300], r[5][16];
    const int rows[5] = {c->mu, c->steps + 2, c->steps + 3, c->steps + 4, c->steps + 5};
    for (int k = 0; k < 5; k++)
        snprintf(r[k], sizeof r[k], "B%d", rows[k] + 1);
    snprintf(f, n, "=IF(B%d<>\"ok\",\"-\",%s)", c->check + 1,
             sl_rpt_interp_formula(ip, sizeof ip, r[0], r[1], r[2], r[3], r[4]));
}

double sl_rpt_lookup_chain(lxw_worksheet *ws, const sl_rpt_fmts *F, int zero_cache,
                           const sl_rpt_lookup_cells *c, const sl_rpt_lookup_table *t,
                           const sl_design *d, size_t floor_index, double mu, int ok)
{
    /* the steps: where the floor is, where mu is, the grid rows around mu
     * and their clearances (cached: row k0 and k1 of d, as MATCH finds them) */
    const int chk = c->check + 1, fs = c->steps + 1, ms = c->steps + 2;
    const lxw_row_t mu0 = c->steps + 2, mu1 = mu0 + 1, c0 = mu0 + 2, c1 = mu0 + 3;
    size_t n = d->n, k1, k0 = sl_rpt_lookup_bracket(d, ok, mu, &k1);
    const char *none = ok ? NULL : "";
    char f[600], next[40], at0[80], at1[80];
    const char *const label[6] = {t->floor_step, t->mu_step, "mu at or below", "mu above",
                                  "clearance at the mu at or below, mm",
                                  "clearance at the mu above, mm"};
    const char *how = "How it is computed: linear interpolation between the two grid rows "
                      "around mu (as every CSV and table of the run):";
    worksheet_merge_range(ws, c->steps - 1, 0, c->steps - 1, 1, how, F->bold);
    worksheet_set_row(ws, c->steps - 1, sl_rpt_text_height(how, t->width, 1), NULL);
    for (int s = 0; s < 6; s++)
        worksheet_write_string(ws, (lxw_row_t)(c->steps + s), 0, label[s], NULL);
    snprintf(f, sizeof f, "=IF(B%d<>\"ok\",\"\",%s)", chk, t->floor_match);
    sl_rpt_lookup_formula(ws, zero_cache, c->steps, f, (double)(floor_index + 1), none, NULL);
    snprintf(f, sizeof f, "=IF(B%d<>\"ok\",\"\",MATCH(B%d,%s,1))", chk, c->mu + 1, t->grid);
    sl_rpt_lookup_formula(ws, zero_cache, c->steps + 1, f, (double)(k0 + 1), none, NULL);
    /* the grid: a column (INDEX(grid,k)) or a row (INDEX(grid,1,k)) */
    snprintf(next, sizeof next, "MIN(B%d+1,%zu)", ms, n);
    const char *by = t->floors_down ? "1," : "";
    snprintf(f, sizeof f, "=IF(B%d<>\"ok\",\"\",INDEX(%s,%sB%d))", chk, t->grid, by, ms);
    sl_rpt_lookup_formula(ws, zero_cache, mu0, f, d->rows[k0].mu, none, F->ratio);
    snprintf(f, sizeof f, "=IF(B%d<>\"ok\",\"\",INDEX(%s,%s%s))", chk, t->grid, by, next);
    sl_rpt_lookup_formula(ws, zero_cache, mu1, f, d->rows[k1].mu, none, F->ratio);
    /* the table: floors down and mu across (plant), or mu down (building) */
    if (t->floors_down) {
        snprintf(at0, sizeof at0, "B%d,B%d", fs, ms);
        snprintf(at1, sizeof at1, "B%d,%s", fs, next);
    } else {
        snprintf(at0, sizeof at0, "B%d,B%d", ms, fs);
        snprintf(at1, sizeof at1, "%s,B%d", next, fs);
    }
    snprintf(f, sizeof f, "=IF(B%d<>\"ok\",\"\",INDEX(%s,%s))", chk, t->table, at0);
    sl_rpt_lookup_formula(ws, zero_cache, c0, f, SL_RPT_MM_PER_M * d->rows[k0].clearance_m,
                          none, F->mm);
    snprintf(f, sizeof f, "=IF(B%d<>\"ok\",\"\",INDEX(%s,%s))", chk, t->table, at1);
    sl_rpt_lookup_formula(ws, zero_cache, c1, f, SL_RPT_MM_PER_M * d->rows[k1].clearance_m,
                          none, F->mm);

    /* the result: C0 + (mu - mu0) (C1 - C0) / (mu1 - mu0), which is
     * sl_design_clearance_at's interpolation (its value is cached) */
    double res = ok ? SL_RPT_MM_PER_M * sl_design_clearance_at(d, mu) : NAN;
    worksheet_write_string(ws, c->result, 0, "Required clearance, mm", F->title);
    sl_rpt_lookup_result_text(f, sizeof f, c);
    sl_rpt_lookup_formula(ws, zero_cache, c->result, f, res, ok ? NULL : "-", F->result);
    if (c->se) /* one rule for the digits: the tables' (summary.csv, plant.csv) */
        for (int k = 0; k < 3; k++)
            whole_mm_when(ws, F, k == 0 ? c->result : k == 1 ? (int)c0 : (int)c1, c->se);
    worksheet_write_string(ws, c->note, 0, "Note", F->bold);
    char few[200] = "", few_text[200] = "";
    if (c->sets) { /* fewer sets than the standard asks for: said first */
        snprintf(few, sizeof few, "IF(AND(ISNUMBER(B%d),B%d<%d),\"only \"&B%d&\" motion sets "
                 "(ASCE/SEI 43-05: at least %d). \",\"\")&", c->sets + 1, c->sets + 1,
                 SL_NLTHA_MIN_SETS, c->sets + 1, SL_NLTHA_MIN_SETS);
        if (ok && d->n_sets < SL_NLTHA_MIN_SETS)
            snprintf(few_text, sizeof few_text, "only %zu motion sets (ASCE/SEI 43-05: at least "
                     "%d). ", d->n_sets, SL_NLTHA_MIN_SETS);
    }
    char note[400];
    snprintf(note, sizeof note, "%s%s", few_text,
             ok && res == 0 ? SL_RPT_LOOKUP_NO_SLIDING : "");
    snprintf(f, sizeof f, "=IF(B%d<>\"ok\",\"\",%sIF(B%d=0,\"%s\",\"\"))", chk, few,
             c->result + 1, SL_RPT_LOOKUP_NO_SLIDING);
    sl_rpt_lookup_formula(ws, zero_cache, c->note, f, 0, note, F->wrap);
    return res;
}
