/* text.c - the shared text helpers of src/io (see text.h). */
#include "io/text.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* Chunk size for reading files, bytes. */
#define SL_TEXT_READ_CHUNK 65536

static char lower(char c)
{
    return (char)tolower((unsigned char)c);
}

int sl_text_is_space(char c)
{
    return c == ' ' || c == '\t' || c == '\v' || c == '\f' || c == '\r';
}

int sl_text_decimal_comma(char *tok)
{
    char *comma = strchr(tok, ',');
    if (!comma)
        return 1;
    if (strchr(tok, '.') || strchr(comma + 1, ','))
        return 0;
    *comma = '.';
    return 1;
}

char *sl_text_dup(const char *s)
{
    return sl_text_dup_mem(s ? s : "", strlen(s ? s : ""));
}

char *sl_text_dup_mem(const char *s, size_t n)
{
    char *d = malloc(n + 1);
    if (d) {
        if (n)
            memcpy(d, s, n);
        d[n] = '\0';
    }
    return d;
}

void sl_text_trim(const char **s, size_t *n)
{
    while (*n > 0 && sl_text_is_space(**s)) {
        (*s)++;
        (*n)--;
    }
    while (*n > 0 && sl_text_is_space((*s)[*n - 1]))
        (*n)--;
}

long sl_text_find_ci(const char *s, size_t n, const char *needle)
{
    size_t m = strlen(needle);
    for (size_t i = 0; m <= n && i <= n - m; i++) {
        size_t k = 0;
        while (k < m && lower(s[i + k]) == lower(needle[k]))
            k++;
        if (k == m)
            return (long)i;
    }
    return -1;
}

size_t sl_text_utf8_len(const char *s, size_t n)
{
    const unsigned char *u = (const unsigned char *)s;
    if (n == 0)
        return 0;
    if (u[0] < 0x80)
        return 1;
    size_t len = u[0] >= 0xC2 && u[0] <= 0xDF ? 2 : u[0] >= 0xE0 && u[0] <= 0xEF ? 3
                 : u[0] >= 0xF0 && u[0] <= 0xF4 ? 4 : 0;
    if (len == 0 || len > n)
        return 0;
    /* the second byte's range excludes overlong forms, surrogates and > U+10FFFF */
    unsigned char lo = u[0] == 0xE0 ? 0xA0 : u[0] == 0xF0 ? 0x90 : 0x80;
    unsigned char hi = u[0] == 0xED ? 0x9F : u[0] == 0xF4 ? 0x8F : 0xBF;
    if (u[1] < lo || u[1] > hi)
        return 0;
    for (size_t k = 2; k < len; k++)
        if ((u[k] & 0xC0) != 0x80)
            return 0;
    return len;
}

void sl_text_quote_into(char *dst, size_t cap, const char *s, size_t n)
{
    size_t k = 0;
    for (size_t i = 0; i < n;) {
        size_t c = sl_text_utf8_len(s + i, n - i), w = c ? c : 1;
        if (k + w > cap) {
            memcpy(dst + k, "...", 3);
            k += 3;
            break;
        }
        const unsigned char b0 = (unsigned char)s[i], b1 = c > 1 ? (unsigned char)s[i + 1] : 0;
        const int control = c == 1 ? b0 < 0x20 || b0 == 0x7f : c == 2 && b0 == 0xC2 && b1 < 0xA0;
        if (c && !control)
            memcpy(dst + k, s + i, c);
        else
            dst[k] = '?';
        k += c && !control ? c : 1;
        i += w;
    }
    dst[k] = '\0';
}

sl_quoted sl_text_quote(const char *tok, size_t n)
{
    sl_quoted q;
    sl_text_quote_into(q.s, SL_TEXT_QUOTE_MAX, tok, n);
    return q;
}

sl_num_result sl_text_parse_num(const char *s, size_t n, double *out)
{
    char buf[SL_TEXT_TOKEN_MAX + 1];
    if (n == 0 || n > SL_TEXT_TOKEN_MAX)
        return SL_NUM_BAD;
    for (size_t i = 0; i < n; i++) {
        char c = s[i];
        if (c == 'x' || c == 'X' || c == '\0' || sl_text_is_space(c))
            return SL_NUM_BAD;
        buf[i] = (c == 'd' || c == 'D') ? 'E' : c;
    }
    buf[n] = '\0';
    char *end = NULL;
    double v = strtod(buf, &end);
    if (end != buf + n)
        return SL_NUM_BAD;
    if (!isfinite(v))
        return SL_NUM_NONFINITE;
    *out = v;
    return SL_NUM_OK;
}

