/* csv.c - the CSV tables (RFC 4180: CRLF line ends, fields quoted when
 * needed, units in the column names) after '#' comment lines that trace the
 * file to its run: program, command, creation time, seed and the CRC-32 of
 * every floor file it holds; first of all, when a floor's motions failed
 * their checks, a "# WARNING:" line saying so (report.h, sheets.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core/units.h"
#include "io/atomic.h"
#include "report/sheets.h"


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

/* A comment line "# key: value" (line breaks in value become blanks). */
static void csv_comment(FILE *f, const char *key, const char *value)
{
    fprintf(f, "# %s: ", key);
    for (const char *p = value ? value : ""; *p; p++)
        fputc(*p == '\r' || *p == '\n' ? ' ' : *p, f);
    fputs("\r\n", f);
}

/* The lines every file starts with. fl: the one floor the file is about
 * (NULL: every floor of the run). */
static void csv_head(FILE *f, const sl_report *r, const sl_report_floor *fl, const char *what)
{
    char buf[1400];
    for (size_t i = 0; i < r->n_floors; i++) /* failed checks: the first lines */
        if ((!fl || fl == &r->floors[i]) && r->floors[i].n_failed_motions)
            csv_comment(f, "WARNING", sl_rpt_failed_text(r, &r->floors[i], buf, sizeof buf));
    csv_comment(f, "program", r->version);
    csv_comment(f, "content", what);
    csv_comment(f, "command", r->command_line && *r->command_line ? r->command_line : "-");
    struct tm tmv;
    gmtime_r(&r->created, &tmv);
    strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tmv);
    csv_comment(f, "created", buf);
    csv_comment(f, "seed", sl_rpt_or_dash(r->seed));
    for (size_t i = 0; i < r->n_floors; i++) {
        const sl_report_floor *q = &r->floors[i];
        if (fl && fl != q)
            continue;
        snprintf(buf, sizeof buf, "%08lx %s (%s, %ld bytes)", q->crc32 & 0xffffffffUL, q->id,
                 q->path, q->size_bytes);
        csv_comment(f, "floor_file_crc32", buf);
    }
    csv_comment(f, "project", sl_rpt_or_dash(r->project.project));
    csv_comment(f, "document", sl_rpt_or_dash(r->project.document));
    csv_comment(f, "revision", sl_rpt_or_dash(r->project.revision));
}

/* The same lines and fields for the plant index (plant_book.c): one writer. */
void sl_rpt_csv_head(FILE *f, const sl_report *r, const char *what) { csv_head(f, r, NULL, what); }

void sl_rpt_csv_comment(FILE *f, const char *key, const char *value) { csv_comment(f, key, value); }

void sl_rpt_csv_field(FILE *f, const char *s) { csv_field(f, s); }

sl_status sl_rpt_floors_alloc(sl_rpt_floors *fl, sl_report *rep, size_t n, const char *path,
                              sl_error *err)
{
    fl->floor = calloc(n ? n : 1, sizeof *fl->floor);
    fl->id = calloc(n ? n : 1, sizeof *fl->id);
    if (!fl->floor || !fl->id) {
        sl_rpt_floors_free(fl);
        return sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
    }
    rep->n_floors = n;
    rep->floors = fl->floor;
    return SL_OK;
}

void sl_rpt_floors_set(sl_rpt_floors *fl, size_t i, const char *building, const char *sep,
                       const char *id, sl_report_floor f)
{
    snprintf(fl->id[i], sizeof fl->id[i], "%s%s%s", building, sep, id);
    f.id = fl->id[i];
    fl->floor[i] = f;
}

