/* entry.c - one floor's result as bytes; see entry.h. Every field is one
 * line of a table: adding a field of sl_analysis the writers read is one
 * line here (and changes the schema hash, so older entries are recomputed). */
#include "plant/entry.h"
#include "core/version.h"
#include "plant/identity.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef enum ftype { F_F64, F_SIZE, F_U64, F_INT, F_UINT, F_ENUM, F_STR } ftype;
typedef struct field {
    const char *name;
    ftype type;
    size_t off, size;
} field;
#define FD(T, f, ty) {#f, ty, offsetof(T, f), sizeof(((T *)0)->f)}
#define NF(t) (sizeof t / sizeof t[0])

/* sl_analysis: the scalars (arrays below, after their counts). The wall
 * times are kept so that a reused floor reports what it cost. */
static const field f_analysis[] = {
    FD(sl_analysis, stop, F_ENUM),          FD(sl_analysis, n_batches, F_SIZE),
    FD(sl_analysis, n_unconverged, F_SIZE), FD(sl_analysis, worst_rel_se, F_F64),
    FD(sl_analysis, floor_seed, F_U64),     FD(sl_analysis, zpa_h_ms2, F_F64),
    FD(sl_analysis, av_ms2, F_F64),         FD(sl_analysis, scatter, F_F64),
    FD(sl_analysis, n_nltha_mu, F_SIZE),    FD(sl_analysis, n_failed_motions, F_SIZE),
    FD(sl_analysis, n_mu_skipped, F_SIZE),  FD(sl_analysis, sa10_fallback, F_INT),
    FD(sl_analysis, time_synth_s, F_F64),   FD(sl_analysis, time_nltha_s, F_F64),
    FD(sl_analysis, time_asce_s, F_F64),    FD(sl_analysis, time_stats_s, F_F64),
    FD(sl_analysis, note, F_STR),           FD(sl_analysis, damping_lim_lo, F_F64),
    FD(sl_analysis, damping_lim_hi, F_F64), FD(sl_analysis, dampings_ok, F_INT),
    FD(sl_analysis, time_checks_s, F_F64),  FD(sl_analysis, n_extra_attempts, F_SIZE)};

static const field f_design[] = {
    FD(sl_design, zpa_h_ms2, F_F64),  FD(sl_design, cap_m, F_F64),
    FD(sl_design, policy, F_ENUM),    FD(sl_design, n_sets, F_SIZE),
    FD(sl_design, fs_nltha, F_F64),   FD(sl_design, fs_asce, F_F64),
    FD(sl_design, cap_factor, F_F64), FD(sl_design, has_crossover, F_INT),
    FD(sl_design, crossover_x, F_F64), FD(sl_design, crossover_mu, F_F64)};

static const field f_row[] = {
    FD(sl_design_row, mu, F_F64),            FD(sl_design_row, x, F_F64),
    FD(sl_design_row, nltha_mean_m, F_F64),  FD(sl_design_row, nltha_sd_m, F_F64),
    FD(sl_design_row, nltha_design_m, F_F64), FD(sl_design_row, asce_best_m, F_F64),
    FD(sl_design_row, asce_design_m, F_F64), FD(sl_design_row, cap_m, F_F64),
    FD(sl_design_row, clearance_m, F_F64),   FD(sl_design_row, flags, F_UINT)};

static const field f_range[] = {
    FD(sl_design_range, x_from, F_F64), FD(sl_design_range, x_to, F_F64),
    FD(sl_design_range, mu_lo, F_F64),  FD(sl_design_range, mu_hi, F_F64),
    FD(sl_design_range, x_lo, F_F64),   FD(sl_design_range, x_hi, F_F64),
    FD(sl_design_range, open_lo, F_INT), FD(sl_design_range, open_hi, F_INT)};

