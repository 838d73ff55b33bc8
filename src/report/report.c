/* report.c - clearance workbook (XLSX) and CSV tables; see report.h. */
#include "report/report.h"

#include <ctype.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <xlsxwriter.h>

#include "core/units.h"
#include "io/atomic.h"
#include "method/stats.h"

#define MM_PER_M 1000.0
#define SHEET_NAME_MAX 31  /* Excel's limit */
#define ID_MAX 64          /* longest floor id */
#define WORKBOOK_NAME "seislide-clearance.xlsx"
/* Print: the floor sheets' fixed scale (the PDF test checks >= 70 %). */
#define FLOOR_PRINT_SCALE 75
/* Charts: log axis floor, mm (a log axis has no 0). */
#define CHART_MIN_MM 0.1
/* Header/footer text limit (Excel: 255 characters). */
#define HF_MAX 255

void sl_report_init(sl_report *r)
{
    memset(r, 0, sizeof *r);
    r->lookup_mu = SL_REPORT_LOOKUP_MU;
}

static char safe_char(char c)
{
    return (isalnum((unsigned char)c) || c == '-' || c == '_') ? c : '_';
}

char *sl_report_floor_id(const char *path, char *buf, size_t n)
{
    const char *base = path ? path : "";
    const char *slash = strrchr(base, '/');
    if (slash)
        base = slash + 1;
    size_t len = strlen(base);
    if (len > 4 && (!strcasecmp(base + len - 4, ".ini") || !strcasecmp(base + len - 4, ".csv")))
        len -= 4;
    size_t k = 0;
    for (size_t i = 0; i < len && k + 1 < n && k < ID_MAX; i++)
        buf[k++] = safe_char(base[i]);
    if (k == 0 && n > 1)
        buf[k++] = '_';
    buf[k] = '\0';
    return buf;
}

sl_status sl_report_check_floors(const sl_report *r, sl_error *err)
{
    for (size_t i = 0; i < r->n_floors; i++)
        for (size_t j = 0; j < i; j++) {
            const sl_report_floor *a = &r->floors[j], *b = &r->floors[i];
            if (!strcmp(a->id, b->id))
                return sl_error_set(err, SL_EINVAL, b->path, 0,
                                    "floor id '%s' (from the file name) is also that of %s: "
                                    "rename one file, the outputs are named by it",
                                    b->id, a->path);
            if (!strcasecmp(a->name, b->name))
                return sl_error_set(err, SL_EINVAL, b->path, 0,
                                    "floor name '%s' is also that of %s: floor names must "
                                    "differ (the workbook's Lookup chooses by name)",
                                    b->name, a->path);
        }
    return SL_OK;
}

int sl_report_owns_name(const char *name)
{
    static const char *const fixed[] = {WORKBOOK_NAME, "summary.csv", "floors.csv",
                                        "asce_below_nltha.csv", "motion_quality.csv", "motions"};
    for (size_t i = 0; i < sizeof fixed / sizeof fixed[0]; i++)
        if (!strcmp(name, fixed[i]))
            return 1;
    size_t n = strlen(name);
    if (!strncmp(name, "floor_", 6) && n > 10 && !strcmp(name + n - 4, ".csv"))
        return 1;
    /* a temporary file of an interrupted older version */
    return name[0] == '.' && strstr(name, ".tmp-") != NULL;
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

char *sl_report_ranges_text(const sl_design *d, char *buf, size_t n)
{
    size_t used = 0;
    buf[0] = '\0';
    if (d->n_ranges == 0) {
        snprintf(buf, n, "none");
        return buf;
    }
    for (size_t q = 0; q < d->n_ranges; q++) {
        const sl_design_range *g = &d->ranges[q];
        int w = snprintf(buf + used, n - used, "%s%s%.3f-%.3f%s", q ? ", " : "",
                         g->open_lo ? "<=" : "", g->mu_lo, g->mu_hi, g->open_hi ? "+" : "");
        if (w < 0 || (size_t)w >= n - used)
            break;
        used += (size_t)w;
    }
    return buf;
}

/* Where the ASCE best estimate is flat (within 0.1 %) or rises with mu:
 * "flat for mu 0.05-0.07 (constant spectral displacement at f_es); rises
 * for mu 0.30-0.70 (f_es on a flank where SA grows faster than f^2)". */
static char *asce_shape_text(const sl_design *d, char *buf, size_t n)
{
    static const char *const why[2] = {"constant spectral displacement at f_es",
                                        "f_es on a flank where SA grows faster than f^2"};
    size_t used = 0;
    buf[0] = '\0';
    for (int kind = 0; kind < 2; kind++) {
        int first = 1;
        for (size_t k = 0; k + 1 < d->n; k++) {
            double a = d->rows[k].asce_best_m, b = d->rows[k + 1].asce_best_m;
            int hit = a > 0 && b > 0 && (kind == 0 ? fabs(b - a) <= 1e-3 * a : b > a * (1 + 1e-3));
            if (!hit)
                continue;
            size_t e = k + 1;
            while (e + 1 < d->n) {
                double c = d->rows[e].asce_best_m, q = d->rows[e + 1].asce_best_m;
                if (!(c > 0 && q > 0 && (kind == 0 ? fabs(q - c) <= 1e-3 * c : q > c * (1 + 1e-3))))
                    break;
                e++;
            }
            int w = snprintf(buf + used, n - used, "%s%s%.2f-%.2f", first ? (used ? "; " : "") : ", ",
                             first ? (kind == 0 ? "flat for mu " : "rises for mu ") : "",
                             d->rows[k].mu, d->rows[e].mu);
            if (w < 0 || (size_t)w >= n - used)
                return buf;
            used += (size_t)w;
            first = 0;
            k = e - 1;
        }
        if (!first) {
            int w = snprintf(buf + used, n - used, " (%s)", why[kind]);
            if (w > 0 && (size_t)w < n - used)
                used += (size_t)w;
        }
    }
    if (!used)
        snprintf(buf, n, "falls with mu over the whole grid");
    return buf;
}

/* "0.123 (mu g/ZPA 0.456)" or the reason there is none. */
static char *crossover_text(const sl_design *d, char *buf, size_t n)
{
    if (d->has_crossover)
        snprintf(buf, n, "mu %.3f (mu g/ZPA %.3f)", d->crossover_mu, d->crossover_x);
    else
        snprintf(buf, n, "none (ASCE is not below NLTHA at the lowest mu of the grid)");
    return buf;
}

/* The standard error of the NLTHA design value at row k, m: the one the
 * convergence statistics give (sl_report_floor.design_se_m: FS SE(mean)
 * below the cap, the cap's SE where the cap governs); without them FS
 * sd / sqrt(N) below the cap and 0 where the cap governs. */
static double design_se_m(const sl_report_floor *fl, size_t k)
{
    if (fl->design_se_m)
        return fl->design_se_m[k];
    const sl_design *d = fl->design;
    const sl_design_row *w = &d->rows[k];
    if ((w->flags & SL_DESIGN_NLTHA_CAPPED) || d->n_sets < 2)
        return 0.0;
    return d->fs_nltha * w->nltha_sd_m / sqrt((double)d->n_sets);
}

/* Clearances in summary.csv and the Summary sheet are shown to the place of
 * their SE's leading digit, between these steps, mm (shown_decimals). */
#define SHOWN_MIN_STEP_MM 0.1
#define SHOWN_MAX_STEP_MM 1.0

/* Decimals to show the clearance of row k with: 0 when the standard error
 * of the NLTHA design value is 1 mm or more, else 1 (stats.h:
 * sl_stats_step). An ASCE clearance comes from the floor's spectra: 1. The
 * value itself is not rounded (the Lookup interpolates the exact values). */
static int shown_decimals(const sl_report_floor *fl, size_t k)
{
    const sl_design_row *w = &fl->design->rows[k];
    double se_mm = w->clearance_m == w->nltha_design_m ? MM_PER_M * design_se_m(fl, k) : 0.0;
    return sl_stats_step_decimals(sl_stats_step(se_mm, SHOWN_MIN_STEP_MM, SHOWN_MAX_STEP_MM));
}

/* Every number the report writes must be finite: ASCE may be undefined
 * (NAN, written as an empty cell), nothing may be infinite. */
static sl_status check_finite(const sl_report *r, sl_error *err)
{
    if (!r || r->n_floors == 0)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "report: no floors to write");
    for (size_t i = 0; i < r->n_floors; i++) {
        const sl_report_floor *fl = &r->floors[i];
        const sl_design *d = fl->design;
        if (d->n != r->floors[0].design->n)
            return sl_error_set(err, SL_EINVAL, fl->path, 0, "floors do not share the friction grid");
        if (!isfinite(fl->zpa_h_ms2) || !(fl->zpa_h_ms2 > 0))
            return sl_error_set(err, SL_EINVAL, fl->path, 0, "horizontal ZPA %g is not finite and > 0",
                                fl->zpa_h_ms2);
        for (size_t k = 0; k < d->n; k++) {
            const sl_design_row *w = &d->rows[k];
            const double must[] = {w->mu, w->x, w->nltha_mean_m, w->nltha_sd_m, w->nltha_design_m,
                                   w->cap_m};
            const double may[] = {w->asce_best_m, w->asce_design_m, w->clearance_m};
            int bad = 0;
            for (size_t c = 0; c < sizeof must / sizeof must[0]; c++)
                bad |= !isfinite(MM_PER_M * must[c]);
            for (size_t c = 0; c < sizeof may / sizeof may[0]; c++)
                bad |= isinf(MM_PER_M * may[c]);
            if (bad)
                return sl_error_set(err, SL_EINVAL, fl->path, 0,
                                    "floor '%s': a result at mu %g is not finite (NLTHA mean %g m, "
                                    "ASCE best %g m): check the file's values and units",
                                    fl->name, w->mu, w->nltha_mean_m, w->asce_best_m);
        }
    }
    return SL_OK;
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

/* 1 when the floor's file gives dampings other than the one matched. */
static int has_dampings(const sl_report_floor *fl)
{
    return fl->dampings && *fl->dampings && strcmp(fl->dampings, "none") != 0;
}

/* A comment line "# key: value" (line breaks in value become blanks). */
static void csv_comment(FILE *f, const char *key, const char *value)
{
    fprintf(f, "# %s: ", key);
    for (const char *p = value ? value : ""; *p; p++)
        fputc(*p == '\r' || *p == '\n' ? ' ' : *p, f);
    fputs("\r\n", f);
}

static void csv_head(FILE *f, const sl_report *r, const char *what)
{
    csv_comment(f, "program", r->version);
    csv_comment(f, "content", what);
    csv_comment(f, "project", r->project.project && *r->project.project ? r->project.project : "-");
    csv_comment(f, "document", r->project.document && *r->project.document ? r->project.document : "-");
    csv_comment(f, "revision", r->project.revision && *r->project.revision ? r->project.revision : "-");
}

static sl_status csv_open(const char *dir, const char *name, sl_atomic **a, sl_error *err)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    *a = sl_atomic_open(path, err);
    return *a ? SL_OK : err ? err->code : SL_EIO;
}

