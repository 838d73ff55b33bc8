/*
 * at2.c - the PEER NGA .AT2 reader (io/motion_read.h): both header layouts
 * of line 4 (NGA-West2 "NPTS=  1991, DT=   .0100 SEC" and older NGA
 * "  1991   0.0100   NPTS, DT"), the units of line 3, then exactly NPTS
 * values. See docs/formats.md.
 */
#include "io/motion_read.h"

#include <ctype.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Line 4 of an AT2 file. Returns 1 with npts and dt set, 0 when the line
 * is not an NPTS/DT line at all, -1 when it is one but malformed (err set). */
static int at2_npts_dt(const char *s, size_t n, long *npts, double *dt,
                       const char *path, long line, sl_error *err)
{
    long at = sl_text_find_ci(s, n, "NPTS");
    if (at < 0)
        return 0;
    const char *np_tok, *dt_tok;
    size_t np_len, dt_len;
    size_t i = (size_t)at + 4;
    while (i < n && sl_text_is_space(s[i]))
        i++;
    if (i < n && s[i] == '=') {
        /* NGA-West2: NPTS=   1991, DT=   .0100 SEC, ... */
        i++;
        while (i < n && sl_text_is_space(s[i]))
            i++;
        np_tok = s + i;
        while (i < n && !sl_text_is_space(s[i]) && s[i] != ',')
            i++;
        np_len = (size_t)(s + i - np_tok);
        long d = sl_text_find_ci(s + i, n - i, "DT");
        if (d < 0) {
            sl_error_set(err, SL_EPARSE, path, line, "AT2 header: 'DT=' missing after NPTS");
            return -1;
        }
        i += (size_t)d + 2;
        while (i < n && sl_text_is_space(s[i]))
            i++;
        if (i >= n || s[i] != '=') {
            sl_error_set(err, SL_EPARSE, path, line, "AT2 header: 'DT=' missing after NPTS");
            return -1;
        }
        i++;
        while (i < n && sl_text_is_space(s[i]))
            i++;
        dt_tok = s + i;
        while (i < n && !sl_text_is_space(s[i]) && s[i] != ',')
            i++;
        dt_len = (size_t)(s + i - dt_tok);
        if (dt_len > 3 && sl_text_find_ci(dt_tok + dt_len - 3, 3, "SEC") == 0)
            dt_len -= 3;
    } else {
        /* older NGA: "  1991   0.0100   NPTS, DT" */
        size_t j = 0;
        while (j < (size_t)at && sl_text_is_space(s[j]))
            j++;
        np_tok = s + j;
        while (j < (size_t)at && !sl_text_is_space(s[j]) && s[j] != ',')
            j++;
        np_len = (size_t)(s + j - np_tok);
        while (j < (size_t)at && (sl_text_is_space(s[j]) || s[j] == ','))
            j++;
        dt_tok = s + j;
        while (j < (size_t)at && !sl_text_is_space(s[j]) && s[j] != ',')
            j++;
        dt_len = (size_t)(s + j - dt_tok);
        while (j < (size_t)at && (sl_text_is_space(s[j]) || s[j] == ','))
            j++;
        if (np_len == 0 || dt_len == 0 || j != (size_t)at || sl_text_find_ci(s + at, n - (size_t)at, "DT") < 0) {
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
        sl_quoted q = sl_text_quote(np_tok, np_len);
        sl_error_set(err, SL_EPARSE, path, line, "AT2 header: bad NPTS value '%s'", q.s);
        return -1;
    }
    long v = 0;
    for (size_t k = 0; k < np_len; k++) {
        if (v > (LONG_MAX - 9) / 10) {
            sl_quoted q = sl_text_quote(np_tok, np_len);
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
    sl_num_result r = sl_text_parse_num(dt_tok, dt_len, &d);
    if (r != SL_NUM_OK) {
        sl_quoted q = sl_text_quote(dt_tok, dt_len);
        if (r == SL_NUM_NONFINITE)
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
    long at = sl_text_find_ci(s, n, "UNITS");
    if (at < 0)
        return SL_OK;
    size_t i = (size_t)at + 5;
    while (i < n && (sl_text_is_space(s[i]) || s[i] == ':' || s[i] == '='))
        i++;
    if (i + 2 <= n && sl_text_find_ci(s + i, 2, "OF") == 0 && (i + 2 == n || sl_text_is_space(s[i + 2])))
        i += 2;
    else if (i + 3 <= n && sl_text_find_ci(s + i, 3, "ARE") == 0 && (i + 3 == n || sl_text_is_space(s[i + 3])))
        i += 3;
    while (i < n && (sl_text_is_space(s[i]) || s[i] == '(' || s[i] == '['))
        i++;
    const char *tok = s + i;
    while (i < n && !sl_text_is_space(s[i]) && s[i] != ',' && s[i] != ';' && s[i] != ')' && s[i] != ']')
        i++;
    size_t len = (size_t)(s + i - tok);
    while (len > 0 && tok[len - 1] == '.')
        len--;
    if (len == 0) {
        sl_quoted q = sl_text_quote(s, n);
        return sl_error_set(err, SL_EPARSE, path, line,
                            "AT2 header: cannot read the units in '%s'", q.s);
    }
    *u = sl_text_unit(tok, len);
    if (*u == SL_UNIT_NONE) {
        sl_quoted q = sl_text_quote(tok, len);
        return sl_error_set(err, SL_EPARSE, path, line, "AT2 header: unknown units '%s'", q.s);
    }
    return SL_OK;
}

sl_motion *sl_motion_read_at2(const char *path, sl_text *t, const sl_read_opts *o,
                              sl_error *err)
{
    const char *ln[4];
    size_t ll[4];
    for (int k = 0; k < 4; k++) {
        if (!sl_text_next(t, &ln[k], &ll[k])) {
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
    if (sl_motion_resolve_units(file_u, o->units, path, 3, &u, err) != SL_OK)
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
    if (sl_motion_check_opt_dt(o->dt_s, dt, path, 4, err) != SL_OK)
        return NULL;

    sl_dvec a = {0};
    /* each value takes at least two bytes (digit and separator) */
    size_t bound = (t->len - t->pos) / 2 + 1;
    size_t want = (size_t)npts < bound ? (size_t)npts : bound;
    if (sl_dvec_reserve(&a, want ? want : 1) != 0) {
        sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
        return NULL;
    }
    double f = sl_unit_to_ms2(u);
    const char *s;
    size_t n;
    while (sl_text_next(t, &s, &n)) {
        if (sl_text_skip_line(s, n))
            continue;
        size_t i = 0;
        for (;;) {
            while (i < n && sl_text_is_space(s[i]))
                i++;
            if (i >= n)
                break;
            const char *tok = s + i;
            while (i < n && !sl_text_is_space(s[i]))
                i++;
            size_t tl = (size_t)(s + i - tok);
            if (a.n == (size_t)npts) {
                sl_quoted q = sl_text_quote(tok, tl);
                sl_error_set(err, SL_EPARSE, path, t->lineno,
                             "NPTS=%ld but more values follow: extra value '%s'", npts, q.s);
                free(a.v);
                return NULL;
            }
            double x;
            sl_num_result r = sl_text_parse_num(tok, tl, &x);
            if (r != SL_NUM_OK) {
                sl_text_token_error(err, path, t->lineno, tok, tl, r);
                free(a.v);
                return NULL;
            }
            if (sl_motion_check_acc(f * x, x, u, path, t->lineno, err)) {
                free(a.v);
                return NULL;
            }
            if (sl_dvec_push(&a, f * x) != 0) {
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
    sl_text_trim(&t1, &n1);
    sl_text_trim(&t2, &n2);
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
    sl_motion *m = sl_motion_new_owned(path, label, k, a.v, a.n, dt);
    free(label);
    if (!m) {
        free(a.v);
        sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
    }
    return m;
}