static const field f_conv[] = {
    FD(sl_stats_conv, n_sets, F_SIZE),       FD(sl_stats_conv, mean_m, F_F64),
    FD(sl_stats_conv, se_m, F_F64),          FD(sl_stats_conv, lognormal_mean_m, F_F64),
    FD(sl_stats_conv, p_slide, F_F64),       FD(sl_stats_conv, design_m, F_F64),
    FD(sl_stats_conv, design_se_m, F_F64),   FD(sl_stats_conv, design_lo_m, F_F64),
    FD(sl_stats_conv, design_hi_m, F_F64),   FD(sl_stats_conv, target_se_m, F_F64),
    FD(sl_stats_conv, converged, F_INT)};

static const field f_damping[] = {
    FD(sl_analysis_damping, comp, F_ENUM),    FD(sl_analysis_damping, damping, F_F64),
    FD(sl_analysis_damping, set_min, F_F64),  FD(sl_analysis_damping, set_max, F_F64),
    FD(sl_analysis_damping, f_min_hz, F_F64), FD(sl_analysis_damping, f_max_hz, F_F64),
    FD(sl_analysis_damping, ok, F_INT)};

/* The checks of a motion the Motion quality sheet and CSV show. */
static const field f_check[] = {
    FD(sl_synth_check, pga_ms2, F_F64),   FD(sl_synth_check, d5_75_s, F_F64),
    FD(sl_synth_check, min_ratio, F_F64), FD(sl_synth_check, max_ratio, F_F64),
    FD(sl_synth_check, run_below, F_SIZE), FD(sl_synth_check, max_corr, F_F64),
    FD(sl_synth_check, v_end_ms, F_F64), FD(sl_synth_check, d_end_m, F_F64),
    FD(sl_synth_check, pass, F_INT),      FD(sl_synth_check, ok_below, F_INT),
    FD(sl_synth_check, ok_above, F_INT),  FD(sl_synth_check, ok_run, F_INT),
    FD(sl_synth_check, ok_d5_75, F_INT),  FD(sl_synth_check, ok_duration, F_INT),
    FD(sl_synth_check, ok_end, F_INT),    FD(sl_synth_check, ok_pga, F_INT),
    FD(sl_synth_check, ok_corr, F_INT),
    /* the rest of the check, so that what run_report_checks says of failed motions
     * (where, how far) and any later column are the same for a reused floor */
    FD(sl_synth_check, damping, F_F64),   FD(sl_synth_check, f_lo_hz, F_F64),
    FD(sl_synth_check, f_hi_hz, F_F64),   FD(sl_synth_check, npoints, F_SIZE),
    FD(sl_synth_check, f_min_ratio_hz, F_F64), FD(sl_synth_check, f_max_ratio_hz, F_F64),
    FD(sl_synth_check, n_below, F_SIZE),  FD(sl_synth_check, duration_s, F_F64),
    FD(sl_synth_check, zpa_ms2, F_F64),   FD(sl_synth_check, pgv_ms, F_F64),
    FD(sl_synth_check, pgd_m, F_F64),     FD(sl_synth_check, iterations, F_UINT),
    FD(sl_synth_check, attempt, F_UINT),  FD(sl_synth_check, pga_zpa, F_F64),
    FD(sl_synth_check, peaks, F_SIZE),    FD(sl_synth_check, va_s, F_F64),
    FD(sl_synth_check, adv2, F_F64),      FD(sl_synth_check, va_expect_s, F_F64),
    FD(sl_synth_check, adv2_expect, F_F64), FD(sl_synth_check, psd_min_ratio, F_F64),
    FD(sl_synth_check, f_psd_min_hz, F_F64), FD(sl_synth_check, corr_record, F_F64),
    FD(sl_synth_check, peaks_record, F_F64), FD(sl_synth_check, ok_peaks, F_INT),
    FD(sl_synth_check, ok_psd, F_INT)};

static const field f_set[] = {FD(sl_synth_set, pass, F_INT)};