static sl_status csv_floor(const sl_report *r, const sl_report_floor *fl, const char *dir,
                           sl_error *err)
{
    sl_atomic *a;
    char name[ID_MAX + 16], buf[1024], flags[256];
    snprintf(name, sizeof name, "floor_%s.csv", fl->id);
    if (csv_open(dir, name, &a, err))
        return err ? err->code : SL_EIO;
    FILE *f = sl_atomic_file(a);
    const sl_design *d = fl->design;
    csv_head(f, r, "design sliding spectra and required clearance of one floor");
    csv_comment(f, "floor_id", fl->id);
    csv_comment(f, "floor", fl->name);
    csv_comment(f, "floor_file", fl->path);
    snprintf(buf, sizeof buf, "%.4f", fl->zpa_h_ms2 / SL_G);
    csv_comment(f, "horizontal_zpa_g", buf);
    csv_comment(f, "units", "displacements and clearance in mm; mu and mu g/ZPA dimensionless");
    snprintf(buf, sizeof buf, "NLTHA design = min(%g x mean, cap); ASCE design = min(%g x best "
             "estimate, cap); cap = %g x mean peak floor displacement (100-40); %zu motion sets",
             d->fs_nltha, d->fs_asce, d->cap_factor, d->n_sets);
    csv_comment(f, "factors", buf);
    if (fl->scatter > 0)
        snprintf(buf, sizeof buf, "%g (log standard deviation of the sets' horizontal intensity, "
                 "mean 1; each set's NLTHA peak averaged over it, docs/run.md; motions written by "
                 "--motions carry no factor; --scatter 0: the sets as synthesized)", fl->scatter);
    else
        snprintf(buf, sizeof buf, "%s", fl->scatter == 0 ? "0 (the sets as synthesized)" : "-");
    csv_comment(f, "nltha_intensity_scatter", buf);
    csv_comment(f, "clearance_policy", sl_clearance_policy_name(d->policy));
    csv_comment(f, "crossover", crossover_text(d, buf, sizeof buf));
    csv_comment(f, "asce_below_nltha_mu", sl_report_ranges_text(d, buf, sizeof buf));
    csv_comment(f, "note", fl->note && *fl->note ? fl->note : "-");
    csv_comment(f, "nltha_err_est_mm", "the largest estimated integration error of any motion's "
                "peak at this mu (the engine's err_est_m; the tolerance is --accuracy)");
    csv_comment(f, "nltha_design_lo90_mm, nltha_design_hi90_mm",
                fl->design_lo_m && fl->design_hi_m ? "the 90 % band of the NLTHA design value"
                : "the 90 % band of the NLTHA design value (empty: not computed in this run)");
    fputs("mu,mu_g_over_zpa,nltha_mean_mm,nltha_sd_mm,nltha_design_mm,nltha_design_se_mm,"
          "nltha_design_lo90_mm,nltha_design_hi90_mm,asce_best_mm,asce_design_mm,cap_mm,"
          "clearance_mm,flags,nltha_err_est_mm\r\n", f);
    for (size_t k = 0; k < d->n; k++) {
        const sl_design_row *w = &d->rows[k];
        const double mm[] = {w->nltha_mean_m, w->nltha_sd_m, w->nltha_design_m, design_se_m(fl, k),
                             fl->design_lo_m ? fl->design_lo_m[k] : NAN,
                             fl->design_hi_m ? fl->design_hi_m[k] : NAN,
                             w->asce_best_m, w->asce_design_m, w->cap_m, w->clearance_m};
        fprintf(f, "%.4g,%.5g,", w->mu, w->x);
        for (size_t c = 0; c < sizeof mm / sizeof mm[0]; c++) {
            csv_num(f, MM_PER_M * mm[c], "%.4f");
            fputc(',', f);
        }
        csv_field(f, sl_report_flags(w->flags, flags, sizeof flags));
        fputc(',', f);
        csv_num(f, fl->err_est_m ? MM_PER_M * fl->err_est_m[k] : NAN, "%.2e");
        fputs("\r\n", f);
    }
    return sl_atomic_commit(a, err);
}

sl_status sl_report_write_csv(const sl_report *r, const char *dir, sl_error *err)
{
    if (check_finite(r, err))
        return err ? err->code : SL_EINVAL;
    sl_atomic *a = NULL;
    char buf[1024];
    for (size_t i = 0; i < r->n_floors; i++)
        if (csv_floor(r, &r->floors[i], dir, err))
            return err ? err->code : SL_EIO;
    /* summary: rows mu, one column per floor */
    if (csv_open(dir, "summary.csv", &a, err))
        return err ? err->code : SL_EIO;
    FILE *f = sl_atomic_file(a);
    csv_head(f, r, "required clearance (mm) per floor; columns named <floor_id>_clearance_mm; "
             "shown to the digit of its standard error (1 mm or 0.1 mm; the floor files hold "
             "every digit)");
    csv_comment(f, "units", "clearance in mm; mu dimensionless");
    for (size_t i = 0; i < r->n_floors; i++) {
        snprintf(buf, sizeof buf, "%s (file %s, horizontal ZPA %.4f g)", r->floors[i].name,
                 r->floors[i].path, r->floors[i].zpa_h_ms2 / SL_G);
        char key[ID_MAX + 16];
        snprintf(key, sizeof key, "floor %s", r->floors[i].id);
        csv_comment(f, key, buf);
    }
    fputs("mu", f);
    for (size_t i = 0; i < r->n_floors; i++)
        fprintf(f, ",%s_clearance_mm", r->floors[i].id);
    fputs("\r\n", f);
    size_t n = r->floors[0].design->n;
    for (size_t k = 0; k < n; k++) {
        fprintf(f, "%.4g", r->floors[0].design->rows[k].mu);
        for (size_t i = 0; i < r->n_floors; i++) {
            double v = MM_PER_M * r->floors[i].design->rows[k].clearance_m;
            fputc(',', f);
            if (isfinite(v))
                fprintf(f, "%.*f", shown_decimals(&r->floors[i], k), v);
        }
        fputs("\r\n", f);
    }
    if (sl_atomic_commit(a, err))
        return err ? err->code : SL_EIO;
    /* per floor: one row, one value per field */
    if (csv_open(dir, "floors.csv", &a, err))
        return err ? err->code : SL_EIO;
    f = sl_atomic_file(a);
    csv_head(f, r, "one row per floor; the ASCE-below-NLTHA ranges are in asce_below_nltha.csv");
    csv_comment(f, "crossover", "the mu where 2.0 x ASCE rises above 3.0 x NLTHA mean when ASCE is "
                "below NLTHA at the lowest mu of the grid; 'none' otherwise (docs/run.md)");
    csv_comment(f, "other_dampings", "every damping of the floor file other than the one "
                "matched, its table against the motions' own spectra at that damping: lowest and "
                "highest set-mean S/T over all of them, ok when each is within the synthesis "
                "limits (0.9-1.3), 'none' when the file gives one damping; reported, not a pass "
                "condition (docs/run.md)");
    fputs("floor_id,floor,file,elevation_m,zpa_h_g,crossover_mu,crossover_mu_g_over_zpa,"
          "n_asce_below_nltha_ranges,clearance_policy,mu_without_nltha,n_sets,sets_stop,note,"
          "other_dampings_min_ratio,other_dampings_max_ratio,other_dampings_check,"
          "other_dampings\r\n",
          f);
    for (size_t i = 0; i < r->n_floors; i++) {
        const sl_report_floor *fl = &r->floors[i];
        const sl_design *d = fl->design;
        fprintf(f, "%s,", fl->id);
        csv_field(f, fl->name);
        fputc(',', f);
        csv_field(f, fl->path);
        fputc(',', f);
        csv_num(f, fl->elevation_m, "%g");
        fprintf(f, ",%.4f,", fl->zpa_h_ms2 / SL_G);
        if (d->has_crossover)
            fprintf(f, "%.4f,%.4f", d->crossover_mu, d->crossover_x);
        else
            fputs("none,none", f);
        fprintf(f, ",%zu,%s,%zu,%zu,%s,", d->n_ranges, sl_clearance_policy_name(d->policy),
                fl->n_mu_skipped, d->n_sets, fl->sets_stop ? fl->sets_stop : "");
        csv_field(f, fl->note && *fl->note ? fl->note : "");
        if (has_dampings(fl)) {
            fputc(',', f);
            csv_num(f, fl->dampings_min, "%.4f");
            fputc(',', f);
            csv_num(f, fl->dampings_max, "%.4f");
            fprintf(f, ",%s,", fl->dampings_ok ? "ok" : "outside");
            csv_field(f, fl->dampings);
        } else {
            fputs(",none,none,none,none", f);
        }
        fputs("\r\n", f);
    }
    if (sl_atomic_commit(a, err))
        return err ? err->code : SL_EIO;
    /* every range where ASCE < NLTHA, one per row */
    if (csv_open(dir, "asce_below_nltha.csv", &a, err))
        return err ? err->code : SL_EIO;
    f = sl_atomic_file(a);
    csv_head(f, r, "every range of mu where the ASCE design value is below the NLTHA design "
             "value; ends interpolated where the difference changes sign; *_open = 1: the range "
             "reaches the end of the grid there");
    fputs("floor_id,range,mu_from,mu_to,mu_g_over_zpa_from,mu_g_over_zpa_to,from_open,to_open\r\n",
          f);
    for (size_t i = 0; i < r->n_floors; i++) {
        const sl_design *d = r->floors[i].design;
        for (size_t q = 0; q < d->n_ranges; q++) {
            const sl_design_range *g = &d->ranges[q];
            fprintf(f, "%s,%zu,%.4f,%.4f,%.4f,%.4f,%d,%d\r\n", r->floors[i].id, q + 1, g->mu_lo,
                    g->mu_hi, g->x_lo, g->x_hi, g->open_lo, g->open_hi);
        }
    }
    if (sl_atomic_commit(a, err))
        return err ? err->code : SL_EIO;
    /* motion quality */
    if (csv_open(dir, "motion_quality.csv", &a, err))
        return err ? err->code : SL_EIO;
    f = sl_atomic_file(a);
    csv_head(f, r, "SRP 3.7.1 checks of every synthesized motion; longest_run_below = most "
             "consecutive frequency points below the target (limit 9)");
    fputs("floor_id,set,component,pga_g,d5_75_s,min_ratio_to_target,max_ratio_to_target,"
          "longest_run_below,max_abs_correlation,v_end_m_s,d_end_m,pass,failed_checks\r\n", f);
    for (size_t q = 0; q < r->n_quality; q++) {
        const sl_report_quality *m = &r->quality[q];
        fprintf(f, "%s,%d,%s,", m->floor, m->set, m->component);
        const double v[] = {m->pga_g, m->d5_75_s, m->min_ratio, m->max_ratio};
        const char *fmt[] = {"%.4f,", "%.3f,", "%.4f,", "%.4f,"};
        for (size_t c = 0; c < 4; c++) {
            csv_num(f, v[c], fmt[c]);
            if (!isfinite(v[c]))
                fputc(',', f);
        }
        fprintf(f, "%d,", m->max_run_below);
        const double w[] = {m->max_corr, m->v_end_ms, m->d_end_m};
        const char *wf[] = {"%.4f", "%.3g", "%.3g"};
        for (size_t c = 0; c < 3; c++) {
            csv_num(f, w[c], wf[c]);
            fputc(',', f);
        }
        fprintf(f, "%s,", m->pass ? "yes" : "no");
        csv_field(f, m->why ? m->why : "");
        fputs("\r\n", f);
    }
    return sl_atomic_commit(a, err);
}

