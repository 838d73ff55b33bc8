/* csvread.c - CSV tables read record by record; see csvread.h. */
#include "report/csvread.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

static void rec_clear(sl_csvrec *r)
{
    for (size_t i = 0; i < r->n; i++)
        free(r->f[i]);
    r->n = 0;
}

void sl_csvrec_free(sl_csvrec *r)
{
    rec_clear(r);
    free(r->f);
    free(r->fline);
    memset(r, 0, sizeof *r);
}

static int rec_push(sl_csvrec *r, char *s, long line)
{
    if (r->n == r->cap) {
        size_t cap = r->cap ? 2 * r->cap : 16;
        char **f = realloc(r->f, cap * sizeof *f);
        if (f)
            r->f = f;
        long *l = realloc(r->fline, cap * sizeof *l);
        if (l)
            r->fline = l;
        if (!f || !l) {
            free(s);
            return -1;
        }
        r->cap = cap;
    }
    r->f[r->n] = s;
    r->fline[r->n++] = line;
    return 0;
}

/* Skip a line end at pos (LF, CRLF or CR); 1 when there was one. */
static int line_end(sl_csvread *c)
{
    if (c->pos < c->len && c->buf[c->pos] == '\r') {
        c->pos++;
        if (c->pos < c->len && c->buf[c->pos] == '\n')
            c->pos++;
        c->line++;
        return 1;
    }
    if (c->pos < c->len && c->buf[c->pos] == '\n') {
        c->pos++;
        c->line++;
        return 1;
    }
    return 0;
}

/* The next record into r: 1, 0 at the end, or an error status (negated).
 * Blank lines and lines starting with '#' are skipped. */
int sl_csvread_next(sl_csvread *c, sl_csvrec *r, sl_error *err)
{
    rec_clear(r);
    for (;;) { /* skip comment and blank lines */
        if (c->pos >= c->len)
            return 0;
        size_t e = c->pos;
        while (e < c->len && (c->buf[e] == ' ' || c->buf[e] == '\t'))
            e++;
        if (e < c->len && c->buf[e] == '#') {
            while (c->pos < c->len && c->buf[c->pos] != '\r' && c->buf[c->pos] != '\n')
                c->pos++;
            line_end(c);
            continue;
        }
        if (e >= c->len || c->buf[e] == '\r' || c->buf[e] == '\n') {
            c->pos = e;
            if (!line_end(c))
                return 0;
            continue;
        }
        break;
    }
    r->line = c->line;
    const char sep = c->sep ? c->sep : ',';
    for (;;) {
        long fl = c->line;
        size_t cap = 64, k = 0;
        char *s = malloc(cap);
        if (!s)
            return -sl_error_set(err, SL_ENOMEM, c->path, 0, "out of memory");
        int quoted = c->pos < c->len && c->buf[c->pos] == '"';
        if (quoted)
            c->pos++;
        for (;;) {
            if (c->pos >= c->len) {
                if (quoted) {
                    free(s);
                    return -sl_error_set_at(err, SL_EPARSE, c->path, fl, (long)r->n + 1,
                                            "a quoted field is not closed before the end of "
                                            "the file");
                }
                break;
            }
            char ch = c->buf[c->pos];
            if (quoted && ch == '"') {
                if (c->pos + 1 < c->len && c->buf[c->pos + 1] == '"') {
                    c->pos += 2;
                } else {
                    c->pos++;
                    char nx = c->pos < c->len ? c->buf[c->pos] : '\n';
                    if (nx != sep && nx != '\r' && nx != '\n') {
                        free(s);
                        return -sl_error_set_at(err, SL_EPARSE, c->path, c->line,
                                                (long)r->n + 1, "text after the closing quote "
                                                "of a field (a quote inside a quoted field is "
                                                "written \"\")");
                    }
                    break;
                }
            } else if (!quoted && (ch == sep || ch == '\r' || ch == '\n')) {
                break;
            } else if (quoted && (ch == '\r' || ch == '\n')) {
                line_end(c); /* a line break inside the field: kept as LF */
                ch = '\n';
            } else {
                c->pos++;
            }
            if (k + 2 > cap) {
                char *g = realloc(s, cap *= 2);
                if (!g) {
                    free(s);
                    return -sl_error_set(err, SL_ENOMEM, c->path, 0, "out of memory");
                }
                s = g;
            }
            s[k++] = ch;
        }
        s[k] = '\0';
        if (rec_push(r, s, fl))
            return -sl_error_set(err, SL_ENOMEM, c->path, 0, "out of memory");
        if (c->pos < c->len && c->buf[c->pos] == sep) {
            c->pos++;
            continue;
        }
        line_end(c);
        return 1;
    }
}

