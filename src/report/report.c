/* report.c - clearance workbook (XLSX) and CSV tables; see report.h. */
#include "report/report.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <xlsxwriter.h>

#include "io/atomic.h"
#include "core/units.h"

#define MM_PER_M 1000.0
#define SHEET_NAME_MAX 31 /* Excel's limit */
#define LOOKUP_DEFAULT_MU 0.30
/* Clearances are shown rounded up to the SE's leading digit, within these
 * steps, mm (shown_mm). */
#define SHOWN_MIN_STEP_MM 0.1
#define SHOWN_MAX_STEP_MM 10.0

char *sl_report_safe_name(const char *name, char *buf, size_t n)
{
    size_t k = 0;
    for (const char *p = name ? name : ""; *p && k + 1 < n; p++)
        buf[k++] = (isalnum((unsigned char)*p) || *p == '-' || *p == '_') ? *p : '_';
    if (k == 0 && n > 1)
        buf[k++] = '_';
    buf[k] = '\0';
    return buf;
}

char *sl_report_flags(unsigned flags, char *buf, size_t n)
{
    static const struct {
        unsigned bit;
        const char *name;
    } names[] = {{SL_DESIGN_NO_SLIDING, "no_sliding"},
                 {SL_DESIGN_NLTHA_CAPPED, "nltha_capped"},
                 {SL_DESIGN_ASCE_CAPPED, "asce_capped"},
                 {SL_DESIGN_UNCONSERVATIVE, "asce_below_nltha"},
                 {SL_DESIGN_ASCE_UNDEFINED, "asce_undefined"}};
    buf[0] = '\0';
    size_t used = 0;
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        if (flags & names[i].bit) {
            int w = snprintf(buf + used, n > used ? n - used : 0, "%s%s", used ? " " : "",
                             names[i].name);
            if (w > 0)
                used += (size_t)w;
        }
    return buf;
}

/* The ranges of mu g/ZPA where ASCE < NLTHA as "a-b<sep>c-d" (cut at n). */
static char *ranges_text(const sl_design *d, const char *sep, char *buf, size_t n)
{
    size_t used = 0;
    buf[0] = '\0';
    for (size_t q = 0; q < d->n_ranges; q++) {
        int w = snprintf(buf + used, n - used, "%s%.4g-%.4g", q ? sep : "", d->ranges[q].x_from,
                         d->ranges[q].x_to);
        if (w < 0 || (size_t)w >= n - used)
            break;
        used += (size_t)w;
    }
    return buf;
}

/* The clearance of row k as shown to a designer, mm: rounded up to the
 * step its standard error supports (stats.h: sl_stats_step, 0.1 to 10 mm).
 * The SE is that of the NLTHA design value where it is the clearance; an
 * ASCE value (policy asce, or envelope where ASCE governs) comes from the
 * floor's spectra and is shown to 0.1 mm. */
static double shown_mm(const sl_report_floor *fl, size_t k, double *step_mm)
{
    const sl_design_row *w = &fl->design->rows[k];
    double se_mm = 0;
    if (fl->conv && w->clearance_m == w->nltha_design_m)
        se_mm = MM_PER_M * fl->conv[k].design_se_m;
    *step_mm = sl_stats_step(se_mm, SHOWN_MIN_STEP_MM, SHOWN_MAX_STEP_MM);
    return sl_stats_round_up(MM_PER_M * w->clearance_m, *step_mm);
}

/* ---- CSV ---------------------------------------------------------------- */

/* One RFC 4180 field: quoted when it holds a comma, quote, CR or LF. */
static void csv_field(FILE *f, const char *s)
{
    if (!strpbrk(s, ",\"\r\n")) {
        fputs(s, f);
        return;
    }
    fputc('"', f);
    for (const char *p = s; *p; p++) {
        if (*p == '"')
            fputc('"', f);
        fputc(*p, f);
    }
    fputc('"', f);
}

static void csv_num(FILE *f, double v, const char *fmt)
{
    if (isfinite(v))
        fprintf(f, fmt, v);
    /* an empty field for a value that does not exist */
}

static sl_status csv_open(const char *dir, const char *name, sl_atomic **a, sl_error *err)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    *a = sl_atomic_open(path, err);
    return *a ? SL_OK : err ? err->code : SL_EIO;
}