void sl_rpt_floors_free(sl_rpt_floors *fl)
{
    free(fl->floor);
    free(fl->id);
    fl->floor = NULL;
    fl->id = NULL;
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
    char name[SL_RPT_ID_MAX + 16], buf[1024], flags[256], file[SL_RPT_ID_MAX + 1];
    snprintf(name, sizeof name, "floor_%s.csv", sl_report_file_name(fl->id, file, sizeof file));
    if (csv_open(dir, name, &a, err))
        return err ? err->code : SL_EIO;
    FILE *f = sl_atomic_file(a);
    const sl_design *d = fl->design;
    csv_head(f, r, fl, "design sliding spectra and required clearance of one floor");
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
    csv_comment(f, "crossover", sl_rpt_crossover_text(d, buf, sizeof buf));
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
        const double mm[] = {w->nltha_mean_m, w->nltha_sd_m, w->nltha_design_m, sl_rpt_design_se_m(fl, k),
                             fl->design_lo_m ? fl->design_lo_m[k] : NAN,
                             fl->design_hi_m ? fl->design_hi_m[k] : NAN,
                             w->asce_best_m, w->asce_design_m, w->cap_m, w->clearance_m};
        fprintf(f, "%.4g,%.5g,", w->mu, w->x);
        for (size_t c = 0; c < sizeof mm / sizeof mm[0]; c++) {
            csv_num(f, SL_RPT_MM_PER_M * mm[c], "%.4f");
            fputc(',', f);
        }
        csv_field(f, sl_report_flags(w->flags, flags, sizeof flags));
        fputc(',', f);
        csv_num(f, fl->err_est_m ? SL_RPT_MM_PER_M * fl->err_est_m[k] : NAN, "%.2e");
        fputs("\r\n", f);
    }
    return sl_atomic_commit(a, err);
}