/* ---- XLSX --------------------------------------------------------------- */

typedef struct fmts {
    lxw_format *bold, *title, *mm, *mm0, *mmbold, *ratio, *mu, *wrap, *result, *input, *header,
        *note, *label, *sci;
} fmts;

/* Layout (0-based rows): the title block, then each table. */
enum {
    TB_ROWS = 8,           /* title + 7 fields */
    SUM_HEAD = TB_ROWS + 1,/* Summary table header row */
    FL_HEAD = 10,          /* floor sheet table header row */
    DATA_HEAD = 3,         /* Data sheet header row */
    FL_COLS = 10           /* floor table columns */
};
/* Lookup cells (0-based rows, column B). */
enum {
    LK_FLOOR = 10, LK_MU, LK_RESULT = 13, LK_CHECK, LK_NOTE, LK_ZPA, LK_X, LK_SE, LK_FLAGS,
    LK_HOW = 21, LK_COL, LK_ROW, LK_MU0, LK_MU1, LK_C0, LK_C1, LK_POLICY = 29
};
/* Data sheet series per floor (chart columns). */
enum { DS_NDESIGN, DS_ADESIGN, DS_MEAN, DS_CAP, DS_CLEAR, DS_LO, DS_HI, DS_N };

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

static const char *or_dash(const char *s) { return s && *s ? s : "-"; }

/* Text for a header/footer: '&' doubled (Excel's escape), cut to fit. */
static void hf_escape(const char *s, char *buf, size_t n)
{
    size_t k = 0;
    for (; s && *s && k + 3 < n; s++) {
        if (*s == '&')
            buf[k++] = '&';
        buf[k++] = *s;
    }
    buf[k] = '\0';
}

/* Page setup shared by every sheet: A4, margins, header with the title
 * block's identity, footer with the sheet and page x of y. */
static void page_setup(lxw_worksheet *ws, const sl_report *r, int landscape)
{
    char proj[80], doc[80], rev[32], h[HF_MAX + 1], ver[80];
    hf_escape(or_dash(r->project.project), proj, sizeof proj);
    hf_escape(or_dash(r->project.document), doc, sizeof doc);
    hf_escape(or_dash(r->project.revision), rev, sizeof rev);
    hf_escape(r->version, ver, sizeof ver);
    worksheet_set_paper(ws, 9); /* A4 */
    worksheet_set_margins(ws, 0.5, 0.5, 0.75, 0.75);
    if (landscape)
        worksheet_set_landscape(ws);
    else
        worksheet_set_portrait(ws);
    snprintf(h, sizeof h, "&L%s&C%s rev. %s&R&A", proj, doc, rev);
    worksheet_set_header(ws, h);
    snprintf(h, sizeof h, "&L%s&C&F&RPage &P of &N", ver);
    worksheet_set_footer(ws, h);
}

static void protect(lxw_worksheet *ws)
{
    lxw_protection p;
    memset(&p, 0, sizeof p);
    worksheet_protect(ws, NULL, &p); /* no password: a guard against typing over, not a lock */
}

/* The title block (rows 0-7, columns first..first+1). */
static void title_block(lxw_worksheet *ws, const fmts *F, const sl_report *r, const char *title,
                        lxw_col_t c)
{
    worksheet_write_string(ws, 0, c, title, F->title);
    const char *const label[] = {"Project", "Document no.", "Revision", "Prepared by",
                                 "Checked by", "Date", "Units"};
    const char *const value[] = {r->project.project, r->project.document, r->project.revision,
                                 r->project.prepared, r->project.checked, r->project.date,
                                 "clearance and displacements in mm; accelerations in g; "
                                 "mu (friction coefficient) dimensionless"};
    for (lxw_row_t i = 0; i < 7; i++) {
        worksheet_write_string(ws, i + 1, c, label[i], F->label);
        worksheet_write_string(ws, i + 1, c + 1, or_dash(value[i]), F->note);
    }
    worksheet_set_row(ws, 7, 30, NULL);
}

/* The shared chart axes: x = mu over the grid, y = log over every floor. */
typedef struct axes {
    double mu_min, mu_max, y_min, y_max;
} axes;

static axes shared_axes(const sl_report *r)
{
    axes a = {r->floors[0].design->rows[0].mu, 0, HUGE_VAL, 0};
    size_t n = r->floors[0].design->n;
    a.mu_max = r->floors[0].design->rows[n - 1].mu;
    for (size_t i = 0; i < r->n_floors; i++)
        for (size_t k = 0; k < n; k++) {
            const sl_design_row *w = &r->floors[i].design->rows[k];
            const double v[] = {w->nltha_design_m, w->asce_design_m, w->nltha_mean_m, w->cap_m};
            for (size_t c = 0; c < 4; c++)
                if (isfinite(v[c]) && v[c] > 0) {
                    a.y_min = fmin(a.y_min, MM_PER_M * v[c]);
                    a.y_max = fmax(a.y_max, MM_PER_M * v[c]);
                }
        }
    if (!(a.y_max > 0)) {
        a.y_min = 1;
        a.y_max = 10;
    }
    a.y_min = fmax(CHART_MIN_MM, pow(10, floor(log10(a.y_min))));
    a.y_max = pow(10, ceil(log10(a.y_max)));
    if (a.y_max <= a.y_min)
        a.y_max = 10 * a.y_min;
    return a;
}

static void chart_axes(lxw_chart *ch, const axes *ax)
{
    chart_axis_set_name(ch->x_axis, "friction coefficient mu");
    chart_axis_set_name(ch->y_axis, "mm (log scale)");
    chart_axis_set_min(ch->x_axis, ax->mu_min);
    chart_axis_set_max(ch->x_axis, ax->mu_max);
    chart_axis_set_num_format(ch->x_axis, "0.00");
    chart_axis_set_log_base(ch->y_axis, 10);
    chart_axis_set_min(ch->y_axis, ax->y_min);
    chart_axis_set_max(ch->y_axis, ax->y_max);
    chart_axis_set_num_format(ch->y_axis, "#,##0.#");
    chart_axis_set_crossing(ch->y_axis, ax->y_min); /* x axis at the bottom */
    chart_legend_set_position(ch, LXW_CHART_LEGEND_BOTTOM);
}

/* Data sheet columns: A mu, then per floor i: se (1 + i), flags (1 + F + i),
 * chart series (1 + 2F + DS_N i + s). */
static lxw_col_t data_col_se(size_t nf, size_t i) { (void)nf; return (lxw_col_t)(1 + i); }
static lxw_col_t data_col_flags(size_t nf, size_t i) { return (lxw_col_t)(1 + nf + i); }
static lxw_col_t data_col_series(size_t nf, size_t i, int s)
{
    return (lxw_col_t)(1 + 2 * nf + DS_N * i + (size_t)s);
}
/* First row of the band block (two rows per range) of floor i. */
static lxw_row_t data_band_row(const sl_report *r, size_t i)
{
    lxw_row_t row = (lxw_row_t)(DATA_HEAD + r->floors[0].design->n + 3);
    for (size_t j = 0; j < i; j++)
        row += (lxw_row_t)(2 * r->floors[j].design->n_ranges);
    return row;
}

