/* rock_cache.c - rocking results kept in the cache folder (rock_cache.h). */
#include "rock/rock_cache.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "analysis.h"
#include "core/version.h"
#include "io/atomic.h"
#include "plant/entry.h"
#include "plant/identity.h"
#include "plant/pbuf.h"

#define MAGIC "SLROCK01"
#define MAX_BYTES (64L << 20)
#define MAX_ITEMS 1000000

void sl_rockc_key_free(sl_rockc_key *k)
{
    if (k)
        free(k->text);
}

sl_status sl_rockc_key_make(const sl_floor *fl, uint64_t run_seed, size_t n_sets,
                            const sl_rockf_opts *o, const sl_rockf_item *items, size_t n,
                            sl_rockc_key *k, sl_error *err)
{
    sl_pbuf w = {0};
    sl_analysis_opts ao;
    sl_analysis_opts_default(&ao);
    ao.seed = run_seed;
    sl_pbuf_str(&w, "seislide rocking result");
    sl_pbuf_str(&w, sl_build_id());
    sl_identity_write(&w, fl, &ao);
    sl_pbuf_u64(&w, n_sets);
    sl_pbuf_f64(&w, o->sigma_ln);
    for (int l = 0; l < SL_ROCKF_NLEVELS; l++) {
        sl_pbuf_f64(&w, o->level[l]);
        sl_pbuf_f64(&w, o->p_target[l]);
    }
    sl_pbuf_f64(&w, o->zmin);
    sl_pbuf_f64(&w, o->zmax);
    sl_pbuf_f64(&w, o->dz);
    sl_pbuf_f64(&w, o->orient_step_deg);
    sl_pbuf_u64(&w, o->min_sets);
    sl_pbuf_f64(&w, o->engine.rtol);
    sl_pbuf_u64(&w, o->engine.substeps);
    sl_pbuf_f64(&w, o->engine.rest_fraction);
    sl_pbuf_f64(&w, o->engine.theta0_rad);
    sl_pbuf_f64(&w, o->engine.omega0_rad_s);
    sl_pbuf_u64(&w, n);
    for (size_t i = 0; i < n; i++) {
        sl_pbuf_f64(&w, items[i].block.b_m);
        sl_pbuf_f64(&w, items[i].block.h_m);
        /* any negative or NaN restitution is Housner's: one key for them */
        double r = items[i].block.restitution >= 0 ? items[i].block.restitution : -1.0;
        sl_pbuf_f64(&w, r);
        sl_pbuf_f64(&w, isnan(items[i].orientation_deg) ? -1e300 : items[i].orientation_deg);
    }
    if (w.oom) {
        sl_pbuf_free(&w);
        return sl_error_set(err, SL_ENOMEM, NULL, 0, "rocking cache: out of memory");
    }
    k->text = w.b;
    k->len = w.n;
    sl_entry_key_hash((const char *)w.b, w.n, k->hash);
    return SL_OK;
}

/* Every field of a result, in one order for writing and reading. */
#define LEVEL_FIELDS(X, v)                                                                 \
    X(v.p_uplift) X(v.p_uplift_se) X(v.p_tip) X(v.p_tip_se) X(v.p_overturn)               \
    X(v.p_overturn_se) X(v.theta_ratio_mean) X(v.theta_ratio_q) X(v.excursion_mean_m)     \
    X(v.excursion_q_m)

static void put_result(sl_pbuf *w, const sl_rockf_result *r)
{
#define PUT(f) sl_pbuf_f64(w, f);
    sl_pbuf_u64(w, r->n_sets);
    sl_pbuf_u64(w, r->n_orient);
    sl_pbuf_u64(w, r->n_runs);
    for (int l = 0; l < SL_ROCKF_NLEVELS; l++) {
        LEVEL_FIELDS(PUT, r->level[l])
    }
    sl_pbuf_f64(w, r->excursion_m);
#undef PUT
}

