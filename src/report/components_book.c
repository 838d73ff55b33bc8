/* components_book.c - components.xlsx (components.h): the Components sheet,
 * whose results are live formulas over the hidden Floors sheet (every
 * floor's table on the grid), with SL_COMP_SPARE_ROWS empty rows for
 * components typed in later; the Summary (counts per verdict and per
 * floor, COUNTIF formulas); the Chart of required against available
 * clearance. Every formula is written with its value computed here
 * (components.c), the formula's C twin. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/casefold.h"
#include "report/components.h"
#include "report/sheets.h"

/* Components sheet rows (0-based): title, note, header; components below. */
enum { CS_TITLE, CS_NOTE, CS_HEAD, CS_FIRST };
/* Helper columns after the visible ones (hidden, not printed). */
enum { H_CHK, H_ROW, H_K, H_MU0, H_MU1, H_C0, H_C1, H_S0, H_S1, H_A0, H_A1, H_BLD, H_FID,
       H_OKX, H_OKY, H_MGX, H_MGY, H_SHX, H_SHY, H_SV, H_RV0, H_RPRE, H_RKX, H_RKY, H_RKE, H_N };
/* Result columns after the inputs. */
enum { R_BH, R_REQ, R_SE, R_ASCE, R_MARGIN, R_VERDICT, R_REASON, R_MODE, R_PTIP, R_PTIP15,
       R_EXC, R_N };
/* Floors sheet: A building, B floor id, C floor name, D key by id, E key
 * by name (the names' keys, sl_casefold_key: MATCH compares without case,
 * and TRIM reads a run of blanks as one), then the grid's clearance, its
 * standard error and the ASCE design value ("-" where the table has none)
 * (row 1: mu). */
enum { FS_BLD, FS_FID, FS_NAME, FS_KID, FS_KNAME, FS_GRID };
/* Column widths (characters). */
#define W_TAG 10.0
#define W_TEXT 12.0
#define W_NUM 9.0
#define W_REASON 30.0
#define W_EXTRA_MAX 13.0
#define W_CHART 100.0 /* the Chart sheet's one column: a landscape page */

/* The verdicts in the order of sl_comp_verdict, then "check input". */
static const char *const verdict_label[] = {"ok", "marginal", "short", "rocking", "outside",
                                            "stands", "overturns", "check input"};
static const lxw_color_t verdict_bg[] = {0xC6EFCE, 0xF8CBAD, 0xFFC7CE, 0xFFEB9C, 0xD9D9D9,
                                         0xC6EFCE, 0xC00000, 0xE4DFEC};
static const lxw_color_t verdict_fg[] = {0x006100, 0x833C0B, 0x9C0006, 0x9C5700, 0x404040,
                                         0x006100, 0xFFFFFF, 0x5B3C88};
#define N_LABELS 8

typedef struct book {
    lxw_workbook *wb;
    sl_rpt_fmts F;
    lxw_format *in_text, *in_num, *in_fixed, *num3, *mm, *pct, *reason, *top, *count,
        *head_text, *vfmt[N_LABELS];
    const sl_comp_results *r;
    const sl_comp_table *t;
    size_t n_extra, vis, last;   /* extra columns; visible columns; last formula row */
    int extra[SL_COMP_MAX_COLS]; /* the file's column of each extra column */
    char g0[48], g1[48];         /* the grid's ends as the reasons show them */
    double diag_mm;              /* the end of the chart's diagonal (Floors) */
    void *labels[3];             /* the chart's point labels, freed after the workbook */
} book;

static lxw_col_t col_res(const book *b, int k) { return (lxw_col_t)(SL_COMP_NCOLS + b->n_extra + (size_t)k); }
static lxw_col_t col_h(const book *b, int k) { return (lxw_col_t)(b->vis + (size_t)k); }

/* "$X5": column c of the 0-based row. */
static char *ref(char *buf, size_t c, lxw_row_t row)
{
    char a[8];
    sl_rpt_col_name(c, a);
    snprintf(buf, 16, "$%s%u", a, (unsigned)row + 1);
    return buf;
}

/* "Components!$X$4:$X$N": column c over every component row. */
static char *range(const book *b, char *buf, size_t n, size_t c)
{
    char a[8];
    sl_rpt_col_name(c, a);
    snprintf(buf, n, "Components!$%s$%d:$%s$%zu", a, CS_FIRST + 1, a, b->last + 1);
    return buf;
}

/* A text for a formula: quotes doubled, inside quotes. */
static char *quoted(const char *s, char *buf, size_t n)
{
    size_t k = 0;
    buf[k++] = '"';
    for (; *s && k + 3 < n; s++) {
        if (*s == '"')
            buf[k++] = '"';
        buf[k++] = *s;
    }
    buf[k++] = '"';
    buf[k] = '\0';
    return buf;
}

static void formats(book *b)
{
    sl_rpt_formats(b->wb, &b->F);
    b->in_text = workbook_add_format(b->wb);
    format_set_bg_color(b->in_text, 0xFFF2CC);
    format_set_border(b->in_text, LXW_BORDER_THIN);
    format_set_border_color(b->in_text, 0xBFBFBF);
    format_set_unlocked(b->in_text);
    format_set_text_wrap(b->in_text);
    format_set_align(b->in_text, LXW_ALIGN_VERTICAL_TOP);
    b->in_num = workbook_add_format(b->wb);
    format_set_bg_color(b->in_num, 0xFFF2CC);
    format_set_border(b->in_num, LXW_BORDER_THIN);
    format_set_border_color(b->in_num, 0xBFBFBF);
    format_set_unlocked(b->in_num);
    format_set_align(b->in_num, LXW_ALIGN_VERTICAL_TOP);
    /* an input a computed rocking result depends on: shown, not edited (the list is
     * edited and the command run again) */
    b->in_fixed = workbook_add_format(b->wb);
    format_set_bg_color(b->in_fixed, 0xEDEDED);
    format_set_border(b->in_fixed, LXW_BORDER_THIN);
    format_set_border_color(b->in_fixed, 0xBFBFBF);
    format_set_align(b->in_fixed, LXW_ALIGN_VERTICAL_TOP);
    b->pct = workbook_add_format(b->wb);
    format_set_num_format(b->pct, "0.0");
    format_set_align(b->pct, LXW_ALIGN_VERTICAL_TOP);
    b->num3 = workbook_add_format(b->wb);
    format_set_num_format(b->num3, "0.000");
    format_set_align(b->num3, LXW_ALIGN_VERTICAL_TOP);
    b->mm = workbook_add_format(b->wb);
    format_set_num_format(b->mm, "0.0");
    format_set_align(b->mm, LXW_ALIGN_VERTICAL_TOP);
    b->top = workbook_add_format(b->wb); /* the verdict: kept off the margin beside it */
    format_set_align(b->top, LXW_ALIGN_VERTICAL_TOP);
    format_set_indent(b->top, 1);
    b->count = workbook_add_format(b->wb); /* a count beside a wrapped name: at its top */
    format_set_align(b->count, LXW_ALIGN_VERTICAL_TOP);
    b->head_text = workbook_add_format(b->wb); /* a text heading after a number's: kept off it */
    format_set_bold(b->head_text);
    format_set_text_wrap(b->head_text);
    format_set_align(b->head_text, LXW_ALIGN_VERTICAL_TOP);
    format_set_bottom(b->head_text, LXW_BORDER_THIN);
    format_set_indent(b->head_text, 1);
    b->reason = workbook_add_format(b->wb);
    format_set_text_wrap(b->reason);
    format_set_align(b->reason, LXW_ALIGN_VERTICAL_TOP);
    for (int v = 0; v < N_LABELS; v++) {
        b->vfmt[v] = workbook_add_format(b->wb);
        format_set_bg_color(b->vfmt[v], verdict_bg[v]);
        format_set_font_color(b->vfmt[v], verdict_fg[v]);
        format_set_bold(b->vfmt[v]);
    }
}

