/*
 * fuzz_result.c - the readers of the plant's result files (src/plant): a
 * cache entry or a shard's result file (sl_cache_read_path, cache.h) and a
 * shard manifest (sl_shard_read, shard.h), which a rerun and `seislide
 * merge` read from disk that may have been damaged, truncated or written by
 * someone else. The first byte picks:
 *   0  the bytes as an entry file, as they are (the outer checks: magic,
 *      lengths, CRC-32, key);
 *   1  the bytes as the payload of an entry given a valid frame (magic, a
 *      key, lengths, CRC-32), so that the decoder (entry.c) itself is
 *      reached: a CRC does not protect against a writer that is wrong;
 *   2  the bytes as a shard manifest, as they are;
 *   3  the bytes as the body of a manifest given a valid frame.
 * A decoded result must keep the counts it was asked for (n_mu rows).
 */
#include "fuzz_common.h"

#include <sys/stat.h>
#include <zlib.h>

#include "plant/cache.h"
#include "plant/entry.h"
#include "plant/pbuf.h"
#include "plant/shard.h"

static const char key_text[] = "fuzz key";

/* magic + u64 fields + bytes + CRC-32 LE, as cache.c and shard.c write them. */
static sl_pbuf frame(const char *magic, const uint64_t *fields, int nf, const uint8_t *data,
                     size_t size)
{
    sl_pbuf w = {0};
    sl_pbuf_bytes(&w, magic, 8);
    for (int i = 0; i < nf; i++)
        sl_pbuf_u64(&w, fields[i]);
    sl_pbuf_bytes(&w, data, size);
    uLong c = crc32(crc32(0L, Z_NULL, 0), w.b, (uInt)w.n);
    unsigned char le[4] = {(unsigned char)c, (unsigned char)(c >> 8), (unsigned char)(c >> 16),
                           (unsigned char)(c >> 24)};
    sl_pbuf_bytes(&w, le, 4);
    return w;
}

static void read_entry(const uint8_t *data, size_t size, const char *hash)
{
    const char *path = fuzz_write("entry.slr", data, size);
    if (!path)
        return;
    enum { N_MU = 16 };
    sl_analysis *a = NULL;
    char why[256];
    sl_cache_read_result r = sl_cache_read_path(path, hash, N_MU, &a, why, sizeof why);
    if (getenv("FUZZ_VERBOSE"))
        fprintf(stderr, "entry: %s\n", r == SL_CACHE_HIT ? "read" : why);
    if (r == SL_CACHE_HIT) {
        fuzz_require(a && a->design && a->design->n == N_MU);
    } else {
        fuzz_require(!a && why[0]);
    }
    sl_analysis_free(a);
}

static void read_manifest(const uint8_t *data, size_t size)
{
    const char *path = fuzz_write(SL_SHARD_MANIFEST, data, size);
    if (!path)
        return;
    char dir[512];
    snprintf(dir, sizeof dir, "%s", path);
    *strrchr(dir, '/') = '\0';
    sl_shard sh;
    memset(&sh, 0, sizeof sh);
    sl_error err;
    sl_error_clear(&err);
    sl_status st = sl_shard_read(dir, &sh, &err);
    if (getenv("FUZZ_VERBOSE"))
        fprintf(stderr, "manifest: %s\n", st == SL_OK ? "read" : err.msg);
    if (st == SL_OK)
        fuzz_require(sh.k >= 1 && sh.k <= sh.n);
    else
        fuzz_require(err.code != SL_OK && err.msg[0]);
    sl_shard_free(&sh);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char hash[17];
    sl_entry_key_hash(key_text, sizeof key_text - 1, hash);
    switch (fuzz_select(&data, &size, 4)) {
    case 0:
        /* the hash of the key the file holds, as a shard manifest records it */
        if (size >= 16) {
            uint64_t klen = 0;
            for (int i = 7; i >= 0; i--)
                klen = klen << 8 | data[8 + i];
            if (klen <= size - 16)
                sl_entry_key_hash((const char *)data + 16, (size_t)klen, hash);
        }
        read_entry(data, size, hash);
        break;
    case 1: {
        uint64_t klen = sizeof key_text - 1;
        sl_pbuf w = {0};
        sl_pbuf_bytes(&w, "SLENTRY1", 8);
        sl_pbuf_u64(&w, klen);
        sl_pbuf_bytes(&w, key_text, klen);
        sl_pbuf_u64(&w, size);
        sl_pbuf_bytes(&w, data, size);
        uLong c = crc32(crc32(0L, Z_NULL, 0), w.b, (uInt)w.n);
        unsigned char le[4] = {(unsigned char)c, (unsigned char)(c >> 8),
                               (unsigned char)(c >> 16), (unsigned char)(c >> 24)};
        sl_pbuf_bytes(&w, le, 4);
        if (!w.oom)
            read_entry(w.b, w.n, hash);
        sl_pbuf_free(&w);
        break;
    }
    case 2:
        read_manifest(data, size);
        break;
    default: {
        /* K and N from the first two bytes, so that 1 <= K <= N mostly holds */
        uint64_t f[3] = {size > 0 ? 1 + data[0] % 4 : 1, size > 1 ? 1 + data[1] % 4 : 1, 0};
        if (f[0] > f[1])
            f[1] = f[0];
        const uint8_t *body = size > 2 ? data + 2 : data;
        size_t blen = size > 2 ? size - 2 : 0;
        f[2] = blen;
        sl_pbuf w = frame("SLSHARD1", f, 3, body, blen);
        if (!w.oom)
            read_manifest(w.b, w.n);
        sl_pbuf_free(&w);
        break;
    }
    }
    return 0;
}
