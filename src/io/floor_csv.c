/* floor_csv.c - the CSV reader of floor files (floor_desc.h, format in
 * floor.h and docs/formats-floor.md). It only reads: "# key: value" comment
 * lines, the header row "f_hz,h1_5,...,v_2" and one row per frequency go
 * into a sl_floor_desc; every rule is checked once, in floor.c.
 *
 * Records follow RFC 4180: fields separated by commas, records by LF or
 * CRLF (a lone CR also ends a line), a field may be quoted with '"' (then
 * it may hold commas, line breaks and doubled quotes ""). Blanks around an
 * unquoted field are ignored. No line-length limit. Columns in messages are
 * 1-based fields of the row. */
#include "io/floor_desc.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* The known "# key:" comment lines beyond the shared floor keys. */
static const char *const zpa_keys[SL_FLOOR_NCOMP] = {"zpa_h1", "zpa_h2", "zpa_v"};

/* The reader's position in the text. */
typedef struct csv {
    sl_floor_desc *d;
    const char *b;
    size_t len, pos;
    long line;         /* line of b[pos] */
    char sep;          /* the field separator: ',' or ';' (from the header row) */
    int periods;       /* 1: the first column is T_s (periods, s) */
} csv;

/* One parsed record: n fields, each a NUL-terminated copy in buf. */
typedef struct record {
    char *buf;
    size_t used, cap;
    size_t *off;       /* offset of field k in buf */
    long *line;        /* line where field k starts */
    size_t n, ncap;
    int quoted_any;
} record;

static void record_free(record *r)
{
    free(r->buf);
    free(r->off);
    free(r->line);
    memset(r, 0, sizeof *r);
}

static const char *field(const record *r, size_t k)
{
    return r->buf + r->off[k];
}

static int put(csv *c, record *r, char ch)
{
    if (r->used == r->cap) {
        size_t cap = r->cap ? 2 * r->cap : 256;
        char *p = realloc(r->buf, cap);
        if (!p)
            return sl_floor_desc_fail(c->d, SL_ENOMEM, c->line, 0, "out of memory");
        r->buf = p;
        r->cap = cap;
    }
    r->buf[r->used++] = ch;
    return 1;
}

static int new_field(csv *c, record *r)
{
    if (r->n == r->ncap) {
        size_t cap = r->ncap ? 2 * r->ncap : 16;
        size_t *o = realloc(r->off, cap * sizeof *o);
        if (o)
            r->off = o;
        long *l = realloc(r->line, cap * sizeof *l);
        if (l)
            r->line = l;
        if (!o || !l)
            return sl_floor_desc_fail(c->d, SL_ENOMEM, c->line, 0, "out of memory");
        r->ncap = cap;
    }
    r->off[r->n] = r->used;
    r->line[r->n] = c->line;
    r->n++;
    return 1;
}

/* Consume a line end at pos (LF, CRLF or CR); 1 if there was one. */
static int eat_eol(csv *c)
{
    if (c->pos < c->len && c->b[c->pos] == '\r') {
        c->pos++;
        if (c->pos < c->len && c->b[c->pos] == '\n')
            c->pos++;
        c->line++;
        return 1;
    }
    if (c->pos < c->len && c->b[c->pos] == '\n') {
        c->pos++;
        c->line++;
        return 1;
    }
    return 0;
}

static int at_eol(const csv *c)
{
    return c->pos >= c->len || c->b[c->pos] == '\n' || c->b[c->pos] == '\r';
}

