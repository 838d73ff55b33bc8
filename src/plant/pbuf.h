/*
 * pbuf.h - the byte encoding of the plant's result files (cache entries and
 * shard manifests, cache.h and shard.h): a growable buffer to write into and
 * a bounded cursor to read from.
 *
 * Encoding: integers as 8 bytes little-endian (two's complement for signed
 * ones), doubles as their IEEE 754 binary64 bits in the same byte order (so
 * every value, NaN payloads aside, reads back bit for bit), strings as an
 * 8-byte length and the bytes. The reader never trusts what it reads: every
 * length is checked against the bytes left and against the caller's limit
 * before anything is copied or allocated; after the first failure every
 * further read fails too (r->bad), so a parser checks once at the end.
 */
#ifndef SL_PLANT_PBUF_H
#define SL_PLANT_PBUF_H

#include <stddef.h>
#include <stdint.h>

typedef struct sl_pbuf {
    unsigned char *b;
    size_t n, cap;
    int oom;                /* an allocation failed: the buffer is incomplete */
} sl_pbuf;

void sl_pbuf_bytes(sl_pbuf *w, const void *p, size_t n);
void sl_pbuf_u64(sl_pbuf *w, uint64_t v);
void sl_pbuf_f64(sl_pbuf *w, double v);
void sl_pbuf_str(sl_pbuf *w, const char *s); /* NULL: written as "" */
void sl_pbuf_free(sl_pbuf *w);
/* The trailer of a result file: append the CRC-32 (zlib) of every byte
 * written so far, 4 bytes little-endian. */
void sl_pbuf_crc32(sl_pbuf *w);
/* The CRC-32 of b[0, n-4) (returned) and the trailer stored in its last 4
 * bytes (*stored); n >= 4. */
unsigned long sl_pbuf_crc32_check(const unsigned char *b, size_t n, unsigned long *stored);

typedef struct sl_preader {
    const unsigned char *b;
    size_t n, pos;
    int bad;                /* a read ran past the end or broke a limit */
    const char *why;        /* what (static text) */
} sl_preader;

uint64_t sl_preader_u64(sl_preader *r);
/* An unsigned integer that must be <= max (else r->bad). */
uint64_t sl_preader_count(sl_preader *r, uint64_t max, const char *what);
double sl_preader_f64(sl_preader *r);
/* A string of at most max bytes into buf (size > max), NUL-terminated;
 * an embedded NUL is refused. */
void sl_preader_str(sl_preader *r, char *buf, size_t max);
/* The same into a malloc'd string (NULL after a failure). */
char *sl_preader_strdup(sl_preader *r, size_t max);
/* n raw bytes (a borrowed pointer into the input, NULL on failure). */
const unsigned char *sl_preader_bytes(sl_preader *r, size_t n);

/* 64-bit FNV-1a of n bytes, continuing from h (start: SL_FNV64_OFFSET). */
#define SL_FNV64_OFFSET 0xcbf29ce484222325ULL
uint64_t sl_fnv64(uint64_t h, const void *p, size_t n);

#endif
