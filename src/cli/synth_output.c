/* synth_output.c - the files of `seislide synth`; see synth_output.h. */
#include "synth_output.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "cli.h"
#include "io/atomic.h"
#include "io/floor.h"
#include "io/motion.h"
#include "report/sheets.h"

/* Write a motion as CSV: time_s,acc_g (atomic). */
static sl_status write_csv_motion(const char *path, const sl_motion *m, sl_error *err)
{
    sl_atomic *a = sl_atomic_open(path, err);
    if (!a)
        return SL_EIO;
    FILE *f = sl_atomic_file(a);
    fputs("time_s,acc_g\n", f);
    for (size_t i = 0; i < m->n; i++)
        fprintf(f, "%.10g,%.10E\n", m->dt_s * (double)i, m->acc_ms2[i] / SL_G);
    return sl_atomic_commit(a, err);
}

/* One report row. */
typedef struct report_row {
    unsigned set;                 /* 1-based */
    const char *comp;             /* h1, h2, v */
    const char *file;             /* motion file name (in DIR) */
    const char *source;           /* target and origin */
    const char *seed;             /* decimal, or "" for records */
    const sl_synth_check *k;
    const double *corr;           /* the set's three pair values */
    const sl_synth_params *p;
    size_t nblk;                  /* other-damping blocks in the header */
} report_row;

/* The report's columns: name, printf format, value. Header and rows come
 * from this one list. */
#define REPORT_NUM_COLUMNS(X)                                        \
    X("attempt", "%u", r->k->attempt)                                \
    X("iterations", "%u", r->k->iterations)                          \
    X("damping", "%.4g", r->k->damping)                              \
    X("f_lo_hz", "%.6g", r->k->f_lo_hz)                              \
    X("f_hi_hz", "%.6g", r->k->f_hi_hz)                              \
    X("points", "%zu", r->k->npoints)                                \
    X("min_ratio", "%.5f", r->k->min_ratio)                          \
    X("f_min_ratio_hz", "%.6g", r->k->f_min_ratio_hz)                \
    X("max_ratio", "%.5f", r->k->max_ratio)                          \
    X("f_max_ratio_hz", "%.6g", r->k->f_max_ratio_hz)                \
    X("run_below", "%zu", r->k->run_below)                           \
    X("points_below", "%zu", r->k->n_below)                          \
    X("pga_g", "%.8g", r->k->pga_ms2 / SL_G)                          \
    X("zpa_g", "%.8g", r->k->zpa_ms2 / SL_G)                          \
    X("pgv_m_s", "%.6g", r->k->pgv_ms)                               \
    X("pgd_m", "%.6g", r->k->pgd_m)                                  \
    X("v_end_m_s", "%.3e", sl_synth_end_residual(r->k->v_end_ms, r->k->pgv_ms)) \
    X("d_end_m", "%.3e", sl_synth_end_residual(r->k->d_end_m, r->k->pgd_m))    \
    X("d5_75_s", "%.4f", r->k->d5_75_s)                              \
    X("duration_s", "%.6g", r->k->duration_s)                        \
    X("corr_h1_h2", "%.4f", r->corr[0])                              \
    X("corr_h1_v", "%.4f", r->corr[1])                               \
    X("corr_h2_v", "%.4f", r->corr[2])                               \
    X("corr_max_abs", "%.4f", r->k->max_corr)                        \
    X("pga_zpa", "%.4f", r->k->pga_zpa)                              \
    X("peaks_above_0.9pga", "%zu", r->k->peaks)                      \
    X("v_over_a_s", "%.4f", r->k->va_s)                              \
    X("v_over_a_expected_s", "%.4f", r->k->va_expect_s)              \
    X("ad_over_v2", "%.3f", r->k->adv2)                              \
    X("ad_over_v2_expected", "%.3f", r->k->adv2_expect)              \
    X("psd_min_ratio", "%.3f", r->k->psd_min_ratio)                  \
    X("f_psd_min_hz", "%.4g", r->k->f_psd_min_hz)                    \
    X("corr_record", "%.4f", r->k->corr_record)                      \
    X("peaks_record", "%.0f", r->k->peaks_record)                    \
    X("lim_min_ratio", "%.6g", 1 - r->p->tol_below)                  \
    X("lim_max_ratio", "%.6g", 1 + r->p->tol_above)                  \
    X("lim_run", "%zu", r->p->max_run_below)                         \
    X("lim_d5_75_s", "%.6g", r->p->min_d5_75_s)                      \
    X("lim_duration_s", "%.6g", r->p->min_duration_s)                \
    X("lim_corr", "%.6g", r->p->max_corr)                            \
    X("lim_end_vel_frac", "%.6g", r->p->end_vel_frac)                \
    X("lim_end_disp_frac", "%.6g", r->p->end_disp_frac)              \
    X("lim_pga_zpa_min", "%.6g", 1 - r->p->pga_tol_below)            \
    X("lim_peaks", "%zu", r->p->max_peaks)                           \
    X("lim_psd_frac", "%.6g", r->p->psd_frac)                        \
    X("ok_below", "%d", r->k->ok_below)                              \
    X("ok_above", "%d", r->k->ok_above)                              \
    X("ok_run", "%d", r->k->ok_run)                                  \
    X("ok_d5_75", "%d", r->k->ok_d5_75)                              \
    X("ok_duration", "%d", r->k->ok_duration)                        \
    X("ok_end", "%d", r->k->ok_end)                                  \
    X("ok_pga", "%d", r->k->ok_pga)                                  \
    X("ok_corr", "%d", r->k->ok_corr)                                \
    X("ok_peaks", "%d", r->k->ok_peaks)                              \
    X("ok_psd", "%d", r->k->ok_psd)                                  \
    X("pass", "%d", r->k->pass)