/* A formula with its cached value: number v, or text s when not NULL. */
static void fcell(lxw_worksheet *ws, lxw_row_t row, lxw_col_t c, const char *f, double v,
                  const char *s, lxw_format *fmt)
{
    if (s)
        worksheet_write_formula_str(ws, row, c, f, fmt, s);
    else
        worksheet_write_formula_num(ws, row, c, f, fmt, v);
}

/* The hidden Floors sheet and its names (cmp_grid, cmp_clear, cmp_se,
 * cmp_key_id, cmp_key_name, cmp_bld, cmp_fid); the diagonal of the chart
 * below the floors. */
static void floors_sheet(book *b)
{
    const sl_comp_results *r = b->r;
    lxw_worksheet *ws = workbook_add_worksheet(b->wb, "Floors");
    size_t n = r->n_mu, nf = r->n_floors;
    static const char *const head[] = {"building", "floor id", "floor name", "key by id",
                                       "key by name"};
    char key[2400], def[200], a[8], z[8];
    for (int c = 0; c < FS_GRID; c++)
        worksheet_write_string(ws, 0, (lxw_col_t)c, head[c], b->F.header);
    for (size_t k = 0; k < n; k++)
        for (size_t blk = 0; blk < 3; blk++)
            worksheet_write_number(ws, 0, (lxw_col_t)(FS_GRID + blk * n + k), r->mu[k], NULL);
    for (size_t i = 0; i < nf; i++) {
        const sl_comp_floor *fl = &r->floors[i];
        lxw_row_t row = (lxw_row_t)(i + 1);
        worksheet_write_string(ws, row, FS_BLD, fl->building, NULL);
        worksheet_write_string(ws, row, FS_FID, fl->id, NULL);
        worksheet_write_string(ws, row, FS_NAME, fl->name, NULL);
        char kb[1000], kf[1000];
        sl_casefold_key(fl->building, kb, sizeof kb);
        snprintf(key, sizeof key, "%s|%s", kb, sl_casefold_key(fl->id, kf, sizeof kf));
        worksheet_write_string(ws, row, FS_KID, key, NULL);
        snprintf(key, sizeof key, "%s|%s", kb, sl_casefold_key(fl->name, kf, sizeof kf));
        worksheet_write_string(ws, row, FS_KNAME, key, NULL);
        for (size_t k = 0; k < n; k++) {
            worksheet_write_number(ws, row, (lxw_col_t)(FS_GRID + k), fl->clearance_mm[k], NULL);
            if (isfinite(fl->se_mm[k]))
                worksheet_write_number(ws, row, (lxw_col_t)(FS_GRID + n + k), fl->se_mm[k], NULL);
            if (isfinite(fl->asce_mm[k]))
                worksheet_write_number(ws, row, (lxw_col_t)(FS_GRID + 2 * n + k), fl->asce_mm[k],
                                       NULL);
            else
                worksheet_write_string(ws, row, (lxw_col_t)(FS_GRID + 2 * n + k), "-", NULL);
        }
    }
    struct { const char *name; size_t c0, c1; int grid; } names[] = {
        {"cmp_grid", FS_GRID, FS_GRID + n - 1, 1}, {"cmp_clear", FS_GRID, FS_GRID + n - 1, 0},
        {"cmp_se", FS_GRID + n, FS_GRID + 2 * n - 1, 0},
        {"cmp_asce", FS_GRID + 2 * n, FS_GRID + 3 * n - 1, 0}, {"cmp_key_id", FS_KID, FS_KID, 0},
        {"cmp_key_name", FS_KNAME, FS_KNAME, 0}, {"cmp_bld", FS_BLD, FS_BLD, 0},
        {"cmp_fid", FS_FID, FS_FID, 0}};
    for (size_t k = 0; k < sizeof names / sizeof names[0]; k++) {
        sl_rpt_col_name(names[k].c0, a);
        sl_rpt_col_name(names[k].c1, z);
        if (names[k].grid)
            snprintf(def, sizeof def, "=Floors!$%s$1:$%s$1", a, z);
        else
            snprintf(def, sizeof def, "=Floors!$%s$2:$%s$%zu", a, z, nf + 1);
        workbook_define_name(b->wb, names[k].name, def);
    }
    /* the chart's diagonal: (0, 0) and (M, M), M a little above every clearance */
    lxw_row_t d = (lxw_row_t)(nf + 2);
    char rq[80], cl[80], ex[80], f[300];
    worksheet_write_string(ws, d, 0, "chart diagonal, mm", b->F.header);
    worksheet_write_number(ws, d + 1, 0, 0, NULL);
    worksheet_write_number(ws, d + 1, 1, 0, NULL);
    snprintf(f, sizeof f, "=1.05*MAX(%s,%s,%s)", range(b, rq, sizeof rq, col_res(b, R_REQ)),
             range(b, cl, sizeof cl, SL_COMP_CLEARANCE), range(b, ex, sizeof ex, col_h(b, H_RKE)));
    fcell(ws, d + 2, 0, f, b->diag_mm, NULL, NULL);
    snprintf(f, sizeof f, "=A%u", (unsigned)d + 3);
    fcell(ws, d + 2, 1, f, b->diag_mm, NULL, NULL);
    worksheet_hide(ws);
}

/* One row of the Components sheet: inputs (a component, or unlocked blanks
 * when w is NULL) and every formula with its value. */