static void data_sheet(lxw_workbook *wb, const fmts *F, const sl_report *r, const axes *ax)
{
    lxw_worksheet *ws = workbook_add_worksheet(wb, "Data");
    size_t nf = r->n_floors, n = r->floors[0].design->n;
    char buf[256], flags[256];
    worksheet_write_string(ws, 0, 0, "Tables the Lookup sheet and the charts read (do not edit)",
                           F->title);
    worksheet_write_string(ws, 1, 0,
                           "Chart columns leave a cell empty where the value is 0 or does not "
                           "exist: a log axis has no 0.", NULL);
    worksheet_write_string(ws, DATA_HEAD, 0, "mu", F->header);
    for (size_t i = 0; i < nf; i++) {
        const sl_report_floor *fl = &r->floors[i];
        snprintf(buf, sizeof buf, "%s: standard error of the NLTHA design value, mm", fl->id);
        worksheet_write_string(ws, DATA_HEAD, data_col_se(nf, i), buf, F->header);
        snprintf(buf, sizeof buf, "%s: flags", fl->id);
        worksheet_write_string(ws, DATA_HEAD, data_col_flags(nf, i), buf, F->header);
        static const char *const sname[DS_N] = {"NLTHA design, mm", "ASCE design, mm",
                                                "NLTHA mean, mm", "cap, mm", "clearance, mm",
                                                "NLTHA design 90 % band low, mm",
                                                "NLTHA design 90 % band high, mm"};
        for (int s = 0; s < DS_N; s++) {
            snprintf(buf, sizeof buf, "%s: %s", fl->id, sname[s]);
            worksheet_write_string(ws, DATA_HEAD, data_col_series(nf, i, s), buf, F->header);
        }
    }
    worksheet_set_row(ws, DATA_HEAD, 60, NULL);
    worksheet_set_column(ws, 0, (lxw_col_t)(2 * nf + DS_N * nf), 12, NULL);
    for (size_t k = 0; k < n; k++) {
        lxw_row_t row = (lxw_row_t)(DATA_HEAD + 1 + k);
        worksheet_write_number(ws, row, 0, r->floors[0].design->rows[k].mu, F->mu);
        for (size_t i = 0; i < nf; i++) {
            const sl_design *d = r->floors[i].design;
            const sl_design_row *w = &d->rows[k];
            const sl_report_floor *fl = &r->floors[i];
            worksheet_write_number(ws, row, data_col_se(nf, i), MM_PER_M * design_se_m(fl, k), F->mm);
            sl_report_flags(w->flags, flags, sizeof flags);
            worksheet_write_string(ws, row, data_col_flags(nf, i), flags[0] ? flags : "-", NULL);
            const double v[DS_N] = {w->nltha_design_m, w->asce_design_m, w->nltha_mean_m, w->cap_m,
                                    w->clearance_m, fl->design_lo_m ? fl->design_lo_m[k] : NAN,
                                    fl->design_hi_m ? fl->design_hi_m[k] : NAN};
            for (int s = 0; s < DS_N; s++) {
                double mm = MM_PER_M * v[s];
                if (isfinite(mm) && mm > 0)
                    worksheet_write_number(ws, row, data_col_series(nf, i, s), mm, F->mm);
            }
        }
    }
    /* bands: the ASCE-below-NLTHA ranges drawn along the bottom of each chart */
    lxw_row_t b0 = data_band_row(r, 0);
    worksheet_write_string(ws, b0 - 1, 0, "floor id", F->header);
    worksheet_write_string(ws, b0 - 1, 1, "ASCE below NLTHA: mu at the range's ends", F->header);
    worksheet_write_string(ws, b0 - 1, 2, "band height, mm", F->header);
    for (size_t i = 0; i < nf; i++) {
        const sl_design *d = r->floors[i].design;
        lxw_row_t row = data_band_row(r, i);
        for (size_t q = 0; q < d->n_ranges; q++) {
            worksheet_write_string(ws, row, 0, r->floors[i].id, NULL);
            worksheet_write_number(ws, row, 1, d->ranges[q].mu_lo, F->ratio);
            worksheet_write_number(ws, row++, 2, ax->y_min * 1.15, NULL);
            worksheet_write_string(ws, row, 0, r->floors[i].id, NULL);
            worksheet_write_number(ws, row, 1, d->ranges[q].mu_hi, F->ratio);
            worksheet_write_number(ws, row++, 2, ax->y_min * 1.15, NULL);
        }
    }
    page_setup(ws, r, 1);
    worksheet_fit_to_pages(ws, 1, 0);
    worksheet_repeat_rows(ws, DATA_HEAD, DATA_HEAD);
    protect(ws);
}

static void add_series(lxw_chart *ch, const char *sheet, lxw_col_t xc, lxw_col_t yc,
                       lxw_row_t r0, lxw_row_t r1, const char *name, lxw_color_t color,
                       float width, uint8_t dash, uint8_t transparency)
{
    char xr[128], yr[128], a[8], b[8];
    col_name(xc, a);
    col_name(yc, b);
    snprintf(xr, sizeof xr, "='%s'!$%s$%u:$%s$%u", sheet, a, (unsigned)r0 + 1, a, (unsigned)r1 + 1);
    snprintf(yr, sizeof yr, "='%s'!$%s$%u:$%s$%u", sheet, b, (unsigned)r0 + 1, b, (unsigned)r1 + 1);
    lxw_chart_series *s = chart_add_series(ch, xr, yr);
    chart_series_set_name(s, name);
    lxw_chart_line line = {.color = color, .width = width, .dash_type = dash,
                           .transparency = transparency};
    chart_series_set_line(s, &line);
    chart_series_set_marker_type(s, LXW_CHART_MARKER_NONE);
}

#define C_NLTHA 0x1F4E79
#define C_ASCE 0xC55A11
#define C_MEAN 0x5B9BD5
#define C_CAP 0x7F7F7F
#define C_BAND 0xFF0000

static lxw_chart *floor_chart(lxw_workbook *wb, const sl_report *r, size_t i, const axes *ax)
{
    const sl_report_floor *fl = &r->floors[i];
    const sl_design *d = fl->design;
    size_t nf = r->n_floors, n = d->n;
    lxw_row_t r0 = DATA_HEAD + 1, r1 = (lxw_row_t)(DATA_HEAD + n);
    lxw_chart *ch = workbook_add_chart(wb, LXW_CHART_SCATTER_STRAIGHT);
    char name[128], title[300];
    snprintf(name, sizeof name, "NLTHA design (%g x mean)", d->fs_nltha);
    add_series(ch, "Data", 0, data_col_series(nf, i, DS_NDESIGN), r0, r1, name, C_NLTHA, 2.25f,
               LXW_CHART_LINE_DASH_SOLID, 0);
    snprintf(name, sizeof name, "ASCE design (%g x best estimate)", d->fs_asce);
    add_series(ch, "Data", 0, data_col_series(nf, i, DS_ADESIGN), r0, r1, name, C_ASCE, 2.25f,
               LXW_CHART_LINE_DASH_SOLID, 0);
    add_series(ch, "Data", 0, data_col_series(nf, i, DS_MEAN), r0, r1, "NLTHA mean", C_MEAN, 1.25f,
               LXW_CHART_LINE_DASH_DASH, 0);
    snprintf(name, sizeof name, "cap (%g x mean peak floor displacement)", d->cap_factor);
    add_series(ch, "Data", 0, data_col_series(nf, i, DS_CAP), r0, r1, name, C_CAP, 1.0f,
               LXW_CHART_LINE_DASH_LONG_DASH, 0);
    int extra = 0;
    if (fl->design_lo_m && fl->design_hi_m) { /* the convergence band, when computed */
        add_series(ch, "Data", 0, data_col_series(nf, i, DS_LO), r0, r1,
                   "NLTHA design, 90 % band", C_NLTHA, 0.75f, LXW_CHART_LINE_DASH_ROUND_DOT, 0);
        add_series(ch, "Data", 0, data_col_series(nf, i, DS_HI), r0, r1, "", C_NLTHA, 0.75f,
                   LXW_CHART_LINE_DASH_ROUND_DOT, 0);
        extra = 2;
    }
    lxw_row_t b = data_band_row(r, i);
    for (size_t q = 0; q < d->n_ranges; q++, b += 2)
        add_series(ch, "Data", 1, 2, b, b + 1, q ? "" : "ASCE below NLTHA (band)", C_BAND, 9.0f,
                   LXW_CHART_LINE_DASH_SOLID, 50);
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
    chart_axes(ch, ax);
    return ch;
}