sl_status sl_text_token_error(sl_error *err, const char *path, long line, const char *tok,
                              size_t n, sl_num_result r)
{
    sl_quoted q = sl_text_quote(tok, n);
    if (r == SL_NUM_NONFINITE)
        return sl_error_set(err, SL_EINVAL, path, line, "value '%s' is not finite", q.s);
    return sl_error_set(err, SL_EPARSE, path, line, "non-numeric value '%s'", q.s);
}

sl_unit sl_text_unit(const char *s, size_t n)
{
    char buf[48];
    size_t k = 0;
    for (size_t i = 0; i < n; i++) {
        char c = lower(s[i]);
        if (sl_text_is_space(c))
            continue;
        if (k + 1 >= sizeof buf)
            return SL_UNIT_NONE;
        buf[k++] = c;
    }
    buf[k] = '\0';
    /* "sec" -> "s", "**2" and UTF-8 superscript two -> "2", "gals" -> "gal" */
    char out[48];
    size_t j = 0;
    for (size_t i = 0; i < k;) {
        if (!strncmp(buf + i, "sec", 3)) {
            out[j++] = 's';
            i += 3;
        } else if (!strncmp(buf + i, "**2", 3)) {
            out[j++] = '2';
            i += 3;
        } else if ((unsigned char)buf[i] == 0xc2 && (unsigned char)buf[i + 1] == 0xb2) {
            out[j++] = '2';
            i += 2;
        } else {
            out[j++] = buf[i++];
        }
    }
    out[j] = '\0';
    if (!strcmp(out, "gals"))
        return SL_UNIT_CMS2;
    return sl_unit_parse(out);
}

int sl_dvec_reserve(sl_dvec *d, size_t cap)
{
    if (cap <= d->cap)
        return 0;
    if (cap > SIZE_MAX / sizeof *d->v)
        return -1;
    double *p = realloc(d->v, cap * sizeof *p);
    if (!p)
        return -1;
    d->v = p;
    d->cap = cap;
    return 0;
}

int sl_dvec_push(sl_dvec *d, double x)
{
    if (d->n == d->cap && sl_dvec_reserve(d, d->cap ? 2 * d->cap : 1024) != 0)
        return -1;
    d->v[d->n++] = x;
    return 0;
}

int sl_lvec_push(sl_lvec *d, long x)
{
    if (d->n == d->cap) {
        size_t cap = d->cap ? 2 * d->cap : 1024;
        if (cap > SIZE_MAX / sizeof *d->v)
            return -1;
        long *p = realloc(d->v, cap * sizeof *p);
        if (!p)
            return -1;
        d->v = p;
        d->cap = cap;
    }
    d->v[d->n++] = x;
    return 0;
}

int sl_text_next(sl_text *t, const char **s, size_t *n)
{
    if (t->pos >= t->len)
        return 0;
    const char *b = t->buf + t->pos;
    size_t rem = t->len - t->pos;
    size_t i = 0;
    while (i < rem && b[i] != '\n' && b[i] != '\r')
        i++;
    *s = b;
    *n = i;
    if (i < rem) {
        if (b[i] == '\r' && i + 1 < rem && b[i + 1] == '\n')
            i++;
        i++;
    }
    t->pos += i;
    t->lineno++;
    return 1;
}

int sl_text_skip_line(const char *s, size_t n)
{
    size_t i = 0;
    while (i < n && sl_text_is_space(s[i]))
        i++;
    return i == n || s[i] == '#';
}

void sl_text_free(sl_text *t)
{
    if (!t)
        return;
    free(t->mem);
    memset(t, 0, sizeof *t);
}

/* Line (1-based, LF, CRLF or CR ends) of byte offset `at` of buf. */
static long line_of(const char *buf, size_t at)
{
    long line = 1;
    for (size_t i = 0; i < at; i++)
        if (buf[i] == '\n' || (buf[i] == '\r' && buf[i + 1] != '\n'))
            line++;
    return line;
}

/* UTF-16 text: a byte-order mark FF FE (little-endian) or FE FF
 * (big-endian), or, without one, NUL bytes at one parity of the first
 * SL_TEXT_UTF16_SCAN bytes (at least a quarter of them) and none at the
 * other: the ASCII of a table saved as "Unicode text". "UTF-16LE",
 * "UTF-16BE" or NULL. */