static void comp_row(book *b, lxw_worksheet *ws, lxw_row_t row, const sl_comp_row *w,
                     const char *dflt_bld, const char *single)
{
    const sl_comp_results *r = b->r;
    const sl_comp_table *t = b->t;
    char f[4200], A[16], B[16], C[16], D[16], E[16], G[16], Fc[16], h[H_N][16], v[R_N][16],
        ip[400], reason[600];
    ref(A, SL_COMP_TAG, row);
    ref(B, SL_COMP_BUILDING, row);
    ref(C, SL_COMP_FLOOR, row);
    ref(D, SL_COMP_MU, row);
    ref(E, SL_COMP_BASE, row);
    ref(Fc, SL_COMP_CG, row);
    ref(G, SL_COMP_CLEARANCE, row);
    for (int k = 0; k < H_N; k++)
        ref(h[k], col_h(b, k), row);
    for (int k = 0; k < R_N; k++)
        ref(v[k], col_res(b, k), row);
    double height = 15.0 + 1;
    /* the inputs */
    for (int c = 0; c < SL_COMP_NCOLS; c++) {
        int num = c >= SL_COMP_MU;
        if (!w) {
            worksheet_write_blank(ws, row, (lxw_col_t)c, num ? b->in_num : b->in_text);
            continue;
        }
        const double nv[] = {0, 0, 0, w->mu, w->base_m, w->cg_height_m, w->clearance_mm};
        const char *s = w->field[t->col[c]];
        if (num) { /* a computed rocking result holds for its mu and block only */
            int fixed = w->has_rock && c != SL_COMP_CLEARANCE;
            worksheet_write_number(ws, row, (lxw_col_t)c, nv[c], fixed ? b->in_fixed : b->in_num);
        } else {
            worksheet_write_string(ws, row, (lxw_col_t)c, s, b->in_text);
            height = fmax(height, sl_rpt_text_height(s, c == SL_COMP_TAG ? W_TAG : W_TEXT, 0));
        }
    }
    for (size_t e = 0; e < b->n_extra; e++) {
        lxw_col_t c = (lxw_col_t)(SL_COMP_NCOLS + e);
        if (!w || !*w->field[b->extra[e]]) {
            worksheet_write_blank(ws, row, c, b->in_text);
            continue;
        }
        worksheet_write_string(ws, row, c, w->field[b->extra[e]], b->in_text);
        height = fmax(height, sl_rpt_text_height(w->field[b->extra[e]], W_EXTRA_MAX, 0));
    }
    /* the values a component gives (components.c), or a blank row's */
    int ok = w != NULL, in = ok && isfinite(w->required_mm);
    size_t k0 = 0, k1 = 0;
    if (in) {
        while (k0 + 1 < r->n_mu && r->mu[k0 + 1] <= w->mu)
            k0++;
        k1 = k0 + 1 < r->n_mu ? k0 + 1 : k0;
    }
    const sl_comp_floor *fl = ok ? &r->floors[w->floor] : NULL;
    int vi = ok ? (int)w->verdict : -1;
    /* the building: as typed, or the default */
    char bexpr[600], q[500];
    if (single)
        snprintf(bexpr, sizeof bexpr, "IF(OR(TRIM(%s)=\"\",TRIM(%s)=%s),\"\",TRIM(%s))", B, B,
                 quoted(single, q, sizeof q), B);
    else if (dflt_bld)
        snprintf(bexpr, sizeof bexpr, "IF(TRIM(%s)=\"\",%s,TRIM(%s))", B,
                 quoted(dflt_bld, q, sizeof q), B);
    else
        snprintf(bexpr, sizeof bexpr, "TRIM(%s)", B);
    char a7[40];
    snprintf(a7, sizeof a7, "COUNTA(%s:%s)", A, G);
    /* H_ROW: the floor's row in Floors (0: none) */
    snprintf(f, sizeof f, "=IF(%s=0,0,IFERROR(MATCH(%s&\"|\"&TRIM(%s),cmp_key_id,0),"
             "IFERROR(MATCH(%s&\"|\"&TRIM(%s),cmp_key_name,0),0)))", a7, bexpr, C, bexpr, C);
    fcell(ws, row, col_h(b, H_ROW), f, ok ? (double)w->floor + 1 : 0, NULL, NULL);
    /* H_CHK: the input check */
    char tags[80];
    range(b, tags, sizeof tags, SL_COMP_TAG);
    snprintf(f, sizeof f,
             "=IF(%s=0,\"\",IF(TRIM(%s)=\"\",\"tag is empty\",IF(COUNTIF(%s,%s)>1,"
             "\"tag again\",IF(%s=0,\"unknown building or floor\","
             "IF(NOT(ISNUMBER(%s)),\"mu is not a number\",IF(%s<=0,\"mu must be > 0\","
             "IF(NOT(ISNUMBER(%s)),\"base_m is not a number\",IF(%s<=0,\"base_m must be > 0\","
             "IF(NOT(ISNUMBER(%s)),\"cg_height_m is not a number\",IF(%s<=0,"
             "\"cg_height_m must be > 0\",IF(NOT(ISNUMBER(%s)),\"clearance_mm is not a number\","
             "IF(%s<0,\"clearance_mm must be >= 0\",\"ok\"))))))))))))",
             a7, A, tags + strlen("Components!"), A, h[H_ROW], D, D, E, E, Fc, Fc, G, G);
    fcell(ws, row, col_h(b, H_CHK), f, 0, ok ? "ok" : "", NULL);
    /* H_K: the grid row at or below mu; the rows around it */
    snprintf(f, sizeof f, "=IF(%s<>\"ok\",\"\",IF(OR(%s<INDEX(cmp_grid,1,1),%s>INDEX(cmp_grid,1,"
             "%zu)),\"\",MATCH(%s,cmp_grid,1)))", h[H_CHK], D, D, r->n_mu, D);
    fcell(ws, row, col_h(b, H_K), f, (double)k0 + 1, in ? NULL : "", NULL);
    const struct { int col; const char *what; int next; double val; } look[] = {
        {H_MU0, "cmp_grid", 0, in ? r->mu[k0] : 0}, {H_MU1, "cmp_grid", 1, in ? r->mu[k1] : 0},
        {H_C0, "cmp_clear", 0, in ? fl->clearance_mm[k0] : 0},
        {H_C1, "cmp_clear", 1, in ? fl->clearance_mm[k1] : 0},
        {H_S0, "cmp_se", 0, in ? fl->se_mm[k0] : 0}, {H_S1, "cmp_se", 1, in ? fl->se_mm[k1] : 0},
        {H_A0, "cmp_asce", 0, in ? fl->asce_mm[k0] : 0},
        {H_A1, "cmp_asce", 1, in ? fl->asce_mm[k1] : 0}};
    for (size_t k = 0; k < sizeof look / sizeof look[0]; k++) {
        char rowarg[40], colarg[60];
        snprintf(rowarg, sizeof rowarg, "%s", look[k].col <= H_MU1 ? "1" : h[H_ROW]);
        if (look[k].next)
            snprintf(colarg, sizeof colarg, "MIN(%s+1,%zu)", h[H_K], r->n_mu);
        else
            snprintf(colarg, sizeof colarg, "%s", h[H_K]);
        snprintf(f, sizeof f, "=IF(%s=\"\",\"\",INDEX(%s,%s,%s))", h[H_K], look[k].what, rowarg,
                 colarg);
        int asce_none = in && look[k].col >= H_A0 && !isfinite(look[k].val); /* "-" */
        fcell(ws, row, col_h(b, look[k].col), f, isfinite(look[k].val) ? look[k].val : 0,
              !in ? "" : asce_none ? "-" : NULL, NULL);
    }
    /* the resolved building and floor id (the Summary counts by them) */
    snprintf(f, sizeof f, "=IF(%s=0,\"\",INDEX(cmp_bld,%s))", h[H_ROW], h[H_ROW]);
    fcell(ws, row, col_h(b, H_BLD), f, 0, ok ? fl->building : "", NULL);
    snprintf(f, sizeof f, "=IF(%s=0,\"\",INDEX(cmp_fid,%s))", h[H_ROW], h[H_ROW]);
    fcell(ws, row, col_h(b, H_FID), f, 0, ok ? fl->id : "", NULL);
    /* the results */
    snprintf(f, sizeof f, "=IF(%s<>\"ok\",\"\",%s/(2*%s))", h[H_CHK], E, Fc);
    fcell(ws, row, col_res(b, R_BH), f, ok ? w->b_over_h : 0, ok ? NULL : "", b->num3);
    snprintf(f, sizeof f, "=IF(%s=\"\",\"\",%s)", h[H_K],
             sl_rpt_interp_formula(ip, sizeof ip, D, h[H_MU0], h[H_MU1], h[H_C0], h[H_C1]));
    fcell(ws, row, col_res(b, R_REQ), f, in ? w->required_mm : 0, in ? NULL : "", b->mm);
    snprintf(f, sizeof f, "=IF(%s=\"\",\"\",%s)", h[H_K],
             sl_rpt_interp_formula(ip, sizeof ip, D, h[H_MU0], h[H_MU1], h[H_S0], h[H_S1]));
    fcell(ws, row, col_res(b, R_SE), f, in && isfinite(w->se_mm) ? w->se_mm : 0, in ? NULL : "",
          b->mm);
    snprintf(f, sizeof f, "=IF(OR(%s=\"\",NOT(ISNUMBER(%s)),NOT(ISNUMBER(%s))),\"\",%s)", h[H_K],
             h[H_A0], h[H_A1],
             sl_rpt_interp_formula(ip, sizeof ip, D, h[H_MU0], h[H_MU1], h[H_A0], h[H_A1]));
    int asce = in && isfinite(w->asce_mm);
    fcell(ws, row, col_res(b, R_ASCE), f, asce ? w->asce_mm : 0, asce ? NULL : "", b->mm);
    snprintf(f, sizeof f, "=IF(%s=\"\",\"\",%s-%s)", h[H_K], G, v[R_REQ]);
    fcell(ws, row, col_res(b, R_MARGIN), f, in ? w->margin_mm : 0, in ? NULL : "", b->mm);
    /* the sliding check's verdict (components.c, verdict()): the margin against
     * SL_COMP_MARGIN_SE SE; "rocking" when mu >= b/h */
    snprintf(f, sizeof f, "=IF(%s=\"\",\"\",IF(%s<>\"ok\",\"check input\",IF(%s>=%s,\"rocking\","
             "IF(%s=\"\",\"outside\",IF(%s<0,\"short\",IF(%s<%g*%s,\"marginal\",\"ok\"))))))",
             h[H_CHK], h[H_CHK], D, v[R_BH], h[H_K], v[R_MARGIN], v[R_MARGIN], SL_COMP_MARGIN_SE,
             v[R_SE]);
    int rk = ok && w->has_rock;
    sl_comp_verdict sv = !ok ? SL_COMP_OK : w->has_rock ? w->slide_verdict : w->verdict;
    fcell(ws, row, col_h(b, H_SV), f, 0, ok ? SL_COMP_VERDICT_NAME[sv] : "", NULL);
    const char *SV = h[H_SV];
    /* the sliding check's reason */
    char sr[2400];
    snprintf(sr, sizeof sr,
             "IF(%s=\"rocking\",\"mu \"&"
             "TEXT(%s,\"0.0##\")&\" >= b/h \"&TEXT(%s,\"0.0##\")&\": rocks before it slides; its "
             "rocking is computed by seislide components\",IF(%s=\"outside\",\"mu \"&"
             "TEXT(%s,\"0.0##\")&\" outside the computed grid %s-%s: no clearance computed\","
             "\"required \"&TEXT(%s,\"0.0\")&\" mm (SE \"&TEXT(%s,\"0.0\")&\") \"&IF(%s=\"short\","
             "\"> available \"&TEXT(%s,\"0.0\")&\" mm: \"&TEXT(-%s,\"0.0\")&\" mm short\",\"<= "
             "available \"&TEXT(%s,\"0.0\")&\" mm: margin \"&TEXT(%s,\"0.0\")&\" mm\"&IF(%s="
             "\"marginal\",\" < %g SE (\"&TEXT(%g*%s,\"0.0\")&\" mm), inside the noise of the "
             "motion sets\",\"\"))))",
             SV, D, v[R_BH], SV, D, b->g0, b->g1, v[R_REQ], v[R_SE], SV, G, v[R_MARGIN], G,
             v[R_MARGIN], SV, SL_COMP_MARGIN_SE, SL_COMP_MARGIN_SE, v[R_SE]);
    /* the rocking check (rk): its result as computed, the clearance live */
    char rv[600] = "", rr[1600] = "", pre[800] = "";
    if (rk) {
        /* the rocking verdict before the excursion is set against the clearance */
        static const sl_comp_verdict of[] = {SL_COMP_STANDS, SL_COMP_MARGINAL, SL_COMP_SHORT,
                                             SL_COMP_OVERTURNS};
        const double target[SL_ROCKF_NLEVELS] = {SL_ROCKF_P_TARGET_1, SL_ROCKF_P_TARGET_2};
        worksheet_write_string(ws, row, col_h(b, H_RV0),
                               SL_COMP_VERDICT_NAME[of[sl_rockf_verdict_of(&w->rock, target,
                                                                           NAN)]],
                               NULL);
        worksheet_write_string(ws, row, col_h(b, H_RPRE), sl_comp_rock_prefix(w, pre, sizeof pre),
                               NULL);
        snprintf(rv, sizeof rv, "IF(%s=\"overturns\",\"overturns\",IF(%s>%s,\"short\",%s))",
                 h[H_RV0], v[R_EXC], G, h[H_RV0]);
        snprintf(rr, sizeof rr, "%s&IF(%s=\"overturns\",\"\",IF(%s>%s,\"; excursion \"&TEXT(%s,"
                 "\"0.0\")&\" mm > available \"&TEXT(%s,\"0.0\")&\" mm: \"&TEXT(%s-%s,\"0.0\")&"
                 "\" mm short\",\"; excursion \"&TEXT(%s,\"0.0\")&\" mm <= available \"&TEXT(%s,"
                 "\"0.0\")&\" mm\"))", h[H_RPRE], h[H_RV0], v[R_EXC], G, v[R_EXC], G, v[R_EXC], G,
                 v[R_EXC], G);
        worksheet_write_string(ws, row, col_res(b, R_MODE), SL_COMP_MODE_NAME[w->mode],
                               b->reason);
        worksheet_write_number(ws, row, col_res(b, R_PTIP), 100 * w->rock.level[0].p_tip, b->pct);
        worksheet_write_number(ws, row, col_res(b, R_PTIP15), 100 * w->rock.level[1].p_tip,
                               b->pct);
        worksheet_write_number(ws, row, col_res(b, R_EXC), 1000 * w->rock.excursion_m, b->mm);
    } else {
        snprintf(f, sizeof f, "=IF(%s<>\"ok\",\"\",IF(%s>=%s,\"rocking\",\"sliding\"))", h[H_CHK],
                 D, v[R_BH]);
        fcell(ws, row, col_res(b, R_MODE), f, 0,
              ok ? SL_COMP_MODE_NAME[w->mode == SL_COMP_MODE_ROCKING ? SL_COMP_MODE_ROCKING
                                                                     : SL_COMP_MODE_SLIDING]
                 : "",
              b->reason);
    }
    /* the verdict: the sliding check's, the rocking check's, or the worse of both */
    if (!rk)
        snprintf(f, sizeof f, "=%s", SV);
    else if (w->mode == SL_COMP_MODE_ROCKING)
        snprintf(f, sizeof f, "=IF(%s<>\"ok\",\"check input\",%s)", h[H_CHK], rv);
    else
        snprintf(f, sizeof f, "=IF(%s<>\"ok\",\"check input\",IF(OR(%s=\"overturns\",%s=\"overturns\"),"
                 "\"overturns\",IF(OR(%s=\"short\",%s=\"short\"),\"short\",IF(OR(%s=\"outside\",%s="
                 "\"outside\"),\"outside\",IF(OR(%s=\"marginal\",%s=\"marginal\"),\"marginal\",\"ok\")))))",
                 h[H_CHK], SV, rv, SV, rv, SV, rv, SV, rv);
    fcell(ws, row, col_res(b, R_VERDICT), f, 0, ok ? SL_COMP_VERDICT_NAME[vi] : "", b->top);
    if (!rk)
        snprintf(f, sizeof f, "=IF(%s=\"\",\"\",IF(%s<>\"ok\",\"check input: \"&%s,%s))", h[H_CHK],
                 h[H_CHK], h[H_CHK], sr);
    else if (w->mode == SL_COMP_MODE_ROCKING)
        snprintf(f, sizeof f, "=IF(%s<>\"ok\",\"check input: \"&%s,%s)", h[H_CHK], h[H_CHK], rr);
    else
        snprintf(f, sizeof f, "=IF(%s<>\"ok\",\"check input: \"&%s,\"slides: \"&%s&\"; rocks: \"&%s)",
                 h[H_CHK], h[H_CHK], sr, rr);
    fcell(ws, row, col_res(b, R_REASON), f, 0,
          ok ? sl_comp_reason(r, w, reason, sizeof reason) : "", b->reason);
    if (ok)
        height = fmax(height, sl_rpt_text_height(reason, W_REASON, 0));
    worksheet_set_row(ws, row, height, NULL);
    /* the chart's points: a sliding check's ok, marginal and short (x its required
     * clearance), #N/A otherwise (not drawn); a rocking check's (x its excursion) */
    const int pts[6][2] = {{H_OKX, SL_COMP_OK}, {H_OKY, SL_COMP_OK},
                           {H_MGX, SL_COMP_MARGINAL}, {H_MGY, SL_COMP_MARGINAL},
                           {H_SHX, SL_COMP_SHORT}, {H_SHY, SL_COMP_SHORT}};
    for (int k = 0; k < 6; k++) {
        int y = pts[k][0] == H_OKY || pts[k][0] == H_MGY || pts[k][0] == H_SHY;
        snprintf(f, sizeof f, "=IF(%s=\"%s\",%s,NA())", SV, SL_COMP_VERDICT_NAME[pts[k][1]],
                 y ? G : v[R_REQ]);
        int on = ok && (int)sv == pts[k][1];
        fcell(ws, row, col_h(b, pts[k][0]), f, on ? (y ? w->clearance_mm : w->required_mm) : 0,
              on ? NULL : "#N/A", NULL);
    }
    int ron = rk && w->rock_verdict != SL_COMP_OVERTURNS;
    if (rk) {
        snprintf(f, sizeof f, "=IF(%s=\"overturns\",NA(),%s)", h[H_RV0], v[R_EXC]);
        fcell(ws, row, col_h(b, H_RKX), f, ron ? 1000 * w->rock.excursion_m : 0,
              ron ? NULL : "#N/A", NULL);
        snprintf(f, sizeof f, "=IF(%s=\"overturns\",NA(),%s)", h[H_RV0], G);
        fcell(ws, row, col_h(b, H_RKY), f, ron ? w->clearance_mm : 0, ron ? NULL : "#N/A", NULL);
        /* the excursion drawn, as a number or text for the diagonal's MAX */
        snprintf(f, sizeof f, "=IF(%s=\"overturns\",\"\",%s)", h[H_RV0], v[R_EXC]);
        fcell(ws, row, col_h(b, H_RKE), f, ron ? 1000 * w->rock.excursion_m : 0, ron ? NULL : "",
              NULL);
    } else {
        fcell(ws, row, col_h(b, H_RKX), "=NA()", 0, "#N/A", NULL);
        fcell(ws, row, col_h(b, H_RKY), "=NA()", 0, "#N/A", NULL);
        worksheet_write_string(ws, row, col_h(b, H_RKE), "", NULL);
    }
}