static void floor_sheet(lxw_workbook *wb, const fmts *F, const sl_report *r, size_t i,
                        const char *sname, const axes *ax)
{
    const sl_report_floor *fl = &r->floors[i];
    lxw_worksheet *ws = workbook_add_worksheet(wb, sname);
    const sl_design *d = fl->design;
    char buf[600], flags[256];
    snprintf(buf, sizeof buf, "Floor: %s", fl->name);
    worksheet_write_string(ws, 0, 0, buf, F->title);
    struct {
        const char *label;
        char value[600];
    } info[9];
    size_t ni = 0;
    info[ni].label = "id and file";
    snprintf(info[ni++].value, sizeof info[0].value, "%s (%s, %s)", fl->id, fl->path, or_dash(fl->units));
    info[ni].label = "elevation; description";
    if (isfinite(fl->elevation_m))
        snprintf(info[ni++].value, sizeof info[0].value, "%g m; %s", fl->elevation_m,
                 or_dash(fl->description));
    else
        snprintf(info[ni++].value, sizeof info[0].value, "-; %s", or_dash(fl->description));
    info[ni].label = "horizontal ZPA";
    snprintf(info[ni++].value, sizeof info[0].value, "%.3f g (mu g/ZPA = mu / %.3f)",
             fl->zpa_h_ms2 / SL_G, fl->zpa_h_ms2 / SL_G);
    info[ni].label = "ASCE < NLTHA for mu in";
    sl_report_ranges_text(d, info[ni++].value, sizeof info[0].value);
    info[ni].label = "crossover";
    crossover_text(d, info[ni++].value, sizeof info[0].value);
    info[ni].label = "clearance; factors";
    snprintf(info[ni++].value, sizeof info[0].value,
             "policy %s; NLTHA design %g x mean of %zu sets, ASCE design %g x best estimate, "
             "both capped at %g x the mean peak floor displacement (PGD, 100-40 rule)",
             sl_clearance_policy_name(d->policy), d->fs_nltha, d->n_sets, d->fs_asce,
             d->cap_factor);
    info[ni].label = "ASCE best estimate";
    asce_shape_text(d, info[ni++].value, sizeof info[0].value);
    info[ni].label = "note";
    snprintf(info[ni++].value, sizeof info[0].value, "%s%s%zu friction values %s",
             fl->note && *fl->note ? fl->note : "", fl->note && *fl->note ? "; " : "",
             fl->n_mu_skipped,
             fl->scatter > 0 ? "with no sliding at any intensity of the scatter (mu g at or above "
                               "every motion's demand even at the strongest intensity)"
                             : "needed no NLTHA (mu g at or above every motion's demand)");
    for (size_t k = 0; k < ni; k++) {
        worksheet_merge_range(ws, (lxw_row_t)(k + 1), 0, (lxw_row_t)(k + 1), 2, info[k].label,
                              F->label);
        worksheet_merge_range(ws, (lxw_row_t)(k + 1), 3, (lxw_row_t)(k + 1), FL_COLS - 1,
                              info[k].value, F->note);
    }
    worksheet_set_row(ws, 6, 30, NULL);
    char h[FL_COLS][96];
    snprintf(h[0], sizeof h[0], "mu");
    snprintf(h[1], sizeof h[1], "mu g / ZPA");
    snprintf(h[2], sizeof h[2], "NLTHA mean, mm");
    snprintf(h[3], sizeof h[3], "NLTHA design (%g x mean), mm", d->fs_nltha);
    snprintf(h[4], sizeof h[4], "its standard error, mm");
    snprintf(h[5], sizeof h[5], "ASCE best estimate, mm");
    snprintf(h[6], sizeof h[6], "ASCE design (%g x best), mm", d->fs_asce);
    snprintf(h[7], sizeof h[7], "cap (%g x PGD), mm", d->cap_factor);
    snprintf(h[8], sizeof h[8], "required clearance, mm");
    snprintf(h[9], sizeof h[9], "flags");
    for (lxw_col_t c = 0; c < FL_COLS; c++)
        worksheet_write_string(ws, FL_HEAD, c, h[c], F->header);
    worksheet_set_row(ws, FL_HEAD, 58, NULL);
    worksheet_set_column(ws, 0, 1, 6.5, NULL);
    worksheet_set_column(ws, 2, 8, 8.5, NULL);
    worksheet_set_column(ws, 9, 9, 14, F->wrap);
    worksheet_freeze_panes(ws, FL_HEAD + 1, 1);
    for (size_t k = 0; k < d->n; k++) {
        const sl_design_row *w = &d->rows[k];
        lxw_row_t row = (lxw_row_t)(FL_HEAD + 1 + k);
        worksheet_write_number(ws, row, 0, w->mu, F->mu);
        worksheet_write_number(ws, row, 1, w->x, F->ratio);
        write_num_or_blank(ws, row, 2, MM_PER_M * w->nltha_mean_m, F->mm);
        write_num_or_blank(ws, row, 3, MM_PER_M * w->nltha_design_m, F->mm);
        write_num_or_blank(ws, row, 4, MM_PER_M * design_se_m(fl, k), F->mm);
        write_num_or_blank(ws, row, 5, MM_PER_M * w->asce_best_m, F->mm);
        write_num_or_blank(ws, row, 6, MM_PER_M * w->asce_design_m, F->mm);
        write_num_or_blank(ws, row, 7, MM_PER_M * w->cap_m, F->mm);
        write_num_or_blank(ws, row, 8, MM_PER_M * w->clearance_m, F->mmbold);
        sl_report_flags(w->flags, flags, sizeof flags);
        worksheet_write_string(ws, row, 9, flags[0] ? flags : "-", F->wrap);
    }
    /* the chart on its own page, below the table */
    lxw_row_t chart_row = (lxw_row_t)(FL_HEAD + d->n + 2);
    lxw_row_t breaks[] = {chart_row, 0};
    worksheet_set_h_pagebreaks(ws, breaks);
    lxw_chart_options co = {.x_offset = 0, .y_offset = 0, .x_scale = 1.3, .y_scale = 1.9};
    worksheet_insert_chart_opt(ws, chart_row, 0, floor_chart(wb, r, i, ax), &co);
    worksheet_merge_range(ws, chart_row + 31, 0, chart_row + 31, FL_COLS - 1,
                          "The red band along the bottom marks every range of mu where the ASCE "
                          "design value is below the NLTHA design value.", F->note);
    worksheet_set_row(ws, chart_row + 31, 30, NULL);
    page_setup(ws, r, 0);
    worksheet_set_print_scale(ws, FLOOR_PRINT_SCALE);
    worksheet_repeat_rows(ws, FL_HEAD, FL_HEAD);
    worksheet_print_area(ws, 0, 0, chart_row + 32, FL_COLS - 1);
    protect(ws);
}

static void summary_sheet(lxw_workbook *wb, const fmts *F, const sl_report *r, const axes *ax)
{
    lxw_worksheet *ws = workbook_add_worksheet(wb, "Summary");
    size_t n = r->floors[0].design->n, nf = r->n_floors;
    title_block(ws, F, r, "Required clearance per floor, mm", 0);
    worksheet_write_string(ws, SUM_HEAD, 0, "mu", F->header);
    for (size_t i = 0; i < nf; i++)
        worksheet_write_string(ws, SUM_HEAD, (lxw_col_t)(i + 1), r->floors[i].name, F->header);
    worksheet_set_row(ws, SUM_HEAD, 45, NULL);
    worksheet_set_column(ws, 0, 0, 26, F->wrap);
    worksheet_set_column(ws, 1, (lxw_col_t)nf, 16, F->wrap);
    worksheet_freeze_panes(ws, SUM_HEAD + 1, 1);
    for (size_t k = 0; k < n; k++) {
        lxw_row_t row = (lxw_row_t)(SUM_HEAD + 1 + k);
        worksheet_write_number(ws, row, 0, r->floors[0].design->rows[k].mu, F->mu);
        for (size_t i = 0; i < nf; i++) {
            write_num_or_blank(ws, row, (lxw_col_t)(i + 1),
                               MM_PER_M * r->floors[i].design->rows[k].clearance_m,
                               shown_decimals(&r->floors[i], k) ? F->mm : F->mm0);
        }
    }
    lxw_row_t b = (lxw_row_t)(SUM_HEAD + n + 2);
    static const char *const lab[] = {"floor id", "floor file", "elevation, m", "description",
                                      "horizontal ZPA, g", "crossover (docs/run.md)",
                                      "ASCE below NLTHA for mu in", "note", "motion sets",
                                      "sets stopped because"};
    for (lxw_row_t q = 0; q < 10; q++)
        worksheet_write_string(ws, b + q, 0, lab[q], F->label);
    char buf[600];
    for (size_t i = 0; i < nf; i++) {
        const sl_report_floor *fl = &r->floors[i];
        lxw_col_t c = (lxw_col_t)(i + 1);
        worksheet_write_string(ws, b, c, fl->id, NULL);
        worksheet_write_string(ws, b + 1, c, fl->path, NULL);
        write_num_or_blank(ws, b + 2, c, fl->elevation_m, NULL);
        worksheet_write_string(ws, b + 3, c, or_dash(fl->description), NULL);
        worksheet_write_number(ws, b + 4, c, fl->zpa_h_ms2 / SL_G, F->ratio);
        worksheet_write_string(ws, b + 5, c, crossover_text(fl->design, buf, sizeof buf), NULL);
        worksheet_write_string(ws, b + 6, c, sl_report_ranges_text(fl->design, buf, sizeof buf), NULL);
        if (has_dampings(fl)) {
            char nb[2048];
            snprintf(nb, sizeof nb, "%s%sother dampings, set-mean S/T of the motions' own "
                     "spectra to the file's table: %s", fl->note ? fl->note : "",
                     fl->note && *fl->note ? "\n" : "", fl->dampings);
            worksheet_write_string(ws, b + 7, c, nb, NULL);
        } else {
            worksheet_write_string(ws, b + 7, c, or_dash(fl->note), NULL);
        }
        worksheet_write_number(ws, b + 8, c, (double)fl->design->n_sets, NULL);
        worksheet_write_string(ws, b + 9, c, or_dash(fl->sets_stop), NULL);
    }
    /* named ranges the Lookup formulas read */
    char last_col[8], def[160];
    col_name(nf, last_col);
    snprintf(def, sizeof def, "=Summary!$B$%d:$%s$%d", SUM_HEAD + 1, last_col, SUM_HEAD + 1);
    workbook_define_name(wb, "floor_names", def);
    snprintf(def, sizeof def, "=Summary!$A$%d:$A$%zu", SUM_HEAD + 2, SUM_HEAD + 1 + n);
    workbook_define_name(wb, "mu_grid", def);
    snprintf(def, sizeof def, "=Summary!$B$%d:$%s$%zu", SUM_HEAD + 2, last_col, SUM_HEAD + 1 + n);
    workbook_define_name(wb, "clearance_mm", def);
    snprintf(def, sizeof def, "=Summary!$B$%u:$%s$%u", (unsigned)b + 5, last_col, (unsigned)b + 5);
    workbook_define_name(wb, "floor_zpa_g", def);
    /* one chart with every floor, on its own page */
    lxw_row_t chart_row = b + 10;
    lxw_chart *ch = workbook_add_chart(wb, LXW_CHART_SCATTER_STRAIGHT);
    static const lxw_color_t pal[] = {0x1F4E79, 0xC55A11, 0x548235, 0x7030A0, 0xBF9000, 0x2E75B6,
                                      0xFF0000, 0x000000};
    for (size_t i = 0; i < nf; i++)
        add_series(ch, "Data", 0, data_col_series(nf, i, DS_CLEAR), DATA_HEAD + 1,
                   (lxw_row_t)(DATA_HEAD + n), r->floors[i].name, pal[i % 8], 2.0f,
                   (uint8_t)(i / 8 % 3 ? LXW_CHART_LINE_DASH_DASH : LXW_CHART_LINE_DASH_SOLID), 0);
    snprintf(buf, sizeof buf, "Required clearance (%s), every floor",
             sl_clearance_policy_name(r->floors[0].design->policy));
    chart_title_set_name(ch, buf);
    chart_axes(ch, ax);
    lxw_row_t breaks[] = {chart_row, 0};
    worksheet_set_h_pagebreaks(ws, breaks);
    /* as wide as the printed columns (26 + 16 per floor characters, about
     * 7 pixels each; a chart is 480 pixels wide at scale 1) */
    lxw_col_t last = (lxw_col_t)(nf > 3 ? nf : 3);
    double width_px = 26 * 7 + 5 + (double)last * (16 * 7 + 5);
    lxw_chart_options co = {.x_offset = 0, .y_offset = 0, .x_scale = width_px / 480 * 0.95,
                            .y_scale = 1.9};
    worksheet_insert_chart_opt(ws, chart_row, 0, ch, &co);
    page_setup(ws, r, 0);
    worksheet_fit_to_pages(ws, 1, 0);
    worksheet_repeat_rows(ws, SUM_HEAD, SUM_HEAD);
    worksheet_print_area(ws, 0, 0, chart_row + 30, last);
    protect(ws);
}