#define SL_TEXT_UTF16_SCAN 512
static const char *utf16_kind(const unsigned char *b, size_t n)
{
    if (n >= 2 && b[0] == 0xff && b[1] == 0xfe)
        return "UTF-16LE";
    if (n >= 2 && b[0] == 0xfe && b[1] == 0xff)
        return "UTF-16BE";
    size_t m = n < SL_TEXT_UTF16_SCAN ? n : SL_TEXT_UTF16_SCAN, nul[2] = {0, 0};
    for (size_t i = 0; i < m; i++)
        nul[i & 1] += b[i] == 0;
    if (m >= 4 && nul[0] == 0 && 4 * nul[1] >= m / 2)
        return "UTF-16LE";
    if (m >= 4 && nul[1] == 0 && 4 * nul[0] >= m / 2)
        return "UTF-16BE";
    return NULL;
}

sl_status sl_text_load(const char *path, const sl_text_opts *o, sl_text *t, sl_error *err)
{
    memset(t, 0, sizeof *t);
    FILE *f = fopen(path, "rb");
    if (!f)
        return sl_error_set(err, SL_EIO, path, 0, "cannot open: %s", strerror(errno));
    struct stat st;
    if (fstat(fileno(f), &st) == 0 && S_ISREG(st.st_mode) && st.st_size > o->max_bytes) {
        fclose(f);
        if (o->limit_name)
            return sl_error_set(err, SL_EINVAL, path, 0, "file of %lld bytes is larger than "
                                "the %ld bytes %s may have (%s); not read",
                                (long long)st.st_size, o->max_bytes, o->what, o->limit_name);
        return sl_error_set(err, SL_EINVAL, path, 0, "file of %lld bytes is larger than the "
                            "%ld bytes %s may have; not read",
                            (long long)st.st_size, o->max_bytes, o->what);
    }
    char *buf = NULL;
    size_t n = 0, cap = 0;
    for (;;) {
        if (cap - n < SL_TEXT_READ_CHUNK + 1) {
            size_t ncap = cap ? 2 * cap : 2 * SL_TEXT_READ_CHUNK;
            char *p = realloc(buf, ncap);
            if (!p) {
                free(buf);
                fclose(f);
                return sl_error_set(err, SL_ENOMEM, path, 0, "out of memory reading the file");
            }
            buf = p;
            cap = ncap;
        }
        size_t got = fread(buf + n, 1, SL_TEXT_READ_CHUNK, f);
        n += got;
        if (n > (size_t)o->max_bytes) { /* a pipe or device without a size */
            free(buf);
            fclose(f);
            return sl_error_set(err, SL_EINVAL, path, 0, "more than the %ld bytes %s may "
                                "have; not read", o->max_bytes, o->what);
        }
        if (got < SL_TEXT_READ_CHUNK) {
            if (ferror(f)) {
                int e = errno;
                free(buf);
                fclose(f);
                return sl_error_set(err, SL_EIO, path, 0, "read error: %s",
                                    e ? strerror(e) : "unknown");
            }
            break;
        }
    }
    fclose(f);
    buf[n] = '\0';
    const char *u16 = o->text_only ? utf16_kind((const unsigned char *)buf, n) : NULL;
    if (u16) {
        free(buf);
        return sl_error_set(err, SL_EPARSE, path, 1,
                            "the file is %s text, not UTF-8: save it as UTF-8 (a spreadsheet: "
                            "Save As 'CSV UTF-8'; a text editor: encoding UTF-8) or convert it "
                            "with iconv -f UTF-16 -t UTF-8",
                            u16);
    }
    if (o->text_only) {
        const char *nul = memchr(buf, '\0', n);
        if (nul) {
            long line = line_of(buf, (size_t)(nul - buf));
            free(buf);
            return sl_error_set(err, SL_EPARSE, path, line,
                                "not a text file: NUL byte at line %ld", line);
        }
    }
    t->mem = buf;
    t->buf = buf;
    t->len = n;
    if (n >= 3 && !memcmp(buf, "\xef\xbb\xbf", 3)) {
        t->buf += 3;
        t->len -= 3;
    }
    return SL_OK;
}

const char *sl_text_find_str_ci(const char *s, const char *needle)
{
    long at = sl_text_find_ci(s, strlen(s), needle);
    return at < 0 ? NULL : s + at;
}
