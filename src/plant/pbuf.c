/* pbuf.c - the byte encoding of the plant's result files; see pbuf.h. */
#include "plant/pbuf.h"

#include <stdlib.h>
#include <string.h>
#include <zlib.h>

void sl_pbuf_bytes(sl_pbuf *w, const void *p, size_t n)
{
    if (w->oom || n == 0)
        return;
    if (w->n + n > w->cap) {
        size_t cap = w->cap ? w->cap : 4096;
        while (cap < w->n + n)
            cap *= 2;
        unsigned char *nb = realloc(w->b, cap);
        if (!nb) {
            w->oom = 1;
            return;
        }
        w->b = nb;
        w->cap = cap;
    }
    memcpy(w->b + w->n, p, n);
    w->n += n;
}

void sl_pbuf_u64(sl_pbuf *w, uint64_t v)
{
    unsigned char le[8];
    for (int i = 0; i < 8; i++)
        le[i] = (unsigned char)(v >> (8 * i));
    sl_pbuf_bytes(w, le, 8);
}

void sl_pbuf_f64(sl_pbuf *w, double v)
{
    uint64_t u;
    memcpy(&u, &v, sizeof u);
    sl_pbuf_u64(w, u);
}

void sl_pbuf_str(sl_pbuf *w, const char *s)
{
    size_t n = s ? strlen(s) : 0;
    sl_pbuf_u64(w, n);
    sl_pbuf_bytes(w, s, n);
}

void sl_pbuf_free(sl_pbuf *w)
{
    free(w->b);
    memset(w, 0, sizeof *w);
}

static int fail(sl_preader *r, const char *why)
{
    if (!r->bad)
        r->why = why;
    r->bad = 1;
    return 0;
}

const unsigned char *sl_preader_bytes(sl_preader *r, size_t n)
{
    if (r->bad || n > r->n - r->pos)
        return fail(r, "truncated"), NULL;
    const unsigned char *p = r->b + r->pos;
    r->pos += n;
    return p;
}

uint64_t sl_preader_u64(sl_preader *r)
{
    const unsigned char *p = sl_preader_bytes(r, 8);
    uint64_t v = 0;
    for (int i = 0; p && i < 8; i++)
        v |= (uint64_t)p[i] << (8 * i);
    return v;
}

uint64_t sl_preader_count(sl_preader *r, uint64_t max, const char *what)
{
    uint64_t v = sl_preader_u64(r);
    if (!r->bad && v > max)
        fail(r, what);
    return r->bad ? 0 : v;
}

double sl_preader_f64(sl_preader *r)
{
    uint64_t u = sl_preader_u64(r);
    double v;
    memcpy(&v, &u, sizeof v);
    return r->bad ? 0 : v;
}

void sl_preader_str(sl_preader *r, char *buf, size_t max)
{
    buf[0] = '\0';
    size_t n = (size_t)sl_preader_count(r, max, "string too long");
    const unsigned char *p = sl_preader_bytes(r, n);
    if (!p)
        return;
    if (memchr(p, '\0', n)) {
        fail(r, "NUL in a string");
        return;
    }
    memcpy(buf, p, n);
    buf[n] = '\0';
}

char *sl_preader_strdup(sl_preader *r, size_t max)
{
    size_t save = r->pos;
    size_t n = (size_t)sl_preader_count(r, max, "string too long");
    r->pos = r->bad ? r->pos : save;
    char *s = r->bad ? NULL : malloc(n + 1);
    if (!s) {
        fail(r, "out of memory");
        return NULL;
    }
    sl_preader_str(r, s, n);
    if (r->bad) {
        free(s);
        return NULL;
    }
    return s;
}

uint64_t sl_fnv64(uint64_t h, const void *p, size_t n)
{
    const unsigned char *c = p;
    for (size_t i = 0; i < n; i++) {
        h ^= c[i];
        h *= 0x100000001b3ULL;
    }
    return h;
}

void sl_pbuf_crc32(sl_pbuf *w)
{
    uLong c = crc32(crc32(0L, Z_NULL, 0), w->b, (uInt)w->n);
    unsigned char le[4] = {(unsigned char)c, (unsigned char)(c >> 8), (unsigned char)(c >> 16),
                           (unsigned char)(c >> 24)};
    sl_pbuf_bytes(w, le, 4);
}

unsigned long sl_pbuf_crc32_check(const unsigned char *b, size_t n, unsigned long *stored)
{
    *stored = (uLong)b[n - 4] | (uLong)b[n - 3] << 8 | (uLong)b[n - 2] << 16 |
              (uLong)b[n - 1] << 24;
    return crc32(crc32(0L, Z_NULL, 0), b, (uInt)(n - 4));
}