sl_status sl_report_write_csv(const sl_report *r, const char *dir, sl_error *err)
{
    sl_atomic *a = NULL;
    char safe[256], flags[256], name[300];
    for (size_t i = 0; i < r->n_floors; i++) {
        const sl_report_floor *fl = &r->floors[i];
        snprintf(name, sizeof name, "floor_%s.csv", sl_report_safe_name(fl->name, safe, sizeof safe));
        if (csv_open(dir, name, &a, err))
            return err ? err->code : SL_EIO;
        FILE *f = sl_atomic_file(a);
        fputs("mu,mu_g_over_zpa,nltha_mean_mm,nltha_sd_mm,nltha_design_mm,asce_best_mm,"
              "asce_design_mm,cap_mm,clearance_mm,flags,n_sets,nltha_design_se_mm,"
              "nltha_design_lo90_mm,nltha_design_hi90_mm,p_slide,lognormal_mean_mm,converged,"
              "clearance_shown_mm\r\n",
              f);
        for (size_t k = 0; k < fl->design->n; k++) {
            const sl_design_row *w = &fl->design->rows[k];
            const double mm[] = {w->nltha_mean_m, w->nltha_sd_m, w->nltha_design_m,
                                 w->asce_best_m, w->asce_design_m, w->cap_m, w->clearance_m};
            fprintf(f, "%.4g,%.5g,", w->mu, w->x);
            for (size_t c = 0; c < sizeof mm / sizeof mm[0]; c++) {
                csv_num(f, MM_PER_M * mm[c], "%.4f");
                fputc(',', f);
            }
            csv_field(f, sl_report_flags(w->flags, flags, sizeof flags));
            if (fl->conv) {
                const sl_stats_conv *cv = &fl->conv[k];
                fprintf(f, ",%zu,", cv->n_sets);
                const double cm[] = {cv->design_se_m, cv->design_lo_m, cv->design_hi_m};
                for (size_t c = 0; c < sizeof cm / sizeof cm[0]; c++) {
                    csv_num(f, MM_PER_M * cm[c], "%.4f");
                    fputc(',', f);
                }
                fprintf(f, "%.4f,", cv->p_slide);
                csv_num(f, MM_PER_M * cv->lognormal_mean_m, "%.4f");
                fprintf(f, ",%s,", cv->converged ? "yes" : "no");
            } else {
                fputs(",,,,,,,,", f);
            }
            double step, v = shown_mm(fl, k, &step);
            if (isfinite(v))
                fprintf(f, "%.*f", sl_stats_step_decimals(step), v);
            fputs("\r\n", f);
        }
        if (sl_atomic_commit(a, err))
            return err ? err->code : SL_EIO;
    }
    /* summary: rows mu, one column per floor */
    if (csv_open(dir, "summary.csv", &a, err))
        return err ? err->code : SL_EIO;
    FILE *f = sl_atomic_file(a);
    fputs("mu", f);
    for (size_t i = 0; i < r->n_floors; i++) {
        char col[300];
        snprintf(col, sizeof col, "%s_clearance_mm", sl_report_safe_name(r->floors[i].name, safe, sizeof safe));
        fputc(',', f);
        csv_field(f, col);
    }
    fputs("\r\n", f);
    size_t n = r->n_floors ? r->floors[0].design->n : 0;
    for (size_t k = 0; k < n; k++) {
        fprintf(f, "%.4g", r->floors[0].design->rows[k].mu);
        for (size_t i = 0; i < r->n_floors; i++) {
            double step, v = shown_mm(&r->floors[i], k, &step);
            fputc(',', f);
            if (isfinite(v))
                fprintf(f, "%.*f", sl_stats_step_decimals(step), v);
        }
        fputs("\r\n", f);
    }
    if (sl_atomic_commit(a, err))
        return err ? err->code : SL_EIO;
    /* per floor: ZPA, crossover, unconservative ranges, note */
    if (csv_open(dir, "floors.csv", &a, err))
        return err ? err->code : SL_EIO;
    f = sl_atomic_file(a);
    fputs("floor,file,zpa_h_g,crossover_mu_g_over_zpa,crossover_mu,asce_below_nltha_mu_g_over_zpa,"
          "clearance_policy,mu_without_nltha,n_sets,sets_stop,note\r\n", f);
    for (size_t i = 0; i < r->n_floors; i++) {
        const sl_report_floor *fl = &r->floors[i];
        const sl_design *d = fl->design;
        char ranges[512];
        ranges_text(d, " ", ranges, sizeof ranges);
        csv_field(f, fl->name);
        fputc(',', f);
        csv_field(f, fl->path);
        fprintf(f, ",%.4f,", fl->zpa_h_ms2 / SL_G);
        csv_num(f, d->crossover_x, "%.4f");
        fputc(',', f);
        csv_num(f, d->crossover_mu, "%.4f");
        fputc(',', f);
        csv_field(f, ranges);
        fputc(',', f);
        csv_field(f, sl_clearance_policy_name(d->policy));
        fprintf(f, ",%zu,%zu,%s,", fl->n_mu_skipped, fl->n_sets, fl->stop ? fl->stop : "");
        csv_field(f, fl->note ? fl->note : "");
        fputs("\r\n", f);
    }
    if (sl_atomic_commit(a, err))
        return err ? err->code : SL_EIO;
    /* motion quality */
    if (csv_open(dir, "motion_quality.csv", &a, err))
        return err ? err->code : SL_EIO;
    f = sl_atomic_file(a);
    fputs("floor,set,component,pga_g,d5_75_s,min_ratio_to_target,max_ratio_to_target,"
          "max_run_below,max_abs_correlation,v_end_m_s,d_end_m,pass,failed_checks\r\n", f);
    for (size_t q = 0; q < r->n_quality; q++) {
        const sl_report_quality *m = &r->quality[q];
        csv_field(f, m->floor);
        fprintf(f, ",%d,%s,%.4f,%.3f,%.4f,%.4f,%d,%.4f,%.3g,%.3g,%s,", m->set, m->component,
                m->pga_g, m->d5_75_s, m->min_ratio, m->max_ratio, m->max_run_below, m->max_corr,
                m->v_end_ms, m->d_end_m, m->pass ? "yes" : "no");
        csv_field(f, m->why ? m->why : "");
        fputs("\r\n", f);
    }
    return sl_atomic_commit(a, err);
}

