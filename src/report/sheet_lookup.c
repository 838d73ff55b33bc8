/* sheet_lookup.c - the "Lookup" sheet: choose a floor, type mu, read the
 * required clearance; every step a visible formula over the Summary's named
 * ranges (floor_names, mu_grid, clearance_mm, floor_zpa_g, floor_sets) and
 * the Data sheet, with its value for the initial inputs computed here; the
 * input check, the steps and the result come from lookup_formula.c, which
 * writes the plant Lookup's too (tests/test_lookup.c recalculates). */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

#include "core/units.h"
#include "report/sheets.h"

/* Lookup cells (0-based rows; values in column B). */
enum {
    LK_FLOOR = 10, LK_MU, LK_RESULT = 13, LK_CHECK, LK_NOTE, LK_ZPA, LK_X, LK_SE, LK_FLAGS,
    LK_HOW = 21, LK_COL, LK_ROW, LK_MU0, LK_MU1, LK_C0, LK_C1, LK_SETS, LK_POLICY = 29
};
#define W_A 36.0 /* column A: labels */
#define W_B 28.0 /* column B: inputs and values; 64 in all, a portrait A4 page */
/* Excel's longest text constant in a formula is 255 characters. */
#define LITERAL_MAX 200

/* Append text s to a formula as "..."&"..." pieces of at most LITERAL_MAX. */
static void literal(char *f, size_t n, const char *s)
{
    size_t used = strlen(f), len = strlen(s);
    for (size_t k = 0; k < len || k == 0; k += LITERAL_MAX) {
        size_t m = len - k < LITERAL_MAX ? len - k : LITERAL_MAX;
        snprintf(f + used, n - used, "%s\"%.*s\"", k ? "&" : "", (int)m, s + k);
        used = strlen(f);
        if (!len)
            break;
    }
}

/* The policy paragraph: parts before and after the chosen floor's count. */
static void policy_parts(const sl_design *d, char *a, size_t na, char *b, size_t nb)
{
    snprintf(a, na, "nltha: %g x the mean peak vector sliding displacement of ", d->fs_nltha);
    snprintf(b, nb, " (ASCE/SEI 43-05), capped at %g x the mean peak floor displacement; asce: "
             "%g x the ASCE best estimate, same cap; envelope: the larger. The standard error is "
             "%g x sd / sqrt(number of the floor's motion sets), where the cap governs the cap's "
             "(%g x the standard error of the mean floor displacement). Each floor's sheet shows "
             "both curves, the cap and every range where ASCE is below NLTHA; the Notes sheet "
             "states the assumptions and limits.",
             d->cap_factor, d->fs_asce, d->fs_nltha, d->cap_factor);
}