sl_status sl_report_write_csv(const sl_report *r, const char *dir, sl_error *err)
{
    if (sl_rpt_check_finite(r, err))
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
    csv_head(f, r, NULL, "required clearance (mm) per floor; columns named <floor_id>_clearance_mm; "
             "shown to the digit of its standard error (1 mm or 0.1 mm; the floor files hold "
             "every digit)");
    csv_comment(f, "units", "clearance in mm; mu dimensionless");
    for (size_t i = 0; i < r->n_floors; i++) {
        snprintf(buf, sizeof buf, "%s (file %s, horizontal ZPA %.4f g)", r->floors[i].name,
                 r->floors[i].path, r->floors[i].zpa_h_ms2 / SL_G);
        char key[SL_RPT_ID_MAX + 16];
        snprintf(key, sizeof key, "floor %s", r->floors[i].id);
        csv_comment(f, key, buf);
    }
    fputs("mu", f);
    for (size_t i = 0; i < r->n_floors; i++) { /* an id as written may need quotes */
        char col[SL_RPT_ID_MAX + 16];
        snprintf(col, sizeof col, "%s_clearance_mm", r->floors[i].id);
        fputc(',', f);
        csv_field(f, col);
    }
    fputs("\r\n", f);
    size_t n = r->floors[0].design->n;
    for (size_t k = 0; k < n; k++) {
        fprintf(f, "%.4g", r->floors[0].design->rows[k].mu);
        for (size_t i = 0; i < r->n_floors; i++) {
            double v = SL_RPT_MM_PER_M * r->floors[i].design->rows[k].clearance_m;
            fputc(',', f);
            if (isfinite(v))
                fprintf(f, "%.*f", sl_rpt_shown_decimals(&r->floors[i], k), v);
        }
        fputs("\r\n", f);
    }
    if (sl_atomic_commit(a, err))
        return err ? err->code : SL_EIO;
    /* per floor: one row, one value per field */
    if (csv_open(dir, "floors.csv", &a, err))
        return err ? err->code : SL_EIO;
    f = sl_atomic_file(a);
    csv_head(f, r, NULL, "one row per floor; the ASCE-below-NLTHA ranges are in asce_below_nltha.csv");
    csv_comment(f, "crossover", "the mu where 2.0 x ASCE rises above 3.0 x NLTHA mean when ASCE is "
                "below NLTHA at the lowest mu of the grid; 'none' otherwise (docs/run.md)");
    csv_comment(f, "other_dampings", "every damping of the floor file other than the one "
                "matched, its table against the motions' own spectra at that damping: lowest and "
                "highest set-mean S/T over all of them, ok when each is within the synthesis "
                "limits (0.9-1.3), 'none' when the file gives one damping; reported, not a pass "
                "condition (docs/run.md)");
    csv_comment(f, "warnings", "every warning the run gave about the floor (its units, the "
                "plausibility of its ZPA, a floor accepted with --accept-floor), '; '-separated; "
                "empty when none");
    fputs("floor_id,floor,file,elevation_m,zpa_h_g,crossover_mu,crossover_mu_g_over_zpa,"
          "n_asce_below_nltha_ranges,clearance_policy,mu_without_nltha,n_sets,sets_stop,note,"
          "other_dampings_min_ratio,other_dampings_max_ratio,other_dampings_check,"
          "other_dampings,warnings\r\n",
          f);
    for (size_t i = 0; i < r->n_floors; i++) {
        const sl_report_floor *fl = &r->floors[i];
        const sl_design *d = fl->design;
        csv_field(f, fl->id);
        fputc(',', f);
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
        if (sl_rpt_has_dampings(fl)) {
            fputc(',', f);
            csv_num(f, fl->dampings_min, "%.4f");
            fputc(',', f);
            csv_num(f, fl->dampings_max, "%.4f");
            fprintf(f, ",%s,", fl->dampings_ok ? "ok" : "outside");
            csv_field(f, fl->dampings);
        } else {
            fputs(",none,none,none,none", f);
        }
        fputc(',', f);
        csv_field(f, sl_rpt_floor_warnings(fl));
        fputs("\r\n", f);
    }
    if (sl_atomic_commit(a, err))
        return err ? err->code : SL_EIO;
    /* every range where ASCE < NLTHA, one per row */
    if (csv_open(dir, "asce_below_nltha.csv", &a, err))
        return err ? err->code : SL_EIO;
    f = sl_atomic_file(a);
    csv_head(f, r, NULL, "every range of mu where the ASCE design value is below the NLTHA design "
             "value; ends interpolated where the difference changes sign; *_open = 1: the range "
             "reaches the end of the grid there");
    fputs("floor_id,range,mu_from,mu_to,mu_g_over_zpa_from,mu_g_over_zpa_to,from_open,to_open\r\n",
          f);
    for (size_t i = 0; i < r->n_floors; i++) {
        const sl_design *d = r->floors[i].design;
        for (size_t q = 0; q < d->n_ranges; q++) {
            const sl_design_range *g = &d->ranges[q];
            csv_field(f, r->floors[i].id);
            fprintf(f, ",%zu,%.4f,%.4f,%.4f,%.4f,%d,%d\r\n", q + 1, g->mu_lo,
                    g->mu_hi, g->x_lo, g->x_hi, g->open_lo, g->open_hi);
        }
    }
    if (sl_atomic_commit(a, err))
        return err ? err->code : SL_EIO;
    /* motion quality */
    if (csv_open(dir, "motion_quality.csv", &a, err))
        return err ? err->code : SL_EIO;
    f = sl_atomic_file(a);
    csv_head(f, r, NULL, "SRP 3.7.1 checks of every synthesized motion; longest_run_below = most "
             "consecutive frequency points below the target (limit 9)");
    fputs("floor_id,set,component,pga_g,d5_75_s,min_ratio_to_target,max_ratio_to_target,"
          "longest_run_below,max_abs_correlation,v_end_m_s,d_end_m,pass,failed_checks\r\n", f);
    for (size_t q = 0; q < r->n_quality; q++) {
        const sl_report_quality *m = &r->quality[q];
        csv_field(f, m->floor);
        fprintf(f, ",%d,%s,", m->set, m->component);
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
    if (sl_atomic_commit(a, err))
        return err ? err->code : SL_EIO;
    /* the rocking lookup (run --rocking-lookup) */
    if (!sl_rpt_has_rocking(r))
        return SL_OK;
    if (csv_open(dir, "rocking_lookup.csv", &a, err))
        return err ? err->code : SL_EIO;
    if (sl_rpt_rocking_csv(r, sl_atomic_file(a))) {
        sl_atomic_abort(a);
        return sl_error_set(err, SL_EIO, dir, 0, "cannot write rocking_lookup.csv");
    }
    return sl_atomic_commit(a, err);
}