/* The grid's ends as the reason shows them (TEXT(x, "0.0##")). */
static void grid_text(const sl_comp_results *r, char *g0, char *g1)
{
    sl_comp_row w0 = {.verdict = SL_COMP_OUTSIDE, .mu = 0};
    char buf[200];
    sl_comp_reason(r, &w0, buf, sizeof buf); /* "mu 0.0 outside the computed grid A-B: ..." */
    const char *p = strstr(buf, "grid ");
    if (p && sscanf(p + 5, "%40[^-]-%40[^:]", g0, g1) == 2)
        return;
    strcpy(g0, "?");
    strcpy(g1, "?");
}

static void components_sheet(book *b, const sl_report *rep)
{
    const sl_comp_table *t = b->t;
    const sl_comp_results *r = b->r;
    lxw_worksheet *ws = workbook_add_worksheet(b->wb, "Components");
    size_t vis = b->vis;
    /* widths */
    const double w_in[SL_COMP_NCOLS] = {W_TAG, W_TEXT - 4, W_TEXT, 5, 7.5, 12, 14};
    for (int c = 0; c < SL_COMP_NCOLS; c++)
        worksheet_set_column(ws, (lxw_col_t)c, (lxw_col_t)c, w_in[c], NULL);
    for (size_t e = 0; e < b->n_extra; e++) {
        double w = (double)strlen(t->header[b->extra[e]]) + 2;
        for (size_t i = 0; i < t->n; i++)
            w = fmax(w, (double)strlen(t->rows[i].field[b->extra[e]]) + 2);
        worksheet_set_column(ws, (lxw_col_t)(SL_COMP_NCOLS + e), (lxw_col_t)(SL_COMP_NCOLS + e),
                             fmin(w, W_EXTRA_MAX), NULL);
    }
    const double w_res[R_N] = {6, 8.5, 6.5, 7, 7.5, 10, W_REASON, 8, 7, 7, 9};
    for (int k = 0; k < R_N; k++)
        worksheet_set_column(ws, col_res(b, k), col_res(b, k), w_res[k], NULL);
    lxw_row_col_options hid = {.hidden = 1};
    worksheet_set_column_opt(ws, col_h(b, 0), col_h(b, H_N - 1), 10, NULL, &hid);
    /* title, note, header */
    worksheet_write_string(ws, CS_TITLE, 0, "Components: required against available clearance",
                           b->F.title);
    char note[2000], shown_dir[1100];
    snprintf(note, sizeof note,
             "Required clearance: the floor's table (run in %s, created %s) at the component's "
             "mu, linear interpolation on the grid %s-%s (clearance policy %s; the ASCE/SEI "
             "43-05 design value beside it). Sliding verdict: outside when mu is off the grid; "
             "short when the margin (clearance_mm - required) is < 0; marginal when it is below "
             "%g x the SE of the required clearance (inside the noise of the motion sets); ok "
             "otherwise. A slender component (mu >= b/h = base_m / (2 cg_height_m): it rocks "
             "before it slides; mode both when mu < b/h <= mu_max) was checked for rocking by "
             "seislide components: P(tip), the probability that it tips (%%), at the floor "
             "motion and at 1.5 x it against ASCE/SEI 43-05's targets of %g %% and %g %%, and "
             "the excursion of its top (mm) against the available clearance: overturns, short, "
             "marginal (within %g SE of a target) or stands; its mu and block (grey) are those "
             "it was computed for: to change them, edit the list and run the command again. "
             "A row typed in below with mu >= b/h reads rocking: its rocking is computed by "
             "seislide components. More components: type them in the yellow cells below the "
             "last one (%d rows are ready, printed with the sheet); building may be left "
             "empty %s.", sl_rpt_shown_path(r->dir, shown_dir, sizeof shown_dir), r->created,
             b->g0, b->g1, r->policy, SL_COMP_MARGIN_SE,
             100 * SL_ROCKF_P_TARGET_1, 100 * SL_ROCKF_P_TARGET_2, SL_ROCKF_SE_DECIDE,
             SL_COMP_SPARE_ROWS,
             r->is_plant ? (r->n_buildings == 1 ? "(one building)" : "only in a one-building "
                            "plant") : "(one building)");
    worksheet_merge_range(ws, CS_NOTE, 0, CS_NOTE, (lxw_col_t)(vis - 1), note, b->F.wrap);
    double width = 0;
    for (size_t c = 0; c < vis; c++)
        width += c < SL_COMP_NCOLS ? w_in[c] : c >= (size_t)col_res(b, 0)
                 ? w_res[c - col_res(b, 0)] : W_EXTRA_MAX / 2;
    worksheet_set_row(ws, CS_NOTE, sl_rpt_text_height(note, width, 0), NULL);
    for (int c = 0; c < SL_COMP_NCOLS; c++) /* a heading over numbers at their right */
        worksheet_write_string(ws, CS_HEAD, (lxw_col_t)c, SL_COMP_COL_NAME[c],
                               c >= SL_COMP_MU ? b->F.header_num : b->F.header);
    for (size_t e = 0; e < b->n_extra; e++)
        worksheet_write_string(ws, CS_HEAD, (lxw_col_t)(SL_COMP_NCOLS + e),
                               t->header[b->extra[e]], e ? b->F.header : b->head_text);
    static const char *const rh[R_N] = {"b/h", "required, mm", "its SE, mm", "ASCE, mm",
                                        "margin, mm", "verdict", "reason", "mode",
                                        "P(tip), %", "P(tip) 1.5 x, %", "excursion, mm"};
    for (int k = 0; k < R_N; k++)
        worksheet_write_string(ws, CS_HEAD, col_res(b, k), rh[k],
                               k < R_VERDICT || k > R_MODE ? b->F.header_num
                               : k == R_VERDICT || k == R_MODE ? b->head_text : b->F.header);
    static const char *const hh[H_N] = {"check", "floor row", "grid k", "mu0", "mu1", "c0", "c1",
                                        "se0", "se1", "asce0", "asce1", "building", "floor id",
                                        "ok x", "ok y", "marginal x", "marginal y", "short x",
                                        "short y", "sliding verdict", "rocking verdict",
                                        "rocking reason", "rocking x", "rocking y",
                                        "rocking excursion"};
    for (int k = 0; k < H_N; k++)
        worksheet_write_string(ws, CS_HEAD, col_h(b, k), hh[k], b->F.header);
    worksheet_set_row(ws, CS_HEAD, 2 * 15.0 + 1, NULL);
    /* rows */
    const char *dflt = r->is_plant && r->n_buildings == 1 ? r->buildings[0] : NULL;
    const char *single = r->is_plant ? NULL : (r->single ? r->single : "");
    for (size_t row = CS_FIRST; row <= b->last; row++)
        comp_row(b, ws, (lxw_row_t)row, row - CS_FIRST < t->n ? &t->rows[row - CS_FIRST] : NULL,
                 dflt, single);
    /* verdicts coloured */
    for (int v = 0; v < N_LABELS; v++) {
        char crit[40];
        lxw_conditional_format cf;
        memset(&cf, 0, sizeof cf);
        cf.type = LXW_CONDITIONAL_TYPE_CELL;
        cf.criteria = LXW_CONDITIONAL_CRITERIA_EQUAL_TO;
        snprintf(crit, sizeof crit, "\"%s\"", verdict_label[v]);
        cf.value_string = crit;
        cf.format = b->vfmt[v];
        worksheet_conditional_format_range(ws, CS_FIRST, col_res(b, R_VERDICT),
                                           (lxw_row_t)b->last, col_res(b, R_VERDICT), &cf);
    }
    worksheet_freeze_panes(ws, CS_FIRST, 1);
    sl_rpt_page_setup(ws, rep, 1, "");
    worksheet_repeat_rows(ws, CS_HEAD, CS_HEAD);
    /* every row, the empty ones ready for more included: rows typed in print (a
     * print area that follows the rows in use is a formula, which LibreOffice
     * does not read: it would print every row there is) */
    worksheet_print_area(ws, 0, 0, (lxw_row_t)b->last, (lxw_col_t)(vis - 1));
    worksheet_fit_to_pages(ws, 1, 0);
    sl_rpt_protect(ws);
    worksheet_activate(ws);
}

