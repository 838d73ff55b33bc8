/* floor.c - floor response spectrum files (see floor.h): loading (the
 * format by extension, the file through io/text.h), the one checking path
 * every reader's description goes through (floor_desc.h), and the floor's
 * accessors and folder listing. */
#include "io/floor_desc.h"

#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

/* The value `h2 = same_as_h1` declares H2 equal to H1. */
#define FLOOR_SAME_AS_H1 "same_as_h1"
/* The units a floor file may name (for messages). */
#define FLOOR_UNITS_LIST "g, m/s2, cm/s2, gal or mm/s2"

static const char *const comp_names[SL_FLOOR_NCOMP] = {"h1", "h2", "v"};

const char *sl_floor_comp_name(sl_floor_comp c)
{
    return (unsigned)c < SL_FLOOR_NCOMP ? comp_names[c] : "?";
}

/* Keys of a floor, declared once: INI [floor] keys and CSV
 * "# key:" lines. */
const char *const sl_floor_key_names[SL_FK_COUNT] = {
    [SL_FK_NAME] = "name",         /* the floor's name (required) */
    [SL_FK_ELEV] = "elevation_m",  /* elevation, m (optional) */
    [SL_FK_UNITS] = "units",       /* units of all spectral values (required) */
    [SL_FK_H2] = "h2",             /* 'same_as_h1' when H2 is not given */
    [SL_FK_DESC] = "description",  /* free text (optional) */
    [SL_FK_SEED] = "seed",         /* the floor's own seed, integer >= 0 (optional) */
    [SL_FK_BUILDING] = "building", /* the building, free text (optional) */
};

sl_floor_key sl_floor_desc_key(const char *name)
{
    for (int i = 0; i < SL_FK_COUNT; i++)
        if (!strcmp(name, sl_floor_key_names[i]))
            return (sl_floor_key)i;
    return SL_FK_COUNT;
}

/* ---- the description ---------------------------------------------- */

void sl_floor_desc_init(sl_floor_desc *d, const char *path, sl_floor_format fmt,
                        sl_error *err)
{
    memset(d, 0, sizeof *d);
    d->path = path;
    d->format = fmt;
    d->err = err;
    d->elevation_m = NAN;
}

static void vals_free(sl_floor_vals *l)
{
    free(l->v);
    free(l->line);
    free(l->col);
    memset(l, 0, sizeof *l);
}

void sl_floor_desc_free(sl_floor_desc *d)
{
    for (int k = 0; k < SL_FK_COUNT; k++)
        free(d->text[k]);
    for (int k = 0; k < SL_FLOOR_NCOMP; k++) {
        vals_free(&d->comp[k].f);
        for (size_t s = 0; s < SL_FLOOR_MAX_DAMPINGS; s++)
            vals_free(&d->comp[k].sa[s].sa);
    }
    memset(d->text, 0, sizeof d->text);
}

static int vfail(sl_floor_desc *d, int earliest, sl_status code, long line, long col,
                 const char *fmt, va_list ap)
{
    if (d->failed && !(earliest && line > 0 &&
                       (line < d->fail_line || (line == d->fail_line && col < d->fail_col))))
        return 0;
    char msg[900];
    vsnprintf(msg, sizeof msg, fmt, ap);
    sl_error_set_at(d->err, code, d->path, line, col, "%s", msg);
    d->failed = 1;
    d->fail_line = line;
    d->fail_col = col;
    return 0;
}

int sl_floor_desc_fail(sl_floor_desc *d, sl_status code, long line, long col, const char *fmt,
                       ...)
{
    va_list ap;
    va_start(ap, fmt);
    vfail(d, 0, code, line, col, fmt, ap);
    va_end(ap);
    return 0;
}

/* As sl_floor_desc_fail(), but an error earlier in the file replaces a
 * later one: the value checks run over the whole description and report
 * what a reader meets first. */
static int fail_first(sl_floor_desc *d, sl_status code, long line, long col, const char *fmt,
                      ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 5, 6)))
#endif
    ;

static int fail_first(sl_floor_desc *d, sl_status code, long line, long col, const char *fmt,
                      ...)
{
    va_list ap;
    va_start(ap, fmt);
    vfail(d, 1, code, line, col, fmt, ap);
    va_end(ap);
    return 0;
}

int sl_floor_desc_number(sl_floor_desc *d, const char *key, const char *tok, long line,
                         long col, double *out)
{
    char *end;
    errno = 0;
    double v = *tok ? strtod(tok, &end) : 0;
    if (!*tok || errno == ERANGE || *end || !isfinite(v)) {
        sl_quoted q = sl_text_quote(tok, strlen(tok));
        return sl_floor_desc_fail(d, SL_EPARSE, line, col, "%s: '%s' is not a finite number",
                                  key, q.s);
    }
    *out = v;
    return 1;
}

int sl_floor_desc_push(sl_floor_desc *d, sl_floor_vals *l, double x, long line, long col)
{
    if (l->n == l->cap) {
        size_t cap = l->cap ? 2 * l->cap : 32;
        double *v = realloc(l->v, cap * sizeof *v);
        if (v)
            l->v = v;
        long *ln = realloc(l->line, cap * sizeof *ln);
        if (ln)
            l->line = ln;
        long *cl = realloc(l->col, cap * sizeof *cl);
        if (cl)
            l->col = cl;
        if (!v || !ln || !cl)
            return sl_floor_desc_fail(d, SL_ENOMEM, line, col, "out of memory");
        l->cap = cap;
    }
    l->v[l->n] = x;
    l->line[l->n] = line;
    l->col[l->n] = col;
    l->n++;
    return 1;
}