/* ---- XLSX --------------------------------------------------------------- */

typedef struct fmts {
    lxw_format *bold, *title, *mm, *mm0, *mmbold, *ratio, *mu, *wrap, *result, *input, *header;
} fmts;

/* A sheet name Excel accepts and that is unique in the workbook. */
static void sheet_name(const char *name, size_t index, char *buf, size_t n)
{
    char base[SHEET_NAME_MAX + 1];
    size_t k = 0;
    for (const char *p = name; *p && k < SHEET_NAME_MAX - 4; p++)
        base[k++] = strchr("[]:*?/\\'", *p) ? '_' : *p;
    base[k] = '\0';
    /* numbered: unique and in order; cut to Excel's limit */
    if (snprintf(buf, n, "%zu %s", index + 1, base) >= (int)n || strlen(buf) > SHEET_NAME_MAX)
        buf[n > SHEET_NAME_MAX ? SHEET_NAME_MAX : n - 1] = '\0';
}

/* Column letters of a 0-based column index. */
static void col_name(size_t c, char *buf)
{
    char tmp[8];
    int k = 0;
    c++;
    while (c > 0) {
        tmp[k++] = (char)('A' + (c - 1) % 26);
        c = (c - 1) / 26;
    }
    for (int i = 0; i < k; i++)
        buf[i] = tmp[k - 1 - i];
    buf[k] = '\0';
}

static void write_num_or_blank(lxw_worksheet *ws, lxw_row_t row, lxw_col_t col, double v,
                               lxw_format *f)
{
    if (isfinite(v))
        worksheet_write_number(ws, row, col, v, f);
    else
        worksheet_write_blank(ws, row, col, f);
}

/* First column of the side notes of a floor sheet (Q), right of the table. */
#define NOTE_COL 16

