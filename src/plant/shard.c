/* shard.c - a shard's manifest; see shard.h. */
#include "plant/shard.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "io/atomic.h"

#define MAGIC "SLSHARD2"
#define STR_MAX 65536

static void put_body(sl_pbuf *w, const sl_plant *p, const sl_shard_settings *s)
{
    sl_pbuf_str(w, s->version);
    sl_pbuf_u64(w, s->seed);
    sl_pbuf_u64(w, s->substeps);
    sl_pbuf_f64(w, s->accuracy);
    const char *pr[6] = {s->project.project, s->project.document, s->project.revision,
                         s->project.prepared, s->project.checked, s->project.date};
    for (int i = 0; i < 6; i++) {
        sl_pbuf_u64(w, pr[i] != NULL);
        sl_pbuf_str(w, pr[i]);
    }
    sl_pbuf_u64(w, s->n_mu);
    for (size_t k = 0; k < s->n_mu; k++)
        sl_pbuf_f64(w, s->mu[k]);
    sl_pbuf_u64(w, (uint64_t)p->is_plant);
    sl_pbuf_u64(w, p->n_buildings);
    for (size_t b = 0; b < p->n_buildings; b++)
        sl_pbuf_str(w, p->building[b]);
    sl_pbuf_u64(w, p->n);
    for (size_t i = 0; i < p->n; i++) {
        const sl_plant_floor *f = &p->floors[i];
        sl_pbuf_u64(w, f->building);
        sl_pbuf_str(w, f->id);
        sl_pbuf_str(w, f->name);
        sl_pbuf_str(w, f->path);
        sl_pbuf_str(w, f->description);
        sl_pbuf_str(w, f->units);
        sl_pbuf_f64(w, f->elevation_m);
        sl_pbuf_u64(w, f->crc32);
        sl_pbuf_u64(w, (uint64_t)f->size_bytes);
        sl_pbuf_str(w, f->key.hash);
        sl_pbuf_u64(w, f->shard);
        sl_pbuf_str(w, f->warnings ? f->warnings : "");
        sl_pbuf_u64(w, (uint64_t)f->accepted);
    }
}

sl_status sl_shard_write_manifest(const char *dir, unsigned k, unsigned n, const sl_plant *p,
                                  const sl_shard_settings *s, sl_error *err)
{
    char path[4400];
    snprintf(path, sizeof path, "%s/%s", dir, SL_SHARD_MANIFEST);
    sl_pbuf body = {0}, w = {0};
    put_body(&body, p, s);
    sl_pbuf_bytes(&w, MAGIC, 8);
    sl_pbuf_u64(&w, k);
    sl_pbuf_u64(&w, n);
    sl_pbuf_u64(&w, body.n);
    sl_pbuf_bytes(&w, body.b, body.n);
    sl_pbuf_crc32(&w);
    sl_status st = SL_OK;
    if (w.oom || body.oom) {
        st = sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
    } else {
        sl_atomic *a = sl_atomic_open(path, err);
        if (!a)
            st = err ? err->code : SL_EIO;
        else if (fwrite(w.b, 1, w.n, sl_atomic_file(a)) != w.n) {
            sl_atomic_abort(a);
            st = sl_error_set(err, SL_EIO, path, 0, "cannot write: %s", strerror(errno));
        } else {
            st = sl_atomic_commit(a, err);
        }
    }
    sl_pbuf_free(&body);
    sl_pbuf_free(&w);
    return st;
}

static sl_status bad(sl_error *err, const char *path, const char *why)
{
    return sl_error_set(err, SL_EINVAL, path, 0, "not a valid shard manifest: %s", why);
}