/* "line L" or "line L, column C" for a message about an earlier place. */
typedef struct where {
    char s[64];
} where;

static where place(long line, long col)
{
    where w;
    if (col > 0)
        snprintf(w.s, sizeof w.s, "line %ld, column %ld", line, col);
    else
        snprintf(w.s, sizeof w.s, "line %ld", line);
    return w;
}

int sl_floor_desc_set(sl_floor_desc *d, sl_floor_key k, const char *value, long line,
                      long col)
{
    const char *name = sl_floor_key_names[k];
    if (d->key_line[k])
        return sl_floor_desc_fail(d, SL_EPARSE, line, col, "key '%s' repeated (first at %s)",
                                  name, place(d->key_line[k], d->key_col[k]).s);
    d->key_line[k] = line;
    d->key_col[k] = col;
    if (!(d->text[k] = strdup(value)))
        return sl_floor_desc_fail(d, SL_ENOMEM, line, col, "out of memory");
    switch (k) {
    case SL_FK_SEED: {
        char *end;
        errno = 0;
        d->seed = strtoull(value, &end, 10);
        if (!*value || *value == '-' || *value == '+' || *end || errno)
            return sl_floor_desc_fail(d, SL_EPARSE, line, col,
                                      "seed: '%s' is not an integer from 0 to "
                                      "18446744073709551615",
                                      value);
        return 1;
    }
    case SL_FK_ELEV:
        return sl_floor_desc_number(d, "elevation_m", value, line, col, &d->elevation_m);
    case SL_FK_H2:
        if (strcmp(value, FLOOR_SAME_AS_H1))
            return sl_floor_desc_fail(d, SL_EINVAL, line, col,
                                      "h2 = '%s': the only value is '" FLOOR_SAME_AS_H1
                                      "' (or give %s)",
                                      value, d->format == SL_FLOOR_CSV ? "h2_<damping> columns"
                                                                       : "a [h2] section");
        return 1;
    default:
        return 1; /* name, units, description, building: checked in finish */
    }
}

sl_floor_sa_desc *sl_floor_desc_add_sa(sl_floor_desc *d, sl_floor_comp c, double damping,
                                       const char *key, long line, long col)
{
    sl_floor_comp_desc *rc = &d->comp[c];
    if (rc->nsa == SL_FLOOR_MAX_DAMPINGS) {
        sl_floor_desc_fail(d, SL_EINVAL, line, col, "%s: more than %d damping ratios for %s",
                           key, SL_FLOOR_MAX_DAMPINGS, comp_names[c]);
        return NULL;
    }
    sl_floor_sa_desc *s = &rc->sa[rc->nsa++];
    s->damping = damping;
    if (d->format == SL_FLOOR_INI)
        snprintf(s->key, sizeof s->key, "sa_%g", damping);
    else
        snprintf(s->key, sizeof s->key, "%s", key);
    s->line = line;
    s->col = col;
    return s;
}

int sl_floor_desc_set_zpa(sl_floor_desc *d, sl_floor_comp c, const char *key, const char *tok,
                          long line, long col)
{
    sl_floor_comp_desc *rc = &d->comp[c];
    if (rc->zpa_line)
        return sl_floor_desc_fail(d, SL_EPARSE, line, col, "key '%s' repeated (first at %s)",
                                  key, place(rc->zpa_line, rc->zpa_col).s);
    rc->zpa_line = line;
    rc->zpa_col = col;
    snprintf(rc->zpa_key, sizeof rc->zpa_key, "%s", key);
    return sl_floor_desc_number(d, key, tok, line, col, &rc->zpa);
}

/* ---- plausibility ratios (floor.h, SL_FLOOR_SPIKE_MAX ...) ----------- */

/* v[j] over the larger of its neighbours (at an end: its one neighbour). */
static double spike_ratio(const double *v, size_t n, size_t j)
{
    double nb = j == 0 ? v[1] : j == n - 1 ? v[n - 2] : fmax(v[j - 1], v[j + 1]);
    return v[j] / nb;
}

/* The value the trend of a table's two values next to an end gives at the
 * end's frequency (j = 0 or n - 1; n >= 3): the straight line in log SA
 * over log f through them, extended, e.g. at the last frequency
 * v[n-2] (v[n-2] / v[n-3])^(ln(f[n-1] / f[n-2]) / ln(f[n-2] / f[n-3])). */
static double end_trend(const double *f, const double *v, size_t n, size_t j)
{
    size_t a = j == 0 ? 1 : n - 2, b = j == 0 ? 2 : n - 3; /* next, and next but one */
    return v[a] * pow(v[a] / v[b], log(f[j] / f[a]) / log(f[a] / f[b]));
}

/* The smaller neighbour of v[j] over v[j]. At an end, whose other neighbour
 * is missing, the smaller of its one neighbour and the trend (end_trend)
 * stands for the pair: a value far below both is a slip, as inside the
 * table, while a steep but steady slope is not. 0 for a table of 2 values. */
static double dip_ratio(const double *f, const double *v, size_t n, size_t j)
{
    if (j > 0 && j < n - 1)
        return fmin(v[j - 1], v[j + 1]) / v[j];
    if (n < 3)
        return 0.0;
    return fmin(v[j == 0 ? 1 : n - 2], end_trend(f, v, n, j)) / v[j];
}

/* SA(lower damping z_lo) / SA(higher damping z_hi), over z_hi / z_lo. */
static double spread_ratio(double sa_lo, double z_lo, double sa_hi, double z_hi)
{
    return sa_lo / sa_hi / (z_hi / z_lo);
}

