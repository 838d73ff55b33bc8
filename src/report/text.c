/* text.c - the statements the sheets and CSV files make about a floor: each
 * computed from that floor's own numbers (sheets.h). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "io/floor.h"
#include "method/asce.h"
#include "method/stats.h"
#include "report/sheets.h"

const char *sl_rpt_or_dash(const char *s) { return s && *s ? s : "-"; }

const char *sl_rpt_floor_warnings(const sl_report_floor *fl)
{
    static _Thread_local char zw[600];
    if (fl->warnings)
        return fl->warnings;
    if (fl->units && fl->path &&
        sl_floor_zpa_warning_text(fl->zpa_h_ms2, fl->units, sl_floor_format_of(fl->path), zw,
                                  sizeof zw))
        return zw;
    return "";
}

char *sl_rpt_warnings_line(const sl_report *r, char *buf, size_t n)
{
    size_t used = 0;
    buf[0] = '\0';
    for (size_t i = 0; i < r->n_floors && used + 1 < n; i++) {
        const char *w = sl_rpt_floor_warnings(&r->floors[i]);
        if (!*w)
            continue;
        int k = snprintf(buf + used, n - used, "%s%s: %s", used ? "; " : "WARNINGS (floors.csv "
                         "column warnings; Notes): ", r->floors[i].id, w);
        if (k < 0 || (size_t)k >= n - used) {
            if (n > 4)
                strcpy(buf + n - 4, "...");
            break;
        }
        used += (size_t)k;
    }
    return buf;
}

/* The standard error of the NLTHA design value at row k, m: the one the
 * convergence statistics give (sl_report_floor.design_se_m: FS SE(mean)
 * below the cap, the cap's SE where the cap governs); without them FS
 * sd / sqrt(N) below the cap and 0 where the cap governs. */
double sl_rpt_design_se_m(const sl_report_floor *fl, size_t k)
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
 * their SE's leading digit, between these steps, mm. */
#define SHOWN_MIN_STEP_MM 0.1
#define SHOWN_MAX_STEP_MM 1.0

/* Decimals to show the clearance of row k with: 0 when the standard error
 * of the NLTHA design value is 1 mm or more, else 1 (stats.h:
 * sl_stats_step). An ASCE clearance comes from the floor's spectra: 1. The
 * value itself is not rounded (the Lookup interpolates the exact values). */
int sl_rpt_shown_decimals(const sl_report_floor *fl, size_t k)
{
    const sl_design_row *w = &fl->design->rows[k];
    double se_mm = w->clearance_m == w->nltha_design_m ? SL_RPT_MM_PER_M * sl_rpt_design_se_m(fl, k)
                                                       : 0.0;
    return sl_stats_step_decimals(sl_stats_step(se_mm, SHOWN_MIN_STEP_MM, SHOWN_MAX_STEP_MM));
}

/* 1 when the floor's file gives dampings other than the one matched. */
int sl_rpt_has_dampings(const sl_report_floor *fl)
{
    return fl->dampings && *fl->dampings && strcmp(fl->dampings, "none") != 0;
}

/* "mu 0.123 (mu g/ZPA 0.456)" or the reason there is none. */
char *sl_rpt_crossover_text(const sl_design *d, char *buf, size_t n)
{
    if (d->has_crossover)
        snprintf(buf, n, "mu %.3f (mu g/ZPA %.3f)", d->crossover_mu, d->crossover_x);
    else
        snprintf(buf, n, "none (ASCE is not below NLTHA at the lowest mu of the grid)");
    return buf;
}

/* Where the ASCE best estimate is flat (within 0.1 %) or rises with mu:
 * "flat for mu 0.05-0.07 (constant spectral displacement at f_es); rises
 * for mu 0.30-0.70 (f_es on a flank where SA grows faster than f^2)". */
char *sl_rpt_asce_shape_text(const sl_design *d, char *buf, size_t n)
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

const char *sl_rpt_flags_legend(void)
{
    return "Flags: asce_below_nltha: ASCE design below NLTHA design; nltha_capped, "
           "asce_capped: that design value is the cap; no_sliding: mu g at or above every "
           "motion's demand (0); asce_undefined: no ASCE value; -: none.";
}

/* The synthesis limits the other dampings are held to (SRP 3.7.1: S/T of
 * the set-mean spectrum), as the floor's text compares them. */
#define DAMPINGS_LO 0.9
#define DAMPINGS_HI 1.3

char *sl_rpt_dampings_text(const sl_report_floor *fl, char *buf, size_t n)
{
    snprintf(buf, n, "other dampings of the file (informational, not a pass condition: the "
             "motions are matched at one damping; at each other one, the lowest and highest "
             "set-mean S/T of the motions' own spectra to the file's table, ok within %g-%g, "
             "OUTSIDE beyond): %s", DAMPINGS_LO, DAMPINGS_HI, fl->dampings);
    return buf;
}

/* A fall between two grid rows steeper than mu^-8 (its slope in log-log)
 * is a step of the ASCE estimate (f_es jumping past a peak of the
 * spectrum); the estimate's smooth fall is far less steep (measured on the
 * example floors, default grid: slope -1.6 to -2.4 everywhere but the one
 * step of 02-el12, -39 between mu 0.42 and 0.43). */
