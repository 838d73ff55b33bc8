/* formats.c - GeoNet V2A, CSMIP V2 and CWA .acc readers (formats.h). */
#include "io/formats.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "core/units.h"
#include "io/text.h"

/* A file as NUL-terminated lines (CR stripped); line k is 1-based k+1. */
typedef struct lines {
    char *buf;
    char **l;
    size_t n;
} lines;

static void lines_free(lines *t)
{
    free(t->buf);
    free(t->l);
    memset(t, 0, sizeof *t);
}

/* The file through the shared loader (io/text.h), cut into lines. */
static sl_status lines_read(const char *path, lines *t, sl_error *err)
{
    memset(t, 0, sizeof *t);
    sl_text tx;
    const sl_text_opts to = {SL_MOTION_MAX_BYTES, "a motion file", NULL, 0};
    sl_status st = sl_text_load(path, &to, &tx, err);
    if (st != SL_OK)
        return st;
    t->buf = tx.mem; /* freed by lines_free; the lines start after the byte-order mark */
    size_t nl = 1;
    for (size_t i = 0; i < tx.len; i++)
        nl += tx.buf[i] == '\n';
    t->l = malloc(nl * sizeof *t->l);
    if (!t->l) {
        lines_free(t);
        return sl_error_set(err, SL_ENOMEM, path, 0, "out of memory reading the file");
    }
    char *p = tx.mem + (tx.buf - tx.mem);
    while (*p) {
        char *nlp = strchr(p, '\n');
        t->l[t->n++] = p;
        if (!nlp)
            break;
        *nlp = '\0';
        if (nlp > p && nlp[-1] == '\r')
            nlp[-1] = '\0';
        p = nlp + 1;
    }
    return SL_OK;
}

static int starts_ci(const char *s, const char *prefix)
{
    while (*s == ' ')
        s++;
    return !strncasecmp(s, prefix, strlen(prefix));
}

/* Copy a trimmed component name. */
static void set_comp(char *dst, const char *s, size_t n)
{
    while (n && isspace((unsigned char)*s)) {
        s++;
        n--;
    }
    while (n && isspace((unsigned char)s[n - 1]))
        n--;
    if (n >= SL_COMP_NAME_MAX)
        n = SL_COMP_NAME_MAX - 1;
    memcpy(dst, s, n);
    dst[n] = '\0';
}

int sl_formats_is_v2a(const char *first_line)
{
    return first_line && starts_ci(first_line, "Corrected accelerogram") &&
           !sl_text_find_str_ci(first_line, "Chan");
}

int sl_formats_is_csmip_v2(const char *first_line)
{
    return first_line && starts_ci(first_line, "Corrected accelerogram") &&
           sl_text_find_str_ci(first_line, "Chan") != NULL;
}

int sl_component_is_vertical(const char *comp)
{
    static const char *const v[] = {"UP", "Z", "V", "VER", "VERT", "VERTICAL", "DOWN", "DWN"};
    char c[SL_COMP_NAME_MAX];
    set_comp(c, comp, strlen(comp));
    for (size_t k = 0; k < sizeof v / sizeof v[0]; k++)
        if (!strcasecmp(c, v[k]))
            return 1;
    return 0;
}

/* Read `npts` fixed-width fields (`per` a line, `width` columns each) from
 * line index `first` on; values in unit u are converted to m/s^2 into a.
 * Blank trailing fields of the last line are allowed. */