/* The geometric mean over n frequencies of lo[j] / hi[j]. */
static double order_mean(const double *lo, const double *hi, size_t n)
{
    double sum = 0.0;
    for (size_t j = 0; j < n; j++)
        sum += log(lo[j] / hi[j]);
    return exp(sum / (double)n);
}

/* Keep x as the worst (i: which ratio) when it is worse than *w. */
static void worst(sl_floor_plausibility *p, int i, double *w, double x, int lower_is_worse,
                  int k, const sl_spectrum *a, size_t j)
{
    if (lower_is_worse ? x < *w : x > *w) {
        *w = x;
        p->at_comp[i] = k;
        p->at_f_hz[i] = a->f_hz[j];
        p->at_damping[i] = a->damping;
    }
}

void sl_floor_plausibility_of(const sl_floor *fl, sl_floor_plausibility *p)
{
    memset(p, 0, sizeof *p);
    p->order = INFINITY;
    p->order_mean = INFINITY;
    p->end_step_lo = p->end_step_hi = 1.0;
    for (int k = 0; k < SL_FLOOR_NCOMP; k++) {
        const sl_floor_component *c = &fl->comp[k];
        for (size_t s = 0; s < c->nspec; s++) {
            const sl_spectrum *a = &c->spec[s];
            for (size_t q = s + 1; q < c->nspec; q++)
                worst(p, 4, &p->order_mean, order_mean(a->sa_ms2, c->spec[q].sa_ms2, a->n), 1, k,
                      a, 0);
            const size_t n = a->n;
            if (n >= 3 && a->f_hz[n - 2] >= SL_FLOOR_RIGID_HZ) {
                double r = a->sa_ms2[n - 1] / a->sa_ms2[n - 2];
                worst(p, 6, &p->end_step_lo, r, 1, k, a, n - 1);
                worst(p, 7, &p->end_step_hi, r, 0, k, a, n - 1);
            }
            for (size_t j = 0; a->n >= 2 && j < a->n; j++) {
                worst(p, 0, &p->spike, spike_ratio(a->sa_ms2, a->n, j), 0, k, a, j);
                worst(p, j ? 1 : 5, j ? &p->dip : &p->dip_first,
                      dip_ratio(a->f_hz, a->sa_ms2, a->n, j), 0, k, a, j);
                for (size_t q = s + 1; q < c->nspec; q++) { /* ascending damping */
                    const sl_spectrum *b = &c->spec[q];
                    worst(p, 2, &p->order, a->sa_ms2[j] / b->sa_ms2[j], 1, k, a, j);
                    worst(p, 3, &p->spread,
                          spread_ratio(a->sa_ms2[j], a->damping, b->sa_ms2[j], b->damping), 0, k,
                          a, j);
                }
            }
        }
    }
}

/* ---- the checks (one path for every format) ------------------------- */

/* H2 is given as its own spectra (INI [h2], CSV h2_ columns). */
static int h2_given(const sl_floor_desc *d)
{
    return d->comp[SL_FLOOR_H2].line != 0;
}

/* Values, each where it stands; the earliest error in the file wins. */
static void check_values(sl_floor_desc *d)
{
    const int csv = d->format == SL_FLOOR_CSV;
    if (d->key_line[SL_FK_NAME] && !d->text[SL_FK_NAME][0])
        fail_first(d, SL_EINVAL, d->key_line[SL_FK_NAME], d->key_col[SL_FK_NAME],
                   "name is empty");
    if (d->key_line[SL_FK_UNITS] && sl_unit_parse(d->text[SL_FK_UNITS]) == SL_UNIT_NONE)
        fail_first(d, SL_EINVAL, d->key_line[SL_FK_UNITS], d->key_col[SL_FK_UNITS],
                   "unknown units '%s' (expected " FLOOR_UNITS_LIST ")", d->text[SL_FK_UNITS]);
    for (int k = 0; k < SL_FLOOR_NCOMP; k++) {
        const sl_floor_comp_desc *rc = &d->comp[k];
        const sl_floor_vals *f = &rc->f;
        for (size_t j = 0; j < f->n; j++) {
            double x = f->v[j];
            if (!(x > 0))
                fail_first(d, SL_EINVAL, f->line[j], f->col[j],
                           "f_hz: frequency %g must be positive", x);
            else if (x < SL_FLOOR_F_MIN_HZ || x > SL_FLOOR_F_MAX_HZ)
                fail_first(d, SL_EINVAL, f->line[j], f->col[j],
                           "f_hz: frequency %g Hz outside %g-%g Hz", x, SL_FLOOR_F_MIN_HZ,
                           SL_FLOOR_F_MAX_HZ);
            else if (j > 0 && !(x > f->v[j - 1]))
                fail_first(d, SL_EINVAL, f->line[j], f->col[j],
                           "f_hz: frequencies must increase strictly: %g after %g", x,
                           f->v[j - 1]);
        }
        for (size_t s = 0; s < rc->nsa; s++) {
            const sl_floor_sa_desc *sa = &rc->sa[s];
            if (!(sa->damping > 0 && sa->damping < 1)) {
                if (csv)
                    fail_first(d, SL_EINVAL, sa->line, sa->col,
                               "%s: damping %g %% outside (0, 100) %%", sa->key,
                               100 * sa->damping);
                else
                    fail_first(d, SL_EINVAL, sa->line, sa->col,
                               "%s: damping %g outside (0, 1)", sa->key, sa->damping);
            }
            for (size_t q = 0; q < s; q++)
                if (fabs(rc->sa[q].damping - sa->damping) <= SL_FLOOR_DAMPING_TOL)
                    fail_first(d, SL_EPARSE, sa->line, sa->col,
                               "[%s] damping %g%s given twice (first at %s)", comp_names[k],
                               csv ? 100 * sa->damping : sa->damping, csv ? " %" : "",
                               place(rc->sa[q].line, rc->sa[q].col).s);
            for (size_t j = 0; j < sa->sa.n; j++)
                if (!(sa->sa.v[j] > 0))
                    fail_first(d, SL_EINVAL, sa->sa.line[j], sa->sa.col[j],
                               "%s: value %g must be positive", sa->key, sa->sa.v[j]);
        }
        if (rc->zpa_line && !(rc->zpa > 0))
            fail_first(d, SL_EINVAL, rc->zpa_line, rc->zpa_col, "%s: value %g must be positive",
                       rc->zpa_key, rc->zpa);
    }
}