static void floor_sheet(lxw_workbook *wb, const fmts *F, const sl_report_floor *fl,
                        const char *sname)
{
    lxw_worksheet *ws = workbook_add_worksheet(wb, sname);
    const sl_design *d = fl->design;
    static const char *const head[] = {
        "mu", "mu g / ZPA", "NLTHA mean, mm", "NLTHA sd, mm", "NLTHA design (3.0 x mean), mm",
        "ASCE best estimate, mm", "ASCE design (2.0 x best), mm", "cap (1.5 x PGD), mm",
        "required clearance, mm", "flags", "motion sets", "SE of NLTHA design, mm",
        "NLTHA design, 90 % band low, mm", "NLTHA design, 90 % band high, mm",
        "clearance as shown (rounded up to the SE's digit), mm"};
    for (lxw_col_t c = 0; c < sizeof head / sizeof head[0]; c++)
        worksheet_write_string(ws, 0, c, head[c], F->header);
    worksheet_set_row(ws, 0, 45, NULL);
    worksheet_set_column(ws, 0, 1, 10, NULL);
    worksheet_set_column(ws, 2, 8, 14, NULL);
    worksheet_set_column(ws, 9, 9, 28, NULL);
    worksheet_set_column(ws, 10, 14, 14, NULL);
    worksheet_freeze_panes(ws, 1, 1);
    char flags[256];
    double ymax = 0;
    for (size_t k = 0; k < d->n; k++) {
        const sl_design_row *w = &d->rows[k];
        lxw_row_t row = (lxw_row_t)(k + 1);
        worksheet_write_number(ws, row, 0, w->mu, F->mu);
        worksheet_write_number(ws, row, 1, w->x, F->ratio);
        write_num_or_blank(ws, row, 2, MM_PER_M * w->nltha_mean_m, F->mm);
        write_num_or_blank(ws, row, 3, MM_PER_M * w->nltha_sd_m, F->mm);
        write_num_or_blank(ws, row, 4, MM_PER_M * w->nltha_design_m, F->mm);
        write_num_or_blank(ws, row, 5, MM_PER_M * w->asce_best_m, F->mm);
        write_num_or_blank(ws, row, 6, MM_PER_M * w->asce_design_m, F->mm);
        write_num_or_blank(ws, row, 7, MM_PER_M * w->cap_m, F->mm);
        write_num_or_blank(ws, row, 8, MM_PER_M * w->clearance_m, F->mmbold);
        worksheet_write_string(ws, row, 9, sl_report_flags(w->flags, flags, sizeof flags), NULL);
        if (fl->conv) {
            const sl_stats_conv *cv = &fl->conv[k];
            worksheet_write_number(ws, row, 10, (double)cv->n_sets, NULL);
            write_num_or_blank(ws, row, 11, MM_PER_M * cv->design_se_m, F->mm);
            write_num_or_blank(ws, row, 12, MM_PER_M * cv->design_lo_m, F->mm);
            write_num_or_blank(ws, row, 13, MM_PER_M * cv->design_hi_m, F->mm);
        }
        double step, shown = shown_mm(fl, k, &step);
        write_num_or_blank(ws, row, 14, shown, step >= 1 ? F->mm0 : F->mm);
        ymax = fmax(ymax, fmax(w->nltha_design_m, isfinite(w->asce_design_m) ? w->asce_design_m : 0));
    }
    /* side notes and the crossover marker (two points: a vertical line) */
    char buf[512];
    worksheet_write_string(ws, 0, NOTE_COL, "floor", F->bold);
    worksheet_write_string(ws, 0, NOTE_COL + 1, fl->name, NULL);
    worksheet_write_string(ws, 1, NOTE_COL, "horizontal ZPA, g", F->bold);
    worksheet_write_number(ws, 1, NOTE_COL + 1, fl->zpa_h_ms2 / SL_G, F->ratio);
    worksheet_write_string(ws, 2, NOTE_COL, "crossover mu g / ZPA", F->bold);
    worksheet_write_string(ws, 4, NOTE_COL, "clearance policy", F->bold);
    worksheet_write_string(ws, 4, NOTE_COL + 1, sl_clearance_policy_name(d->policy), NULL);
    worksheet_write_string(ws, 5, NOTE_COL, "note", F->bold);
    worksheet_write_string(ws, 5, NOTE_COL + 1, fl->note && *fl->note ? fl->note : "-", F->wrap);
    worksheet_write_string(ws, 3, NOTE_COL, "mu needing no NLTHA (mu g >= demand)", F->bold);
    worksheet_write_number(ws, 3, NOTE_COL + 1, (double)fl->n_mu_skipped, NULL);
    worksheet_write_string(ws, 6, NOTE_COL, "ASCE below NLTHA for mu g/ZPA in", F->bold);
    worksheet_write_string(ws, 6, NOTE_COL + 1, d->n_ranges ? ranges_text(d, ", ", buf, sizeof buf) : "none",
                           NULL);
    worksheet_write_string(ws, 7, NOTE_COL, "motion sets (why they stopped)", F->bold);
    snprintf(buf, sizeof buf, "%zu (%s)", fl->n_sets, fl->stop ? fl->stop : "-");
    worksheet_write_string(ws, 7, NOTE_COL + 1, buf, NULL);
    worksheet_set_column(ws, NOTE_COL, NOTE_COL, 30, NULL);
    worksheet_set_column(ws, NOTE_COL + 1, NOTE_COL + 1, 40, NULL);
    if (d->has_crossover) {
        worksheet_write_number(ws, 2, NOTE_COL + 1, d->crossover_x, F->ratio);
        worksheet_write_string(ws, 8, NOTE_COL, "crossover marker x", NULL);
        worksheet_write_string(ws, 8, NOTE_COL + 1, "marker y, mm", NULL);
        worksheet_write_number(ws, 9, NOTE_COL, d->crossover_x, NULL);
        worksheet_write_number(ws, 9, NOTE_COL + 1, 0, NULL);
        worksheet_write_number(ws, 10, NOTE_COL, d->crossover_x, NULL);
        worksheet_write_number(ws, 10, NOTE_COL + 1, MM_PER_M * ymax, NULL);
    } else {
        worksheet_write_string(ws, 2, NOTE_COL + 1, "none", NULL);
    }

    lxw_chart *ch = workbook_add_chart(wb, LXW_CHART_SCATTER_STRAIGHT);
    char xr[128], yr[128];
    unsigned last = (unsigned)d->n + 1;
    static const struct {
        lxw_col_t col;
        const char *name;
    } series[] = {{4, "NLTHA design (3.0 x mean)"}, {6, "ASCE design (2.0 x best)"},
                  {2, "NLTHA mean"}, {7, "cap (1.5 x PGD)"},
                  {12, "NLTHA design, 90 % band low"}, {13, "NLTHA design, 90 % band high"}};
    size_t n_series = sizeof series / sizeof series[0] - (fl->conv ? 0 : 2);
    for (size_t q = 0; q < n_series; q++) {
        char c[8];
        col_name(series[q].col, c);
        snprintf(xr, sizeof xr, "='%s'!$B$2:$B$%u", sname, last);
        snprintf(yr, sizeof yr, "='%s'!$%s$2:$%s$%u", sname, c, c, last);
        lxw_chart_series *s = chart_add_series(ch, xr, yr);
        chart_series_set_name(s, series[q].name);
    }
    if (d->has_crossover) {
        snprintf(xr, sizeof xr, "='%s'!$Q$10:$Q$11", sname);
        snprintf(yr, sizeof yr, "='%s'!$R$10:$R$11", sname);
        lxw_chart_series *s = chart_add_series(ch, xr, yr);
        chart_series_set_name(s, "crossover");
    }
    snprintf(buf, sizeof buf, "Design sliding spectra: %s", fl->name);
    chart_title_set_name(ch, buf);
    chart_axis_set_name(ch->x_axis, "mu g / ZPA");
    chart_axis_set_name(ch->y_axis, "sliding displacement, mm");
    chart_axis_set_min(ch->x_axis, 0);
    chart_legend_set_position(ch, LXW_CHART_LEGEND_BOTTOM);
    lxw_chart_options co = {.x_offset = 0, .y_offset = 0, .x_scale = 1.6, .y_scale = 1.5};
    worksheet_insert_chart_opt(ws, 12, NOTE_COL, ch, &co);
    /* printing: landscape, one page wide */
    worksheet_set_landscape(ws);
    worksheet_fit_to_pages(ws, 1, 0);
    worksheet_repeat_rows(ws, 0, 0);
}