static void put_fields(sl_pbuf *w, const void *obj, const field *t, size_t n)
{
    const unsigned char *o = obj;
    for (size_t i = 0; i < n; i++) {
        const void *p = o + t[i].off;
        switch (t[i].type) {
        case F_F64: sl_pbuf_f64(w, *(const double *)p); break;
        case F_SIZE: sl_pbuf_u64(w, *(const size_t *)p); break;
        case F_U64: sl_pbuf_u64(w, *(const uint64_t *)p); break;
        case F_UINT: sl_pbuf_u64(w, *(const unsigned *)p); break;
        case F_INT: sl_pbuf_u64(w, (uint64_t)(int64_t)*(const int *)p); break;
        case F_ENUM: {
            int v = 0;
            memcpy(&v, p, t[i].size < sizeof v ? t[i].size : sizeof v);
            sl_pbuf_u64(w, (uint64_t)(int64_t)v);
            break;
        }
        case F_STR: sl_pbuf_str(w, (const char *)p); break;
        }
    }
}

static void get_fields(sl_preader *r, void *obj, const field *t, size_t n)
{
    unsigned char *o = obj;
    for (size_t i = 0; i < n; i++) {
        void *p = o + t[i].off;
        switch (t[i].type) {
        case F_F64: *(double *)p = sl_preader_f64(r); break;
        case F_SIZE: *(size_t *)p = (size_t)sl_preader_count(r, SIZE_MAX, ""); break;
        case F_U64: *(uint64_t *)p = sl_preader_u64(r); break;
        case F_UINT: *(unsigned *)p = (unsigned)sl_preader_count(r, UINT32_MAX, "bad value"); break;
        case F_INT:
        case F_ENUM: {
            int64_t v = (int64_t)sl_preader_u64(r);
            if (v < -2147483647 || v > 2147483647) {
                r->bad = 1;
                r->why = "bad value";
                v = 0;
            }
            int iv = (int)v;
            memcpy(p, &iv, t[i].size < sizeof iv ? t[i].size : sizeof iv);
            break;
        }
        case F_STR: sl_preader_str(r, (char *)p, t[i].size - 1); break;
        }
    }
}

/* The schema: every table's field names and types, hashed. */
static uint64_t schema_hash(void)
{
    static const struct {
        const field *t;
        size_t n;
    } all[] = {{f_analysis, NF(f_analysis)}, {f_design, NF(f_design)}, {f_row, NF(f_row)},
               {f_range, NF(f_range)},       {f_conv, NF(f_conv)},     {f_damping, NF(f_damping)},
               {f_check, NF(f_check)},       {f_set, NF(f_set)}};
    /* the per-mu and per-set arrays, in the order they are written */
    static const char *const arrays[] = {"design_lo_m", "design_hi_m", "design_se_m",
                                         "err_est_m",   "vr_f_hz",     "vr_corr_sa",
                                         "vr_corr_pgv", "vr_factor",   "pgd_m"};
    uint64_t h = SL_FNV64_OFFSET;
    for (size_t i = 0; i < NF(arrays); i++)
        h = sl_fnv64(h, arrays[i], strlen(arrays[i]) + 1);
    for (size_t a = 0; a < NF(all); a++)
        for (size_t i = 0; i < all[a].n; i++) {
            h = sl_fnv64(h, all[a].t[i].name, strlen(all[a].t[i].name) + 1);
            h = sl_fnv64(h, &all[a].t[i].type, sizeof all[a].t[i].type);
        }
    return h;
}

void sl_entry_key_hash(const char *text, size_t len, char out[17])
{
    snprintf(out, 17, "%016llx", (unsigned long long)sl_fnv64(SL_FNV64_OFFSET, text, len));
}

/* The key text is the same byte encoding as the entries (pbuf.h): the
 * program, the library's source fingerprint, the schema, then the floor's
 * identity (identity.h). */