/* What must be there: keys, directions, spectra, sizes. */
static int check_complete(sl_floor_desc *d)
{
    const int csv = d->format == SL_FLOOR_CSV;
    long eof = d->eof_line > 0 ? d->eof_line : 1;
    long top = d->floor_line;
    if (!csv && !d->floor_line)
        return sl_floor_desc_fail(d, SL_EPARSE, eof, 0, "missing section [floor]");
    if (!d->key_line[SL_FK_NAME])
        return sl_floor_desc_fail(d, SL_EPARSE, top, 0,
                                  csv ? "no '# name: ...' line before the header row"
                                      : "[floor] has no 'name'");
    if (!d->key_line[SL_FK_UNITS])
        return sl_floor_desc_fail(d, SL_EPARSE, top, 0,
                                  csv ? "no '# units: ...' line before the header row ("
                                        FLOOR_UNITS_LIST ")"
                                      : "[floor] has no 'units' (" FLOOR_UNITS_LIST ")");
    long h2l = d->key_line[SL_FK_H2];
    const sl_floor_comp_desc *h2 = &d->comp[SL_FLOOR_H2];
    if (h2l && h2_given(d))
        return sl_floor_desc_fail(d, SL_EPARSE, h2l, d->key_col[SL_FK_H2],
                                  csv ? "'# h2: " FLOOR_SAME_AS_H1 "' and h2_ columns (line "
                                        "%ld): give one"
                                      : "'h2 = " FLOOR_SAME_AS_H1 "' and a [h2] section (line "
                                        "%ld): give one",
                                  h2->line);
    if (h2l && h2->zpa_line)
        return sl_floor_desc_fail(d, SL_EPARSE, h2->zpa_line, h2->zpa_col,
                                  "%s given but H2 is declared the same as H1", h2->zpa_key);
    if (!h2l && !h2_given(d))
        return sl_floor_desc_fail(d, SL_EPARSE, top, 0,
                                  csv ? "H2 not given: add h2_<damping> columns or declare "
                                        "'# h2: " FLOOR_SAME_AS_H1 "'"
                                      : "H2 not given: add a [h2] section or declare 'h2 = "
                                        FLOOR_SAME_AS_H1 "' in [floor]");
    for (int k = 0; k < SL_FLOOR_NCOMP; k++) {
        const sl_floor_comp_desc *rc = &d->comp[k];
        if (k == SL_FLOOR_H2 && h2l)
            continue;
        if (!rc->line) {
            if (csv)
                return sl_floor_desc_fail(d, SL_EPARSE, top, 0,
                                          "no %s_<damping> column in the header row",
                                          comp_names[k]);
            return sl_floor_desc_fail(d, SL_EPARSE, eof, 0, "missing section [%s]",
                                      comp_names[k]);
        }
        if (!rc->f_line)
            return sl_floor_desc_fail(d, SL_EPARSE, rc->line, 0, "[%s] has no 'f_hz'",
                                      comp_names[k]);
        if (rc->f.n < SL_FLOOR_MIN_POINTS)
            return sl_floor_desc_fail(d, SL_EINVAL, rc->f_line, rc->f_col,
                                      csv ? "%s: %zu frequency row(s); at least %d"
                                          : "[%s] f_hz has %zu value(s); at least %d",
                                      csv ? "f_hz" : comp_names[k], rc->f.n,
                                      SL_FLOOR_MIN_POINTS);
        if (rc->nsa == 0)
            return sl_floor_desc_fail(d, SL_EPARSE, rc->line, 0,
                                      "[%s] has no spectrum (a key sa_<damping>, e.g. sa_0.05)",
                                      comp_names[k]);
        for (size_t s = 0; s < rc->nsa; s++)
            if (rc->sa[s].sa.n != rc->f.n)
                return sl_floor_desc_fail(d, SL_EINVAL, rc->sa[s].line, rc->sa[s].col,
                                          "[%s] %s has %zu values but f_hz (line %ld) has %zu",
                                          comp_names[k], rc->sa[s].key, rc->sa[s].sa.n,
                                          rc->f_line, rc->f.n);
    }
    return 1;
}

/* Build component k of the floor from its description (values to SI,
 * ascending damping), with the SA and ZPA limits and the ZPA's agreement
 * with the high-frequency end. */