static sl_status read_fixed(const lines *t, size_t first, size_t npts, int per, int width,
                            sl_unit u, const char *path, double *a, sl_error *err)
{
    const double f = sl_unit_to_ms2(u);
    const double amax = SL_MOTION_MAX_ABS_G * SL_G;
    size_t k = 0;
    for (size_t li = first; k < npts; li++) {
        if (li >= t->n)
            return sl_error_set(err, SL_EPARSE, path, (long)li,
                                "file ends after %zu of %zu acceleration values", k, npts);
        const char *s = t->l[li];
        const size_t len = strlen(s);
        for (int j = 0; j < per && k < npts; j++) {
            const size_t at = (size_t)j * (size_t)width;
            char fld[64];
            size_t w = at < len ? len - at : 0;
            if (w > (size_t)width)
                w = (size_t)width;
            memcpy(fld, s + (at < len ? at : len), w);
            fld[w] = '\0';
            char *end;
            errno = 0;
            double x = strtod(fld, &end);
            while (*end == ' ')
                end++;
            if (end == fld || *end != '\0' || errno == ERANGE)
                return sl_error_set(err, SL_EPARSE, path, (long)li + 1,
                                    "value %zu of %zu: non-numeric field '%s' (columns %zu-%zu)",
                                    k + 1, npts, fld, at + 1, at + (size_t)width);
            const double si = x * f;
            if (!isfinite(si) || fabs(si) > amax)
                return sl_error_set(err, SL_EINVAL, path, (long)li + 1,
                                    "acceleration %g %s is more than %g g in magnitude", x,
                                    sl_unit_name(u), SL_MOTION_MAX_ABS_G);
            a[k++] = si;
        }
    }
    return SL_OK;
}

/* Turn a parsed block into a motion owned by c. */
static sl_status add_channel(sl_channels *c, const char *path, double *a, size_t npts,
                             double dt, const char *comp, long line, sl_error *err)
{
    if (c->n >= SL_CHANNELS_MAX)
        return sl_error_set(err, SL_EPARSE, path, line, "more than %d channels",
                            SL_CHANNELS_MAX);
    sl_motion *m = sl_motion_from_array(a, npts, dt, comp);
    char *p = m ? malloc(strlen(path) + 1) : NULL;
    if (!p) {
        sl_motion_free(m);
        return sl_error_set(err, SL_ENOMEM, path, line, "out of memory");
    }
    strcpy(p, path);
    free(m->path);
    m->path = p;
    set_comp(c->comp[c->n], comp, strlen(comp));
    c->m[c->n++] = m;
    return SL_OK;
}

static sl_status check_npts_dt(long npts, double dt, const char *path, long line, sl_error *err)
{
    if (npts <= 0 || npts > SL_MOTION_MAX_BYTES / 4)
        return sl_error_set(err, SL_EINVAL, path, line, "number of points %ld out of range",
                            npts);
    if (!(dt > 0) || !isfinite(dt) || dt > 10)
        return sl_error_set(err, SL_EINVAL, path, line, "sample interval %g s out of range",
                            dt);
    return SL_OK;
}

/* GeoNet V2A: one channel starting at line index s. *next = first index
 * after its acceleration block. */