static sl_status parse_body(sl_shard *sh, const char *path, sl_error *err)
{
    sl_preader r = {.b = sh->body, .n = sh->body_len};
    sl_plant *p = &sh->plant;
    sh->strings[0] = sl_preader_strdup(&r, STR_MAX);
    sh->set.version = sh->strings[0];
    sh->set.seed = sl_preader_u64(&r);
    sh->set.substeps = (unsigned)sl_preader_count(&r, UINT32_MAX, "bad sub-steps");
    sh->set.accuracy = sl_preader_f64(&r);
    const char **pr[6] = {&sh->set.project.project, &sh->set.project.document,
                          &sh->set.project.revision, &sh->set.project.prepared,
                          &sh->set.project.checked, &sh->set.project.date};
    for (int i = 0; i < 6; i++) {
        int given = (int)sl_preader_count(&r, 1, "bad flag");
        sh->strings[1 + i] = sl_preader_strdup(&r, STR_MAX);
        *pr[i] = given ? sh->strings[1 + i] : NULL;
    }
    size_t n_mu = (size_t)sl_preader_count(&r, SL_ENTRY_MAX_MU, "too many friction values");
    if (!r.bad && (n_mu == 0 || n_mu > (r.n - r.pos) / 8))
        return bad(err, path, "bad friction grid");
    if (!r.bad && !(sh->mu = malloc(n_mu * sizeof *sh->mu)))
        return sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
    for (size_t k = 0; !r.bad && k < n_mu; k++)
        sh->mu[k] = sl_preader_f64(&r);
    sh->set.n_mu = r.bad ? 0 : n_mu;
    sh->set.mu = sh->mu;
    p->is_plant = (int)sl_preader_count(&r, 1, "bad flag");
    p->n_buildings = (size_t)sl_preader_count(&r, SL_PLANT_MAX_BUILDINGS, "too many buildings");
    p->building = calloc(SL_PLANT_MAX_BUILDINGS, sizeof *p->building);
    p->floors = calloc(SL_PLANT_MAX_FLOORS, sizeof *p->floors);
    if (!p->building || !p->floors)
        return sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
    for (size_t b = 0; !r.bad && b < p->n_buildings; b++)
        sl_preader_str(&r, p->building[b], SL_DELIVER_ID_MAX - 1);
    size_t n = (size_t)sl_preader_count(&r, SL_PLANT_MAX_FLOORS, "too many floors");
    for (size_t i = 0; !r.bad && i < n; i++) {
        sl_plant_floor *f = &p->floors[p->n++];
        f->building = (size_t)sl_preader_count(&r, p->n_buildings ? p->n_buildings - 1 : 0,
                                               "bad building index");
        f->id = sl_preader_strdup(&r, SL_DELIVER_ID_MAX - 1);
        f->name = sl_preader_strdup(&r, STR_MAX);
        f->path = sl_preader_strdup(&r, STR_MAX);
        f->description = sl_preader_strdup(&r, STR_MAX);
        f->units = sl_preader_strdup(&r, STR_MAX);
        f->elevation_m = sl_preader_f64(&r);
        f->crc32 = (unsigned long)sl_preader_count(&r, UINT32_MAX, "bad CRC");
        f->size_bytes = (long)sl_preader_count(&r, INT64_MAX, "bad size");
        sl_preader_str(&r, f->key.hash, 16);
        f->shard = (unsigned)sl_preader_count(&r, sh->n, "bad shard number");
        f->warnings = sl_preader_strdup(&r, STR_MAX);
        f->accepted = (int)sl_preader_count(&r, 1, "bad flag");
        if (!r.bad && (strlen(f->key.hash) != 16 || strspn(f->key.hash, "0123456789abcdef") != 16))
            return bad(err, path, "bad key hash");
    }
    if (r.bad)
        return bad(err, path, r.why ? r.why : "truncated");
    if (r.pos != r.n)
        return bad(err, path, "trailing bytes");
    if (p->n == 0 || p->n_buildings == 0 || (!p->is_plant && p->n_buildings != 1))
        return bad(err, path, "no floors");
    return SL_OK;
}

sl_status sl_shard_read(const char *dir, sl_shard *sh, sl_error *err)
{
    char path[4400];
    snprintf(path, sizeof path, "%s/%s", dir, SL_SHARD_MANIFEST);
    FILE *f = fopen(path, "rb");
    if (!f)
        return sl_error_set(err, SL_EIO, path, 0, "cannot read: %s (is %s the output folder of "
                            "a `seislide run --shard K/N`?)", strerror(errno), dir);
    struct stat st;
    unsigned char *b = NULL;
    size_t n = 0;
    if (fstat(fileno(f), &st) == 0 && S_ISREG(st.st_mode) && st.st_size <= 64L * 1024 * 1024 &&
        (b = malloc((size_t)st.st_size + 1)))
        n = fread(b, 1, (size_t)st.st_size + 1, f);
    fclose(f);
    if (!b || n != (size_t)st.st_size) {
        free(b);
        return bad(err, path, "cannot read it whole (at most 64 MiB)");
    }
    sl_status s = SL_OK;
    if (n < 8 + 24 + 4 || memcmp(b, MAGIC, 8) != 0) {
        s = bad(err, path, "no " MAGIC " header");
        goto done;
    }
    unsigned long have, want = sl_pbuf_crc32_check(b, n, &have);
    if (want != have) {
        s = bad(err, path, "checksum mismatch");
        goto done;
    }
    sl_preader r = {.b = b, .n = n - 4, .pos = 8};
    sh->k = (unsigned)sl_preader_count(&r, SL_PLANT_MAX_SHARDS, "bad K");
    sh->n = (unsigned)sl_preader_count(&r, SL_PLANT_MAX_SHARDS, "bad N");
    size_t len = (size_t)sl_preader_count(&r, n, "bad length");
    const unsigned char *body = sl_preader_bytes(&r, len);
    if (r.bad || r.pos != r.n || sh->k < 1 || sh->k > sh->n) {
        s = bad(err, path, r.bad && r.why ? r.why : "bad shard number or length");
        goto done;
    }
    if (!(sh->body = malloc(len ? len : 1))) {
        s = sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
        goto done;
    }
    memcpy(sh->body, body, len);
    sh->body_len = len;
    s = parse_body(sh, path, err);
done:
    free(b);
    return s;
}

void sl_shard_free(sl_shard *sh)
{
    sl_plant_free(&sh->plant);
    for (int i = 0; i < 8; i++)
        free(sh->strings[i]);
    free(sh->mu);
    free(sh->body);
    memset(sh, 0, sizeof *sh);
}