static void get_result(sl_preader *rd, sl_rockf_result *r)
{
#define GET(f) f = sl_preader_f64(rd);
    memset(r, 0, sizeof *r);
    r->n_sets = (size_t)sl_preader_count(rd, 1000000, "sets");
    r->n_orient = (size_t)sl_preader_count(rd, 100000, "orientations");
    r->n_runs = (size_t)sl_preader_u64(rd);
    for (int l = 0; l < SL_ROCKF_NLEVELS; l++) {
        LEVEL_FIELDS(GET, r->level[l])
    }
    r->excursion_m = sl_preader_f64(rd);
#undef GET
}

static void entry_path(const char *dir, const sl_rockc_key *k, char *buf, size_t n)
{
    snprintf(buf, n, "%s/%s%s", dir, k->hash, SL_ROCKC_SUFFIX);
}

int sl_rockc_read(const char *dir, const sl_rockc_key *k, sl_rockf_result *out, size_t n)
{
    char path[4400];
    entry_path(dir, k, path, sizeof path);
    FILE *f = fopen(path, "rb");
    if (!f)
        return 0;
    struct stat sb;
    unsigned char *b = NULL;
    int ok = 0;
    if (fstat(fileno(f), &sb) == 0 && sb.st_size >= 12 && sb.st_size <= MAX_BYTES &&
        (b = malloc((size_t)sb.st_size)) &&
        fread(b, 1, (size_t)sb.st_size, f) == (size_t)sb.st_size) {
        size_t len = (size_t)sb.st_size;
        unsigned long stored, crc = sl_pbuf_crc32_check(b, len, &stored);
        sl_preader rd = {b, len - 4, 0, 0, NULL};
        const unsigned char *m = sl_preader_bytes(&rd, 8);
        size_t klen = (size_t)sl_preader_count(&rd, (uint64_t)len, "key");
        const unsigned char *key = sl_preader_bytes(&rd, klen);
        sl_preader_count(&rd, (uint64_t)len, "payload");
        size_t items = (size_t)sl_preader_count(&rd, MAX_ITEMS, "items");
        if (crc == stored && m && !memcmp(m, MAGIC, 8) && key && klen == k->len &&
            !memcmp(key, k->text, klen) && items == n && !rd.bad) {
            for (size_t i = 0; i < n; i++)
                get_result(&rd, &out[i]);
            ok = !rd.bad && rd.pos == rd.n;
        }
    }
    free(b);
    fclose(f);
    return ok;
}

sl_status sl_rockc_write(const char *dir, const sl_rockc_key *k, const sl_rockf_result *out,
                         size_t n, sl_error *err)
{
    sl_pbuf p = {0}, w = {0};
    sl_pbuf_u64(&p, n);
    for (size_t i = 0; i < n; i++)
        put_result(&p, &out[i]);
    sl_pbuf_bytes(&w, MAGIC, 8);
    sl_pbuf_u64(&w, k->len);
    sl_pbuf_bytes(&w, k->text, k->len);
    sl_pbuf_u64(&w, p.n);
    sl_pbuf_bytes(&w, p.b, p.n);
    sl_pbuf_crc32(&w);
    sl_status st = SL_OK;
    if (p.oom || w.oom)
        st = sl_error_set(err, SL_ENOMEM, NULL, 0, "rocking cache: out of memory");
    char path[4400];
    entry_path(dir, k, path, sizeof path);
    sl_atomic *a = st ? NULL : sl_atomic_open(path, err);
    if (!st && !a)
        st = err ? err->code : SL_EIO;
    if (a) {
        if (fwrite(w.b, 1, w.n, sl_atomic_file(a)) != w.n) {
            sl_atomic_abort(a);
            st = sl_error_set(err, SL_EIO, path, 0, "cannot write");
        } else {
            st = sl_atomic_commit(a, err);
        }
    }
    sl_pbuf_free(&p);
    sl_pbuf_free(&w);
    return st;
}