static int build_comp(sl_floor_desc *d, const sl_floor_comp_desc *rc, sl_floor_component *out,
                      sl_unit u, const char *units_text)
{
    const double to_si = sl_unit_to_ms2(u);
    out->spec = calloc(rc->nsa, sizeof *out->spec);
    if (!out->spec)
        return sl_floor_desc_fail(d, SL_ENOMEM, 0, 0, "out of memory");
    size_t order[SL_FLOOR_MAX_DAMPINGS];
    for (size_t s = 0; s < rc->nsa; s++) {
        size_t j = s;
        while (j > 0 && rc->sa[order[j - 1]].damping > rc->sa[s].damping) {
            order[j] = order[j - 1];
            j--;
        }
        order[j] = s;
    }
    size_t n = rc->f.n;
    double zpa_end = 0.0;
    for (size_t i = 0; i < rc->nsa; i++) {
        const sl_floor_sa_desc *sa = &rc->sa[order[i]];
        sl_spectrum *s = &out->spec[i];
        s->f_hz = malloc(n * sizeof *s->f_hz);
        s->sa_ms2 = malloc(n * sizeof *s->sa_ms2);
        out->nspec = i + 1;
        if (!s->f_hz || !s->sa_ms2)
            return sl_floor_desc_fail(d, SL_ENOMEM, 0, 0, "out of memory");
        s->n = n;
        s->damping = sa->damping;
        memcpy(s->f_hz, rc->f.v, n * sizeof *s->f_hz);
        for (size_t j = 0; j < n; j++) {
            s->sa_ms2[j] = sa->sa.v[j] * to_si;
            if (!isfinite(s->sa_ms2[j]) || s->sa_ms2[j] > SL_FLOOR_MAX_SA_G * SL_G)
                return sl_floor_desc_fail(d, SL_EINVAL, sa->sa.line[j], sa->sa.col[j],
                                          "%s: value %g %s is above %g g (overflows or is not "
                                          "a floor acceleration)",
                                          sa->key, sa->sa.v[j], units_text, SL_FLOOR_MAX_SA_G);
        }
        if (s->sa_ms2[n - 1] > zpa_end)
            zpa_end = s->sa_ms2[n - 1];
    }
    out->zpa_given = rc->zpa_line != 0;
    out->zpa_ms2 = out->zpa_given ? rc->zpa * to_si : zpa_end;
    if (!isfinite(out->zpa_ms2) || out->zpa_ms2 > SL_FLOOR_MAX_SA_G * SL_G)
        return sl_floor_desc_fail(d, SL_EINVAL, rc->zpa_line, rc->zpa_col,
                                  "%s: value %g %s is above %g g", rc->zpa_key, rc->zpa,
                                  units_text, SL_FLOOR_MAX_SA_G);
    if (out->zpa_given) {
        /* the lowest damping is the last to reach the ZPA at high frequency */
        const sl_spectrum *lo = &out->spec[0];
        double end = lo->sa_ms2[n - 1], r = out->zpa_ms2 / end;
        if (!(r >= SL_FLOOR_ZPA_END_MIN && r <= SL_FLOOR_ZPA_END_MAX))
            return sl_floor_desc_fail(
                d, SL_EINVAL, rc->zpa_line, rc->zpa_col,
                "%s: %g %s is %.3g x the %g %% spectrum's value at its highest frequency "
                "(%g %s at %g Hz); a ZPA must lie within %g-%g x of it (check the value and "
                "the units, or leave the ZPA out to take it from the spectrum)",
                rc->zpa_key, rc->zpa, units_text, r, 100 * lo->damping, end / to_si, units_text,
                lo->f_hz[n - 1], SL_FLOOR_ZPA_END_MIN, SL_FLOOR_ZPA_END_MAX);
    }
    out->line = rc->line;
    return 1;
}

/* "h1_2" (CSV) or "[h1] sa_0.02" (INI): the column or key of a spectrum. */
static where spec_name(const sl_floor_desc *d, int k, const sl_floor_sa_desc *sa)
{
    where w;
    if (d->format == SL_FLOOR_CSV)
        snprintf(w.s, sizeof w.s, "%s", sa->key);
    else
        snprintf(w.s, sizeof w.s, "[%s] %s", comp_names[k], sa->key);
    return w;
}

/* The rigid range and the plausibility of the values against their own
 * column and the other dampings of their direction (floor.h,
 * SL_FLOOR_SPIKE_MAX ...); the earliest refusal in the file wins. */