static sl_status v2a_channel(const lines *t, size_t s, const char *path, sl_channels *c,
                             size_t *next, sl_error *err)
{
    enum { TEXT = 16, INTS = 4, REALS = 6, PER = 10, WIDTH = 8 };
    if (s + TEXT + INTS + REALS > t->n)
        return sl_error_set(err, SL_EPARSE, path, (long)t->n,
                            "V2A header of the channel at line %zu is cut short", s + 1);
    long npts = -1, npl = 0, dtl = 0, cl = 0, ul = 0;
    double dt = 0;
    char comp[SL_COMP_NAME_MAX] = "";
    sl_unit u = SL_UNIT_NONE;
    for (size_t i = s; i < s + TEXT; i++) {
        const char *l = t->l[i], *p;
        if ((p = sl_text_find_str_ci(l, "Number of points")) != NULL) {
            npl = (long)i + 1;
            if (sscanf(p + 16, "%ld", &npts) != 1)
                return sl_error_set(err, SL_EPARSE, path, npl, "bad number of points in '%s'", l);
        } else if ((p = sl_text_find_str_ci(l, "data at")) != NULL) {
            dtl = (long)i + 1;
            if (sscanf(p + 7, "%lf", &dt) != 1)
                return sl_error_set(err, SL_EPARSE, path, dtl, "bad sample interval in '%s'", l);
        } else if (starts_ci(l, "Component")) {
            cl = (long)i + 1;
            const char *q = l + strspn(l, " ") + 9;
            q += strspn(q, " ");
            set_comp(comp, q, strcspn(q, " "));
        } else if (starts_ci(l, "Acceleration:")) {
            ul = (long)i + 1;
            /* "Acceleration:  peak  -41.6 mm/s/s at 43.68 sec ..." */
            const char *q = sl_text_find_str_ci(l, "peak");
            double pk;
            char unit[32];
            if (!q || sscanf(q + 4, "%lf %31s", &pk, unit) != 2)
                return sl_error_set(err, SL_EPARSE, path, ul, "no peak and unit in '%s'", l);
            if (!strcasecmp(unit, "mm/s/s") || !strcasecmp(unit, "mm/s2"))
                u = SL_UNIT_MMS2;
            else
                return sl_error_set(err, SL_EINVAL, path, ul,
                                    "V2A acceleration unit '%s' (expected mm/s/s)", unit);
        }
    }
    if (!npl || !dtl || !cl || !ul)
        return sl_error_set(err, SL_EPARSE, path, (long)s + 1,
                            "V2A channel header lacks %s", !npl ? "'Number of points'"
                            : !dtl ? "'data at ... sec intervals'"
                            : !cl ? "'Component'" : "the 'Acceleration:' line");
    sl_status st = check_npts_dt(npts, dt, path, npl, err);
    if (st != SL_OK)
        return st;
    /* the integer header's 4th line repeats npts in fields 4-6 (10I8) */
    long ih[10];
    const char *il = t->l[s + TEXT + 3];
    if (sscanf(il, "%ld %ld %ld %ld", &ih[0], &ih[1], &ih[2], &ih[3]) != 4 || ih[3] != npts)
        return sl_error_set(err, SL_EPARSE, path, (long)(s + TEXT + 4),
                            "integer header '%s' does not repeat the %ld points", il, npts);
    double *a = malloc((size_t)npts * sizeof *a);
    if (!a)
        return sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
    const size_t first = s + TEXT + INTS + REALS;
    st = read_fixed(t, first, (size_t)npts, PER, WIDTH, u, path, a, err);
    if (st == SL_OK)
        st = add_channel(c, path, a, (size_t)npts, dt, comp, (long)s + 1, err);
    free(a);
    *next = first + ((size_t)npts + PER - 1) / PER;
    return st;
}

/* A CSMIP unit text: "cm/sec2", "cm/sec/sec", "g" ... */
static sl_unit csmip_unit(const char *s, size_t n)
{
    char u[32];
    if (n >= sizeof u)
        return SL_UNIT_NONE;
    memcpy(u, s, n);
    u[n] = '\0';
    if (!strcasecmp(u, "cm/sec2") || !strcasecmp(u, "cm/sec/sec") || !strcasecmp(u, "cm/s2") ||
        !strcasecmp(u, "cm/s/s") || !strcasecmp(u, "gal"))
        return SL_UNIT_CMS2;
    if (!strcasecmp(u, "g"))
        return SL_UNIT_G;
    if (!strcasecmp(u, "mm/sec2") || !strcasecmp(u, "mm/sec/sec"))
        return SL_UNIT_MMS2;
    return SL_UNIT_NONE;
}