#define ASCE_STEP_SLOPE (-8.0)

char *sl_rpt_asce_drops_text(const sl_design *d, int brief, char *buf, size_t n)
{
    size_t used = 0, z = d->n; /* z: the first row from which the estimate stays 0 */
    buf[0] = '\0';
    while (z > 0 && d->rows[z - 1].asce_best_m == 0)
        z--;
    for (size_t k = 0; k + 1 < d->n && k + 1 < z; k++) {
        double a = d->rows[k].asce_best_m, b = d->rows[k + 1].asce_best_m;
        if (!(a > 0 && b > 0 &&
              log(b / a) / log(d->rows[k + 1].mu / d->rows[k].mu) < ASCE_STEP_SLOPE))
            continue;
        int w = snprintf(buf + used, n - used, "%sthe design value steps from %.1f to %.1f mm "
                         "between mu %.2f and %.2f%s", used ? "; " : "",
                         1e3 * d->rows[k].asce_design_m, 1e3 * d->rows[k + 1].asce_design_m,
                         d->rows[k].mu, d->rows[k + 1].mu,
                         brief ? "" : " (c_s = 2 mu_e g rises past a peak of the 10 % spectrum: "
                                      "f_es jumps to its far side)");
        if (w < 0 || (size_t)w >= n - used)
            return buf;
        used += (size_t)w;
    }
    if (z < d->n && z > 0)
    {
        char why[96] = "";
        if (!brief)
            snprintf(why, sizeof why, ", where mu_e g = mu (1 - %g a_v/g) g reaches the ZPA",
                     SL_ASCE_VERTICAL_COEF);
        snprintf(buf + used, n - used, "%s0 from mu %.2f (mu g/ZPA %.2f)%s", used ? "; " : "",
                 d->rows[z].mu, d->rows[z].x, why);
    }
    return buf;
}

/* The check names sl_report_quality.why holds (deliver.c), in its order. */
static const char *const check_names[] = {"below",    "above",   "run_below", "d5_75",
                                          "duration", "end_v_d", "pga",       "correlation"};
#define N_CHECKS (sizeof check_names / sizeof check_names[0])

char *sl_rpt_failed_text(const sl_report *r, const sl_report_floor *fl, char *buf, size_t n)
{
    buf[0] = '\0';
    if (fl->n_failed_motions == 0)
        return buf;
    size_t count[N_CHECKS] = {0}, total = 0;
    for (size_t q = 0; q < r->n_quality; q++) {
        const sl_report_quality *m = &r->quality[q];
        if (!m->floor || strcmp(m->floor, fl->id))
            continue;
        total++;
        if (m->pass || !m->why)
            continue;
        char word[32];
        for (const char *p = m->why; sscanf(p, "%31s", word) == 1;) {
            for (size_t c = 0; c < N_CHECKS; c++)
                count[c] += !strcmp(word, check_names[c]);
            p = strstr(p, word) + strlen(word);
        }
    }
    if (!total)
        total = 3 * fl->design->n_sets;
    size_t used = 0;
    int w = snprintf(buf, n, "CHECKS FAILED: %zu of %zu motion components of floor %s failed "
                     "their SRP 3.7.1 checks (", fl->n_failed_motions, total, fl->id);
    used = w > 0 && (size_t)w < n ? (size_t)w : n - 1;
    int any = 0;
    for (size_t c = 0; c < N_CHECKS; c++)
        if (count[c]) {
            w = snprintf(buf + used, n - used, "%s%s %zu", any ? ", " : "", check_names[c],
                         count[c]);
            used += w > 0 && (size_t)w < n - used ? (size_t)w : 0;
            any = 1;
        }
    snprintf(buf + used, n - used, "%smotion_quality.csv); its results were kept by "
             "--accept-failed-checks", any ? "; " : "");
    return buf;
}

char *sl_rpt_failed_ids(const sl_report *r, char *buf, size_t n)
{
    size_t used = 0;
    buf[0] = '\0';
    for (size_t i = 0; i < r->n_floors; i++)
        if (r->floors[i].n_failed_motions) {
            int w = snprintf(buf + used, n - used, "%s%s", used ? ", " : "", r->floors[i].id);
            if (w < 0 || (size_t)w >= n - used)
                break;
            used += (size_t)w;
        }
    return buf;
}

const char *sl_rpt_sa10_text(const sl_report_floor *fl)
{
    return fl->sa10_fallback ? "the floor file gives no 10 %-damped spectrum: the ASCE/SEI 43-05 "
                               "estimate used the mean 10 % spectrum of the floor's synthesized "
                               "motions instead"
                             : "";
}

/* fmt takes the floor id (%s) and its number of sets (%zu). */
char *sl_rpt_sets_text(const sl_report *r, const char *fmt, char *buf, size_t n)
{
    size_t used = 0;
    buf[0] = '\0';
    for (size_t i = 0; i < r->n_floors; i++) {
        if (used) {
            int s = snprintf(buf + used, n - used, "; ");
            if (s < 0 || (size_t)s >= n - used)
                break;
            used += (size_t)s;
        }
        int w = snprintf(buf + used, n - used, fmt, r->floors[i].id, r->floors[i].design->n_sets);
        if (w < 0 || (size_t)w >= n - used)
            break;
        used += (size_t)w;
    }
    return buf;
}
