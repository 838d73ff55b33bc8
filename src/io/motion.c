/*
 * motion.c - read ground-motion records (PEER .AT2, one/two-column text,
 * CSV with a header) into SI acceleration histories, and derive PGA, PGV,
 * PGD, Arias intensity and the 5-75 % significant duration.
 *
 * The reader loads the whole file, walks it line by line (LF, CRLF or CR
 * line ends; a UTF-8 byte-order mark is skipped) and checks every token in
 * full. On any error it frees what it built and fills the error record with
 * the file, the 1-based line of the offending token and the token quoted.
 * See docs/formats.md, section "Ground motions".
 */
#include "io/motion.h"

#include "core/standards.h"

#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

/* Relative tolerance on sample intervals: the steps of a time column
 * against their mean, an explicit dt against the file's, and the dt of the
 * components of a set against each other (dimensionless). */
#define SL_MOTION_DT_REL_TOL 1e-6

/* Factor on the orthogonal component in the 100-40 combination of peak
 * horizontal displacements (dimensionless). */

/* Husid-curve fractions bounding the significant duration D5-75. */
#define SL_MOTION_HUSID_LO 0.05
#define SL_MOTION_HUSID_HI 0.75

/* Longest numeric token accepted, characters (longer ones are rejected). */
#define SL_MOTION_TOKEN_MAX 127

/* Characters of an offending token quoted in an error message. */
#define SL_MOTION_QUOTE_MAX 40

/* Most fields on one line of a column or CSV file. */
#define SL_MOTION_FIELDS_MAX 16


/* Chunk size for reading files, bytes. */
#define SL_MOTION_READ_CHUNK 65536

static const char units_hint[] = "units not given (use --units g|m/s2|cm/s2)";

/* ------------------------------------------------------------------ */
/* Small helpers                                                       */
/* ------------------------------------------------------------------ */

static char *dup_str(const char *s)
{
    size_t n = strlen(s ? s : "");
    char *d = malloc(n + 1);
    if (d) {
        memcpy(d, s ? s : "", n);
        d[n] = '\0';
    }
    return d;
}

static char *dup_mem(const char *s, size_t n)
{
    char *d = malloc(n + 1);
    if (d) {
        memcpy(d, s, n);
        d[n] = '\0';
    }
    return d;
}

static int is_space(char c)
{
    return c == ' ' || c == '\t' || c == '\v' || c == '\f' || c == '\r';
}

static char lower(char c)
{
    return (char)tolower((unsigned char)c);
}

/* Trim blanks at both ends of [*s, *s + *n). */
static void trim(const char **s, size_t *n)
{
    while (*n > 0 && is_space(**s)) {
        (*s)++;
        (*n)--;
    }
    while (*n > 0 && is_space((*s)[*n - 1]))
        (*n)--;
}

/* Case-insensitive search for `needle` in s[0..n); offset or -1. */
static long find_ci(const char *s, size_t n, const char *needle)
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

/* Quote a token for an error message: at most SL_MOTION_QUOTE_MAX
 * characters, non-printable bytes shown as '?'. */
typedef struct quoted {
    char s[SL_MOTION_QUOTE_MAX + 4];
} quoted;

static quoted quote(const char *tok, size_t n)
{
    quoted q;
    size_t k = n > SL_MOTION_QUOTE_MAX ? SL_MOTION_QUOTE_MAX : n;
    for (size_t i = 0; i < k; i++) {
        unsigned char c = (unsigned char)tok[i];
        q.s[i] = (c >= 0x20 && c < 0x7f) ? (char)c : '?';
    }
    if (k < n) {
        memcpy(q.s + k, "...", 4);
    } else {
        q.s[k] = '\0';
    }
    return q;
}

/* Parse a whole token as a finite number. strtod syntax plus a Fortran
 * 'D' exponent; hexadecimal and anything left over are rejected. */
typedef enum num_result { NUM_OK, NUM_BAD, NUM_NONFINITE } num_result;

static num_result parse_num(const char *s, size_t n, double *out)
{
    char buf[SL_MOTION_TOKEN_MAX + 1];
    if (n == 0 || n > SL_MOTION_TOKEN_MAX)
        return NUM_BAD;
    for (size_t i = 0; i < n; i++) {
        char c = s[i];
        if (c == 'x' || c == 'X' || c == '\0' || is_space(c))
            return NUM_BAD;
        buf[i] = (c == 'd' || c == 'D') ? 'E' : c;
    }
    buf[n] = '\0';
    char *end = NULL;
    double v = strtod(buf, &end);
    if (end != buf + n)
        return NUM_BAD;
    if (!isfinite(v))
        return NUM_NONFINITE;
    *out = v;
    return NUM_OK;
}

/* Fill err for a token that parse_num() refused. */
static sl_status token_error(sl_error *err, const char *path, long line,
                             const char *tok, size_t n, num_result r)
{
    quoted q = quote(tok, n);
    if (r == NUM_NONFINITE)
        return sl_error_set(err, SL_EINVAL, path, line, "value '%s' is not finite", q.s);
    return sl_error_set(err, SL_EPARSE, path, line, "non-numeric value '%s'", q.s);
}

/* Map a unit written in a file ("G", "CM/SEC/SEC", "cm/s^2", "gal",
 * "m/s**2", "m/s²") to a unit; SL_UNIT_NONE if not understood. */