/* Then one block per other damping of a floor file (sl_synth_other;
 * blocks 1..nblk, nblk the most any component has; empty fields where a
 * component has fewer): the damping, this motion's lowest and highest S/T
 * at it, the set mean's lowest and highest S/T and where, its verdict. */
#define REPORT_OTHER_COLUMNS(X)                                      \
    X("damping", "%.4g", o->damping)                                 \
    X("min_ratio", "%.5f", o->min_ratio)                             \
    X("max_ratio", "%.5f", o->max_ratio)                             \
    X("set_mean_min", "%.5f", o->set_min)                            \
    X("f_set_mean_min_hz", "%.6g", o->f_set_min_hz)                  \
    X("set_mean_max", "%.5f", o->set_max)                            \
    X("f_set_mean_max_hz", "%.6g", o->f_set_max_hz)                  \
    X("ok_set_mean", "%d", o->ok_set)

static void report_header(FILE *f, size_t nblk)
{
    fputs("set,component,file,target,seed", f);
#define X(name, fmt, expr) fputs("," name, f);
    REPORT_NUM_COLUMNS(X)
#undef X
    for (size_t q = 1; q <= nblk; q++) {
#define X(name, fmt, expr) fprintf(f, ",other%zu_" name, q);
        REPORT_OTHER_COLUMNS(X)
#undef X
    }
    fputc('\n', f);
}

/* A number field: empty when the value is not finite (not applicable or
 * not known: corr_record of a synthetic motion, a correlation of a missing
 * component), never "nan". */
static void put_double(FILE *f, const char *fmt, double v)
{
    fputc(',', f);
    if (isfinite(v))
        fprintf(f, fmt, v);
}
#define PUT_FIELD(f, fmt, v)                                                             \
    _Generic((v), double: put_double((f), (fmt), (double)(v)), default: fprintf((f), "," fmt, (v)))

static void report_line(FILE *f, const report_row *r)
{
    fprintf(f, "%u,%s,", r->set, r->comp);
    sl_rpt_csv_field(f, r->file);
    fputc(',', f);
    sl_rpt_csv_field(f, r->source);
    fprintf(f, ",%s", r->seed);
#define X(name, fmt, expr) PUT_FIELD(f, fmt, expr);
    REPORT_NUM_COLUMNS(X)
#undef X
    for (size_t q = 0; q < r->nblk; q++) {
        const sl_synth_other *o = &r->k->other[q];
        if (q >= r->k->n_other) {
#define X(name, fmt, expr) fputc(',', f);
            REPORT_OTHER_COLUMNS(X)
#undef X
            continue;
        }
#define X(name, fmt, expr) PUT_FIELD(f, fmt, expr);
        REPORT_OTHER_COLUMNS(X)
#undef X
    }
    fputc('\n', f);
}


