/* verify_data.c - verification problems of the synthesis (SRP 3.7.1 limits
 * and the release bits), the statistics (hand calculations), the input
 * reading (embedded floor files) and the workbook's Lookup formula
 * (docs/verification.md). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/units.h"
#include "io/floor.h"
#include "method/design.h"
#include "method/stats.h"
#include "report/sheets.h"
#include "synth/synth.h"
#include "verify/verify_problems.h"

/* ---- synthesis ------------------------------------------------------------- */

/* Set 0 of seed SYN_SEED for RG 1.60 at 0.3 g, 5 %, default parameters (20 s
 * at 0.005 s). */
#define SYN_SEED 2027u
#define SYN_PGA_G 0.3

/* The fingerprints of that set's H1 samples (sl_verify_fingerprint),
 * recorded at release 0.1.0: GCC 12.2 (Debian), -O2 -ffp-contract=off,
 * x86-64, FFTW 3.3.10, the AVX2 and the baseline instances alike, on each
 * of the two paths glibc 2.36's libm takes by CPU: its FMA routines (the
 * first; any CPU with FMA) and its plain ones (a CPU without FMA, or
 * GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX2,-FMA), which differ in the last
 * bit of a few sin/cos/exp values. Any other fingerprint is a change. */
static const uint64_t syn_release_bits[] = {0xa81521776e5490f1ull, 0x720d9329d435974bull};

static sl_status synth_set(sl_synth_set *out, sl_error *err)
{
    memset(out, 0, sizeof *out);
    sl_synth_params p;
    sl_synth_params_default(&p);
    const size_t n = (size_t)lround(SL_SYNTH_DURATION_S / SL_SYNTH_DT_S) + 1;
    sl_synth *s = sl_synth_alloc(n, SL_SYNTH_DT_S, &p, err);
    if (!s)
        return err ? err->code : SL_ENOMEM;
    sl_spectrum *sp[SL_SYNTH_NCOMP] = {NULL, NULL, NULL};
    sl_synth_target tgt[SL_SYNTH_NCOMP];
    sl_status st = sl_synth_targets_rg160(SYN_PGA_G * SL_G, SL_SYNTH_DAMPING, &p, sp, tgt, err);
    if (st == SL_OK) {
        st = sl_synth_make_set(s, tgt, SYN_SEED, 0, out, err);
        if (st == SL_ENOCONV)
            st = SL_OK; /* a failed check is the problem's verdict, not an error */
    }
    for (int c = 0; c < SL_SYNTH_NCOMP; c++)
        sl_spectrum_free(sp[c]);
    sl_synth_free(s);
    return st;
}

typedef enum syn_what { SYN_MIN, SYN_MAX, SYN_RUN, SYN_D575, SYN_CORR, SYN_VEND } syn_what;

static sl_status synth_value(syn_what w, sl_verify_value *v, sl_error *err)
{
    sl_synth_set set;
    sl_status st = synth_set(&set, err);
    const sl_synth_check *k = &set.check[SL_SYNTH_H1];
    static const struct {
        sl_verify_kind kind;
        double limit;
    } lim[] = {
        [SYN_MIN] = {SL_VERIFY_AT_LEAST, 1 - SL_SYNTH_TOL_BELOW},
        [SYN_MAX] = {SL_VERIFY_AT_MOST, 1 + SL_SYNTH_TOL_ABOVE},
        [SYN_RUN] = {SL_VERIFY_AT_MOST, SL_SYNTH_MAX_RUN_BELOW},
        [SYN_D575] = {SL_VERIFY_AT_LEAST, SL_SYNTH_MIN_D5_75_S},
        [SYN_CORR] = {SL_VERIFY_AT_MOST, SL_SYNTH_MAX_CORR},
        [SYN_VEND] = {SL_VERIFY_AT_MOST, SL_SYNTH_END_VEL_FRAC},
    };
    v->kind = lim[w].kind;
    v->reference = lim[w].limit;
    if (st == SL_OK) {
        double c = 0;
        switch (w) {
        case SYN_MIN: v->computed = k->min_ratio; break;
        case SYN_MAX: v->computed = k->max_ratio; break;
        case SYN_RUN: v->computed = (double)k->run_below; break;
        case SYN_D575: v->computed = k->d5_75_s; break;
        case SYN_CORR:
            for (int q = 0; q < SL_SYNTH_NPAIR; q++)
                c = fmax(c, fabs(set.corr[q]));
            v->computed = c;
            break;
        case SYN_VEND: v->computed = fabs(k->v_end_ms) / k->pgv_ms; break;
        }
    }
    sl_synth_set_clear(&set);
    return st;
}

SL_VERIFY_FN(sl_verify_y01)
{
    (void)ctx;
    return synth_value(SYN_MIN, v, err);
}