/* CSMIP V2: the channel whose header starts at line index s. */
static sl_status csmip_channel(const lines *t, size_t s, size_t end, const char *path,
                               sl_channels *c, sl_error *err)
{
    char comp[SL_COMP_NAME_MAX] = "";
    size_t ai = 0;
    int have_comp = 0;
    for (size_t i = s + 1; i < end; i++) {
        const char *l = t->l[i];
        if (!have_comp && starts_ci(l, "Chan")) {
            const char *q = strchr(l, ':');
            if (q) {
                set_comp(comp, q + 1, strlen(q + 1));
                have_comp = 1;
            }
        }
        if (sl_text_find_str_ci(l, "points of accel data")) {
            ai = i;
            break;
        }
    }
    if (!ai)
        return sl_error_set(err, SL_EPARSE, path, (long)s + 1,
                            "CSMIP channel without a 'points of accel data' line");
    if (!have_comp)
        return sl_error_set(err, SL_EPARSE, path, (long)s + 1,
                            "CSMIP channel without a 'Chan k: NAME' line");
    const char *l = t->l[ai];
    const long line = (long)ai + 1;
    long npts;
    double dt;
    const char *p = sl_text_find_str_ci(l, "spaced at");
    if (sscanf(l, "%ld", &npts) != 1 || !p || sscanf(p + 9, "%lf", &dt) != 1)
        return sl_error_set(err, SL_EPARSE, path, line, "bad points or interval in '%s'", l);
    sl_status st = check_npts_dt(npts, dt, path, line, err);
    if (st != SL_OK)
        return st;
    /* unit: "..., in cm/sec2. (8f10.6)" or "(UNITS: CM/SEC/SEC)" */
    sl_unit u = SL_UNIT_NONE;
    const char *q;
    if ((q = sl_text_find_str_ci(l, "UNITS:")) != NULL) {
        q += 6;
        q += strspn(q, " ");
        u = csmip_unit(q, strcspn(q, ") "));
    } else if ((q = sl_text_find_str_ci(p, ", in ")) != NULL) {
        q += 5;
        size_t n = strcspn(q, " ");
        if (n && q[n - 1] == '.')
            n--;
        u = csmip_unit(q, n);
    }
    if (u == SL_UNIT_NONE)
        return sl_error_set(err, SL_EINVAL, path, line, "unknown or missing unit in '%s'", l);
    int per = 8, width = 10;
    if ((q = strchr(l, '(')) != NULL && !sl_text_find_str_ci(q, "UNITS")) {
        int dec;
        if (sscanf(q, "(%d%*[fFeE]%d.%d)", &per, &width, &dec) != 3 || per < 1 || per > 20 ||
            width < 2 || width > 40)
            return sl_error_set(err, SL_EPARSE, path, line, "bad data format in '%s'", q);
    }
    double *a = malloc((size_t)npts * sizeof *a);
    if (!a)
        return sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
    st = read_fixed(t, ai + 1, (size_t)npts, per, width, u, path, a, err);
    if (st == SL_OK)
        st = add_channel(c, path, a, (size_t)npts, dt, comp, (long)s + 1, err);
    free(a);
    return st;
}

sl_status sl_channels_read(const char *path, sl_channels *out, sl_error *err)
{
    memset(out, 0, sizeof *out);
    lines t;
    sl_status st = lines_read(path, &t, err);
    if (st != SL_OK)
        return st;
    const int v2a = t.n && sl_formats_is_v2a(t.l[0]);
    const int csmip = t.n && sl_formats_is_csmip_v2(t.l[0]);
    if (!v2a && !csmip) {
        st = sl_error_set(err, SL_EPARSE, path, 1,
                          "not a GeoNet V2A or CSMIP V2 file (first line '%.60s')",
                          t.n ? t.l[0] : "");
    } else if (v2a) {
        size_t i = 0;
        while (st == SL_OK && i < t.n) {
            if (starts_ci(t.l[i], "Corrected accelerogram")) {
                st = v2a_channel(&t, i, path, out, &i, err);
            } else {
                i++;
            }
        }
    } else {
        for (size_t i = 0; st == SL_OK && i < t.n; i++) {
            if (!starts_ci(t.l[i], "Corrected accelerogram"))
                continue;
            size_t end = i + 1;
            while (end < t.n && !starts_ci(t.l[end], "Corrected accelerogram"))
                end++;
            st = csmip_channel(&t, i, end, path, out, err);
            i = end - 1;
        }
    }
    lines_free(&t);
    if (st == SL_OK && out->n == 0)
        st = sl_error_set(err, SL_EPARSE, path, 0, "no channels");
    if (st != SL_OK)
        sl_channels_free(out);
    return st;
}

void sl_channels_free(sl_channels *c)
{
    if (!c)
        return;
    for (size_t k = 0; k < c->n; k++)
        sl_motion_free(c->m[k]);
    memset(c, 0, sizeof *c);
}