int synth_write_outputs(const synth_output *o, const sl_synth_set *sets, size_t nsets)
{
    int match = o->match != NULL;
    const char(*desc)[512] = o->desc;
    sl_error err;
    sl_error_clear(&err);
    char path[SYNTH_PATH_MAX], file[256], title[1024], seed[32];
    if (match)
        seed[0] = '\0';
    else
        snprintf(seed, sizeof seed, "%llu", o->seed);
    snprintf(path, sizeof path, "%s/report.csv", o->outdir);
    sl_atomic *rep = sl_atomic_open(path, &err);
    if (!rep) {
        cli_print_error(&err);
        return CLI_EXIT_ERROR;
    }
    FILE *rf = sl_atomic_file(rep);
    size_t nblk = 0;
    for (size_t k = 0; k < nsets; k++)
        for (int c = 0; c < SL_SYNTH_NCOMP; c++)
            nblk = sets[k].check[c].n_other > nblk ? sets[k].check[c].n_other : nblk;
    report_header(rf, nblk);
    for (size_t k = 0; k < nsets; k++) {
        for (int c = 0; c < SL_SYNTH_NCOMP; c++) {
            const sl_motion *m = sl_synth_set_motion(&sets[k], (sl_synth_comp)c);
            if (!m)
                continue;
            const char *cn = sl_synth_comp_name((sl_synth_comp)c);
            const char *ext = o->csv ? "csv" : "AT2";
            if (match)
                snprintf(file, sizeof file, "match_%s.%s", cn, ext);
            else
                snprintf(file, sizeof file, "set%02lu_%s.%s", (unsigned long)(k + 1), cn, ext);
            int w = snprintf(path, sizeof path, "%s/%s", o->outdir, file);
            if (w < 0 || (size_t)w >= sizeof path) {
                cli_msg("%s: output path too long", o->outdir);
                sl_atomic_abort(rep);
                return CLI_EXIT_ERROR;
            }
            /* A title too long for one line is cut (it is free text). */
            int tw = match ? snprintf(title, sizeof title, "%s matched to %s (%s)",
                                      o->match[c], desc[c], sl_build_id())
                           : snprintf(title, sizeof title,
                                      "set %02lu %s: %s, seed %s (%s)",
                                      (unsigned long)(k + 1), cn, desc[c], seed,
                                      sl_build_id());
            if (tw < 0)
                title[0] = '\0';
            sl_status st = o->csv ? write_csv_motion(path, m, &err)
                                  : sl_synth_write_at2(path, m, title, &err);
            if (st) {
                cli_print_error(&err);
                sl_atomic_abort(rep);
                return CLI_EXIT_ERROR;
            }
            report_row row = {(unsigned)(k + 1), cn, file, desc[c], seed,
                              &sets[k].check[c], sets[k].corr, o->p, nblk};
            report_line(rf, &row);
        }
    }
    if (sl_atomic_commit(rep, &err)) {
        cli_print_error(&err);
        return CLI_EXIT_ERROR;
    }
    return CLI_EXIT_OK;
}

void synth_describe_targets(const sl_floor *fl, double rg_pga_g,
                            const sl_synth_target tgt[SL_SYNTH_NCOMP],
                            char desc[SL_SYNTH_NCOMP][512])
{
    for (int c = 0; c < SL_SYNTH_NCOMP; c++) {
        if (fl)
            snprintf(desc[c], sizeof desc[c], "floor %s [%s] at %g damping; ZPA %.4g g",
                     fl->path, sl_synth_comp_name((sl_synth_comp)c), tgt[c].spec->damping,
                     tgt[c].zpa_ms2 / SL_G);
        else
            snprintf(desc[c], sizeof desc[c], "RG 1.60 %s at %g damping; PGA %g g",
                     c == SL_SYNTH_V ? "vertical" : "horizontal", tgt[c].spec->damping,
                     rg_pga_g);
    }
}

void synth_print_dampings(const sl_synth_set *sets, size_t nsets, const sl_synth_params *p)
{
    if (nsets == 0)
        return;
    for (int c = 0; c < SL_SYNTH_NCOMP; c++)
        for (size_t q = 0; q < sets[0].check[c].n_other; q++) {
            const sl_synth_other *o = &sets[0].check[c].other[q];
            cli_msg("synth: [%s] %g %% table against the motions' own %g %% spectra: set mean "
                    "S/T %.3f (%.3g Hz) to %.3f (%.3g Hz), %s (limits %g-%g)",
                    sl_synth_comp_name((sl_synth_comp)c), 100 * o->damping, 100 * o->damping,
                    o->set_min, o->f_set_min_hz, o->set_max, o->f_set_max_hz,
                    o->ok_set ? "ok" : "OUTSIDE", 1 - p->tol_below, 1 + p->tol_above);
        }
}