/* Counts per verdict and per floor: COUNTIF(S) over the Components sheet. */
static void summary_sheet(book *b, const sl_report *rep)
{
    const sl_comp_results *r = b->r;
    const sl_comp_table *t = b->t;
    lxw_worksheet *ws = workbook_add_worksheet(b->wb, "Summary");
    int plant = r->is_plant;
    lxw_col_t c0 = plant ? 1 : 0; /* the floor id column */
    /* a landscape page at about 100 % for one building (98 units) */
    double w_b = 14; /* the building column: as wide as its longest name, up to 24 */
    for (size_t i = 0; plant && i < r->n_floors; i++)
        w_b = fmax(w_b, fmin(24, 0.95 * (double)strlen(r->floors[i].building) + 2));
    const double w_id = 12, w_name = 24, w_all = 11, w_n = 8.5;
    if (plant)
        worksheet_set_column(ws, 0, 0, w_b, NULL);
    worksheet_set_column(ws, c0, c0, w_id, NULL);
    worksheet_set_column(ws, c0 + 1, c0 + 1, w_name, NULL);
    worksheet_set_column(ws, c0 + 2, c0 + 2, w_all, NULL);
    worksheet_set_column(ws, c0 + 3, c0 + 2 + N_LABELS, w_n, NULL);
    lxw_col_t last = c0 + 2 + N_LABELS;
    double width = (plant ? w_b : 0) + w_id + w_name + w_all + w_n * N_LABELS;
    sl_rpt_title_block(ws, &b->F, rep, "Components: counts per verdict and per floor", 0,
                       last, width);
    char src[3000], p1[1100], p2[1100]; /* the paths as a page shows them (components.csv:
                                           * whole) */
    snprintf(src, sizeof src, "Components file %s (%zu components, CRC-32 %08lx); required "
             "clearances from %s (seislide run, %s, created %s). Counts follow the Components "
             "sheet, rows typed in later included.", sl_rpt_shown_path(t->path, p1, sizeof p1),
             t->n, t->crc32 & 0xffffffffUL, sl_rpt_shown_path(r->dir, p2, sizeof p2),
             r->is_plant ? "a plant" : "one building", r->created);
    size_t n_rock = 0;
    for (size_t i = 0; i < t->n; i++)
        n_rock += t->rows[i].has_rock;
    if (n_rock) { /* what the rocking check leaves out */
        size_t k = strlen(src);
        snprintf(src + k, sizeof src - k, " %zu component(s) checked for rocking: NLTHA of a "
                 "rigid rectangular block of uniform mass rocking about a base edge on a rigid "
                 "floor (Housner 1963) over the floor's own motion sets, each scaled by a "
                 "log-normal intensity factor of log standard deviation %.2f; left out: sliding "
                 "and rocking together (slide-rock), a centre of mass off the middle of the base "
                 "or a non-uniform mass, a flexible base or floor, rocking on a corner in 3-D, "
                 "the block leaving the floor (docs/rocking.md).", n_rock, SL_ROCKF_SCATTER);
    }
    lxw_row_t row = SL_RPT_TB_ROWS + 1;
    worksheet_merge_range(ws, row, 0, row, last, src, b->F.wrap);
    worksheet_set_row(ws, row, sl_rpt_text_height(src, width, 0), NULL);
    char vr[80], br[80], fr[80], f[600];
    range(b, vr, sizeof vr, col_res(b, R_VERDICT));
    range(b, br, sizeof br, col_h(b, H_BLD));
    range(b, fr, sizeof fr, col_h(b, H_FID));
    /* per verdict */
    row += 2;
    worksheet_write_string(ws, row, 0, "Verdict", b->F.header);
    worksheet_write_string(ws, row, 1, "Components", b->F.header_num);
    lxw_row_t v0 = row + 1;
    for (int v = 0; v < N_LABELS; v++) {
        worksheet_write_string(ws, v0 + (lxw_row_t)v, 0, verdict_label[v], b->vfmt[v]);
        snprintf(f, sizeof f, "=COUNTIF(%s,\"%s\")", vr, verdict_label[v]);
        fcell(ws, v0 + (lxw_row_t)v, 1, f, v < SL_COMP_NVERDICTS ? (double)t->count[v] : 0, NULL,
              NULL);
    }
    worksheet_write_string(ws, v0 + N_LABELS, 0, "all", b->F.bold);
    snprintf(f, sizeof f, "=SUM(B%u:B%u)", (unsigned)v0 + 1, (unsigned)v0 + N_LABELS);
    fcell(ws, v0 + N_LABELS, 1, f, (double)t->n, NULL, b->F.bold);
    /* per floor */
    row = v0 + N_LABELS + 2;
    lxw_row_t head = row;
    if (plant)
        worksheet_write_string(ws, row, 0, "Building", b->F.header);
    worksheet_write_string(ws, row, c0, "Floor", b->F.header);
    worksheet_write_string(ws, row, c0 + 1, "Floor name", b->F.header);
    worksheet_write_string(ws, row, c0 + 2, "Components", b->F.header_num);
    for (int v = 0; v < N_LABELS; v++) /* each count under its heading: both at the right */
        worksheet_write_string(ws, row, c0 + 3 + (lxw_col_t)v, verdict_label[v],
                               b->F.header_num);
    worksheet_set_row(ws, row, sl_rpt_text_height("check input", w_n, 1), NULL);
    for (size_t i = 0; i < r->n_floors; i++) {
        const sl_comp_floor *fl = &r->floors[i];
        row++;
        char crit[300], a[16];
        if (plant)
            worksheet_write_string(ws, row, 0, fl->building, b->F.wrap);
        worksheet_write_string(ws, row, c0, fl->id, b->F.wrap);
        worksheet_write_string(ws, row, c0 + 1, fl->name, b->F.wrap);
        worksheet_set_row(ws, row, fmax(fmax(sl_rpt_text_height(fl->name, w_name, 0),
                                             sl_rpt_text_height(fl->id, w_id, 0)),
                                        plant ? sl_rpt_text_height(fl->building, w_b, 0) : 0),
                          NULL);
        /* the floor's cells as criteria */
        ref(a, c0, row);
        if (plant) {
            char ab[16];
            snprintf(crit, sizeof crit, "%s,%s,%s,%s", br, ref(ab, 0, row), fr, a);
        } else {
            snprintf(crit, sizeof crit, "%s,%s", fr, a);
        }
        size_t cnt[SL_COMP_NVERDICTS] = {0}, all = 0;
        for (size_t k = 0; k < t->n; k++)
            if (t->rows[k].floor == i) {
                cnt[t->rows[k].verdict]++;
                all++;
            }
        snprintf(f, sizeof f, "=COUNTIFS(%s)", crit);
        fcell(ws, row, c0 + 2, f, (double)all, NULL, b->count);
        for (int v = 0; v < N_LABELS; v++) {
            snprintf(f, sizeof f, "=COUNTIFS(%s,%s,\"%s\")", crit, vr, verdict_label[v]);
            fcell(ws, row, c0 + 3 + (lxw_col_t)v, f, v < SL_COMP_NVERDICTS ? (double)cnt[v] : 0,
                  NULL, b->count);
        }
    }
    sl_rpt_page_setup(ws, rep, 1, "");
    worksheet_repeat_rows(ws, head, head);
    worksheet_print_area(ws, 0, 0, row, last);
    worksheet_fit_to_pages(ws, 1, 0);
    sl_rpt_protect(ws);
}