/* Parse one record from pos (RFC 4180). */
static int read_record(csv *c, record *r)
{
    r->used = 0;
    r->n = 0;
    r->quoted_any = 0;
    for (;;) {
        if (!new_field(c, r))
            return 0;
        long col = (long)r->n;
        while (c->pos < c->len && (c->b[c->pos] == ' ' || c->b[c->pos] == '\t'))
            c->pos++;
        if (c->pos < c->len && c->b[c->pos] == '"') {
            long qline = c->line;
            r->quoted_any = 1;
            c->pos++;
            for (;;) {
                if (c->pos >= c->len)
                    return sl_floor_desc_fail(c->d, SL_EPARSE, qline, col,
                                              "quote not closed (the field opened here runs "
                                              "to the end of the file)");
                char ch = c->b[c->pos];
                if (ch == '"') {
                    if (c->pos + 1 < c->len && c->b[c->pos + 1] == '"') {
                        if (!put(c, r, '"'))
                            return 0;
                        c->pos += 2;
                        continue;
                    }
                    c->pos++;
                    break;
                }
                if (ch == '\n' || (ch == '\r' && !(c->pos + 1 < c->len && c->b[c->pos + 1] == '\n')))
                    c->line++;
                if (!put(c, r, ch))
                    return 0;
                c->pos++;
            }
            while (c->pos < c->len && (c->b[c->pos] == ' ' || c->b[c->pos] == '\t'))
                c->pos++;
            if (!at_eol(c) && c->b[c->pos] != c->sep)
                return sl_floor_desc_fail(c->d, SL_EPARSE, c->line, col,
                                          "text after the closing quote of a field (a quote "
                                          "inside a quoted field is written \"\")");
        } else {
            size_t start = c->pos;
            while (!at_eol(c) && c->b[c->pos] != c->sep) {
                if (c->b[c->pos] == '"')
                    return sl_floor_desc_fail(c->d, SL_EPARSE, c->line, col,
                                              "a quote inside an unquoted field (quote the "
                                              "whole field and double the quote)");
                c->pos++;
            }
            size_t end = c->pos;
            while (end > start && (c->b[end - 1] == ' ' || c->b[end - 1] == '\t'))
                end--;
            for (size_t i = start; i < end; i++)
                if (!put(c, r, c->b[i]))
                    return 0;
        }
        if (!put(c, r, '\0'))
            return 0;
        if (c->pos < c->len && c->b[c->pos] == c->sep) {
            c->pos++;
            continue;
        }
        eat_eol(c);
        return 1;
    }
}

/* The physical line at pos, without its end; advances past it. */
static void take_line(csv *c, const char **s, size_t *n)
{
    *s = c->b + c->pos;
    size_t i = c->pos;
    while (i < c->len && c->b[i] != '\n' && c->b[i] != '\r')
        i++;
    *n = i - c->pos;
    c->pos = i;
    eat_eol(c);
}

/* Blank, or only separators and blanks (a spreadsheet's empty row). */
static int blank_line(const csv *c, const char *s, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (s[i] != ' ' && s[i] != '\t' && s[i] != c->sep)
            return 0;
    return 1;
}

/* Not text: a control byte (other than tab and line ends), a byte-order
 * mark after the start, or bytes that are not UTF-8; named by line. */
static int check_bytes(csv *c)
{
    long line = 1;
    const unsigned char *b = (const unsigned char *)c->b;
    for (size_t i = 0; i < c->len; i++) {
        unsigned ch = b[i];
        if (ch == '\n' || (ch == '\r' && !(i + 1 < c->len && b[i + 1] == '\n'))) {
            line++;
            continue;
        }
        if (ch == '\r' || ch == '\t')
            continue;
        if (ch < 0x20 || ch == 0x7f)
            return sl_floor_desc_fail(c->d, SL_EPARSE, line, 0,
                                      "not a text file: control byte 0x%02x at line %ld", ch,
                                      line);
        if (ch < 0x80)
            continue;
        size_t k = ch >= 0xf0 && ch < 0xf5 ? 3 : ch >= 0xe0 ? 2 : ch >= 0xc2 && ch < 0xe0 ? 1 : 0;
        if (ch >= 0xf5)
            k = 0;
        int ok = k > 0 && i + k < c->len;
        for (size_t j = 1; ok && j <= k; j++)
            ok = (b[i + j] & 0xc0) == 0x80;
        if (!ok)
            return sl_floor_desc_fail(c->d, SL_EPARSE, line, 0,
                                      "not UTF-8 text: byte 0x%02x at line %ld", ch, line);
        if (k == 2 && ch == 0xef && b[i + 1] == 0xbb && b[i + 2] == 0xbf)
            return sl_floor_desc_fail(c->d, SL_EPARSE, line, 0,
                                      "a byte-order mark inside the file (only the very first "
                                      "bytes may hold one)");
        i += k;
    }
    return 1;
}