void sl_rpt_lookup_sheet(lxw_workbook *wb, const sl_rpt_fmts *F, const sl_report *r)
{
    lxw_worksheet *ws = workbook_add_worksheet(wb, "Lookup");
    const sl_design *d0 = r->floors[0].design;
    size_t n = d0->n, nf = r->n_floors;
    int zc = r->lookup_zero_cache;
    double mu_min = d0->rows[0].mu, mu_max = d0->rows[n - 1].mu;
    char f[3000], msg[160], list_formula[40], buf[2000], ids[400];
    worksheet_set_column(ws, 0, 0, W_A, NULL);
    worksheet_set_column(ws, 1, 1, W_B, NULL);
    sl_rpt_title_block(ws, F, r, "Required clearance around an unanchored component", 0, 1, W_B);
    sl_rpt_failed_ids(r, ids, sizeof ids);
    char wl[1200];
    sl_rpt_warnings_line(r, wl, sizeof wl); /* the run's warnings, also here */
    sl_rpt_warn_row(ws, F, ids, "sheet Motion quality", wl, 1, W_A + W_B);

    /* the two inputs: unlocked, validated */
    const char *floor0 = r->lookup_floor ? r->lookup_floor : r->floors[0].name;
    worksheet_write_string(ws, LK_FLOOR, 0, "Floor (choose from the list)", F->bold);
    if (*floor0)
        worksheet_write_string(ws, LK_FLOOR, 1, floor0, F->input);
    else
        worksheet_write_blank(ws, LK_FLOOR, 1, F->input);
    lxw_data_validation dv;
    memset(&dv, 0, sizeof dv);
    dv.validate = LXW_VALIDATION_TYPE_LIST_FORMULA;
    snprintf(list_formula, sizeof list_formula, "=floor_names");
    dv.value_formula = list_formula;
    dv.input_title = "Floor";
    dv.input_message = "Choose the floor the component stands on.";
    dv.error_title = "Unknown floor";
    dv.error_message = "Choose a floor from the list (the names of the Summary sheet).";
    worksheet_data_validation_cell(ws, LK_FLOOR, 1, &dv);
    snprintf(msg, sizeof msg, "Friction coefficient mu, %.2f-%.2f", mu_min, mu_max);
    worksheet_write_string(ws, LK_MU, 0, msg, F->bold);
    worksheet_set_row(ws, LK_MU, sl_rpt_text_height(msg, W_A, 1), NULL);
    if (r->lookup_mu_text)
        worksheet_write_string(ws, LK_MU, 1, r->lookup_mu_text, F->input);
    else if (isfinite(r->lookup_mu))
        worksheet_write_number(ws, LK_MU, 1, r->lookup_mu, F->input);
    else
        worksheet_write_blank(ws, LK_MU, 1, F->input);
    lxw_data_validation dm;
    memset(&dm, 0, sizeof dm);
    dm.validate = LXW_VALIDATION_TYPE_DECIMAL;
    dm.criteria = LXW_VALIDATION_CRITERIA_BETWEEN;
    dm.minimum_number = mu_min;
    dm.maximum_number = mu_max;
    dm.input_title = "Friction coefficient";
    snprintf(msg, sizeof msg, "A number from %.2f to %.2f (static = kinetic friction).", mu_min,
             mu_max);
    dm.input_message = msg;
    dm.error_title = "mu outside the table";
    dm.error_message = msg;
    worksheet_data_validation_cell(ws, LK_MU, 1, &dm);

    /* the input check and the chain (lookup_formula.c), formulas and values */
    size_t fi = nf;
    for (size_t i = 0; i < nf; i++)
        if (!strcasecmp(floor0, r->floors[i].name))
            fi = i;
    double mu0 = r->lookup_mu;
    char t_blank[40], t_unknown[80], match[80];
    snprintf(t_blank, sizeof t_blank, "B%d=\"\"", LK_FLOOR + 1);
    snprintf(t_unknown, sizeof t_unknown, "ISNA(MATCH(B%d,floor_names,0))", LK_FLOOR + 1);
    const sl_rpt_lookup_test tests[] = {
        {t_blank, "choose a floor from the list", !*floor0},
        {t_unknown, "unknown floor: choose one from the list", fi == nf}};
    const sl_rpt_lookup_cells cells = {.mu = LK_MU, .result = LK_RESULT, .check = LK_CHECK,
                                       .note = LK_NOTE, .steps = LK_COL, .se = LK_SE,
                                       .sets = LK_SETS};
    int ok = sl_rpt_lookup_check(ws, F, zc, &cells, tests, 2, r->lookup_mu_text, mu0, mu_min,
                                 mu_max);
    snprintf(match, sizeof match, "MATCH(B%d,floor_names,0)", LK_FLOOR + 1);
    const sl_rpt_lookup_table table = {.grid = "mu_grid", .table = "clearance_mm",
                                       .floor_match = match,
                                       .floor_step = "column of the floor in Summary",
                                       .mu_step = "row of the mu at or below", .width = W_A + W_B};
    size_t k1, k0 = sl_rpt_lookup_bracket(d0, ok, mu0, &k1);
    const sl_design *dsel = ok ? r->floors[fi].design : d0;
    sl_rpt_lookup_chain(ws, F, zc, &cells, &table, dsel, ok ? fi : 0, mu0, ok);
    const int B_CHECK = LK_CHECK + 1, B_COL = LK_COL + 1, B_ROW = LK_ROW + 1;
    char longest[400];
    snprintf(longest, sizeof longest, "only 9 motion sets (ASCE/SEI 43-05: at least 5). %s",
             SL_RPT_LOOKUP_NO_SLIDING);
    worksheet_set_row(ws, LK_NOTE, sl_rpt_text_height(longest, W_B, 0), NULL);
    worksheet_write_string(ws, LK_ZPA, 0, "Floor's horizontal ZPA, g", F->bold);
    snprintf(f, sizeof f, "=IF(B%d<>\"ok\",\"\",INDEX(floor_zpa_g,1,B%d))", B_CHECK, B_COL);
    sl_rpt_lookup_formula(ws, zc, LK_ZPA, f, ok ? r->floors[fi].zpa_h_ms2 / SL_G : 0,
                          ok ? NULL : "", F->ratio);
    worksheet_write_string(ws, LK_X, 0, "mu g / ZPA", F->bold);
    snprintf(f, sizeof f, "=IF(B%d<>\"ok\",\"\",B%d/B%d)", B_CHECK, LK_MU + 1, LK_ZPA + 1);
    sl_rpt_lookup_formula(ws, zc, LK_X, f, ok ? mu0 * SL_G / r->floors[fi].zpa_h_ms2 : 0,
                          ok ? NULL : "", F->ratio);
    /* the standard error, interpolated as the clearance is */
    char c_from[8], c_to[8], se_rng[64], fl_rng[64];
    sl_rpt_col_name(sl_rpt_data_col_se(nf, 0), c_from);
    sl_rpt_col_name(sl_rpt_data_col_se(nf, nf - 1), c_to);
    snprintf(se_rng, sizeof se_rng, "Data!$%s$%d:$%s$%zu", c_from, SL_RPT_DATA_HEAD + 2, c_to,
             SL_RPT_DATA_HEAD + 1 + n);
    sl_rpt_col_name(sl_rpt_data_col_flags(nf, 0), c_from);
    sl_rpt_col_name(sl_rpt_data_col_flags(nf, nf - 1), c_to);
    snprintf(fl_rng, sizeof fl_rng, "Data!$%s$%d:$%s$%zu", c_from, SL_RPT_DATA_HEAD + 2, c_to,
             SL_RPT_DATA_HEAD + 1 + n);
    worksheet_write_string(ws, LK_SE, 0, "Standard error of the NLTHA design value, mm", F->bold);
    snprintf(f, sizeof f,
             "=IF(B%d<>\"ok\",\"\",INDEX(%s,B%d,B%d)+IF(B%d=B%d,0,(B%d-B%d)*(INDEX(%s,MIN(B%d+1,%zu),"
             "B%d)-INDEX(%s,B%d,B%d))/(B%d-B%d)))",
             B_CHECK, se_rng, B_ROW, B_COL, LK_MU1 + 1, LK_MU0 + 1, LK_MU + 1, LK_MU0 + 1, se_rng,
             B_ROW, n, B_COL, se_rng, B_ROW, B_COL, LK_MU1 + 1, LK_MU0 + 1);
    double se = 0;
    if (ok) {
        double s0 = sl_rpt_design_se_m(&r->floors[fi], k0), s1 = sl_rpt_design_se_m(&r->floors[fi], k1);
        double m0 = dsel->rows[k0].mu, m1 = dsel->rows[k1].mu;
        se = SL_RPT_MM_PER_M * (s0 + (m1 == m0 ? 0 : (mu0 - m0) * (s1 - s0) / (m1 - m0)));
    }
    sl_rpt_lookup_formula(ws, zc, LK_SE, f, se, ok ? NULL : "", F->mm);
    worksheet_set_row(ws, LK_SE, sl_rpt_text_height("Standard error of the NLTHA design value, mm",
                                                    W_A, 1), NULL);
    worksheet_write_string(ws, LK_FLAGS, 0, "Flags at the grid rows around mu", F->bold);
    snprintf(f, sizeof f, "=IF(B%d<>\"ok\",\"\",INDEX(%s,B%d,B%d)&\" | \"&INDEX(%s,MIN(B%d+1,%zu),B%d))",
             B_CHECK, fl_rng, B_ROW, B_COL, fl_rng, B_ROW, n, B_COL);
    char fl0[256], fl1[256], flc[600] = "";
    if (ok) {
        sl_report_flags(dsel->rows[k0].flags, fl0, sizeof fl0);
        sl_report_flags(dsel->rows[k1].flags, fl1, sizeof fl1);
        snprintf(flc, sizeof flc, "%s | %s", fl0[0] ? fl0 : "-", fl1[0] ? fl1 : "-");
    }
    sl_rpt_lookup_formula(ws, zc, LK_FLAGS, f, 0, flc, F->wrap);
    /* room for the longest flags of two rows */
    worksheet_set_row(ws, LK_FLAGS, sl_rpt_text_height("nltha_capped asce_capped "
                      "asce_below_nltha | nltha_capped asce_capped asce_below_nltha", W_B, 0),
                      NULL);
    worksheet_merge_range(ws, LK_FLAGS + 1, 0, LK_FLAGS + 1, 1, sl_rpt_flags_legend(), F->note);
    worksheet_set_row(ws, LK_FLAGS + 1, sl_rpt_text_height(sl_rpt_flags_legend(), W_A + W_B, 0),
                      NULL);

    worksheet_write_string(ws, LK_SETS, 0, "motion sets of the floor", NULL);
    snprintf(f, sizeof f, "=IF(B%d<>\"ok\",\"\",INDEX(floor_sets,1,B%d))", B_CHECK, B_COL);
    sl_rpt_lookup_formula(ws, zc, LK_SETS, f, ok ? (double)dsel->n_sets : 0, ok ? NULL : "", NULL);

    /* the policy, with the chosen floor's own number of sets */
    worksheet_write_string(ws, LK_POLICY, 0, "Clearance policy", F->bold);
    worksheet_write_string(ws, LK_POLICY, 1, sl_clearance_policy_name(d0->policy), NULL);
    char pa[200], pb[1200];
    policy_parts(d0, pa, sizeof pa, pb, sizeof pb);
    const char *any = "the floor's synthesized motion sets";
    if (ok)
        snprintf(buf, sizeof buf, "%s%zu synthesized motion sets of this floor%s", pa,
                 dsel->n_sets, pb);
    else
        snprintf(buf, sizeof buf, "%s%s%s", pa, any, pb);
    snprintf(f, sizeof f, "=");
    literal(f, sizeof f, pa);
    snprintf(f + strlen(f), sizeof f - strlen(f),
             "&IF(B%d=\"ok\",B%d&\" synthesized motion sets of this floor\",\"%s\")&", B_CHECK,
             LK_SETS + 1, any);
    literal(f, sizeof f, pb);
    worksheet_merge_range(ws, LK_POLICY + 1, 0, LK_POLICY + 1, 1, "", F->wrap);
    if (zc)
        worksheet_write_formula_num(ws, LK_POLICY + 1, 0, f, F->wrap, 0);
    else
        worksheet_write_formula_str(ws, LK_POLICY + 1, 0, f, F->wrap, buf);
    worksheet_set_row(ws, LK_POLICY + 1, sl_rpt_text_height(buf, W_A + W_B, 0), NULL);
    sl_rpt_page_setup(ws, r, 0, ids);
    worksheet_fit_to_pages(ws, 1, 1);
    sl_rpt_protect(ws);
    worksheet_activate(ws);
}