sl_status sl_csvread_detect_sep(sl_csvread *c, sl_error *err)
{
    c->sep = ',';
    long line = c->line;
    for (size_t i = c->pos; i < c->len;) {
        size_t e = i;
        while (e < c->len && c->buf[e] != '\n' && c->buf[e] != '\r')
            e++;
        size_t k = i;
        while (k < e && (c->buf[k] == ' ' || c->buf[k] == '\t'))
            k++;
        if (k < e && c->buf[k] != '#') {
            size_t commas = 0, semis = 0;
            int quoted = 0;
            for (size_t j = k; j < e; j++) {
                quoted ^= c->buf[j] == '"';
                commas += !quoted && c->buf[j] == ',';
                semis += !quoted && c->buf[j] == ';';
            }
            if (commas && semis)
                return sl_error_set(err, SL_EPARSE, c->path, line, "the header row holds both "
                                    "',' and ';': separate the columns with one of them (',' "
                                    "with decimal points, or ';' with decimal commas)");
            if (semis)
                c->sep = ';';
            return SL_OK;
        }
        i = e;
        if (i < c->len && c->buf[i] == '\r')
            i++;
        if (i < c->len && c->buf[i] == '\n')
            i++;
        line++;
    }
    return SL_OK;
}

/* Trimmed copy of a field for matching and numbers (into buf). */
const char *sl_csv_trimmed(const char *s, char *buf, size_t n)
{
    while (*s && sl_text_is_space(*s))
        s++;
    size_t k = strlen(s);
    while (k && sl_text_is_space(s[k - 1]))
        k--;
    if (k >= n)
        k = n - 1;
    memcpy(buf, s, k);
    buf[k] = '\0';
    return buf;
}


/* The column named `name` in a header record, or -1. */
int sl_csv_header_col(const sl_csvrec *h, const char *name)
{
    char b[256];
    for (size_t i = 0; i < h->n; i++)
        if (!strcasecmp(sl_csv_trimmed(h->f[i], b, sizeof b), name))
            return (int)i;
    return -1;
}

sl_status sl_csv_load(const char *path, long max, sl_text *t, sl_error *err)
{
    sl_text_opts o = {.max_bytes = max, .what = "a CSV table", .text_only = 1};
    return sl_text_load(path, &o, t, err);
}

sl_status sl_csv_open(const char *path, long max, sl_text *t, sl_csvread *rd, sl_error *err)
{
    sl_status st = sl_csv_load(path, max, t, err);
    if (!st)
        *rd = (sl_csvread){.path = path, .buf = t->buf, .len = t->len, .line = 1};
    return st;
}

/* A header record with the named columns (cols[k] set), after the comment
 * lines; *rd positioned at the first data row. */
sl_status sl_csv_header(sl_csvread *rd, sl_csvrec *h, const char *const *names, size_t nn,
                              int *cols, sl_error *err)
{
    int got = sl_csvread_next(rd, h, err);
    if (got < 0)
        return (sl_status)-got;
    if (!got)
        return sl_error_set(err, SL_EPARSE, rd->path, rd->line, "no header row");
    for (size_t k = 0; k < nn; k++)
        if ((cols[k] = sl_csv_header_col(h, names[k])) < 0)
            return sl_error_set_at(err, SL_EPARSE, rd->path, h->line, 0,
                                   "no column '%s' in the header (not a table seislide run "
                                   "wrote)", names[k]);
    return SL_OK;
}

sl_status sl_csv_num(const sl_csvread *rd, const sl_csvrec *w, int col, double *v, int empty_nan,
                           sl_error *err)
{
    char b[SL_TEXT_TOKEN_MAX + 1];
    const char *s = (size_t)col < w->n ? sl_csv_trimmed(w->f[col], b, sizeof b) : "";
    if (!*s && empty_nan) {
        *v = NAN;
        return SL_OK;
    }
    sl_num_result nr = sl_text_parse_num(s, strlen(s), v);
    if (nr != SL_NUM_OK)
        return sl_error_set_at(err, nr == SL_NUM_BAD ? SL_EPARSE : SL_EINVAL, rd->path,
                               w->line, col + 1, "%s value '%s'",
                               nr == SL_NUM_BAD ? "non-numeric" : "non-finite",
                               sl_text_quote(s, strlen(s)).s);
    return SL_OK;
}
