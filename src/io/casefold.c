/* casefold.c - names compared without case and with their blanks trimmed,
 * as a spreadsheet's MATCH over TRIM compares them; see casefold.h. */
#include "io/casefold.h"

#include <string.h>

#include "io/text.h"

/* The folding table (generated: tools/casefold_table.py). */
#include "io/casefold_table.h"

unsigned long sl_casefold_cp(unsigned long cp)
{
    size_t lo = 0, hi = sizeof FOLD / sizeof FOLD[0]; /* the last range starting at or below */
    while (hi - lo > 1) {
        size_t mid = (lo + hi) / 2;
        if (FOLD[mid].lo <= cp)
            lo = mid;
        else
            hi = mid;
    }
    if (cp >= FOLD[lo].lo && cp <= FOLD[lo].hi && (cp - FOLD[lo].lo) % FOLD[lo].step == 0)
        return (unsigned long)((long)cp + FOLD[lo].delta);
    return cp;
}

/* A name read unit by unit: code points folded, blanks trimmed at either
 * end and each run inside one space; a byte that is not UTF-8 is the unit
 * BYTE_UNIT + byte (kept distinct from every character). */
#define BYTE_UNIT 0x110000UL
#define END_UNIT 0x120000UL
typedef struct reader {
    const char *p;
    size_t len;  /* the last unit's bytes (0: a folded blank run) */
} reader;

static void reader_init(reader *r, const char *s)
{
    while (*s && sl_text_is_space(*s))
        s++;
    r->p = s;
    r->len = 0;
}

static unsigned long decode(const char *s, size_t n)
{
    const unsigned char *u = (const unsigned char *)s;
    if (n == 1)
        return u[0];
    unsigned long cp = u[0] & (n == 2 ? 0x1F : n == 3 ? 0x0F : 0x07);
    for (size_t k = 1; k < n; k++)
        cp = cp << 6 | (u[k] & 0x3F);
    return cp;
}

static unsigned long reader_next(reader *r)
{
    if (!*r->p)
        return END_UNIT;
    if (sl_text_is_space(*r->p)) {
        while (*r->p && sl_text_is_space(*r->p))
            r->p++;
        return *r->p ? ' ' : END_UNIT; /* blanks at the end: none */
    }
    size_t n = sl_text_utf8_len(r->p, strnlen(r->p, 4));
    if (!n) {
        unsigned long b = BYTE_UNIT + (unsigned char)*r->p;
        r->p++;
        return b;
    }
    unsigned long cp = sl_casefold_cp(decode(r->p, n));
    r->p += n;
    return cp;
}

int sl_casefold_same(const char *a, const char *b)
{
    reader x, y;
    reader_init(&x, a ? a : "");
    reader_init(&y, b ? b : "");
    for (;;) {
        unsigned long u = reader_next(&x), v = reader_next(&y);
        if (u != v)
            return 0;
        if (u == END_UNIT)
            return 1;
    }
}

/* cp as UTF-8 into out (4 bytes): its length. */
static size_t encode(unsigned long cp, char *out)
{
    if (cp < 0x80) {
        out[0] = (char)cp;
        return 1;
    }
    if (cp < 0x800) {
        out[0] = (char)(0xC0 | cp >> 6);
        out[1] = (char)(0x80 | (cp & 0x3F));
        return 2;
    }
    if (cp < 0x10000) {
        out[0] = (char)(0xE0 | cp >> 12);
        out[1] = (char)(0x80 | (cp >> 6 & 0x3F));
        out[2] = (char)(0x80 | (cp & 0x3F));
        return 3;
    }
    out[0] = (char)(0xF0 | cp >> 18);
    out[1] = (char)(0x80 | (cp >> 12 & 0x3F));
    out[2] = (char)(0x80 | (cp >> 6 & 0x3F));
    out[3] = (char)(0x80 | (cp & 0x3F));
    return 4;
}

char *sl_casefold_key(const char *s, char *buf, size_t n)
{
    if (!n)
        return buf;
    reader r;
    reader_init(&r, s ? s : "");
    size_t k = 0;
    for (unsigned long u; (u = reader_next(&r)) != END_UNIT;) {
        char c[4];
        size_t len = 1;
        if (u >= BYTE_UNIT)
            c[0] = (char)(u - BYTE_UNIT);
        else
            len = encode(u, c);
        if (k + len + 1 > n)
            break;
        memcpy(buf + k, c, len);
        k += len;
    }
    buf[k] = '\0';
    return buf;
}