/* Available against required clearance: a point per ok or short component,
 * above the diagonal enough gap. */
static void chart_sheet(book *b, const sl_report *rep)
{
    lxw_worksheet *ws = workbook_add_worksheet(b->wb, "Chart");
    worksheet_set_column(ws, 0, 0, W_CHART, NULL);
    worksheet_write_string(ws, 0, 0, "Components: available against required clearance",
                           b->F.title);
    const char *cap = "One point per component checked for sliding (its sliding verdict ok, "
                      "marginal or short), tagged: the required clearance at its mu on its floor "
                      "against the gap it has; and one per component checked for rocking that "
                      "does not overturn (blue triangle): the excursion of its top against the "
                      "gap. Points on or above the dashed line have enough gap; below it they "
                      "are short. Components that overturn and those whose mu is off the grid "
                      "are not drawn (see the Components sheet). The axes start at 0 and grow "
                      "with the rows typed in; a point of a row typed in is labelled with its "
                      "tag in Excel, with its available clearance in LibreOffice.";
    worksheet_write_string(ws, 1, 0, cap, b->F.wrap);
    worksheet_set_row(ws, 1, sl_rpt_text_height(cap, W_CHART, 0), NULL);
    lxw_chart *ch = workbook_add_chart(b->wb, LXW_CHART_SCATTER);
    char x[120], y[120];
    const struct { int hx, hy; const char *name; lxw_color_t color; uint8_t marker; } s[] = {
        {H_OKX, H_OKY, "ok", 0x2E7D32, LXW_CHART_MARKER_CIRCLE},
        {H_MGX, H_MGY, "marginal", 0xC55A11, LXW_CHART_MARKER_SQUARE},
        {H_SHX, H_SHY, "short", 0xC00000, LXW_CHART_MARKER_DIAMOND},
        {H_RKX, H_RKY, "rocking (excursion)", 0x1F4E79, LXW_CHART_MARKER_TRIANGLE}};
    /* each point tagged: a label per row, the tag's cell (not drawn with the point) */
    size_t np = b->last - CS_FIRST + 1;
    lxw_chart_data_label *lab = calloc(np, sizeof *lab), **labp = calloc(np + 1, sizeof *labp);
    char (*lref)[40] = calloc(np, sizeof *lref);
    static lxw_chart_font lfont = {.size = 7, .color = 0x404040};
    for (size_t i = 0; lab && labp && lref && i < np; i++) {
        /* a written row: its tag as text (LibreOffice shows a label's text, not a cell
         * it refers to); a row for typing: the tag's cell (Excel shows it; LibreOffice
         * the point's value) */
        if (i < b->t->n)
            snprintf(lref[i], sizeof lref[i], "%s", b->t->rows[i].field[b->t->col[SL_COMP_TAG]]);
        else
            snprintf(lref[i], sizeof lref[i], "=Components!$A$%zu", CS_FIRST + i + 1);
        lab[i].value = lref[i];
        lab[i].font = &lfont;
        labp[i] = &lab[i];
    }
    for (int k = 0; k < 4; k++) {
        char xr[80], yr[80];
        snprintf(x, sizeof x, "=%s", range(b, xr, sizeof xr, col_h(b, s[k].hx)));
        snprintf(y, sizeof y, "=%s", range(b, yr, sizeof yr, col_h(b, s[k].hy)));
        lxw_chart_series *se = chart_add_series(ch, x, y);
        chart_series_set_name(se, s[k].name);
        chart_series_set_marker_type(se, s[k].marker);
        chart_series_set_marker_size(se, 6);
        lxw_chart_fill fill = {.color = s[k].color};
        lxw_chart_line mline = {.color = s[k].color};
        chart_series_set_marker_fill(se, &fill);
        chart_series_set_marker_line(se, &mline);
        if (lab && labp && lref) {
            chart_series_set_labels(se);
            chart_series_set_labels_custom(se, labp);
            chart_series_set_labels_position(se, LXW_CHART_LABEL_POSITION_RIGHT);
            chart_series_set_labels_font(se, &lfont);
        }
    }
    unsigned d = (unsigned)b->r->n_floors + 4; /* Floors: the diagonal's rows (1-based) */
    snprintf(x, sizeof x, "=Floors!$A$%u:$A$%u", d, d + 1);
    snprintf(y, sizeof y, "=Floors!$B$%u:$B$%u", d, d + 1);
    lxw_chart_series *dg = chart_add_series(ch, x, y);
    chart_series_set_name(dg, "available = required");
    lxw_chart_line line = {.color = 0x404040, .width = 1.25, .dash_type = LXW_CHART_LINE_DASH_DASH};
    chart_series_set_line(dg, &line);
    chart_series_set_marker_type(dg, LXW_CHART_MARKER_NONE);
    chart_show_hidden_data(ch); /* the points are in hidden columns */
    chart_title_set_name(ch, "Available against required clearance");
    chart_axis_set_name(ch->x_axis, "Required clearance at the component's mu (sliding) or "
                                    "excursion (rocking), mm");
    chart_axis_set_name(ch->y_axis, "Available clearance, mm");
    /* both axes from 0, their ends left to the spreadsheet: they follow the points, rows
     * typed in included (the diagonal ends a little above every point, Floors) */
    chart_axis_set_min(ch->x_axis, 0);
    chart_axis_set_min(ch->y_axis, 0);
    chart_axis_major_gridlines_set_visible(ch->x_axis, LXW_TRUE);
    chart_legend_set_position(ch, LXW_CHART_LEGEND_BOTTOM);
    lxw_chart_options co = {.x_scale = 1.5, .y_scale = 1.85};
    worksheet_insert_chart_opt(ws, 3, 0, ch, &co);
    sl_rpt_page_setup(ws, rep, 1, "");
    worksheet_print_area(ws, 0, 0, 32, 0);
    worksheet_fit_to_pages(ws, 1, 1);
    sl_rpt_protect(ws);
    /* libxlsxwriter copies the labels when the workbook is written: kept until then */
    b->labels[0] = lab;
    b->labels[1] = labp;
    b->labels[2] = lref;
}