static void summary_sheet(lxw_workbook *wb, const fmts *F, const sl_report *r)
{
    lxw_worksheet *ws = workbook_add_worksheet(wb, "Summary");
    size_t n = r->floors[0].design->n;
    worksheet_write_string(ws, 0, 0, "mu", F->header);
    for (size_t i = 0; i < r->n_floors; i++)
        worksheet_write_string(ws, 0, (lxw_col_t)(i + 1), r->floors[i].name, F->header);
    worksheet_set_row(ws, 0, 45, NULL);
    worksheet_set_column(ws, 0, 0, 24, NULL);
    worksheet_set_column(ws, 1, (lxw_col_t)r->n_floors, 16, NULL);
    worksheet_freeze_panes(ws, 1, 1);
    for (size_t k = 0; k < n; k++) {
        worksheet_write_number(ws, (lxw_row_t)(k + 1), 0, r->floors[0].design->rows[k].mu, F->mu);
        for (size_t i = 0; i < r->n_floors; i++) {
            double step, v = shown_mm(&r->floors[i], k, &step);
            write_num_or_blank(ws, (lxw_row_t)(k + 1), (lxw_col_t)(i + 1), v,
                               step >= 1 ? F->mm0 : F->mm);
        }
    }
    worksheet_fit_to_pages(ws, 1, 0);
    worksheet_repeat_rows(ws, 0, 0);
    lxw_row_t b = (lxw_row_t)(n + 2);
    worksheet_write_string(ws, b, 0, "required clearance, mm: the rows above (rounded up to "
                           "the digit of its standard error)", F->bold);
    worksheet_write_string(ws, b + 4, 0, "motion sets", F->bold);
    worksheet_write_string(ws, b + 5, 0, "sets stopped because", F->bold);
    worksheet_write_string(ws, b + 1, 0, "horizontal ZPA, g", F->bold);
    worksheet_write_string(ws, b + 2, 0, "crossover mu g / ZPA", F->bold);
    worksheet_write_string(ws, b + 3, 0, "crossover mu", F->bold);
    for (size_t i = 0; i < r->n_floors; i++) {
        const sl_report_floor *fl = &r->floors[i];
        lxw_col_t c = (lxw_col_t)(i + 1);
        worksheet_write_number(ws, b + 1, c, fl->zpa_h_ms2 / SL_G, F->ratio);
        worksheet_write_number(ws, b + 4, c, (double)fl->n_sets, NULL);
        worksheet_write_string(ws, b + 5, c, fl->stop ? fl->stop : "", NULL);
        if (fl->design->has_crossover) {
            worksheet_write_number(ws, b + 2, c, fl->design->crossover_x, F->ratio);
            worksheet_write_number(ws, b + 3, c, fl->design->crossover_mu, F->ratio);
        } else {
            worksheet_write_string(ws, b + 2, c, "none", NULL);
            worksheet_write_string(ws, b + 3, c, "none", NULL);
        }
    }
}