static int fail_decimal(csv *c, const char *key, const char *tok, long line, long col)
{
    sl_quoted q = sl_text_quote(tok, strlen(tok));
    return sl_floor_desc_fail(c->d, SL_EPARSE, line, col,
                              "%s: '%s' mixes ',' and '.' (or holds two commas): in a table "
                              "separated by ';' write numbers with one decimal comma and no "
                              "thousands separator, e.g. 0,36",
                              key, q.s);
}

/* A "# ..." line before the header: "# key: value" sets a key (an unknown
 * key is an error); a comment whose first word is not followed by ':' is
 * free text. */
static int comment_line(csv *c, const char *s, size_t n, long line)
{
    size_t i = 1;
    while (i < n && (s[i] == ' ' || s[i] == '\t'))
        i++;
    size_t k0 = i;
    while (i < n && (isalnum((unsigned char)s[i]) || s[i] == '_'))
        i++;
    if (i == k0 || i >= n || s[i] != ':')
        return 1; /* free comment */
    char key[40];
    size_t kl = i - k0 < sizeof key - 1 ? i - k0 : sizeof key - 1;
    for (size_t j = 0; j < kl; j++)
        key[j] = (char)tolower((unsigned char)s[k0 + j]);
    key[kl] = '\0';
    const char *v = s + i + 1;
    size_t vn = n - i - 1;
    sl_text_trim(&v, &vn);
    while (vn > 0 && (v[vn - 1] == c->sep || v[vn - 1] == ' ' || v[vn - 1] == '\t'))
        vn--; /* a spreadsheet pads a comment row with empty cells: "# units: g;;;" */
    char *value = sl_text_dup_mem(v, vn);
    if (!value)
        return sl_floor_desc_fail(c->d, SL_ENOMEM, line, 0, "out of memory");
    int ok;
    sl_floor_key fk = sl_floor_desc_key(key);
    int numeric = fk == SL_FK_ELEV || !strncmp(key, "zpa_", 4);
    if (numeric && c->sep == ';' && !sl_text_decimal_comma(value)) {
        ok = fail_decimal(c, key, value, line, 0);
    } else if (fk != SL_FK_COUNT) {
        ok = sl_floor_desc_set(c->d, fk, value, line, 0);
    } else {
        int z = -1;
        for (int q = 0; q < SL_FLOOR_NCOMP; q++)
            if (!strcmp(key, zpa_keys[q]))
                z = q;
        if (z >= 0) {
            ok = sl_floor_desc_set_zpa(c->d, (sl_floor_comp)z, key, value, line, 0);
        } else {
            char known[256] = "";
            for (int q = 0; q < SL_FK_COUNT; q++) {
                strncat(known, q ? ", " : "", sizeof known - strlen(known) - 1);
                strncat(known, sl_floor_key_names[q], sizeof known - strlen(known) - 1);
            }
            for (int q = 0; q < SL_FLOOR_NCOMP; q++) {
                strncat(known, ", ", sizeof known - strlen(known) - 1);
                strncat(known, zpa_keys[q], sizeof known - strlen(known) - 1);
            }
            ok = sl_floor_desc_fail(c->d, SL_EPARSE, line, 0,
                                    "unknown comment key '%s' (expected %s; a free comment must "
                                    "not start with 'word:')",
                                    key, known);
        }
    }
    free(value);
    return ok;
}

/* A column name that gives a damping and no direction: "5", "5%", "5 %",
 * "sa_5", "SA 5%", "damping_5", "zeta=0.05" (a table of one direction). */
static int bare_damping(const char *name)
{
    const char *p = name;
    while (isalpha((unsigned char)*p))
        p++;
    while (*p == '_' || *p == ' ' || *p == '-' || *p == '=' || *p == '(' || *p == '[')
        p++;
    size_t n = strlen(p);
    while (n > 0 && (p[n - 1] == '%' || p[n - 1] == ' ' || p[n - 1] == ')' || p[n - 1] == ']'))
        n--;
    double x;
    return n > 0 && sl_text_parse_num(p, n, &x) == SL_NUM_OK;
}

/* The header row: f_hz first, then <h1|h2|v>_<damping %> columns.
 * sa[k] is the spectrum of column k (NULL for f_hz). */