sl_status sl_comp_write_xlsx(const sl_comp_results *r, const sl_comp_table *t, const char *path,
                             const sl_comp_opts *o, sl_error *err)
{
    book b = {.r = r, .t = t};
    for (size_t c = 0; c < t->n_cols; c++) {
        int req = 0;
        for (int k = 0; k < SL_COMP_NCOLS; k++)
            req |= t->col[k] == (int)c;
        if (!req)
            b.extra[b.n_extra++] = (int)c;
    }
    b.vis = SL_COMP_NCOLS + b.n_extra + R_N;
    b.last = CS_FIRST + t->n + SL_COMP_SPARE_ROWS - 1;
    grid_text(r, b.g0, b.g1);
    for (size_t i = 0; i < t->n; i++) { /* the diagonal's end, as its formula (Floors) */
        const sl_comp_row *w = &t->rows[i];
        double m = w->clearance_mm;
        if (isfinite(w->required_mm))
            m = fmax(m, w->required_mm);
        if (w->has_rock && w->rock_verdict != SL_COMP_OVERTURNS) /* as drawn (H_RKE) */
            m = fmax(m, 1000 * w->rock.excursion_m);
        b.diag_mm = fmax(b.diag_mm, 1.05 * m);
    }
    sl_report rep;
    sl_comp_report(r, o, &rep);
    sl_atomic *a;
    b.wb = sl_rpt_workbook_open(path, "Components: required against available clearance",
                                "verdict per unanchored component", &rep.project, o->created,
                                &a, err);
    if (!b.wb)
        return err ? err->code : SL_EIO;
    formats(&b);
    components_sheet(&b, &rep);
    summary_sheet(&b, &rep);
    chart_sheet(&b, &rep);
    floors_sheet(&b);
    sl_status st = sl_rpt_workbook_close(b.wb, a, path, err);
    for (int k = 0; k < 3; k++)
        free(b.labels[k]);
    return st;
}