static void check_plausible_values(sl_floor_desc *d, const char *u)
{
    const int csv = d->format == SL_FLOOR_CSV;
    for (int k = 0; k < SL_FLOOR_NCOMP; k++) {
        const sl_floor_comp_desc *rc = &d->comp[k];
        if (!rc->line)
            continue; /* H2 declared the same as H1 */
        const size_t n = rc->f.n;
        const double *f = rc->f.v;
        char period[64] = "";
        if (d->periods)
            snprintf(period, sizeof period, " (its shortest period is %g s)", 1 / f[n - 1]);
        if (!rc->zpa_line && f[n - 1] < SL_FLOOR_RIGID_HZ)
            fail_first(d, SL_EINVAL, rc->f.line[n - 1], rc->f.col[n - 1],
                       "%s%s%s: the table ends at %g Hz%s, below the rigid range (%g Hz), "
                       "and gives no ZPA, so the floor's ZPA is not known: extend the table to "
                       "%g Hz or more, or give zpa (%s)",
                       csv ? "" : "[", csv ? (d->periods ? "T_s" : "f_hz") : comp_names[k],
                       csv ? "" : "] f_hz", f[n - 1], period, SL_FLOOR_RIGID_HZ,
                       SL_FLOOR_RIGID_HZ,
                       csv ? (k == SL_FLOOR_H1 ? "'# zpa_h1: <value>'"
                              : k == SL_FLOOR_H2 ? "'# zpa_h2: <value>'" : "'# zpa_v: <value>'")
                           : "'zpa = <value>' in the section");
        for (size_t s = 0; s < rc->nsa; s++) {
            const sl_floor_sa_desc *a = &rc->sa[s];
            const double *v = a->sa.v;
            where name = spec_name(d, k, a);
            for (size_t j = 0; j < n; j++) {
                const long line = a->sa.line[j], col = a->sa.col[j];
                double r = spike_ratio(v, n, j);
                if (r > SL_FLOOR_SPIKE_MAX) {
                    fail_first(d, SL_EINVAL, line, col,
                               "%s at %g Hz: value %g %s is %.3g x %s (%g %s at %g Hz); a "
                               "floor spectrum does not jump more than %g x from one frequency "
                               "of its table to the next: check the value (a typo or a "
                               "misplaced decimal point)",
                               name.s, f[j], v[j], u, r,
                               j == 0 || j == n - 1 ? "its neighbour" : "the larger of its "
                                                                        "neighbours",
                               v[j] / r, u,
                               j == 0 ? f[1]
                               : j == n - 1 ? f[n - 2]
                               : v[j - 1] > v[j + 1] ? f[j - 1] : f[j + 1],
                               SL_FLOOR_SPIKE_MAX);
                    continue;
                }
                r = dip_ratio(f, v, n, j);
                if (r > SL_FLOOR_DIP_MAX && j > 0 && j < n - 1)
                    fail_first(d, SL_EINVAL, line, col,
                               "%s at %g Hz: value %g %s is 1/%.3g of the smaller of its "
                               "neighbours (%g %s); a floor spectrum does not drop more than "
                               "%g x between neighbouring frequencies of its table: check the "
                               "value (a typo or a misplaced decimal point)",
                               name.s, f[j], v[j], u, r, v[j] * r, u, SL_FLOOR_DIP_MAX);
                else if ((j == 0 || j == n - 1) &&
                         r > (j ? SL_FLOOR_DIP_MAX : SL_FLOOR_DIP_FIRST_MAX))
                    fail_first(d, SL_EINVAL, line, col,
                               "%s at %g Hz, the %s frequency of its table: value %g %s is "
                               "1/%.3g of the smaller of its neighbour (%g %s at %g Hz) and the "
                               "trend of the two values next to it (%.4g %s there); a floor "
                               "spectrum does not drop more than %g x at %s of its table: check "
                               "the value (a typo, a misplaced decimal point, a row slipped)",
                               name.s, f[j], j ? "last" : "first", v[j], u, r,
                               v[j ? n - 2 : 1], u, f[j ? n - 2 : 1], end_trend(f, v, n, j), u,
                               j ? SL_FLOOR_DIP_MAX : SL_FLOOR_DIP_FIRST_MAX,
                               j ? "the high-frequency end" : "the low-frequency end");
                else if (j == n - 1 && !rc->zpa_line && n >= 3 && f[n - 2] >= SL_FLOOR_RIGID_HZ &&
                         !(v[j] >= SL_FLOOR_END_STEP_MIN * v[j - 1] &&
                           v[j] <= SL_FLOOR_END_STEP_MAX * v[j - 1]))
                    fail_first(d, SL_EINVAL, line, col,
                               "%s at %g Hz: value %g %s, the last of the table, gives the ZPA "
                               "(none is given) and is %.3g x the value before it (%g %s at %g "
                               "Hz); in the rigid range (at or above %g Hz) a floor spectrum "
                               "stays within %g-%g x from one frequency of its table to the "
                               "next: check the value (the last row slipped?) or give the ZPA "
                               "(%s)",
                               name.s, f[j], v[j], u, v[j] / v[j - 1], v[j - 1], u, f[j - 1],
                               SL_FLOOR_RIGID_HZ, SL_FLOOR_END_STEP_MIN, SL_FLOOR_END_STEP_MAX,
                               csv ? (k == SL_FLOOR_H1 ? "'# zpa_h1: <value>'"
                                      : k == SL_FLOOR_H2 ? "'# zpa_h2: <value>'"
                                                         : "'# zpa_v: <value>'")
                                   : "'zpa = <value>' in the section");
                for (size_t q = 0; q < rc->nsa; q++) {
                    const sl_floor_sa_desc *b = &rc->sa[q];
                    if (!(b->damping > a->damping))
                        continue;
                    const double w = b->sa.v[j];
                    where bn = spec_name(d, k, b);
                    if (v[j] < SL_FLOOR_ORDER_MIN * w)
                        fail_first(d, SL_EINVAL, line, col,
                                   "%s at %g Hz: value %g %s is %.3g x the higher damping's "
                                   "%s there (%g %s, %s); a lower damping gives at least %g x "
                                   "a higher one: check the value and the %s",
                                   name.s, f[j], v[j], u, v[j] / w, bn.s, w, u,
                                   place(b->sa.line[j], b->sa.col[j]).s, SL_FLOOR_ORDER_MIN,
                                   csv ? "column headers" : "keys");
                    else if (spread_ratio(v[j], a->damping, w, b->damping) > SL_FLOOR_SPREAD_MAX)
                        fail_first(d, SL_EINVAL, line, col,
                                   "%s at %g Hz: value %g %s is %.3g x the higher damping's "
                                   "%s there (%g %s, %s); a floor spectrum at damping %g %% is "
                                   "at most %g x (%g / %g) = %.3g x that at %g %%: check the "
                                   "value and the units of the %s",
                                   name.s, f[j], v[j], u, v[j] / w, bn.s, w, u,
                                   place(b->sa.line[j], b->sa.col[j]).s, 100 * a->damping,
                                   SL_FLOOR_SPREAD_MAX, 100 * b->damping, 100 * a->damping,
                                   SL_FLOOR_SPREAD_MAX * b->damping / a->damping,
                                   100 * b->damping, csv ? "column" : "list");
                }
            }
        }
    }
}