SL_VERIFY_FN(sl_verify_y02)
{
    (void)ctx;
    return synth_value(SYN_MAX, v, err);
}

SL_VERIFY_FN(sl_verify_y03)
{
    (void)ctx;
    return synth_value(SYN_RUN, v, err);
}

SL_VERIFY_FN(sl_verify_y04)
{
    (void)ctx;
    return synth_value(SYN_D575, v, err);
}

SL_VERIFY_FN(sl_verify_y05)
{
    (void)ctx;
    return synth_value(SYN_CORR, v, err);
}

SL_VERIFY_FN(sl_verify_y06)
{
    (void)ctx;
    return synth_value(SYN_VEND, v, err);
}

SL_VERIFY_FN(sl_verify_y07)
{
    (void)ctx;
    sl_synth_set set;
    sl_status st = synth_set(&set, err);
    v->kind = SL_VERIFY_BITS;
    v->ref_bits = syn_release_bits[0];
    if (st == SL_OK && set.set.h1)
        v->got_bits = sl_verify_fingerprint(set.set.h1->acc_ms2, set.set.h1->n);
    for (size_t k = 1; k < sizeof syn_release_bits / sizeof syn_release_bits[0]; k++)
        if (v->got_bits == syn_release_bits[k]) /* the other libm path's record */
            v->ref_bits = syn_release_bits[k];
    sl_synth_set_clear(&set);
    return st;
}

/* ---- statistics --------------------------------------------------------------- */

SL_VERIFY_FN(sl_verify_t01)
{
    (void)ctx;
    const double x[] = {1, 2, 3, 4, 5};
    sl_stats_mean s;
    sl_status st = sl_stats_mean_compute(x, 5, 1, &s, err);
    v->computed = st == SL_OK ? s.se : NAN;
    v->reference = sqrt(0.5);
    v->rel_tol = 1e-14;
    return st;
}

static sl_status lognormal(int se, sl_verify_value *v, sl_error *err)
{
    const double e = exp(1.0), x[] = {0, 0, e, e * e * e};
    sl_stats_mean s;
    sl_status st = sl_stats_mean_compute(x, 4, 1, &s, err);
    v->computed = st != SL_OK ? NAN : se ? s.ln_se : s.ln_mean;
    v->reference = 0.5 * exp(3.0) * (se ? sqrt(3.25) : 1.0);
    v->rel_tol = 1e-14;
    return st;
}

SL_VERIFY_FN(sl_verify_t02)
{
    (void)ctx;
    return lognormal(0, v, err);
}

SL_VERIFY_FN(sl_verify_t03)
{
    (void)ctx;
    return lognormal(1, v, err);
}

SL_VERIFY_FN(sl_verify_t04)
{
    (void)ctx;
    (void)err;
    double x[11], lo, hi;
    for (int i = 0; i < 11; i++)
        x[i] = 11 - i; /* any order: the band sorts */
    sl_stats_band(x, 11, 0.90, &lo, &hi);
    v->computed = lo;
    v->reference = 1.5;
    v->abs_tol = 1e-15;
    return SL_OK;
}

SL_VERIFY_FN(sl_verify_t05)
{
    (void)ctx;
    double x[20], lo = NAN, hi = NAN;
    for (int i = 0; i < 20; i++)
        x[i] = i % 2;
    sl_status st = sl_stats_boot_mean_band(x, 20, 20000, 0.90, 7, &lo, &hi, err);
    v->computed = hi - lo;
    v->reference = (14.0 - 6.0) / 20.0;
    v->abs_tol = 0.05;
    return st;
}

SL_VERIFY_FN(sl_verify_t06)
{
    (void)ctx;
    (void)err;
    const double peak[] = {1.0, 0.1, 3.0, 0.3}, pgd[] = {1.0, 2.0};
    double d[2], se[2];
    sl_stats_design_value(peak, 2, 2, pgd, 3.0, 1.5, d, se);
    v->computed = d[0] == 2.25 ? se[0] : NAN; /* the capped row */
    v->reference = 0.75;
    v->rel_tol = 1e-14;
    return SL_OK;
}

/* ---- input reading -------------------------------------------------------------- */

/* One floor, twice: the INI form and the CSV form (docs/formats-floor.md). */
static const char floor_ini[] =
    "; verification floor (seislide verify)\n"
    "[floor]\n"
    "name = Verification floor\n"
    "units = g\n"
    "h2 = same_as_h1\n"
    "\n"
    "[h1]\n"
    "f_hz = 0.5, 1, 2, 5, 10, 33\n"
    "sa_0.05 = 0.2, 0.35, 0.5, 0.8, 0.6, 0.3\n"
    "sa_0.1 = 0.15, 0.28, 0.4, 0.6, 0.5, 0.3\n"
    "\n"
    "[v]\n"
    "f_hz = 0.5, 1, 2, 5, 10, 33\n"
    "sa_0.05 = 0.1, 0.2, 0.3, 0.5, 0.4, 0.2\n";