static int header_row(csv *c, const record *r, long line, sl_floor_sa_desc **sa,
                      sl_floor_comp *comp)
{
    for (size_t k = 0; k < r->n; k++) {
        const char *name = field(r, k);
        long col = (long)k + 1;
        sa[k] = NULL;
        if (!*name)
            return sl_floor_desc_fail(c->d, SL_EPARSE, line, col, "empty column name");
        if (!strcasecmp(name, "f_hz") || !strcasecmp(name, "t_s")) {
            if (k != 0)
                return sl_floor_desc_fail(c->d, SL_EPARSE, line, col,
                                          "column '%s' again (the first column is the only "
                                          "frequency or period column)",
                                          name);
            c->periods = !strcasecmp(name, "t_s");
            c->d->periods = c->periods;
            continue;
        }
        if (k == 0)
            return sl_floor_desc_fail(c->d, SL_EPARSE, line, col,
                                      "first column '%s': it must be 'f_hz' (frequency, Hz) or "
                                      "'T_s' (period, s)",
                                      sl_text_quote(name, strlen(name)).s);
        const char *us = strchr(name, '_');
        int q = -1;
        for (int j = 0; us && j < SL_FLOOR_NCOMP; j++) {
            const char *cn = sl_floor_comp_name((sl_floor_comp)j);
            if ((size_t)(us - name) == strlen(cn) && !strncasecmp(name, cn, strlen(cn)))
                q = j;
        }
        sl_quoted qn = sl_text_quote(name, strlen(name));
        if (q < 0 && bare_damping(name))
            return sl_floor_desc_fail(c->d, SL_EPARSE, line, col,
                                      "column '%s' gives a damping but no direction: a floor "
                                      "file is one file per floor, not per direction; put the "
                                      "H1, H2 and V tables of the floor side by side in one "
                                      "file, the columns named h1_<damping %%>, h2_<damping %%> "
                                      "and v_<damping %%> (e.g. h1_5, h2_5, v_5), or declare "
                                      "'# h2: same_as_h1'",
                                      qn.s);
        if (q < 0)
            return sl_floor_desc_fail(c->d, SL_EPARSE, line, col,
                                      "unknown column '%s' (expected h1_<damping %%>, "
                                      "h2_<damping %%> or v_<damping %%>, e.g. h1_5)",
                                      qn.s);
        double pct;
        if (sl_text_parse_num(us + 1, strlen(us + 1), &pct) != SL_NUM_OK)
            return sl_floor_desc_fail(c->d, SL_EPARSE, line, col,
                                      "column '%s': the damping after '_' must be a number in "
                                      "percent, e.g. %s_5",
                                      qn.s, sl_floor_comp_name((sl_floor_comp)q));
        comp[k] = (sl_floor_comp)q;
        sl_floor_comp_desc *rc = &c->d->comp[q];
        if (!rc->line) {
            rc->line = line;
            rc->f_line = line;
            rc->f_col = 1;
        }
        /* the ratio from the text with the point moved (2.3 -> 2.3e-2), so it is
         * the same double as the INI's 0.023 */
        double ratio = pct / 100;
        char tok[64];
        if (!strpbrk(us + 1, "eEdD") && strlen(us + 1) < sizeof tok - 4) {
            snprintf(tok, sizeof tok, "%se-2", us + 1);
            ratio = strtod(tok, NULL);
        }
        if (!(sa[k] = sl_floor_desc_add_sa(c->d, (sl_floor_comp)q, ratio, name, line, col)))
            return 0;
    }
    if (r->n < 2)
        return sl_floor_desc_fail(c->d, SL_EPARSE, line, 0,
                                  "the header row names no spectrum column (e.g. "
                                  "f_hz,h1_5,h1_10,v_5)");
    return 1;
}

/* One row per frequency: as many cells as header columns, each a number. */
/* The first row under the header names units rather than numbers: its
 * first cell is not a number and some cell reads as a unit ("Hz", "(g)",
 * "[m/s2]", "s"). */
static int units_row(const record *r)
{
    double x;
    const char *c0 = field(r, 0);
    if (!*c0 || sl_text_parse_num(c0, strlen(c0), &x) == SL_NUM_OK)
        return 0;
    for (size_t k = 0; k < r->n; k++) {
        const char *s = field(r, k);
        size_t n = strlen(s);
        while (n > 0 && (*s == '(' || *s == '[' || *s == ' '))
            s++, n--;
        while (n > 0 && (s[n - 1] == ')' || s[n - 1] == ']' || s[n - 1] == ' '))
            n--;
        if ((n == 2 && !strncasecmp(s, "hz", 2)) || (n == 1 && (*s == 's' || *s == 'S')) ||
            (n > 0 && sl_text_unit(s, n) != SL_UNIT_NONE))
            return 1;
    }
    return 0;
}