static void lookup_sheet(lxw_workbook *wb, const fmts *F, const sl_report *r)
{
    lxw_worksheet *ws = workbook_add_worksheet(wb, "Lookup");
    const sl_design *d0 = r->floors[0].design;
    size_t n = d0->n;
    double mu_min = d0->rows[0].mu, mu_max = d0->rows[n - 1].mu;
    char last_col[8], f[1024], muvals[64], floors_range[64];
    col_name(r->n_floors, last_col);
    unsigned last = (unsigned)n + 1;
    snprintf(muvals, sizeof muvals, "Summary!$A$2:$A$%u", last);
    snprintf(floors_range, sizeof floors_range, "Summary!$B$1:$%s$1", last_col);
    worksheet_set_column(ws, 0, 0, 42, NULL);
    worksheet_set_column(ws, 1, 1, 30, NULL);
    worksheet_write_string(ws, 0, 0, "Required clearance around an unanchored component", F->title);
    worksheet_write_string(ws, 2, 0, "Floor (choose from the list)", F->bold);
    worksheet_write_string(ws, 2, 1, r->floors[0].name, F->input);
    lxw_data_validation dv;
    memset(&dv, 0, sizeof dv);
    dv.validate = LXW_VALIDATION_TYPE_LIST_FORMULA;
    char list_formula[80];
    snprintf(list_formula, sizeof list_formula, "=%s", floors_range);
    dv.value_formula = list_formula;
    dv.input_title = "Floor";
    dv.input_message = "Choose the floor the component stands on.";
    worksheet_data_validation_cell(ws, 2, 1, &dv);
    double mu0 = (LOOKUP_DEFAULT_MU >= mu_min && LOOKUP_DEFAULT_MU <= mu_max) ? LOOKUP_DEFAULT_MU : mu_min;
    worksheet_write_string(ws, 3, 0, "Friction coefficient mu (type it)", F->bold);
    worksheet_write_number(ws, 3, 1, mu0, F->input);
    lxw_data_validation dm;
    memset(&dm, 0, sizeof dm);
    dm.validate = LXW_VALIDATION_TYPE_DECIMAL;
    dm.criteria = LXW_VALIDATION_CRITERIA_BETWEEN;
    dm.minimum_number = mu_min;
    dm.maximum_number = mu_max;
    dm.input_title = "Friction coefficient";
    char msg[128];
    snprintf(msg, sizeof msg, "Between %.2f and %.2f (static = kinetic).", mu_min, mu_max);
    dm.input_message = msg;
    dm.error_title = "mu outside the table";
    dm.error_message = msg;
    worksheet_data_validation_cell(ws, 3, 1, &dm);

    /* cached values for the default choice, computed as the formulas do */
    size_t rlow = 0;
    while (rlow + 1 < n && d0->rows[rlow + 1].mu <= mu0)
        rlow++;
    size_t rhigh = rlow + 1 < n ? rlow + 1 : rlow;
    double x0 = d0->rows[rlow].mu, x1 = d0->rows[rhigh].mu;
    double y0 = MM_PER_M * d0->rows[rlow].clearance_m, y1 = MM_PER_M * d0->rows[rhigh].clearance_m;
    double res = x1 == x0 ? y0 : y0 + (mu0 - x0) * (y1 - y0) / (x1 - x0);

    worksheet_write_string(ws, 5, 0, "Required clearance, mm", F->title);
    snprintf(f, sizeof f,
             "=IF(OR(B4<%g,B4>%g),\"mu outside %g-%g\",IF(B11=B10,B12,B12+(B4-B10)*(B13-B12)/(B11-B10)))",
             mu_min, mu_max, mu_min, mu_max);
    worksheet_write_formula_num(ws, 5, 1, f, F->result, res);
    worksheet_write_string(ws, 7, 0, "How it is computed (linear interpolation in mu):", F->bold);
    worksheet_write_string(ws, 8, 0, "column of the floor in Summary", NULL);
    snprintf(f, sizeof f, "=MATCH(B3,%s,0)", floors_range);
    worksheet_write_formula_num(ws, 8, 1, f, NULL, 1);
    worksheet_write_string(ws, 9, 0, "mu at or below", NULL);
    snprintf(f, sizeof f, "=INDEX(%s,MATCH(B4,%s,1))", muvals, muvals);
    worksheet_write_formula_num(ws, 9, 1, f, F->mu, x0);
    worksheet_write_string(ws, 10, 0, "mu above", NULL);
    snprintf(f, sizeof f, "=INDEX(%s,MIN(MATCH(B4,%s,1)+1,%zu))", muvals, muvals, n);
    worksheet_write_formula_num(ws, 10, 1, f, F->mu, x1);
    worksheet_write_string(ws, 11, 0, "clearance at the mu at or below, mm", NULL);
    snprintf(f, sizeof f, "=INDEX(Summary!$B$2:$%s$%u,MATCH(B4,%s,1),B9)", last_col, last, muvals);
    worksheet_write_formula_num(ws, 11, 1, f, F->mm, y0);
    worksheet_write_string(ws, 12, 0, "clearance at the mu above, mm", NULL);
    snprintf(f, sizeof f, "=INDEX(Summary!$B$2:$%s$%u,MIN(MATCH(B4,%s,1)+1,%zu),B9)", last_col,
             last, muvals, n);
    worksheet_write_formula_num(ws, 12, 1, f, F->mm, y1);
    worksheet_write_string(ws, 14, 0, "Clearance policy", F->bold);
    worksheet_write_string(ws, 14, 1, sl_clearance_policy_name(d0->policy), NULL);
    worksheet_merge_range(ws, 15, 0, 15, 1,
                          "nltha: 3.0 x the mean peak vector sliding displacement of the "
                          "synthesized motion sets (ASCE/SEI 43-05), capped at 1.5 x the mean "
                          "peak floor displacement; asce: 2.0 x the ASCE best estimate, same "
                          "cap; envelope: the larger. See each floor's sheet for both curves, "
                          "the cap and the crossover.",
                          F->wrap);
    worksheet_set_row(ws, 15, 60, NULL);
    worksheet_fit_to_pages(ws, 1, 1);
    worksheet_activate(ws);
}