static const char floor_csv[] =
    "# name: Verification floor\n"
    "# units: g\n"
    "# h2: same_as_h1\n"
    "f_hz,h1_5,h1_10,v_5\n"
    "0.5,0.2,0.15,0.1\n"
    "1,0.35,0.28,0.2\n"
    "2,0.5,0.4,0.3\n"
    "5,0.8,0.6,0.5\n"
    "10,0.6,0.5,0.4\n"
    "33,0.3,0.3,0.2\n";

/* frequencies falling on line 8 */
static const char floor_bad_ini[] =
    "; verification floor with an error on line 8\n"
    "[floor]\n"
    "name = Bad floor\n"
    "units = g\n"
    "h2 = same_as_h1\n"
    "\n"
    "[h1]\n"
    "f_hz = 0.5, 2, 1, 5, 10, 33\n"
    "sa_0.05 = 0.2, 0.35, 0.5, 0.8, 0.6, 0.3\n"
    "\n"
    "[v]\n"
    "f_hz = 0.5, 1, 2, 5, 10, 33\n"
    "sa_0.05 = 0.1, 0.2, 0.3, 0.5, 0.4, 0.2\n";

/* a bad number in column 3 of line 6 */
static const char floor_bad_csv[] =
    "# name: Bad floor\n"
    "# units: g\n"
    "# h2: same_as_h1\n"
    "f_hz,h1_5,h1_10,v_5\n"
    "0.5,0.2,0.15,0.1\n"
    "1,0.35,0.28x,0.2\n"
    "33,0.3,0.3,0.2\n";

/* Write text to scratch/name, load it as a floor, remove the file.
 * *fl the floor (NULL when refused, err filled). Returns SL_OK or SL_EIO
 * when the scratch file cannot be written. */
static sl_status load_text(const sl_verify_ctx *ctx, const char *name, const char *text,
                           sl_floor **fl, sl_error *err)
{
    char path[1200];
    *fl = NULL;
    snprintf(path, sizeof path, "%s/%s", ctx && ctx->scratch_dir ? ctx->scratch_dir : ".", name);
    FILE *f = fopen(path, "w");
    if (!f || fputs(text, f) == EOF || fclose(f) != 0) {
        if (f)
            fclose(f);
        return sl_error_set(err, SL_EIO, path, 0, "cannot write the scratch file");
    }
    *fl = sl_floor_load(path, err);
    unlink(path);
    return SL_OK;
}

/* Differences between two floors' descriptions (fields and values). */
static double floor_diff(const sl_floor *a, const sl_floor *b)
{
    double d = 0;
    d += strcmp(a->name, b->name) != 0;
    d += strcmp(a->description, b->description) != 0;
    d += !(a->elevation_m == b->elevation_m || (isnan(a->elevation_m) && isnan(b->elevation_m)));
    d += a->units != b->units;
    d += a->h2_same_as_h1 != b->h2_same_as_h1;
    d += a->has_seed != b->has_seed;
    for (int k = 0; k < SL_FLOOR_NCOMP; k++) {
        const sl_floor_component *x = &a->comp[k], *y = &b->comp[k];
        d += x->nspec != y->nspec;
        d += x->zpa_ms2 != y->zpa_ms2;
        d += x->zpa_given != y->zpa_given;
        for (size_t s = 0; s < x->nspec && s < y->nspec; s++) {
            d += x->spec[s].n != y->spec[s].n;
            d += x->spec[s].damping != y->spec[s].damping;
            for (size_t j = 0; j < x->spec[s].n && j < y->spec[s].n; j++)
                d += x->spec[s].f_hz[j] != y->spec[s].f_hz[j] ||
                     x->spec[s].sa_ms2[j] != y->spec[s].sa_ms2[j];
        }
    }
    return d;
}

SL_VERIFY_FN(sl_verify_i01)
{
    sl_floor *a = NULL, *b = NULL;
    sl_status st = load_text(ctx, "verify-floor.ini", floor_ini, &a, err);
    if (st == SL_OK && a)
        st = load_text(ctx, "verify-floor.csv", floor_csv, &b, err);
    if (st == SL_OK && (!a || !b))
        st = err ? err->code : SL_EINVAL;
    if (st == SL_OK && (a->format != SL_FLOOR_INI || b->format != SL_FLOOR_CSV))
        st = sl_error_set(err, SL_EINVAL, NULL, 0, "the files were not read as INI and CSV");
    v->computed = st == SL_OK ? floor_diff(a, b) : NAN;
    v->reference = 0;
    sl_floor_free(a);
    sl_floor_free(b);
    return st;
}