static int data_row(csv *c, const record *r, size_t ncol, sl_floor_sa_desc **sa, int first)
{
    long line = r->line[0];
    if (r->n != ncol) {
        size_t at = r->n < ncol ? r->n : ncol;
        return sl_floor_desc_fail(c->d, SL_EPARSE, r->line[at < r->n ? at : r->n - 1],
                                  (long)at + 1,
                                  "ragged row: %zu cells, the header row has %zu", r->n, ncol);
    }
    if (first && units_row(r))
        return sl_floor_desc_fail(c->d, SL_EPARSE, line, 1,
                                  "a units row under the header row ('%s', '%s', ...): give the "
                                  "units once, as '# units: g' (or m/s2, cm/s2, gal, mm/s2) "
                                  "above the header row, and delete this row (frequencies are "
                                  "in Hz in column f_hz, periods in s in column T_s)",
                                  sl_text_quote(field(r, 0), strlen(field(r, 0))).s,
                                  sl_text_quote(field(r, 1), strlen(field(r, 1))).s);
    for (size_t k = 0; k < r->n; k++) {
        char *cell = r->buf + r->off[k];
        long col = (long)k + 1;
        const char *key = sa[k] ? sa[k]->key : c->periods ? "T_s" : "f_hz";
        if (!*cell)
            return sl_floor_desc_fail(c->d, SL_EPARSE, r->line[k], col,
                                      "%s: empty cell (every row gives every column a value)",
                                      key);
        if (c->sep == ';' && !sl_text_decimal_comma(cell))
            return fail_decimal(c, key, cell, r->line[k], col);
        double x;
        if (!sl_floor_desc_number(c->d, key, cell, r->line[k], col, &x))
            return 0;
        if (!sa[k] && c->periods) {
            if (x == 0)
                return sl_floor_desc_fail(c->d, SL_EINVAL, r->line[k], col,
                                          "T_s: period 0 s (the zero-period acceleration): give "
                                          "it as '# zpa_h1: <value>' (zpa_h2, zpa_v) lines above "
                                          "the header row and delete this row");
            if (!(x >= 1 / SL_FLOOR_F_MAX_HZ && x <= 1 / SL_FLOOR_F_MIN_HZ))
                return sl_floor_desc_fail(c->d, SL_EINVAL, r->line[k], col,
                                          "T_s: period %g s outside %g-%g s (frequencies "
                                          "%g-%g Hz)",
                                          x, 1 / SL_FLOOR_F_MAX_HZ, 1 / SL_FLOOR_F_MIN_HZ,
                                          SL_FLOOR_F_MIN_HZ, SL_FLOOR_F_MAX_HZ);
        }
        int ok = 1;
        if (sa[k]) {
            ok = sl_floor_desc_push(c->d, &sa[k]->sa, x, r->line[k], col);
        } else {
            for (int q = 0; q < SL_FLOOR_NCOMP && ok; q++)
                if (c->d->comp[q].line)
                    ok = sl_floor_desc_push(c->d, &c->d->comp[q].f, x, line, col);
        }
        if (!ok)
            return 0;
    }
    return 1;
}

/* The separator, from the header row (the first line that is neither
 * blank nor a comment): ';' when it holds ';' and no ',' outside quotes
 * (a European spreadsheet's CSV, with decimal commas), else ','. Both: an
 * error naming the row. */
static int find_separator(csv *c)
{
    c->sep = ',';
    size_t i = 0;
    long line = 1;
    while (i < c->len) {
        size_t e = i;
        while (e < c->len && c->b[e] != '\n' && c->b[e] != '\r')
            e++;
        size_t k = i;
        while (k < e && (c->b[k] == ' ' || c->b[k] == '\t'))
            k++;
        if (k < e && c->b[k] != '#') {
            size_t commas = 0, semis = 0;
            int quoted = 0;
            for (size_t j = k; j < e; j++) {
                quoted ^= c->b[j] == '"';
                commas += !quoted && c->b[j] == ',';
                semis += !quoted && c->b[j] == ';';
            }
            if (commas && semis)
                return sl_floor_desc_fail(c->d, SL_EPARSE, line, 0,
                                          "the header row holds both ',' and ';': separate the "
                                          "columns with one of them (',' with decimal points, "
                                          "or ';' with decimal commas)");
            if (semis)
                c->sep = ';';
            return 1;
        }
        i = e;
        if (i < c->len && c->b[i] == '\r')
            i++;
        if (i < c->len && c->b[i] == '\n')
            i++;
        line++;
    }
    return 1;
}