sl_status sl_entry_key_make(const sl_floor *fl, const sl_analysis_opts *o, const char *version,
                            sl_entry_key *k, sl_error *err)
{
    sl_pbuf w = {0};
    sl_pbuf_str(&w, "seislide floor result");
    sl_pbuf_str(&w, version);
    sl_pbuf_str(&w, sl_source_id()); /* the code that computed it (core/version.h) */
    sl_pbuf_u64(&w, schema_hash());
    sl_identity_write(&w, fl, o); /* the settings and the floor (identity.h) */
    if (w.oom) {
        sl_pbuf_free(&w);
        return sl_error_set(err, SL_ENOMEM, fl->path, 0, "out of memory");
    }
    k->text = (char *)w.b;
    k->len = w.n;
    sl_entry_key_hash(k->text, k->len, k->hash);
    return SL_OK;
}

void sl_entry_key_free(sl_entry_key *k)
{
    free(k->text);
    memset(k, 0, sizeof *k);
}

static void put_array(sl_pbuf *w, const double *v, size_t n)
{
    sl_pbuf_u64(w, v ? 1 : 0);
    for (size_t i = 0; v && i < n; i++)
        sl_pbuf_f64(w, v[i]);
}

void sl_entry_encode(sl_pbuf *w, const sl_analysis *a)
{
    const sl_design *d = a->design;
    put_fields(w, a, f_analysis, NF(f_analysis));
    put_fields(w, d, f_design, NF(f_design));
    sl_pbuf_u64(w, d->n);
    for (size_t k = 0; k < d->n; k++)
        put_fields(w, &d->rows[k], f_row, NF(f_row));
    sl_pbuf_u64(w, d->n_ranges);
    for (size_t k = 0; k < d->n_ranges; k++)
        put_fields(w, &d->ranges[k], f_range, NF(f_range));
    sl_pbuf_u64(w, a->conv ? 1 : 0);
    for (size_t k = 0; a->conv && k < d->n; k++)
        put_fields(w, &a->conv[k], f_conv, NF(f_conv));
    put_array(w, a->design_lo_m, d->n);
    put_array(w, a->design_hi_m, d->n);
    put_array(w, a->design_se_m, d->n);
    put_array(w, a->err_est_m, d->n);
    put_array(w, a->vr_f_hz, d->n);
    put_array(w, a->vr_corr_sa, d->n);
    put_array(w, a->vr_corr_pgv, d->n);
    put_array(w, a->vr_factor, d->n);
    sl_pbuf_u64(w, a->n_sets);
    put_array(w, a->pgd_m, a->n_sets);
    sl_pbuf_u64(w, a->n_dampings);
    for (size_t k = 0; k < a->n_dampings; k++)
        put_fields(w, &a->dampings[k], f_damping, NF(f_damping));
    sl_pbuf_u64(w, a->sets ? 1 : 0);
    for (size_t s = 0; a->sets && s < a->n_sets; s++) {
        put_fields(w, &a->sets[s], f_set, NF(f_set));
        for (int c = 0; c < SL_SYNTH_NCOMP; c++)
            put_fields(w, &a->sets[s].check[c], f_check, NF(f_check));
    }
}

static double *get_array(sl_preader *r, size_t n)
{
    uint64_t present = sl_preader_count(r, 1, "bad array flag");
    if (r->bad || !present)
        return NULL;
    if (n > (r->n - r->pos) / 8) { /* before allocating: the bytes must be there */
        r->bad = 1;
        r->why = "truncated";
        return NULL;
    }
    double *v = malloc((n ? n : 1) * sizeof *v);
    if (!v) {
        r->bad = 1;
        r->why = "out of memory";
        return NULL;
    }
    for (size_t i = 0; i < n; i++)
        v[i] = sl_preader_f64(r);
    return v;
}