static void quality_sheet(lxw_workbook *wb, const fmts *F, const sl_report *r)
{
    lxw_worksheet *ws = workbook_add_worksheet(wb, "Motion quality");
    static const char *const head[] = {
        "floor", "set", "component", "PGA, g", "D5-75, s", "min ratio to target",
        "max ratio to target", "longest run below", "max |correlation|", "v end, m/s",
        "d end, m", "pass", "failed checks"};
    for (lxw_col_t c = 0; c < 13; c++)
        worksheet_write_string(ws, 0, c, head[c], F->header);
    worksheet_set_row(ws, 0, 30, NULL);
    worksheet_set_column(ws, 0, 0, 24, NULL);
    worksheet_set_column(ws, 1, 11, 11, NULL);
    worksheet_set_column(ws, 12, 12, 40, NULL);
    worksheet_freeze_panes(ws, 1, 0);
    for (size_t q = 0; q < r->n_quality; q++) {
        const sl_report_quality *m = &r->quality[q];
        lxw_row_t row = (lxw_row_t)(q + 1);
        worksheet_write_string(ws, row, 0, m->floor, NULL);
        worksheet_write_number(ws, row, 1, m->set, NULL);
        worksheet_write_string(ws, row, 2, m->component, NULL);
        write_num_or_blank(ws, row, 3, m->pga_g, F->ratio);
        write_num_or_blank(ws, row, 4, m->d5_75_s, F->ratio);
        write_num_or_blank(ws, row, 5, m->min_ratio, F->ratio);
        write_num_or_blank(ws, row, 6, m->max_ratio, F->ratio);
        worksheet_write_number(ws, row, 7, m->max_run_below, NULL);
        write_num_or_blank(ws, row, 8, m->max_corr, F->ratio);
        write_num_or_blank(ws, row, 9, m->v_end_ms, NULL);
        write_num_or_blank(ws, row, 10, m->d_end_m, NULL);
        worksheet_write_string(ws, row, 11, m->pass ? "yes" : "NO", m->pass ? NULL : F->bold);
        worksheet_write_string(ws, row, 12, m->why ? m->why : "", NULL);
    }
}