/* The reverse of a list of values with their places. */
static void reverse(sl_floor_vals *l)
{
    for (size_t i = 0, j = l->n ? l->n - 1 : 0; i < j; i++, j--) {
        double v = l->v[i];
        l->v[i] = l->v[j];
        l->v[j] = v;
        long a = l->line[i];
        l->line[i] = l->line[j];
        l->line[j] = a;
        a = l->col[i];
        l->col[i] = l->col[j];
        l->col[j] = a;
    }
}

/* A T_s table: periods strictly monotone (either way), turned into
 * frequencies 1/T in ascending order, the rows' values with them. */
static int periods_to_frequencies(csv *c)
{
    sl_floor_desc *d = c->d;
    for (int q = 0; q < SL_FLOOR_NCOMP; q++) {
        sl_floor_comp_desc *rc = &d->comp[q];
        sl_floor_vals *f = &rc->f;
        if (!rc->line || f->n < 2)
            continue;
        const int up = f->v[1] > f->v[0];
        for (size_t j = 1; j < f->n; j++)
            if (!(up ? f->v[j] > f->v[j - 1] : f->v[j] < f->v[j - 1]))
                return sl_floor_desc_fail(d, SL_EINVAL, f->line[j], f->col[j],
                                          "T_s: periods must increase (or decrease) strictly: "
                                          "%g after %g",
                                          f->v[j], f->v[j - 1]);
        for (size_t j = 0; j < f->n; j++)
            f->v[j] = 1 / f->v[j];
        if (up) {
            reverse(f);
            for (size_t s = 0; s < rc->nsa; s++)
                reverse(&rc->sa[s].sa);
        }
    }
    return 1;
}

int sl_floor_read_csv(sl_floor_desc *d, sl_text *t)
{
    csv c = {d, t->buf, t->len, 0, 1, ',', 0};
    d->floor_line = 1;
    if (!check_bytes(&c) || !find_separator(&c))
        return 0;
    record r = {0};
    sl_floor_sa_desc **sa = NULL;
    sl_floor_comp *comp = NULL;
    size_t ncol = 0;
    int ok = 1;
    long header_line = 0;
    int first_row = 1;
    while (ok && c.pos < c.len) {
        long line = c.line;
        size_t save = c.pos;
        const char *s;
        size_t n;
        take_line(&c, &s, &n);
        if (blank_line(&c, s, n))
            continue;
        if (s[0] == '#') {
            if (header_line)
                ok = sl_floor_desc_fail(d, SL_EPARSE, line, 0,
                                        "a comment line after the header row (comments and "
                                        "'# key:' lines go before it)");
            else
                ok = comment_line(&c, s, n, line);
            continue;
        }
        c.pos = save; /* a record: parse it from its start (quotes may span lines) */
        c.line = line;
        if (!(ok = read_record(&c, &r)))
            break;
        if (!header_line) {
            header_line = line;
            ncol = r.n;
            sa = calloc(ncol, sizeof *sa);
            comp = calloc(ncol, sizeof *comp);
            if (!sa || !comp)
                ok = sl_floor_desc_fail(d, SL_ENOMEM, line, 0, "out of memory");
            else
                ok = header_row(&c, &r, line, sa, comp);
        } else {
            ok = data_row(&c, &r, ncol, sa, first_row);
            first_row = 0;
        }
    }
    d->eof_line = c.line;
    if (ok && !header_line)
        ok = sl_floor_desc_fail(d, SL_EPARSE, c.line > 1 ? c.line - 1 : 1, 0,
                                "no header row (f_hz,h1_5,...,v_5) and no data");
    if (header_line)
        d->floor_line = header_line; /* where a missing key or column is reported */
    if (ok && c.periods)
        ok = periods_to_frequencies(&c);
    record_free(&r);
    free(sa);
    free(comp);
    return ok;
}