sl_motion *sl_smc_read(const char *path, char *comp, size_t compn, sl_error *err)
{
    enum { TEXT = 11, INT_LINES = 6, INT_PER = 8, REAL_LINES = 10 };
    lines t;
    if (lines_read(path, &t, err) != SL_OK)
        return NULL;
    sl_motion *m = NULL;
    double *a = NULL;
    if (t.n < TEXT + INT_LINES + REAL_LINES || !starts_ci(t.l[0], "2 CORRECTED ACCELEROGRAM")) {
        sl_error_set(err, SL_EPARSE, path, 1,
                     "not an SMC corrected accelerogram (line 1 '%.40s', %zu lines)",
                     t.n ? t.l[0] : "", t.n);
        goto done;
    }
    /* the component: text line 6 "... component=    360" or "... component=   up" */
    const char *c = sl_text_find_str_ci(t.l[5], "component=");
    if (!c) {
        sl_error_set(err, SL_EPARSE, path, 6, "no 'component=' in '%s'", t.l[5]);
        goto done;
    }
    c += 10;
    c += strspn(c, " ");
    char cbuf[SL_COMP_NAME_MAX];
    set_comp(cbuf, c, strcspn(c, " "));
    if (comp && compn) {
        strncpy(comp, cbuf, compn - 1);
        comp[compn - 1] = '\0';
    }
    /* integer header: 48 values 8I10; field 16 = comment lines, 17 = npts */
    long ih[INT_LINES * INT_PER];
    for (int i = 0; i < INT_LINES; i++) {
        const char *l = t.l[TEXT + i];
        if (sscanf(l, "%ld %ld %ld %ld %ld %ld %ld %ld", &ih[i * 8], &ih[i * 8 + 1],
                   &ih[i * 8 + 2], &ih[i * 8 + 3], &ih[i * 8 + 4], &ih[i * 8 + 5],
                   &ih[i * 8 + 6], &ih[i * 8 + 7]) != 8) {
            sl_error_set(err, SL_EPARSE, path, TEXT + i + 1, "bad integer header line '%s'", l);
            goto done;
        }
    }
    const long ncomment = ih[15], npts = ih[16];
    /* real header: 50 values 5E15.7; field 2 = samples per second */
    double sps;
    if (sscanf(t.l[TEXT + INT_LINES], "%*f %lf", &sps) != 1 || !(sps > 0)) {
        sl_error_set(err, SL_EPARSE, path, TEXT + INT_LINES + 1,
                     "bad sampling rate (field 2) in '%s'", t.l[TEXT + INT_LINES]);
        goto done;
    }
    if (check_npts_dt(npts, 1.0 / sps, path, TEXT + 3, err) != SL_OK)
        goto done;
    if (ncomment < 0 || ncomment > 10000) {
        sl_error_set(err, SL_EPARSE, path, TEXT + 2, "comment line count %ld", ncomment);
        goto done;
    }
    a = malloc((size_t)npts * sizeof *a);
    if (!a) {
        sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
        goto done;
    }
    /* data: 8E10.4, corrected acceleration in cm/s/s (the SMC convention) */
    if (read_fixed(&t, TEXT + INT_LINES + REAL_LINES + (size_t)ncomment, (size_t)npts, 8, 10,
                   SL_UNIT_CMS2, path, a, err) != SL_OK)
        goto done;
    m = sl_motion_from_array(a, (size_t)npts, 1.0 / sps, cbuf);
    char *pp = m ? malloc(strlen(path) + 1) : NULL;
    if (!pp) {
        sl_motion_free(m);
        m = NULL;
        sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
        goto done;
    }
    strcpy(pp, path);
    free(m->path);
    m->path = pp;
done:
    free(a);
    lines_free(&t);
    return m;
}

sl_motion *sl_cwa_acc_read(const char *path, sl_error *err)
{
    sl_read_opts ro;
    memset(&ro, 0, sizeof ro);
    ro.format = SL_FORMAT_TWOCOL;
    ro.units = SL_UNIT_MS2; /* the distribution's unit (no header) */
    return sl_motion_read(path, &ro, err);
}