static sl_unit unit_from_text(const char *s, size_t n)
{
    char buf[48];
    size_t k = 0;
    for (size_t i = 0; i < n; i++) {
        char c = lower(s[i]);
        if (is_space(c))
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

/* A growable array of doubles. */
typedef struct dvec {
    double *v;
    size_t n, cap;
} dvec;

static int dvec_reserve(dvec *d, size_t cap)
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

static int dvec_push(dvec *d, double x)
{
    if (d->n == d->cap && dvec_reserve(d, d->cap ? 2 * d->cap : 1024) != 0)
        return -1;
    d->v[d->n++] = x;
    return 0;
}

/* A growable array of line numbers. */
typedef struct lvec {
    long *v;
    size_t n, cap;
} lvec;

static int lvec_push(lvec *d, long x)
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

/* ------------------------------------------------------------------ */
/* Text: the file in memory, walked line by line                       */
/* ------------------------------------------------------------------ */

typedef struct text {
    const char *buf;  /* after the byte-order mark */
    size_t len;
    size_t pos;
    long lineno;      /* number of the line last returned (1-based) */
} text;

/* Next line without its line end; 0 at the end of the text. */
static int text_next(text *t, const char **s, size_t *n)
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

/* Blank (only white space) or a comment (first non-blank is '#'). */
static int skip_line(const char *s, size_t n)
{
    size_t i = 0;
    while (i < n && is_space(s[i]))
        i++;
    return i == n || s[i] == '#';
}

/* An acceleration after conversion to SI: finite and within the limit. */
static sl_status check_acc(double si, double raw, sl_unit u, const char *path, long line,
                           sl_error *err)
{
    if (fabs(si) <= SL_MOTION_MAX_ABS_G * SL_G)
        return SL_OK;
    return sl_error_set(err, SL_EINVAL, path, line, "acceleration %g %s is %s %g g in magnitude "
                        "(not a floor or ground motion; check the value and the units)",
                        raw, sl_unit_name(u), isfinite(si) ? "above" : "infinite in SI, above",
                        SL_MOTION_MAX_ABS_G);
}

/* Read a whole file; adds a terminating NUL. */
static sl_status slurp(const char *path, char **out, size_t *len, sl_error *err)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return sl_error_set(err, SL_EIO, path, 0, "cannot open: %s", strerror(errno));
    struct stat st;
    if (fstat(fileno(f), &st) == 0 && S_ISREG(st.st_mode) && st.st_size > SL_MOTION_MAX_BYTES) {
        fclose(f);
        return sl_error_set(err, SL_EINVAL, path, 0, "file of %lld bytes is larger than the "
                            "%ld bytes a motion file may have; not read",
                            (long long)st.st_size, SL_MOTION_MAX_BYTES);
    }
    char *buf = NULL;
    size_t n = 0, cap = 0;
    for (;;) {
        if (cap - n < SL_MOTION_READ_CHUNK + 1) {
            size_t ncap = cap ? 2 * cap : 2 * SL_MOTION_READ_CHUNK;
            char *p = realloc(buf, ncap);
            if (!p) {
                free(buf);
                fclose(f);
                return sl_error_set(err, SL_ENOMEM, path, 0, "out of memory reading the file");
            }
            buf = p;
            cap = ncap;
        }
        size_t got = fread(buf + n, 1, SL_MOTION_READ_CHUNK, f);
        n += got;
        if (got < SL_MOTION_READ_CHUNK) {
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
    *out = buf;
    *len = n;
    return SL_OK;
}

static sl_motion *motion_new(const char *path, const char *label, size_t label_len,
                             double *acc_owned, size_t n, double dt_s)
{
    sl_motion *m = calloc(1, sizeof *m);
    if (!m)
        return NULL;
    m->path = dup_str(path);
    m->label = label ? dup_mem(label, label_len) : dup_str("");
    if (!m->path || !m->label) {
        free(m->path);
        free(m->label);
        free(m);
        return NULL;
    }
    m->n = n;
    m->dt_s = dt_s;
    m->acc_ms2 = acc_owned;
    return m;
}

/* Decide the unit: from the file (`file_u`, SL_UNIT_NONE if the file names
 * none) and the caller (`opt_u`). */
static sl_status resolve_units(sl_unit file_u, sl_unit opt_u, const char *path,
                               long line, sl_unit *out, sl_error *err)
{
    if (file_u != SL_UNIT_NONE && opt_u != SL_UNIT_NONE && file_u != opt_u)
        return sl_error_set(err, SL_EINVAL, path, line,
                            "units %s in the file disagree with the units given (%s)",
                            sl_unit_name(file_u), sl_unit_name(opt_u));
    *out = file_u != SL_UNIT_NONE ? file_u : opt_u;
    if (*out == SL_UNIT_NONE)
        return sl_error_set(err, SL_EINVAL, path, line, "%s", units_hint);
    return SL_OK;
}

/* An explicit dt (opts) must agree with the file's. */
static sl_status check_opt_dt(double opt_dt, double file_dt, const char *path,
                              long line, sl_error *err)
{
    if (opt_dt > 0 && fabs(opt_dt - file_dt) > SL_MOTION_DT_REL_TOL * file_dt)
        return sl_error_set(err, SL_EINVAL, path, line,
                            "dt %.9g s given disagrees with the file's dt %.9g s",
                            opt_dt, file_dt);
    return SL_OK;
}

/* ------------------------------------------------------------------ */
/* PEER .AT2                                                           */
/* ------------------------------------------------------------------ */

/* Line 4 of an AT2 file. Returns 1 with npts and dt set, 0 when the line
 * is not an NPTS/DT line at all, -1 when it is one but malformed (err set). */
static int at2_npts_dt(const char *s, size_t n, long *npts, double *dt,
                       const char *path, long line, sl_error *err)
{
    long at = find_ci(s, n, "NPTS");
    if (at < 0)
        return 0;
    const char *np_tok, *dt_tok;
    size_t np_len, dt_len;
    size_t i = (size_t)at + 4;
    while (i < n && is_space(s[i]))
        i++;
    if (i < n && s[i] == '=') {
        /* NGA-West2: NPTS=   1991, DT=   .0100 SEC, ... */
        i++;
        while (i < n && is_space(s[i]))
            i++;
        np_tok = s + i;
        while (i < n && !is_space(s[i]) && s[i] != ',')
            i++;
        np_len = (size_t)(s + i - np_tok);
        long d = find_ci(s + i, n - i, "DT");
        if (d < 0) {
            sl_error_set(err, SL_EPARSE, path, line, "AT2 header: 'DT=' missing after NPTS");
            return -1;
        }
        i += (size_t)d + 2;
        while (i < n && is_space(s[i]))
            i++;
        if (i >= n || s[i] != '=') {
            sl_error_set(err, SL_EPARSE, path, line, "AT2 header: 'DT=' missing after NPTS");
            return -1;
        }
        i++;
        while (i < n && is_space(s[i]))
            i++;
        dt_tok = s + i;
        while (i < n && !is_space(s[i]) && s[i] != ',')
            i++;
        dt_len = (size_t)(s + i - dt_tok);
        if (dt_len > 3 && find_ci(dt_tok + dt_len - 3, 3, "SEC") == 0)
            dt_len -= 3;
    } else {
        /* older NGA: "  1991   0.0100   NPTS, DT" */
        size_t j = 0;
        while (j < (size_t)at && is_space(s[j]))
            j++;
        np_tok = s + j;
        while (j < (size_t)at && !is_space(s[j]) && s[j] != ',')
            j++;
        np_len = (size_t)(s + j - np_tok);
        while (j < (size_t)at && (is_space(s[j]) || s[j] == ','))
            j++;
        dt_tok = s + j;
        while (j < (size_t)at && !is_space(s[j]) && s[j] != ',')
            j++;
        dt_len = (size_t)(s + j - dt_tok);
        while (j < (size_t)at && (is_space(s[j]) || s[j] == ','))
            j++;
        if (np_len == 0 || dt_len == 0 || j != (size_t)at || find_ci(s + at, n - (size_t)at, "DT") < 0) {
            sl_error_set(err, SL_EPARSE, path, line,
                         "AT2 header: expected 'NPTS= n, DT= dt SEC' or 'n dt NPTS, DT'");
            return -1;
        }
    }
    /* NPTS: a positive decimal integer */
    int digits = np_len > 0;
    for (size_t k = 0; k < np_len; k++)
        digits = digits && isdigit((unsigned char)np_tok[k]);
    if (!digits || np_len > 18) {
        quoted q = quote(np_tok, np_len);
        sl_error_set(err, SL_EPARSE, path, line, "AT2 header: bad NPTS value '%s'", q.s);
        return -1;
    }
    long v = 0;
    for (size_t k = 0; k < np_len; k++) {
        if (v > (LONG_MAX - 9) / 10) {
            quoted q = quote(np_tok, np_len);
            sl_error_set(err, SL_EPARSE, path, line, "AT2 header: bad NPTS value '%s'", q.s);
            return -1;
        }
        v = 10 * v + (np_tok[k] - '0');
    }
    if (v <= 0) {
        sl_error_set(err, SL_EINVAL, path, line, "NPTS %ld must be > 0", v);
        return -1;
    }
    double d = 0;
    num_result r = parse_num(dt_tok, dt_len, &d);
    if (r != NUM_OK) {
        quoted q = quote(dt_tok, dt_len);
        if (r == NUM_NONFINITE)
            sl_error_set(err, SL_EINVAL, path, line, "value '%s' is not finite", q.s);
        else
            sl_error_set(err, SL_EPARSE, path, line, "AT2 header: bad DT value '%s'", q.s);
        return -1;
    }
    if (!(d > 0)) {
        sl_error_set(err, SL_EINVAL, path, line, "dt %g must be > 0", d);
        return -1;
    }
    *npts = v;
    *dt = d;
    return 1;
}

/* Units on line 3: "... IN UNITS OF G", "The units are (g)", "UNITS: G".
 * Sets *u (SL_UNIT_NONE when the line does not mention units); error if it
 * mentions units we cannot read. */
static sl_status at2_units(const char *s, size_t n, sl_unit *u, const char *path,
                           long line, sl_error *err)
{
    *u = SL_UNIT_NONE;
    long at = find_ci(s, n, "UNITS");
    if (at < 0)
        return SL_OK;
    size_t i = (size_t)at + 5;
    while (i < n && (is_space(s[i]) || s[i] == ':' || s[i] == '='))
        i++;
    if (i + 2 <= n && find_ci(s + i, 2, "OF") == 0 && (i + 2 == n || is_space(s[i + 2])))
        i += 2;
    else if (i + 3 <= n && find_ci(s + i, 3, "ARE") == 0 && (i + 3 == n || is_space(s[i + 3])))
        i += 3;
    while (i < n && (is_space(s[i]) || s[i] == '(' || s[i] == '['))
        i++;
    const char *tok = s + i;
    while (i < n && !is_space(s[i]) && s[i] != ',' && s[i] != ';' && s[i] != ')' && s[i] != ']')
        i++;
    size_t len = (size_t)(s + i - tok);
    while (len > 0 && tok[len - 1] == '.')
        len--;
    if (len == 0) {
        quoted q = quote(s, n);
        return sl_error_set(err, SL_EPARSE, path, line,
                            "AT2 header: cannot read the units in '%s'", q.s);
    }
    *u = unit_from_text(tok, len);
    if (*u == SL_UNIT_NONE) {
        quoted q = quote(tok, len);
        return sl_error_set(err, SL_EPARSE, path, line, "AT2 header: unknown units '%s'", q.s);
    }
    return SL_OK;
}

static sl_motion *read_at2(const char *path, text *t, const sl_read_opts *o, sl_error *err)
{
    const char *ln[4];
    size_t ll[4];
    for (int k = 0; k < 4; k++) {
        if (!text_next(t, &ln[k], &ll[k])) {
            sl_error_set(err, SL_EPARSE, path, t->lineno,
                         "truncated AT2 header: %ld line(s), expected 4 "
                         "(title, event/station, units, NPTS/DT)",
                         t->lineno);
            return NULL;
        }
    }
    sl_unit file_u, u;
    if (at2_units(ln[2], ll[2], &file_u, path, 3, err) != SL_OK)
        return NULL;
    if (resolve_units(file_u, o->units, path, 3, &u, err) != SL_OK)
        return NULL;
    long npts = 0;
    double dt = 0;
    int h = at2_npts_dt(ln[3], ll[3], &npts, &dt, path, 4, err);
    if (h < 0)
        return NULL;
    if (h == 0) {
        sl_error_set(err, SL_EPARSE, path, 4,
                     "AT2 header: expected 'NPTS= n, DT= dt SEC' or 'n dt NPTS, DT'");
        return NULL;
    }
    if (check_opt_dt(o->dt_s, dt, path, 4, err) != SL_OK)
        return NULL;

    dvec a = {0};
    /* each value takes at least two bytes (digit and separator) */
    size_t bound = (t->len - t->pos) / 2 + 1;
    size_t want = (size_t)npts < bound ? (size_t)npts : bound;
    if (dvec_reserve(&a, want ? want : 1) != 0) {
        sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
        return NULL;
    }
    double f = sl_unit_to_ms2(u);
    const char *s;
    size_t n;
    while (text_next(t, &s, &n)) {
        if (skip_line(s, n))
            continue;
        size_t i = 0;
        for (;;) {
            while (i < n && is_space(s[i]))
                i++;
            if (i >= n)
                break;
            const char *tok = s + i;
            while (i < n && !is_space(s[i]))
                i++;
            size_t tl = (size_t)(s + i - tok);
            if (a.n == (size_t)npts) {
                quoted q = quote(tok, tl);
                sl_error_set(err, SL_EPARSE, path, t->lineno,
                             "NPTS=%ld but more values follow: extra value '%s'", npts, q.s);
                free(a.v);
                return NULL;
            }
            double x;
            num_result r = parse_num(tok, tl, &x);
            if (r != NUM_OK) {
                token_error(err, path, t->lineno, tok, tl, r);
                free(a.v);
                return NULL;
            }
            if (check_acc(f * x, x, u, path, t->lineno, err)) {
                free(a.v);
                return NULL;
            }
            if (dvec_push(&a, f * x) != 0) {
                sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
                free(a.v);
                return NULL;
            }
        }
    }
    if (a.n < (size_t)npts) {
        sl_error_set(err, SL_EPARSE, path, t->lineno, "truncated: NPTS=%ld but only %zu values",
                     npts, a.n);
        free(a.v);
        return NULL;
    }
    /* label: title line and event/station line */
    const char *t1 = ln[0], *t2 = ln[1];
    size_t n1 = ll[0], n2 = ll[1];
    trim(&t1, &n1);
    trim(&t2, &n2);
    char *label = malloc(n1 + n2 + 3);
    if (!label) {
        free(a.v);
        sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
        return NULL;
    }
    size_t k = 0;
    memcpy(label, t1, n1);
    k += n1;
    if (n1 && n2) {
        memcpy(label + k, "; ", 2);
        k += 2;
    }
    memcpy(label + k, t2, n2);
    k += n2;
    sl_motion *m = motion_new(path, label, k, a.v, a.n, dt);
    free(label);
    if (!m) {
        free(a.v);
        sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
    }
    return m;
}

/* ------------------------------------------------------------------ */
/* Column files: one column, two columns, CSV with a header            */
/* ------------------------------------------------------------------ */

typedef struct field {
    const char *s;
    size_t n;
} field;

/* Split a line into fields: separated by commas (each trimmed, possibly
 * empty) when `comma`, else by runs of white space. Returns the count
 * (which may exceed `max`; only `max` are stored). */
static size_t split(const char *s, size_t n, int comma, field *f, size_t max)
{
    size_t count = 0, i = 0;
    if (comma) {
        for (;;) {
            size_t j = i;
            while (j < n && s[j] != ',')
                j++;
            const char *fs = s + i;
            size_t fn = j - i;
            trim(&fs, &fn);
            if (count < max) {
                f[count].s = fs;
                f[count].n = fn;
            }
            count++;
            if (j >= n)
                break;
            i = j + 1;
        }
        return count;
    }
    for (;;) {
        while (i < n && is_space(s[i]))
            i++;
        if (i >= n)
            break;
        size_t j = i;
        while (j < n && !is_space(s[j]))
            j++;
        if (count < max) {
            f[count].s = s + i;
            f[count].n = j - i;
        }
        count++;
        i = j;
    }
    return count;
}

static int has_char(const char *s, size_t n, char c)
{
    return memchr(s, c, n) != NULL;
}

typedef enum col_kind { COL_TIME, COL_ACC } col_kind;

/* Classify one CSV header name: "time_s", "t (s)", "acc_g", "acc (cm/s2)",
 * "a[m/s2]", "gal", "g". Sets kind and unit (SL_UNIT_NONE when the name
 * gives none). Error for anything else. */
static sl_status csv_column(const field *f, col_kind *kind, sl_unit *u, const char *path,
                            long line, sl_error *err)
{
    const char *s = f->s;
    size_t n = f->n;
    if (n >= 2 && s[0] == '"' && s[n - 1] == '"') {
        s++;
        n -= 2;
        trim(&s, &n);
    }
    quoted q = quote(s, n);
    size_t b = 0;
    while (b < n && isalpha((unsigned char)s[b]))
        b++;
    const char *rest = s + b;
    size_t rn = n - b;
    while (rn > 0 && (is_space(*rest) || *rest == '_' || *rest == '(' || *rest == '[' ||
                      *rest == '-')) {
        rest++;
        rn--;
    }
    while (rn > 0 && (is_space(rest[rn - 1]) || rest[rn - 1] == ')' || rest[rn - 1] == ']'))
        rn--;
    char base[16];
    if (b == 0 || b >= sizeof base)
        goto unknown;
    for (size_t i = 0; i < b; i++)
        base[i] = lower(s[i]);
    base[b] = '\0';
    if (!strcmp(base, "t") || !strcmp(base, "time")) {
        *kind = COL_TIME;
        *u = SL_UNIT_NONE;
        if (rn > 0) {
            char tu[8];
            size_t k = 0;
            for (size_t i = 0; i < rn && k + 1 < sizeof tu; i++)
                tu[k++] = lower(rest[i]);
            tu[k] = '\0';
            if (rn >= sizeof tu || (strcmp(tu, "s") && strcmp(tu, "sec") && strcmp(tu, "seconds")))
                return sl_error_set(err, SL_EPARSE, path, line,
                                    "time column '%s': unit must be seconds (s)", q.s);
        }
        return SL_OK;
    }
    if (!strcmp(base, "a") || !strcmp(base, "acc") || !strcmp(base, "accel") ||
        !strcmp(base, "acceleration")) {
        *kind = COL_ACC;
        *u = SL_UNIT_NONE;
        if (rn > 0) {
            *u = unit_from_text(rest, rn);
            if (*u == SL_UNIT_NONE) {
                quoted qu = quote(rest, rn);
                return sl_error_set(err, SL_EPARSE, path, line,
                                    "unknown units '%s' in column '%s'", qu.s, q.s);
            }
        }
        return SL_OK;
    }
    /* a bare unit name: "g", "gal", "m/s2", "cm/s^2" */
    *u = unit_from_text(s, n);
    if (*u != SL_UNIT_NONE) {
        *kind = COL_ACC;
        return SL_OK;
    }
unknown:
    return sl_error_set(err, SL_EPARSE, path, line,
                        "unknown column '%s' (expected a time column such as 'time_s' "
                        "and one acceleration column such as 'acc_g')",
                        q.s);
}

/* Read a column file from the start of `t`: one column, two columns, or
 * CSV with a header; `fmt` is SL_FORMAT_AUTO (decide from the first
 * non-comment line), ONECOL, TWOCOL or CSV. */
static sl_motion *read_columns(const char *path, text *t, sl_format fmt,
                               const sl_read_opts *o, sl_error *err)
{
    const char *s = NULL;
    size_t n = 0;
    int found = 0;
    while (text_next(t, &s, &n)) {
        if (!skip_line(s, n)) {
            found = 1;
            break;
        }
    }
    if (!found) {
        sl_error_set(err, SL_EPARSE, path, t->lineno, "no data");
        return NULL;
    }
    long first_line = t->lineno;
    int comma = has_char(s, n, ',');
    field f[SL_MOTION_FIELDS_MAX];
    size_t nf = split(s, n, comma, f, SL_MOTION_FIELDS_MAX);
    if (nf > SL_MOTION_FIELDS_MAX) {
        sl_error_set(err, SL_EPARSE, path, first_line, "too many fields (%zu)", nf);
        return NULL;
    }
    int all_numeric = 1;
    for (size_t k = 0; k < nf; k++) {
        double x;
        if (parse_num(f[k].s, f[k].n, &x) == NUM_BAD)
            all_numeric = 0;
    }
    int header = 0;
    if (fmt == SL_FORMAT_CSV) {
        if (!comma || all_numeric) {
            sl_error_set(err, SL_EPARSE, path, first_line,
                         "CSV header expected (a time column and an acceleration column, "
                         "e.g. 'time_s,acc_g')");
            return NULL;
        }
        header = 1;
    } else if (fmt == SL_FORMAT_AUTO) {
        int letter = 0;
        for (size_t k = 0; k < n; k++)
            letter = letter || isalpha((unsigned char)s[k]);
        header = comma && letter && !all_numeric;
    }

    /* column layout */
    long t_col = -1, a_col = -1;
    size_t ncols = nf;
    sl_unit file_u = SL_UNIT_NONE;
    if (header) {
        for (size_t k = 0; k < nf; k++) {
            col_kind kind = COL_ACC;
            sl_unit cu = SL_UNIT_NONE;
            if (csv_column(&f[k], &kind, &cu, path, first_line, err) != SL_OK)
                return NULL;
            if (kind == COL_TIME) {
                if (t_col >= 0) {
                    sl_error_set(err, SL_EPARSE, path, first_line, "more than one time column");
                    return NULL;
                }
                t_col = (long)k;
            } else {
                if (a_col >= 0) {
                    sl_error_set(err, SL_EPARSE, path, first_line,
                                 "more than one acceleration column");
                    return NULL;
                }
                a_col = (long)k;
                file_u = cu;
            }
        }
        if (a_col < 0 || t_col < 0) {
            sl_error_set(err, SL_EPARSE, path, first_line, "no %s column in the CSV header",
                         a_col < 0 ? "acceleration" : "time");
            return NULL;
        }
    } else {
        size_t want = fmt == SL_FORMAT_ONECOL ? 1 : fmt == SL_FORMAT_TWOCOL ? 2 : nf;
        if (fmt == SL_FORMAT_AUTO && nf != 1 && nf != 2) {
            sl_error_set(err, SL_EPARSE, path, first_line,
                         "cannot tell the format: %zu fields (expected an AT2 header, "
                         "a CSV header, or 1 or 2 numeric columns)",
                         nf);
            return NULL;
        }
        ncols = want;
        t_col = want == 2 ? 0 : -1;
        a_col = want == 2 ? 1 : 0;
    }

    sl_unit u;
    if (resolve_units(file_u, o->units, path, header ? first_line : 0, &u, err) != SL_OK)
        return NULL;
    if (t_col < 0 && !(o->dt_s > 0)) {
        sl_error_set(err, SL_EINVAL, path, 0,
                     "dt not given for a file without a time column (use --dt)");
        return NULL;
    }

    dvec a = {0}, tv = {0};
    lvec lines = {0};
    sl_motion *m = NULL;
    double fac = sl_unit_to_ms2(u);
    int have = !header; /* the first line holds data */
    for (;;) {
        if (!have) {
            if (!text_next(t, &s, &n))
                break;
            if (skip_line(s, n))
                continue;
        }
        have = 0;
        long line = t->lineno;
        nf = split(s, n, comma, f, SL_MOTION_FIELDS_MAX);
        if (nf != ncols) {
            sl_error_set(err, SL_EPARSE, path, line, "expected %zu field%s, found %zu", ncols,
                         ncols == 1 ? "" : "s", nf);
            goto fail;
        }
        for (size_t k = 0; k < nf; k++) {
            double x;
            num_result r = parse_num(f[k].s, f[k].n, &x);
            if (r != NUM_OK) {
                if (f[k].n == 0)
                    sl_error_set(err, SL_EPARSE, path, line, "empty field %zu", k + 1);
                else
                    token_error(err, path, line, f[k].s, f[k].n, r);
                goto fail;
            }
            int bad = 0;
            if ((long)k == a_col && check_acc(fac * x, x, u, path, line, err))
                goto fail;
            if ((long)k == t_col && !(fabs(x) <= SL_MOTION_MAX_TIME_S)) {
                sl_error_set(err, SL_EINVAL, path, line, "time %g s outside +-%g s", x,
                             SL_MOTION_MAX_TIME_S);
                goto fail;
            }
            if ((long)k == a_col)
                bad = dvec_push(&a, fac * x);
            else if ((long)k == t_col)
                bad = dvec_push(&tv, x) || lvec_push(&lines, line);
            if (bad) {
                sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
                goto fail;
            }
        }
    }
    if (a.n == 0) {
        sl_error_set(err, SL_EPARSE, path, t->lineno, "no data");
        goto fail;
    }
    double dt = o->dt_s;
    if (t_col >= 0) {
        if (a.n < 2) {
            sl_error_set(err, SL_EPARSE, path, lines.v[0],
                         "need at least 2 samples to get dt from the time column");
            goto fail;
        }
        for (size_t i = 1; i < tv.n; i++) {
            if (!(tv.v[i] > tv.v[i - 1])) {
                sl_error_set(err, SL_EINVAL, path, lines.v[i],
                             "time %.9g s does not increase (previous %.9g s): "
                             "dt must be > 0",
                             tv.v[i], tv.v[i - 1]);
                goto fail;
            }
        }
        /* every step against the first, so the line of a jump is named;
         * then dt is the mean step, the most accurate value */
        double h0 = tv.v[1] - tv.v[0];
        for (size_t i = 2; i < tv.n; i++) {
            double h = tv.v[i] - tv.v[i - 1];
            if (fabs(h - h0) > SL_MOTION_DT_REL_TOL * h0) {
                sl_error_set(err, SL_EINVAL, path, lines.v[i],
                             "non-uniform time column: step %.9g s to t = %.9g s differs "
                             "from the first step %.9g s by more than %g relative",
                             h, tv.v[i], h0, SL_MOTION_DT_REL_TOL);
                goto fail;
            }
        }
        dt = (tv.v[tv.n - 1] - tv.v[0]) / (double)(tv.n - 1);
        if (check_opt_dt(o->dt_s, dt, path, 0, err) != SL_OK)
            goto fail;
    }
    {
        const char *base = strrchr(path, '/');
        base = base ? base + 1 : path;
        m = motion_new(path, base, strlen(base), a.v, a.n, dt);
    }
    if (!m) {
        sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
        goto fail;
    }
    free(tv.v);
    free(lines.v);
    return m;
fail:
    free(a.v);
    free(tv.v);
    free(lines.v);
    return NULL;
}

/* ------------------------------------------------------------------ */
/* Public: reading                                                     */
/* ------------------------------------------------------------------ */

static int ext_is_at2(const char *path)
{
    size_t n = strlen(path);
    return n >= 4 && path[n - 4] == '.' && find_ci(path + n - 3, 3, "AT2") == 0;
}

sl_motion *sl_motion_read(const char *path, const sl_read_opts *opts, sl_error *err)
{
    sl_read_opts o = {0};
    if (opts)
        o = *opts;
    sl_error_clear(err);
    if (!path) {
        sl_error_set(err, SL_EINVAL, NULL, 0, "no file name given");
        return NULL;
    }
    if ((int)o.format < SL_FORMAT_AUTO || o.format > SL_FORMAT_CSV) {
        sl_error_set(err, SL_EINVAL, path, 0, "unknown format code %d", (int)o.format);
        return NULL;
    }
    if ((int)o.units < SL_UNIT_NONE || o.units > SL_UNIT_MMS2) {
        sl_error_set(err, SL_EINVAL, path, 0, "unknown units code %d", (int)o.units);
        return NULL;
    }
    if (o.dt_s != 0 && !(o.dt_s > 0 && isfinite(o.dt_s))) {
        sl_error_set(err, SL_EINVAL, path, 0, "dt %g must be > 0", o.dt_s);
        return NULL;
    }

    char *buf = NULL;
    size_t len = 0;
    if (slurp(path, &buf, &len, err) != SL_OK)
        return NULL;
    text t = {buf, len, 0, 0};
    if (len >= 3 && !memcmp(buf, "\xef\xbb\xbf", 3)) {
        t.buf += 3;
        t.len -= 3;
    }
    if (t.len == 0) {
        free(buf);
        sl_error_set(err, SL_EPARSE, path, 0, "empty file");
        return NULL;
    }

    sl_format fmt = o.format;
    if (fmt == SL_FORMAT_AUTO) {
        if (ext_is_at2(path)) {
            fmt = SL_FORMAT_AT2;
        } else {
            /* AT2 when line 4 is an NPTS/DT line */
            text probe = t;
            const char *s = NULL;
            size_t n = 0;
            int k = 0;
            while (k < 4 && text_next(&probe, &s, &n))
                k++;
            if (k == 4 && find_ci(s, n, "NPTS") >= 0)
                fmt = SL_FORMAT_AT2;
        }
    }
    sl_motion *m = fmt == SL_FORMAT_AT2 ? read_at2(path, &t, &o, err)
                                        : read_columns(path, &t, fmt, &o, err);
    free(buf);
    return m;
}

sl_motion *sl_motion_from_array(const double *acc_ms2, size_t n, double dt_s,
                                const char *label)
{
    if (!acc_ms2 || n == 0 || !(dt_s > 0) || !isfinite(dt_s) || n > SIZE_MAX / sizeof(double))
        return NULL;
    double *a = malloc(n * sizeof *a);
    if (!a)
        return NULL;
    memcpy(a, acc_ms2, n * sizeof *a);
    sl_motion *m = motion_new("", label ? label : "", label ? strlen(label) : 0, a, n, dt_s);
    if (!m)
        free(a);
    return m;
}

sl_motion *sl_motion_copy(const sl_motion *m)
{
    if (!m || !m->acc_ms2 || m->n == 0)
        return NULL;
    sl_motion *c = sl_motion_from_array(m->acc_ms2, m->n, m->dt_s, m->label);
    if (!c)
        return NULL;
    char *p = dup_str(m->path);
    if (!p) {
        sl_motion_free(c);
        return NULL;
    }
    free(c->path);
    c->path = p;
    return c;
}

void sl_motion_free(sl_motion *m)
{
    if (!m)
        return;
    free(m->path);
    free(m->label);
    free(m->acc_ms2);
    free(m);
}

/* ------------------------------------------------------------------ */
/* Derived quantities                                                  */
/* ------------------------------------------------------------------ */

double sl_motion_pga(const sl_motion *m)
{
    double p = 0;
    if (!m)
        return 0;
    for (size_t i = 0; i < m->n; i++) {
        double x = fabs(m->acc_ms2[i]);
        if (x > p)
            p = x;
    }
    return p;
}

/* Exact integration of piecewise-linear acceleration from rest; peaks of
 * |v| and |d| over the samples. Either history pointer may be NULL. */
static void integrate(const sl_motion *m, double *vel, double *disp, double *pgv, double *pgd)
{
    double v = 0, d = 0, pv = 0, pd = 0;
    if (!m || m->n == 0) {
        *pgv = *pgd = 0;
        return;
    }
    const double dt = m->dt_s;
    const double *a = m->acc_ms2;
    if (vel)
        vel[0] = 0;
    if (disp)
        disp[0] = 0;
    for (size_t i = 0; i + 1 < m->n; i++) {
        d += dt * v + dt * dt * (2 * a[i] + a[i + 1]) / 6;
        v += dt * (a[i] + a[i + 1]) / 2;
        if (vel)
            vel[i + 1] = v;
        if (disp)
            disp[i + 1] = d;
        if (fabs(v) > pv)
            pv = fabs(v);
        if (fabs(d) > pd)
            pd = fabs(d);
    }
    *pgv = pv;
    *pgd = pd;
}

double sl_motion_pgv(const sl_motion *m)
{
    double pv, pd;
    integrate(m, NULL, NULL, &pv, &pd);
    return pv;
}

double sl_motion_pgd(const sl_motion *m)
{
    double pv, pd;
    integrate(m, NULL, NULL, &pv, &pd);
    return pd;
}

void sl_motion_integrate(const sl_motion *m, double *vel_ms, double *disp_m)
{
    double pv, pd;
    integrate(m, vel_ms, disp_m, &pv, &pd);
}

/* Integral of a^2 over step i for linear a: dt/3 (a_i^2 + a_i a_{i+1} + a_{i+1}^2). */
static double step_a2(const double *a, size_t i, double dt)
{
    return dt / 3 * (a[i] * a[i] + a[i] * a[i + 1] + a[i + 1] * a[i + 1]);
}

double sl_motion_arias(const sl_motion *m)
{
    if (!m)
        return 0;
    double s = 0;
    for (size_t i = 0; i + 1 < m->n; i++)
        s += step_a2(m->acc_ms2, i, m->dt_s);
    return SL_PI / (2 * SL_G) * s;
}

/* Time at which the Husid curve reaches the fraction p of the total
 * (linear interpolation between samples). */
static double husid_time(const sl_motion *m, double total, double p)
{
    double c = 0, target = p * total;
    for (size_t i = 0; i + 1 < m->n; i++) {
        double inc = step_a2(m->acc_ms2, i, m->dt_s);
        if (c + inc >= target && inc > 0)
            return m->dt_s * ((double)i + (target - c) / inc);
        c += inc;
    }
    return m->dt_s * (double)(m->n - 1);
}

double sl_motion_d5_75(const sl_motion *m)
{
    if (!m || m->n < 2)
        return 0;
    double total = 0;
    for (size_t i = 0; i + 1 < m->n; i++)
        total += step_a2(m->acc_ms2, i, m->dt_s);
    if (!(total > 0))
        return 0;
    return husid_time(m, total, SL_MOTION_HUSID_HI) - husid_time(m, total, SL_MOTION_HUSID_LO);
}

void sl_motion_scale(sl_motion *m, double s)
{
    if (!m)
        return;
    for (size_t i = 0; i < m->n; i++)
        m->acc_ms2[i] *= s;
}

/* ------------------------------------------------------------------ */
/* Sets                                                                */
/* ------------------------------------------------------------------ */

static const char *comp_name(const sl_motion *m)
{
    if (m->path && m->path[0])
        return m->path;
    if (m->label && m->label[0])
        return m->label;
    return "(unnamed)";
}

int sl_motion_name_is_vertical(const char *path)
{
    const char *b = strrchr(path, '/');
    b = b ? b + 1 : path;
    size_t n = strlen(b);
    const char *dot = strrchr(b, '.');
    if (dot)
        n = (size_t)(dot - b);
    static const char *const tails[] = {"UP", "DWN", "DOWN", "VER", "VRT", "-V", "-Z", "_Z", "_V"};
    for (size_t k = 0; k < sizeof tails / sizeof tails[0]; k++) {
        size_t m = strlen(tails[k]);
        if (n >= m && !strncasecmp(b + n - m, tails[k], m))
            return 1;
    }
    return 0;
}

sl_status sl_set_check_fit(sl_set *set, int truncate, sl_set_fit *fit, sl_error *err)
{
    sl_error_clear(err);
    if (fit)
        memset(fit, 0, sizeof *fit);
    if (!set || !set->h1)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "component H1 missing");
    sl_motion *c[3] = {set->h1, set->h2, set->v};
    static const char *const tag[3] = {"H1", "H2", "V"};
    size_t nmin = SIZE_MAX, nmax = 0;
    for (int k = 0; k < 3; k++) {
        if (!c[k])
            continue;
        if (!c[k]->acc_ms2 || c[k]->n == 0)
            return sl_error_set(err, SL_EINVAL, c[k]->path, 0, "%s '%s' has no samples",
                                tag[k], comp_name(c[k]));
        if (!(c[k]->dt_s > 0) || !isfinite(c[k]->dt_s))
            return sl_error_set(err, SL_EINVAL, c[k]->path, 0, "%s '%s': dt %g must be > 0",
                                tag[k], comp_name(c[k]), c[k]->dt_s);
        if (c[k]->n < nmin)
            nmin = c[k]->n;
        if (c[k]->n > nmax)
            nmax = c[k]->n;
    }
    for (int k = 1; k < 3; k++) {
        if (!c[k])
            continue;
        double d0 = c[0]->dt_s, dk = c[k]->dt_s;
        if (fabs(dk - d0) > SL_MOTION_DT_REL_TOL * fmax(d0, dk))
            return sl_error_set(err, SL_EINVAL, NULL, 0,
                                "components have different dt: H1 '%s' dt %.9g s, "
                                "%s '%s' dt %.9g s (must agree within %g relative)",
                                comp_name(c[0]), d0, tag[k], comp_name(c[k]), dk,
                                SL_MOTION_DT_REL_TOL);
    }
    for (int k = 0; k < 3; k++) {
        if (!c[k])
            continue;
        for (size_t i = 0; i < c[k]->n; i++) {
            if (!isfinite(c[k]->acc_ms2[i]))
                return sl_error_set(err, SL_EINVAL, c[k]->path, 0,
                                    "%s '%s': sample %zu (t = %.9g s) is not finite", tag[k],
                                    comp_name(c[k]), i + 1, (double)i * c[k]->dt_s);
        }
    }
    const size_t n = truncate ? nmin : nmax;
    /* pad: grow every short component first, so a failure leaves the set as it was */
    for (int k = 0; k < 3 && !truncate; k++) {
        if (!c[k] || c[k]->n == n)
            continue;
        double *p = realloc(c[k]->acc_ms2, n * sizeof *p);
        if (!p)
            return sl_error_set(err, SL_ENOMEM, c[k]->path, 0, "%s '%s': out of memory padding",
                                tag[k], comp_name(c[k]));
        c[k]->acc_ms2 = p;
    }
    for (int k = 0; k < 3; k++) {
        if (!c[k])
            continue;
        if (fit) {
            fit->n_in[k] = c[k]->n;
            fit->changed |= (c[k]->n != n);
        }
        for (size_t i = c[k]->n; i < n; i++)
            c[k]->acc_ms2[i] = 0.0; /* the ground at rest after its record */
        c[k]->n = n;
        c[k]->dt_s = c[0]->dt_s;
    }
    if (fit) {
        fit->n = n;
        fit->truncated = truncate != 0;
    }
    return SL_OK;
}

sl_status sl_set_check(sl_set *set, int truncate, sl_error *err)
{
    return sl_set_check_fit(set, truncate, NULL, err);
}

double sl_set_pga_h(const sl_set *set)
{
    if (!set)
        return 0;
    return fmax(sl_motion_pga(set->h1), sl_motion_pga(set->h2));
}

double sl_set_scale_pga_h(sl_set *set, double pga_ms2)
{
    double pga = sl_set_pga_h(set);
    if (!(pga > 0))
        return 0;
    double s = pga_ms2 / pga;
    sl_motion *m[3] = {set->h1, set->h2, set->v};
    for (int q = 0; q < 3; q++)
        if (m[q])
            sl_motion_scale(m[q], s);
    return s;
}

double sl_set_pgd_100_40(const sl_set *set)
{
    if (!set || !set->h1)
        return 0;
    double p1 = sl_motion_pgd(set->h1);
    if (!set->h2)
        return p1;
    double p2 = sl_motion_pgd(set->h2);
    return fmax(p1 + SL_COMB_100_40 * p2, p2 + SL_COMB_100_40 * p1);
}