SL_VERIFY_FN(sl_verify_i02)
{
    sl_floor *a = NULL;
    sl_status st = load_text(ctx, "verify-floor.ini", floor_ini, &a, err);
    if (st == SL_OK && !a)
        st = err ? err->code : SL_EINVAL;
    v->reference = 0.5 * SL_G;
    v->rel_tol = 1e-15;
    if (st == SL_OK) {
        const sl_spectrum *s = sl_floor_spectrum(a, SL_FLOOR_H1, 0.05);
        v->computed = s && s->n == 6 && s->f_hz[2] == 2.0 ? s->sa_ms2[2] : NAN;
    }
    sl_floor_free(a);
    return st;
}

/* A refused file: the line (or column) the error names; accepted: fails. */
static sl_status refused(const sl_verify_ctx *ctx, const char *name, const char *text,
                         int want_col, long ref, long line, sl_verify_value *v, sl_error *err)
{
    sl_floor *a = NULL;
    sl_error e;
    sl_error_clear(&e);
    sl_status st = load_text(ctx, name, text, &a, &e);
    v->reference = (double)ref;
    if (st != SL_OK) {
        *err = e;
        return st;
    }
    if (a) {
        sl_floor_free(a);
        return sl_error_set(err, SL_EINVAL, NULL, 0, "the bad file %s was accepted", name);
    }
    if (e.code != SL_EPARSE && e.code != SL_EINVAL)
        return sl_error_set(err, e.code, NULL, 0, "refused for another reason: %s", e.msg);
    if (e.line != line)
        return sl_error_set(err, e.code, NULL, 0, "refused at line %ld, not %ld: %s", e.line,
                            line, e.msg);
    v->computed = (double)(want_col ? e.col : e.line);
    return SL_OK;
}

SL_VERIFY_FN(sl_verify_i03)
{
    return refused(ctx, "verify-bad.ini", floor_bad_ini, 0, 8, 8, v, err);
}

SL_VERIFY_FN(sl_verify_i04)
{
    return refused(ctx, "verify-bad.csv", floor_bad_csv, 1, 3, 6, v, err);
}

/* ---- the workbook's Lookup ---------------------------------------------------- */

/* Three grid rows mu 0.1, 0.2, 0.3 with clearances 0.05, 0.03, 0.05 m; the
 * Lookup at mu 0.25: rows 0.2 and 0.3, C = 0.03 + 0.05/0.1 x 0.02 = 0.04. */
static const sl_design_row lk_rows[3] = {
    {.mu = 0.1, .clearance_m = 0.05}, {.mu = 0.2, .clearance_m = 0.03}, {.mu = 0.3, .clearance_m = 0.05}};
#define LK_MU 0.25
#define LK_REF 0.04

SL_VERIFY_FN(sl_verify_w01)
{
    (void)ctx;
    sl_design d;
    memset(&d, 0, sizeof d);
    d.n = 3;
    d.rows = (sl_design_row *)lk_rows;
    size_t k1, k0 = sl_rpt_lookup_bracket(&d, 1, LK_MU, &k1);
    /* the cells as a Lookup sheet places them (rows 0-based) */
    const sl_rpt_lookup_cells c = {.mu = 3, .result = 5, .check = 4, .note = 6, .steps = 8};
    const int mu0 = c.steps + 2, mu1 = c.steps + 3, c0 = c.steps + 4, c1 = c.steps + 5;
    char f[SL_RPT_LOOKUP_RESULT_LEN];
    sl_rpt_lookup_result_text(f, sizeof f, &c);
    const sl_verify_cell cells[] = {
        {c.mu + 1, LK_MU, NULL},
        {c.check + 1, 0, "ok"},
        {mu0 + 1, lk_rows[k0].mu, NULL},
        {mu1 + 1, lk_rows[k1].mu, NULL},
        {c0 + 1, lk_rows[k0].clearance_m, NULL},
        {c1 + 1, lk_rows[k1].clearance_m, NULL},
    };
    double x = NAN;
    int is_text = 0;
    sl_status st = sl_verify_formula_eval(f, cells, sizeof cells / sizeof cells[0], &x, &is_text, err);
    v->computed = st == SL_OK && !is_text ? x : NAN;
    v->reference = sl_design_clearance_at(&d, LK_MU);
    v->rel_tol = 1e-12;
    return st;
}

SL_VERIFY_FN(sl_verify_w02)
{
    (void)ctx;
    (void)err;
    sl_design d;
    memset(&d, 0, sizeof d);
    d.n = 3;
    d.rows = (sl_design_row *)lk_rows;
    v->computed = sl_design_clearance_at(&d, LK_MU);
    v->reference = LK_REF;
    v->rel_tol = 1e-12;
    return SL_OK;
}