sl_analysis *sl_entry_decode(sl_preader *r, size_t n_mu)
{
    sl_analysis *a = calloc(1, sizeof *a);
    sl_design *d = calloc(1, sizeof *d);
    if (!a || !d) {
        free(a);
        free(d);
        r->bad = 1;
        r->why = "out of memory";
        return NULL;
    }
    a->design = d;
    get_fields(r, a, f_analysis, NF(f_analysis));
    get_fields(r, d, f_design, NF(f_design));
    size_t n = (size_t)sl_preader_count(r, SL_ENTRY_MAX_MU, "too many friction values");
    if (!r->bad && n != n_mu) {
        r->bad = 1;
        r->why = "friction grid differs";
    }
    /* every allocation is bounded by the bytes actually left */
    size_t left = r->n - r->pos;
    if (!r->bad && n > left / (8 * NF(f_row))) {
        r->bad = 1;
        r->why = "truncated";
    }
    d->n = r->bad ? 0 : n;
    if (!r->bad && !(d->rows = calloc(n ? n : 1, sizeof *d->rows)))
        r->bad = 1;
    for (size_t k = 0; !r->bad && k < n; k++)
        get_fields(r, &d->rows[k], f_row, NF(f_row));
    size_t nr = (size_t)sl_preader_count(r, n, "too many ranges");
    if (!r->bad && nr && !(d->ranges = calloc(nr, sizeof *d->ranges)))
        r->bad = 1;
    d->n_ranges = r->bad ? 0 : nr;
    for (size_t k = 0; !r->bad && k < nr; k++)
        get_fields(r, &d->ranges[k], f_range, NF(f_range));
    if (sl_preader_count(r, 1, "bad array flag")) {
        if (!r->bad && !(a->conv = calloc(n ? n : 1, sizeof *a->conv)))
            r->bad = 1;
        for (size_t k = 0; !r->bad && k < n; k++)
            get_fields(r, &a->conv[k], f_conv, NF(f_conv));
    }
    a->design_lo_m = get_array(r, n);
    a->design_hi_m = get_array(r, n);
    a->design_se_m = get_array(r, n);
    a->err_est_m = get_array(r, n);
    a->vr_f_hz = get_array(r, n);
    a->vr_corr_sa = get_array(r, n);
    a->vr_corr_pgv = get_array(r, n);
    a->vr_factor = get_array(r, n);
    size_t ns = (size_t)sl_preader_count(r, SL_ENTRY_MAX_SETS, "too many sets");
    a->pgd_m = get_array(r, ns);
    size_t nd = (size_t)sl_preader_count(r, SL_ANALYSIS_MAX_DAMPINGS, "too many dampings");
    a->n_dampings = r->bad ? 0 : nd;
    for (size_t k = 0; !r->bad && k < nd; k++)
        get_fields(r, &a->dampings[k], f_damping, NF(f_damping));
    if (sl_preader_count(r, 1, "bad sets flag")) {
        if (!r->bad && ns > (r->n - r->pos) / 8) {
            r->bad = 1;
            r->why = "truncated";
        }
        if (!r->bad && !(a->sets = calloc(ns ? ns : 1, sizeof *a->sets)))
            r->bad = 1;
        for (size_t s = 0; !r->bad && s < ns; s++) {
            get_fields(r, &a->sets[s], f_set, NF(f_set));
            for (int c = 0; c < SL_SYNTH_NCOMP; c++)
                get_fields(r, &a->sets[s].check[c], f_check, NF(f_check));
        }
    }
    a->n_sets = a->sets ? ns : 0;
    /* counts that must agree with each other */
    if (!r->bad && (d->n_sets != ns || !a->sets || !a->pgd_m || ns == 0 ||
                    a->note[sizeof a->note - 1] != '\0')) {
        r->bad = 1;
        r->why = "inconsistent counts";
    }
    if (!r->bad && r->pos != r->n) {
        r->bad = 1;
        r->why = "trailing bytes";
    }
    if (r->bad) {
        if (!r->why)
            r->why = "out of memory";
        a->n_sets = a->sets ? ns : 0;
        sl_analysis_free(a);
        return NULL;
    }
    return a;
}