/* A lower damping's column on average below a higher one's (two columns or
 * keys swapped), named at the lower damping's header or key; checked when
 * no value was refused on its own (a single wrong value is named at its
 * cell). */
static void check_order_means(sl_floor_desc *d)
{
    const int csv = d->format == SL_FLOOR_CSV;
    for (int k = 0; k < SL_FLOOR_NCOMP; k++) {
        const sl_floor_comp_desc *rc = &d->comp[k];
        for (size_t s = 0; rc->line && s < rc->nsa; s++)
            for (size_t q = 0; q < rc->nsa; q++) {
                const sl_floor_sa_desc *a = &rc->sa[s], *b = &rc->sa[q];
                double m = b->damping > a->damping ? order_mean(a->sa.v, b->sa.v, rc->f.n)
                                                   : INFINITY;
                if (m < SL_FLOOR_ORDER_MEAN_MIN)
                    fail_first(d, SL_EINVAL, a->line, a->col,
                               "%s: on average over the table (geometric mean) %.3g x the "
                               "higher damping's %s (%s); a lower damping gives at least %g x a "
                               "higher one on average: are the %s of the two dampings swapped?",
                               spec_name(d, k, a).s, m, spec_name(d, k, b).s,
                               place(b->line, b->col).s, SL_FLOOR_ORDER_MEAN_MIN,
                               csv ? "column headers" : "keys");
            }
    }
}

void sl_floor_free(sl_floor *fl)
{
    if (!fl)
        return;
    free(fl->path);
    free(fl->name);
    free(fl->description);
    free(fl->building);
    free(fl->units_text);
    for (int k = 0; k < SL_FLOOR_NCOMP; k++) {
        for (size_t s = 0; s < fl->comp[k].nspec; s++)
            sl_spectrum_clear(&fl->comp[k].spec[s]);
        free(fl->comp[k].spec);
    }
    free(fl);
}

static char *take(char **p, const char *fallback)
{
    char *s = *p ? *p : strdup(fallback);
    *p = NULL;
    return s;
}

sl_floor *sl_floor_desc_finish(sl_floor_desc *d)
{
    if (d->failed)
        return NULL;
    check_values(d);
    if (d->failed || !check_complete(d))
        return NULL;
    sl_floor *fl = calloc(1, sizeof *fl);
    if (!fl) {
        sl_floor_desc_fail(d, SL_ENOMEM, 0, 0, "out of memory");
        return NULL;
    }
    fl->format = d->format;
    fl->path = strdup(d->path);
    fl->units = sl_unit_parse(d->text[SL_FK_UNITS]);
    fl->units_line = d->key_line[SL_FK_UNITS];
    fl->units_text = take(&d->text[SL_FK_UNITS], "");
    fl->name = take(&d->text[SL_FK_NAME], "");
    fl->description = take(&d->text[SL_FK_DESC], "");
    fl->building = take(&d->text[SL_FK_BUILDING], "");
    fl->elevation_m = d->elevation_m;
    fl->h2_same_as_h1 = d->key_line[SL_FK_H2] != 0;
    fl->has_seed = d->key_line[SL_FK_SEED] != 0;
    fl->seed = (uint64_t)d->seed;
    if (!fl->path || !fl->units_text || !fl->name || !fl->description || !fl->building)
        sl_floor_desc_fail(d, SL_ENOMEM, 0, 0, "out of memory");
    for (int k = 0; k < SL_FLOOR_NCOMP && !d->failed; k++) {
        int src = (k == SL_FLOOR_H2 && fl->h2_same_as_h1) ? SL_FLOOR_H1 : k;
        build_comp(d, &d->comp[src], &fl->comp[k], fl->units, fl->units_text);
    }
    if (!d->failed)
        check_plausible_values(d, fl->units_text);
    if (!d->failed)
        check_order_means(d);
    if (d->failed) {
        sl_floor_free(fl);
        return NULL;
    }
    return fl;
}

/* ---- public --------------------------------------------------------- */

sl_floor_format sl_floor_format_of(const char *path)
{
    size_t n = path ? strlen(path) : 0;
    return n >= 4 && !strcasecmp(path + n - 4, ".csv") ? SL_FLOOR_CSV : SL_FLOOR_INI;
}

sl_floor *sl_floor_load(const char *path, sl_error *err)
{
    if (!path) {
        sl_error_set(err, SL_EINVAL, NULL, 0, "floor: no file name");
        return NULL;
    }
    sl_text t;
    const sl_text_opts to = {SL_FLOOR_MAX_BYTES, "a floor file", "SL_FLOOR_MAX_BYTES", 1};
    if (sl_text_load(path, &to, &t, err) != SL_OK)
        return NULL;
    sl_floor_desc d;
    sl_floor_desc_init(&d, path, sl_floor_format_of(path), err);
    int ok = d.format == SL_FLOOR_CSV ? sl_floor_read_csv(&d, &t) : sl_floor_read_ini(&d, &t);
    sl_text_free(&t);
    sl_floor *fl = ok ? sl_floor_desc_finish(&d) : NULL;
    sl_floor_desc_free(&d);
    return fl;
}