static void inputs_sheet(lxw_workbook *wb, const fmts *F, const sl_report *r)
{
    lxw_worksheet *ws = workbook_add_worksheet(wb, "Inputs");
    worksheet_set_column(ws, 0, 0, 30, NULL);
    worksheet_set_column(ws, 1, 1, 70, NULL);
    lxw_row_t row = 0;
    worksheet_write_string(ws, row++, 0, "What reproduces this workbook", F->title);
    worksheet_write_string(ws, row, 0, "program", F->bold);
    worksheet_write_string(ws, row++, 1, r->version, NULL);
    worksheet_write_string(ws, row, 0, "command", F->bold);
    worksheet_write_string(ws, row++, 1, r->command_line ? r->command_line : "", NULL);
    char buf[64];
    struct tm tmv;
    gmtime_r(&r->created, &tmv);
    strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tmv);
    worksheet_write_string(ws, row, 0, "created (UTC)", F->bold);
    worksheet_write_string(ws, row++, 1, buf, NULL);
    for (size_t s = 0; s < r->n_settings; s++) {
        worksheet_write_string(ws, row, 0, r->settings[s].name, F->bold);
        worksheet_write_string(ws, row++, 1, r->settings[s].value, NULL);
    }
    row++;
    worksheet_write_string(ws, row, 0, "floor", F->header);
    worksheet_write_string(ws, row, 1, "file", F->header);
    worksheet_write_string(ws, row, 2, "bytes", F->header);
    worksheet_write_string(ws, row++, 3, "CRC-32", F->header);
    for (size_t i = 0; i < r->n_floors; i++) {
        const sl_report_floor *fl = &r->floors[i];
        worksheet_write_string(ws, row, 0, fl->name, NULL);
        worksheet_write_string(ws, row, 1, fl->path, NULL);
        worksheet_write_number(ws, row, 2, (double)fl->size_bytes, NULL);
        snprintf(buf, sizeof buf, "%08lx", fl->crc32 & 0xffffffffUL);
        worksheet_write_string(ws, row++, 3, buf, NULL);
    }
}

sl_status sl_report_write_xlsx(const sl_report *r, const char *path, sl_error *err)
{
    if (!r || r->n_floors == 0)
        return sl_error_set(err, SL_EINVAL, path, 0, "no floors to write");
    for (size_t i = 1; i < r->n_floors; i++)
        if (r->floors[i].design->n != r->floors[0].design->n)
            return sl_error_set(err, SL_EINVAL, path, 0, "floors do not share the friction grid");
    sl_atomic *a = sl_atomic_open(path, err);
    if (!a)
        return err ? err->code : SL_EIO;
    lxw_workbook_options wo = {.constant_memory = LXW_FALSE, .tmpdir = NULL, .use_zip64 = LXW_FALSE};
    lxw_workbook *wb = workbook_new_opt(sl_atomic_tmpname(a), &wo);
    if (!wb) {
        sl_atomic_abort(a);
        return sl_error_set(err, SL_EIO, path, 0, "cannot create the workbook");
    }
    lxw_doc_properties props;
    memset(&props, 0, sizeof props);
    props.title = "Required clearance around unanchored components";
    props.subject = "Design sliding spectra per floor (NLTHA and ASCE/SEI 43-05)";
    props.author = "seislide";
    props.created = r->created;
    workbook_set_properties(wb, &props);
    fmts F;
    F.bold = workbook_add_format(wb);
    format_set_bold(F.bold);
    F.title = workbook_add_format(wb);
    format_set_bold(F.title);
    format_set_font_size(F.title, 14);
    F.mm = workbook_add_format(wb);
    format_set_num_format(F.mm, "0.0");
    F.mm0 = workbook_add_format(wb);
    format_set_num_format(F.mm0, "0");
    F.mmbold = workbook_add_format(wb);
    format_set_num_format(F.mmbold, "0.0");
    format_set_bold(F.mmbold);
    F.ratio = workbook_add_format(wb);
    format_set_num_format(F.ratio, "0.000");
    F.mu = workbook_add_format(wb);
    format_set_num_format(F.mu, "0.00");
    F.wrap = workbook_add_format(wb);
    format_set_text_wrap(F.wrap);
    format_set_align(F.wrap, LXW_ALIGN_VERTICAL_TOP);
    F.result = workbook_add_format(wb);
    format_set_bold(F.result);
    format_set_font_size(F.result, 14);
    format_set_num_format(F.result, "0.0");
    format_set_bg_color(F.result, 0xE2EFDA);
    format_set_border(F.result, LXW_BORDER_THIN);
    F.input = workbook_add_format(wb);
    format_set_bg_color(F.input, 0xFFF2CC);
    format_set_border(F.input, LXW_BORDER_THIN);
    F.header = workbook_add_format(wb);
    format_set_bold(F.header);
    format_set_text_wrap(F.header);
    format_set_bottom(F.header, LXW_BORDER_THIN);

    lookup_sheet(wb, &F, r);
    summary_sheet(wb, &F, r);
    for (size_t i = 0; i < r->n_floors; i++) {
        char sname[SHEET_NAME_MAX + 8];
        sheet_name(r->floors[i].name, i, sname, sizeof sname);
        floor_sheet(wb, &F, &r->floors[i], sname);
    }
    quality_sheet(wb, &F, r);
    inputs_sheet(wb, &F, r);
    lxw_error le = workbook_close(wb);
    if (le != LXW_NO_ERROR) {
        sl_atomic_abort(a);
        return sl_error_set(err, SL_EIO, path, 0, "cannot write the workbook: %s", lxw_strerror(le));
    }
    return sl_atomic_commit(a, err);
}