/* Write a formula with its cached value (a number, or text when isnan(v)
 * and s given). */
static void formula(lxw_worksheet *ws, int zero_cache, lxw_row_t row, const char *f, double v, const char *s,
                    lxw_format *fmt)
{
    if (zero_cache)
        worksheet_write_formula_num(ws, row, 1, f, fmt, 0);
    else if (s)
        worksheet_write_formula_str(ws, row, 1, f, fmt, s);
    else
        worksheet_write_formula_num(ws, row, 1, f, fmt, v);
}

static void lookup_sheet(lxw_workbook *wb, const fmts *F, const sl_report *r)
{
    lxw_worksheet *ws = workbook_add_worksheet(wb, "Lookup");
    const sl_design *d0 = r->floors[0].design;
    size_t n = d0->n, nf = r->n_floors;
    double mu_min = d0->rows[0].mu, mu_max = d0->rows[n - 1].mu;
    char f[1400], msg[160], list_formula[40];
    worksheet_set_column(ws, 0, 0, 44, F->wrap);
    worksheet_set_column(ws, 1, 1, 44, F->wrap);
    title_block(ws, F, r, "Required clearance around an unanchored component", 0);

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
    worksheet_write_string(ws, LK_MU, 0, "Friction coefficient mu (type it)", F->bold);
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

    /* cached values for the initial inputs: the C twin of the formulas */
    size_t fi = nf;
    for (size_t i = 0; i < nf; i++)
        if (!strcasecmp(floor0, r->floors[i].name))
            fi = i;
    double mu0 = r->lookup_mu;
    const char *check = "ok";
    if (!*floor0)
        check = "choose a floor from the list";
    else if (fi == nf)
        check = "unknown floor: choose one from the list";
    else if (r->lookup_mu_text && *r->lookup_mu_text)
        check = "mu must be a number";
    else if (!isfinite(mu0) || r->lookup_mu_text)
        check = "type mu";
    else if (mu0 < mu_min || mu0 > mu_max)
        check = "mu outside the table";
    int ok = !strcmp(check, "ok");
    size_t k0 = 0;
    if (ok)
        while (k0 + 1 < n && d0->rows[k0 + 1].mu <= mu0)
            k0++;
    size_t k1 = k0 + 1 < n ? k0 + 1 : k0;
    const sl_design *dsel = ok ? r->floors[fi].design : d0;
    double res = ok ? MM_PER_M * sl_design_clearance_at(dsel, mu0) : NAN;

    worksheet_write_string(ws, LK_RESULT, 0, "Required clearance, mm", F->title);
    snprintf(f, sizeof f, "=IF(B%d<>\"ok\",\"-\",IF(B%d=B%d,B%d,B%d+(B%d-B%d)*(B%d-B%d)/(B%d-B%d)))",
             LK_CHECK + 1, LK_MU1 + 1, LK_MU0 + 1, LK_C0 + 1, LK_C0 + 1, LK_MU + 1, LK_MU0 + 1,
             LK_C1 + 1, LK_C0 + 1, LK_MU1 + 1, LK_MU0 + 1);
    formula(ws, r->lookup_zero_cache, LK_RESULT, f, res, ok ? NULL : "-", F->result);
    worksheet_write_string(ws, LK_CHECK, 0, "Input check", F->bold);
    snprintf(f, sizeof f,
             "=IF(B%d=\"\",\"choose a floor from the list\",IF(ISNA(MATCH(B%d,floor_names,0)),"
             "\"unknown floor: choose one from the list\",IF(B%d=\"\",\"type mu\","
             "IF(NOT(ISNUMBER(B%d)),\"mu must be a number\",IF(OR(B%d<%.10g,B%d>%.10g),"
             "\"mu outside the table\",\"ok\")))))",
             LK_FLOOR + 1, LK_FLOOR + 1, LK_MU + 1, LK_MU + 1, LK_MU + 1, mu_min, LK_MU + 1, mu_max);
    formula(ws, r->lookup_zero_cache, LK_CHECK, f, 0, check, F->bold);
    snprintf(msg, sizeof msg, "the table covers mu %.2f to %.2f", mu_min, mu_max);
    worksheet_write_string(ws, LK_CHECK, 2, msg, NULL);
    worksheet_write_string(ws, LK_NOTE, 0, "Note", F->bold);
    snprintf(f, sizeof f, "=IF(B%d<>\"ok\",\"\",IF(B%d=0,\"no sliding predicted: mu g is at or "
             "above what every motion demands\",\"\"))", LK_CHECK + 1, LK_RESULT + 1);
    formula(ws, r->lookup_zero_cache, LK_NOTE, f, 0, ok && res == 0 ? "no sliding predicted: mu g is at or above what "
            "every motion demands" : "", NULL);
    worksheet_write_string(ws, LK_ZPA, 0, "Floor's horizontal ZPA, g", F->bold);
    snprintf(f, sizeof f, "=IF(B%d<>\"ok\",\"\",INDEX(floor_zpa_g,1,B%d))", LK_CHECK + 1, LK_COL + 1);
    formula(ws, r->lookup_zero_cache, LK_ZPA, f, ok ? r->floors[fi].zpa_h_ms2 / SL_G : 0, ok ? NULL : "", F->ratio);
    worksheet_write_string(ws, LK_X, 0, "mu g / ZPA", F->bold);
    snprintf(f, sizeof f, "=IF(B%d<>\"ok\",\"\",B%d/B%d)", LK_CHECK + 1, LK_MU + 1, LK_ZPA + 1);
    formula(ws, r->lookup_zero_cache, LK_X, f, ok ? mu0 * SL_G / r->floors[fi].zpa_h_ms2 : 0, ok ? NULL : "", F->ratio);
    /* the standard error, interpolated as the clearance is */
    char se_col_from[8], se_col_to[8], fl_from[8], fl_to[8];
    col_name(data_col_se(nf, 0), se_col_from);
    col_name(data_col_se(nf, nf - 1), se_col_to);
    col_name(data_col_flags(nf, 0), fl_from);
    col_name(data_col_flags(nf, nf - 1), fl_to);
    char se_rng[64], fl_rng[64];
    snprintf(se_rng, sizeof se_rng, "Data!$%s$%d:$%s$%zu", se_col_from, DATA_HEAD + 2, se_col_to,
             DATA_HEAD + 1 + n);
    snprintf(fl_rng, sizeof fl_rng, "Data!$%s$%d:$%s$%zu", fl_from, DATA_HEAD + 2, fl_to,
             DATA_HEAD + 1 + n);
    worksheet_write_string(ws, LK_SE, 0,
                           "Standard error of the NLTHA design value, mm (design factor x sd / "
                           "sqrt(number of motion sets); where the cap governs, the cap's: "
                           "1.5 x sd of the floor displacements / sqrt(number of sets))", F->bold);
    snprintf(f, sizeof f,
             "=IF(B%d<>\"ok\",\"\",INDEX(%s,B%d,B%d)+IF(B%d=B%d,0,(B%d-B%d)*(INDEX(%s,MIN(B%d+1,%zu),"
             "B%d)-INDEX(%s,B%d,B%d))/(B%d-B%d)))",
             LK_CHECK + 1, se_rng, LK_ROW + 1, LK_COL + 1, LK_MU1 + 1, LK_MU0 + 1, LK_MU + 1,
             LK_MU0 + 1, se_rng, LK_ROW + 1, n, LK_COL + 1, se_rng, LK_ROW + 1, LK_COL + 1,
             LK_MU1 + 1, LK_MU0 + 1);
    double se = 0;
    if (ok) {
        double s0 = design_se_m(&r->floors[fi], k0), s1 = design_se_m(&r->floors[fi], k1);
        double m0 = dsel->rows[k0].mu, m1 = dsel->rows[k1].mu;
        se = MM_PER_M * (s0 + (m1 == m0 ? 0 : (mu0 - m0) * (s1 - s0) / (m1 - m0)));
    }
    formula(ws, r->lookup_zero_cache, LK_SE, f, se, ok ? NULL : "", F->mm);
    worksheet_set_row(ws, LK_SE, 48, NULL);
    worksheet_set_row(ws, LK_CHECK, 30, NULL);
    worksheet_write_string(ws, LK_FLAGS, 0, "Flags at the grid rows around mu", F->bold);
    snprintf(f, sizeof f, "=IF(B%d<>\"ok\",\"\",INDEX(%s,B%d,B%d)&\" | \"&INDEX(%s,MIN(B%d+1,%zu),B%d))",
             LK_CHECK + 1, fl_rng, LK_ROW + 1, LK_COL + 1, fl_rng, LK_ROW + 1, n, LK_COL + 1);
    char fl0[256], fl1[256], flc[600] = "";
    if (ok) {
        sl_report_flags(dsel->rows[k0].flags, fl0, sizeof fl0);
        sl_report_flags(dsel->rows[k1].flags, fl1, sizeof fl1);
        snprintf(flc, sizeof flc, "%s | %s", fl0[0] ? fl0 : "-", fl1[0] ? fl1 : "-");
    }
    formula(ws, r->lookup_zero_cache, LK_FLAGS, f, 0, flc, NULL);

    worksheet_merge_range(ws, LK_HOW, 0, LK_HOW, 1, "How it is computed (linear interpolation in "
                          "mu, as sl_design_clearance_at in the program):", F->bold);
    worksheet_write_string(ws, LK_COL, 0, "column of the floor in Summary", NULL);
    snprintf(f, sizeof f, "=IF(B%d<>\"ok\",\"\",MATCH(B%d,floor_names,0))", LK_CHECK + 1, LK_FLOOR + 1);
    formula(ws, r->lookup_zero_cache, LK_COL, f, (double)(fi + 1), ok ? NULL : "", NULL);
    worksheet_write_string(ws, LK_ROW, 0, "row of the mu at or below", NULL);
    snprintf(f, sizeof f, "=IF(B%d<>\"ok\",\"\",MATCH(B%d,mu_grid,1))", LK_CHECK + 1, LK_MU + 1);
    formula(ws, r->lookup_zero_cache, LK_ROW, f, (double)(k0 + 1), ok ? NULL : "", NULL);
    worksheet_write_string(ws, LK_MU0, 0, "mu at or below", NULL);
    snprintf(f, sizeof f, "=IF(B%d<>\"ok\",\"\",INDEX(mu_grid,B%d))", LK_CHECK + 1, LK_ROW + 1);
    formula(ws, r->lookup_zero_cache, LK_MU0, f, dsel->rows[k0].mu, ok ? NULL : "", F->mu);
    worksheet_write_string(ws, LK_MU1, 0, "mu above", NULL);
    snprintf(f, sizeof f, "=IF(B%d<>\"ok\",\"\",INDEX(mu_grid,MIN(B%d+1,%zu)))", LK_CHECK + 1,
             LK_ROW + 1, n);
    formula(ws, r->lookup_zero_cache, LK_MU1, f, dsel->rows[k1].mu, ok ? NULL : "", F->mu);
    worksheet_write_string(ws, LK_C0, 0, "clearance at the mu at or below, mm", NULL);
    snprintf(f, sizeof f, "=IF(B%d<>\"ok\",\"\",INDEX(clearance_mm,B%d,B%d))", LK_CHECK + 1,
             LK_ROW + 1, LK_COL + 1);
    formula(ws, r->lookup_zero_cache, LK_C0, f, MM_PER_M * dsel->rows[k0].clearance_m, ok ? NULL : "", F->mm);
    worksheet_write_string(ws, LK_C1, 0, "clearance at the mu above, mm", NULL);
    snprintf(f, sizeof f, "=IF(B%d<>\"ok\",\"\",INDEX(clearance_mm,MIN(B%d+1,%zu),B%d))",
             LK_CHECK + 1, LK_ROW + 1, n, LK_COL + 1);
    formula(ws, r->lookup_zero_cache, LK_C1, f, MM_PER_M * dsel->rows[k1].clearance_m, ok ? NULL : "", F->mm);

    worksheet_write_string(ws, LK_POLICY, 0, "Clearance policy", F->bold);
    worksheet_write_string(ws, LK_POLICY, 1, sl_clearance_policy_name(d0->policy), NULL);
    snprintf(f, sizeof f,
             "nltha: %g x the mean peak vector sliding displacement of %zu synthesized motion "
             "sets (ASCE/SEI 43-05), capped at %g x the mean peak floor displacement; asce: %g x "
             "the ASCE best estimate, same cap; envelope: the larger. Each floor's sheet shows both "
             "curves, the cap and every range where ASCE is below NLTHA; the Notes sheet states "
             "the assumptions and limits.",
             d0->fs_nltha, d0->n_sets, d0->cap_factor, d0->fs_asce);
    worksheet_merge_range(ws, LK_POLICY + 1, 0, LK_POLICY + 1, 1, f, F->wrap);
    worksheet_set_row(ws, LK_POLICY + 1, 75, NULL);
    page_setup(ws, r, 0);
    worksheet_fit_to_pages(ws, 1, 1);
    protect(ws);
    worksheet_activate(ws);
}