const sl_spectrum *sl_floor_spectrum(const sl_floor *fl, sl_floor_comp c, double damping)
{
    if (!fl || (unsigned)c >= SL_FLOOR_NCOMP)
        return NULL;
    const sl_floor_component *fc = &fl->comp[c];
    for (size_t s = 0; s < fc->nspec; s++)
        if (fabs(fc->spec[s].damping - damping) <= SL_FLOOR_DAMPING_TOL)
            return &fc->spec[s];
    return NULL;
}

const sl_spectrum *sl_floor_sa10(const sl_floor *fl, sl_floor_comp c)
{
    return sl_floor_spectrum(fl, c, SL_FLOOR_ASCE_DAMPING);
}

sl_status sl_floor_check_plausible(const sl_floor *fl, sl_error *err)
{
    double h = fmax(fl->comp[SL_FLOOR_H1].zpa_ms2, fl->comp[SL_FLOOR_H2].zpa_ms2) / SL_G;
    if (h < SL_FLOOR_ZPA_MIN_G || h > SL_FLOOR_ZPA_MAX_G) {
        const char *u = fl->units_text && fl->units_text[0] ? fl->units_text
                                                            : sl_unit_name(fl->units);
        return sl_error_set(err, SL_EINVAL, fl->path, fl->units_line,
                            "%s %s gives a horizontal ZPA of %.4g g, outside the plausible "
                            "%g-%g g for a floor: check the units and the values",
                            fl->format == SL_FLOOR_CSV ? "# units:" : "units =", u, h,
                            SL_FLOOR_ZPA_MIN_G, SL_FLOOR_ZPA_MAX_G);
    }
    return SL_OK;
}

int sl_floor_zpa_warning_text(double zpa_h_ms2, const char *units_text, sl_floor_format fmt,
                              char *buf, size_t n)
{
    const double h = zpa_h_ms2 / SL_G;
    if (n)
        buf[0] = '\0';
    if (!(h < SL_FLOOR_ZPA_WARN_MIN_G || h > SL_FLOOR_ZPA_WARN_MAX_G))
        return 0;
    const int low = h < SL_FLOOR_ZPA_WARN_MIN_G;
    snprintf(buf, n,
             "%s %s gives a horizontal ZPA of %.3g g, unusual for a floor (a floor's ZPA is "
             "usually %g-%g g): check that the values are in %s%s",
             fmt == SL_FLOOR_CSV ? "# units:" : "units =", units_text, h,
             SL_FLOOR_ZPA_WARN_MIN_G, SL_FLOOR_ZPA_WARN_MAX_G, units_text,
             low ? " (values in g labelled m/s2 give 1/9.81 of the ZPA)"
                 : " (values in m/s2 labelled g give 9.81 x the ZPA)");
    return 1;
}

int sl_floor_zpa_warning(const sl_floor *fl, char *buf, size_t n)
{
    const char *u = fl->units_text && fl->units_text[0] ? fl->units_text
                                                        : sl_unit_name(fl->units);
    return sl_floor_zpa_warning_text(
        fmax(fl->comp[SL_FLOOR_H1].zpa_ms2, fl->comp[SL_FLOOR_H2].zpa_ms2), u, fl->format, buf,
        n);
}

/* A floor file in a folder listing: *.ini or *.csv (any case), not hidden. */
static int is_floor_name(const struct dirent *e)
{
    size_t n = strlen(e->d_name);
    return e->d_name[0] != '.' && n > 4 &&
           (!strcasecmp(e->d_name + n - 4, ".ini") || !strcasecmp(e->d_name + n - 4, ".csv"));
}

static int by_name(const struct dirent **a, const struct dirent **b)
{
    return strcmp((*a)->d_name, (*b)->d_name);
}

sl_status sl_floor_list(const char *arg, char **paths, size_t *n, size_t max, sl_error *err)
{
    struct stat st;
    if (stat(arg, &st) != 0)
        return sl_error_set(err, SL_EIO, arg, 0, "%s", strerror(errno));
    if (!S_ISDIR(st.st_mode)) {
        if (*n >= max)
            return sl_error_set(err, SL_EINVAL, arg, 0, "more than %zu floor files", max);
        if (!(paths[*n] = strdup(arg)))
            return sl_error_set(err, SL_ENOMEM, arg, 0, "out of memory");
        (*n)++;
        return SL_OK;
    }
    struct dirent **ents = NULL;
    int ne = scandir(arg, &ents, is_floor_name, by_name);
    if (ne < 0)
        return sl_error_set(err, SL_EIO, arg, 0, "%s", strerror(errno));
    sl_status s = SL_OK;
    if (ne == 0)
        s = sl_error_set(err, SL_EIO, arg, 0, "no floor files (*.ini, *.csv) in this folder");
    size_t alen = strlen(arg);
    for (int i = 0; i < ne; i++) {
        if (!s) {
            size_t len = alen + 1 + strlen(ents[i]->d_name) + 1;
            char *p = *n >= max ? NULL : malloc(len);
            if (*n >= max)
                s = sl_error_set(err, SL_EINVAL, arg, 0, "more than %zu floor files", max);
            else if (!p)
                s = sl_error_set(err, SL_ENOMEM, arg, 0, "out of memory");
            else {
                snprintf(p, len, "%s/%s", arg, ents[i]->d_name); /* as glob() gave it */
                paths[(*n)++] = p;
            }
        }
        free(ents[i]);
    }
    free(ents);
    return s;
}