static void quality_sheet(lxw_workbook *wb, const fmts *F, const sl_report *r)
{
    lxw_worksheet *ws = workbook_add_worksheet(wb, "Motion quality");
    static const char *const head[] = {
        "floor id", "set", "comp.", "PGA, g", "D5-75, s", "min ratio to target",
        "max ratio to target", "longest run below target", "max abs. correlation",
        "v end, m/s", "d end, m", "pass", "failed checks"};
    for (lxw_col_t c = 0; c < 13; c++)
        worksheet_write_string(ws, 0, c, head[c], F->header);
    worksheet_set_row(ws, 0, 62, NULL);
    worksheet_set_column(ws, 0, 0, 14, NULL);
    worksheet_set_column(ws, 1, 2, 5, NULL);
    worksheet_set_column(ws, 3, 8, 8.5, NULL);
    worksheet_set_column(ws, 9, 10, 9.5, F->sci);
    worksheet_set_column(ws, 11, 11, 5, NULL);
    worksheet_set_column(ws, 12, 12, 24, F->wrap);
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
        write_num_or_blank(ws, row, 9, m->v_end_ms, F->sci);
        write_num_or_blank(ws, row, 10, m->d_end_m, F->sci);
        worksheet_write_string(ws, row, 11, m->pass ? "yes" : "NO", m->pass ? NULL : F->bold);
        worksheet_write_string(ws, row, 12, m->why && *m->why ? m->why : "-", NULL);
    }
    page_setup(ws, r, 1);
    worksheet_fit_to_pages(ws, 1, 0);
    worksheet_repeat_rows(ws, 0, 0);
    protect(ws);
}

static void notes_sheet(lxw_workbook *wb, const fmts *F, const sl_report *r)
{
    lxw_worksheet *ws = workbook_add_worksheet(wb, "Notes");
    const sl_design *d = r->floors[0].design;
    char t[12][1100];
    size_t k = 0;
    snprintf(t[k++], sizeof t[0], "Model: a rigid block standing on a level floor, free to slide "
             "in both horizontal directions at once; the floor moves in three components (two "
             "horizontals and the vertical, which changes the normal force). Sliding only: "
             "rocking, overturning, uplift and impact are not modelled.");
    snprintf(t[k++], sizeof t[0], "Friction: Coulomb, isotropic in the floor plane, the static "
             "coefficient equal to the kinetic one (mu). The block sticks while the friction "
             "force can hold it; mu g at or above every motion's demand means no sliding.");
    snprintf(t[k++], sizeof t[0], "Motions: %zu spectrum-compatible three-component sets per "
             "floor, synthesized from the floor response spectra and checked as in US NRC SRP "
             "3.7.1 (sheet Motion quality; 'longest run of points below target' = the most "
             "consecutive frequency points below the target spectrum, limit 9).", d->n_sets);
    char scat[700] = "";
    if (r->floors[0].scatter > 0)
        snprintf(scat, sizeof scat, " Each set's peak is its mean over a record-to-record "
                 "intensity factor of its horizontals (log-normal, mean 1, log standard deviation "
                 "%g): the floor motions behind a spectrum differ in intensity, and sliding near mu "
                 "g = ZPA grows faster than the intensity (docs/run.md, Intensity scatter). This "
                 "goes beyond A.1's mean of spectrum-compatible analyses: --scatter 0 gives that "
                 "procedure. The motions written with --motions carry no factor. Above the ZPA the "
                 "NLTHA value comes from the strongest intensities alone, which is why ASCE (zero "
                 "there) can be listed below NLTHA at high mu.", r->floors[0].scatter);
    snprintf(t[k++], sizeof t[0], "NLTHA design value = %g x the mean over the sets of the peak "
             "vector sliding displacement (ASCE/SEI 43-05 A.1 asks for 3.0 x the mean of at least "
             "5 analyses).%s", d->fs_nltha, scat);
    snprintf(t[k++], sizeof t[0], "ASCE design value = %g x the ASCE/SEI 43-05 best estimate "
             "delta = c_s / (2 pi f_es)^2 with c_s = 2 mu_e g and f_es the lowest frequency where "
             "the 10 %%-damped spectrum SA_vH reaches c_s: delta is the spectral displacement "
             "SD_vH(f_es) = SA_vH / (2 pi f)^2 there. Where f_es lies in a part of the spectrum with "
             "constant spectral displacement (RG 1.60 below 0.25 Hz: about 502 mm at 0.3 g) the "
             "estimate is flat in mu (e.g. mu 0.05-0.07); where f_es lies on a rising flank that "
             "grows faster than f^2 (a floor's amplification below its mode, e.g. the roof at "
             "1.5-2.1 Hz) the estimate rises with mu, until mu g reaches the ZPA and it drops to 0. "
             "Each floor sheet names its flat and rising ranges.", d->fs_asce);
    snprintf(t[k++], sizeof t[0], "Cap = %g x the mean over the sets of the peak floor "
             "displacement (PGD), the horizontals combined by the 100-40 rule: a block cannot "
             "slide much further than the floor moves. Design values are min(value, cap); flags "
             "nltha_capped and asce_capped mark where the cap governs.", d->cap_factor);
    snprintf(t[k++], sizeof t[0], "Crossover and ranges: every range of mu where the ASCE design "
             "value is below the NLTHA design value is listed (ends interpolated where the "
             "difference changes sign; '<=' or '+' when the range reaches the grid's end). The "
             "crossover, in the source study's sense, is the upper end of such a range when it "
             "starts at the lowest mu of the grid; otherwise 'none'.");
    snprintf(t[k++], sizeof t[0], "Required clearance: by the policy (%s): nltha = NLTHA design "
             "value (ASCE 43-05 permits NLTHA everywhere), asce = ASCE design value, envelope = "
             "the larger. Between grid values of mu the clearance is interpolated linearly.",
             sl_clearance_policy_name(d->policy));
    snprintf(t[k++], sizeof t[0], "Uncertainty: the NLTHA mean of %zu sets has a standard error "
             "of sd / sqrt(%zu); the design value's standard error (design factor x that; where the "
             "cap governs, the cap's: 1.5 x the standard error of the mean floor displacement) is "
             "shown per row and on the Lookup. Another seed gives values within about two standard "
             "errors. The factor 3.0 covers record-to-record variability, not modelling error.",
             d->n_sets, d->n_sets);
    snprintf(t[k++], sizeof t[0], "Limits: values at mu outside the table are not extrapolated. "
             "Results apply to the floor spectra given (sheet Inputs: files and CRC-32) and to "
             "components whose base does not rock; anchor components for which this is not "
             "true.");
    worksheet_set_column(ws, 0, 0, 72, F->wrap); /* fits a portrait A4 page at 100 % */
    worksheet_write_string(ws, 0, 0, "Assumptions and limits", F->title);
    for (size_t i = 0; i < k; i++) {
        worksheet_write_string(ws, (lxw_row_t)(i + 2), 0, t[i], F->wrap);
        /* LibreOffice does not grow a wrapped row: about 80 characters a line of the
         * 72-wide column, 15 points a line, and a blank line between paragraphs */
        worksheet_set_row(ws, (lxw_row_t)(i + 2), 15.0 * (double)(2 + strlen(t[i]) / 80), NULL);
    }
    page_setup(ws, r, 0);
    worksheet_fit_to_pages(ws, 1, 0);
    protect(ws);
}

static void inputs_sheet(lxw_workbook *wb, const fmts *F, const sl_report *r)
{
    lxw_worksheet *ws = workbook_add_worksheet(wb, "Inputs");
    worksheet_set_column(ws, 0, 0, 30, F->wrap);
    worksheet_set_column(ws, 1, 1, 60, F->wrap);
    worksheet_set_column(ws, 2, 5, 12, F->wrap);
    lxw_row_t row = 0;
    worksheet_write_string(ws, row++, 0, "What reproduces this workbook", F->title);
    worksheet_write_string(ws, row, 0, "program", F->bold);
    worksheet_write_string(ws, row++, 1, r->version, NULL);
    worksheet_write_string(ws, row, 0, "command", F->bold);
    const char *cl = r->command_line ? r->command_line : "";
    worksheet_write_string(ws, row, 1, cl, F->note);
    /* a wrapped cell's height (LibreOffice does not grow it): 15 points a line of about
     * 75 characters in the 60-wide column */
    worksheet_set_row(ws, row++, 15.0 * (double)(1 + strlen(cl) / 75), NULL);
    char buf[64];
    struct tm tmv;
    gmtime_r(&r->created, &tmv);
    strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tmv);
    worksheet_write_string(ws, row, 0, "created (UTC)", F->bold);
    worksheet_write_string(ws, row++, 1, buf, NULL);
    for (size_t s = 0; s < r->n_settings; s++) { /* wrapped values: heights as above */
        worksheet_write_string(ws, row, 0, r->settings[s].name, F->bold);
        worksheet_write_string(ws, row, 1, r->settings[s].value, NULL);
        worksheet_set_row(ws, row++, 15.0 * (double)(1 + strlen(r->settings[s].value) / 75), NULL);
    }
    row++;
    static const char *const head[] = {"floor", "file", "id", "units", "bytes", "CRC-32"};
    for (lxw_col_t c = 0; c < 6; c++)
        worksheet_write_string(ws, row, c, head[c], F->header);
    row++;
    for (size_t i = 0; i < r->n_floors; i++) {
        const sl_report_floor *fl = &r->floors[i];
        worksheet_write_string(ws, row, 0, fl->name, NULL);
        worksheet_write_string(ws, row, 1, fl->path, NULL);
        worksheet_write_string(ws, row, 2, fl->id, NULL);
        worksheet_write_string(ws, row, 3, or_dash(fl->units), NULL);
        worksheet_write_number(ws, row, 4, (double)fl->size_bytes, NULL);
        snprintf(buf, sizeof buf, "%08lx", fl->crc32 & 0xffffffffUL);
        worksheet_write_string(ws, row++, 5, buf, NULL);
    }
    page_setup(ws, r, 1);
    worksheet_fit_to_pages(ws, 1, 0);
    protect(ws);
}

static void make_formats(lxw_workbook *wb, fmts *F)
{
    F->bold = workbook_add_format(wb);
    format_set_bold(F->bold);
    format_set_text_wrap(F->bold);
    format_set_align(F->bold, LXW_ALIGN_VERTICAL_TOP);
    F->label = workbook_add_format(wb);
    format_set_bold(F->label);
    format_set_align(F->label, LXW_ALIGN_VERTICAL_TOP);
    F->title = workbook_add_format(wb);
    format_set_bold(F->title);
    format_set_font_size(F->title, 14);
    F->mm = workbook_add_format(wb);
    format_set_num_format(F->mm, "0.0");
    F->mm0 = workbook_add_format(wb);
    format_set_num_format(F->mm0, "0");
    F->mmbold = workbook_add_format(wb);
    format_set_num_format(F->mmbold, "0.0");
    format_set_bold(F->mmbold);
    F->ratio = workbook_add_format(wb);
    format_set_num_format(F->ratio, "0.000");
    F->sci = workbook_add_format(wb);
    format_set_num_format(F->sci, "0.0E+00");
    F->mu = workbook_add_format(wb);
    format_set_num_format(F->mu, "0.00");
    F->wrap = workbook_add_format(wb);
    format_set_text_wrap(F->wrap);
    format_set_align(F->wrap, LXW_ALIGN_VERTICAL_TOP);
    format_set_indent(F->wrap, 1);
    F->note = workbook_add_format(wb);
    format_set_text_wrap(F->note);
    format_set_align(F->note, LXW_ALIGN_VERTICAL_TOP);
    F->result = workbook_add_format(wb);
    format_set_bold(F->result);
    format_set_font_size(F->result, 14);
    format_set_num_format(F->result, "0.0");
    format_set_bg_color(F->result, 0xE2EFDA);
    format_set_border(F->result, LXW_BORDER_THIN);
    format_set_align(F->result, LXW_ALIGN_LEFT);
    F->input = workbook_add_format(wb);
    format_set_bg_color(F->input, 0xFFF2CC);
    format_set_border(F->input, LXW_BORDER_THIN);
    format_set_unlocked(F->input);
    format_set_align(F->input, LXW_ALIGN_LEFT);
    F->header = workbook_add_format(wb);
    format_set_bold(F->header);
    format_set_text_wrap(F->header);
    format_set_align(F->header, LXW_ALIGN_VERTICAL_TOP);
    format_set_bottom(F->header, LXW_BORDER_THIN);
}

sl_status sl_report_write_xlsx(const sl_report *r, const char *path, sl_error *err)
{
    if (check_finite(r, err))
        return err ? err->code : SL_EINVAL;
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
    props.company = (char *)(uintptr_t)r->project.project;
    props.keywords = (char *)(uintptr_t)r->project.document;
    /* libxlsxwriter reads created = 0 as "now": the epoch itself is written
     * as one second after it, so --created 0 still gives identical files */
    props.created = r->created > 0 ? r->created : 1;
    workbook_set_properties(wb, &props);
    fmts F;
    make_formats(wb, &F);
    axes ax = shared_axes(r);
    lookup_sheet(wb, &F, r);
    summary_sheet(wb, &F, r, &ax);
    for (size_t i = 0; i < r->n_floors; i++) {
        char sname[SHEET_NAME_MAX + 8];
        sheet_name(r->floors[i].name, i, sname, sizeof sname);
        floor_sheet(wb, &F, r, i, sname, &ax);
    }
    quality_sheet(wb, &F, r);
    notes_sheet(wb, &F, r);
    inputs_sheet(wb, &F, r);
    data_sheet(wb, &F, r, &ax);
    lxw_error le = workbook_close(wb);
    if (le != LXW_NO_ERROR) {
        sl_atomic_abort(a);
        return sl_error_set(err, SL_EIO, path, 0, "cannot write the workbook: %s", lxw_strerror(le));
    }
    return sl_atomic_commit(a, err);
}
