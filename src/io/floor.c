/* floor.c - floor response spectrum files read with inih (see floor.h).
 *
 * inih calls a handler for every `key = value` (and again for each indented
 * continuation line of a multi-line value) but, as Debian builds it, does
 * not pass line numbers. The file is therefore fed through our own line
 * reader (ini_parse_stream), which counts lines, remembers whether the
 * current line was indented, sees section headers (so that empty, unknown
 * or repeated sections are caught too) and refuses lines longer than inih's
 * buffer instead of letting them be split. */
#include "io/floor.h"

#include "io/text.h"

#include <errno.h>
#include <glob.h>
#include <ini.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* The value `h2 = same_as_h1` declares H2 equal to H1. */
#define FLOOR_SAME_AS_H1 "same_as_h1"
/* Prefix of a spectrum key: sa_<damping ratio>. */
#define FLOOR_SA_PREFIX "sa_"

static const char *const comp_names[SL_FLOOR_NCOMP] = {"h1", "h2", "v"};

const char *sl_floor_comp_name(sl_floor_comp c)
{
    return (unsigned)c < SL_FLOOR_NCOMP ? comp_names[c] : "?";
}

/* A growing list of numbers with the line each came from. */
typedef struct numlist {
    size_t n, cap;
    double *v;
    long *line;
} numlist;

static void numlist_free(numlist *l)
{
    free(l->v);
    free(l->line);
    memset(l, 0, sizeof *l);
}

static int numlist_push(numlist *l, double x, long line)
{
    if (l->n == l->cap) {
        size_t cap = l->cap ? 2 * l->cap : 32;
        double *v = realloc(l->v, cap * sizeof *v);
        if (!v)
            return -1;
        l->v = v;
        long *ln = realloc(l->line, cap * sizeof *ln);
        if (!ln)
            return -1;
        l->line = ln;
        l->cap = cap;
    }
    l->v[l->n] = x;
    l->line[l->n] = line;
    l->n++;
    return 0;
}

/* What a component section collected. */
typedef struct raw_comp {
    long line;          /* section header line, 0 if absent */
    long f_line;        /* line of f_hz, 0 if absent */
    numlist f;
    size_t nsa;
    double damping[SL_FLOOR_MAX_DAMPINGS];
    long sa_line[SL_FLOOR_MAX_DAMPINGS];
    numlist sa[SL_FLOOR_MAX_DAMPINGS];
    long zpa_line;
    double zpa;
} raw_comp;

/* Parsing state shared by the reader and the handler. */
typedef struct ctx {
    const char *path;
    sl_text text;       /* the file in memory (io/text.h) */
    long lineno;        /* line just read */
    int indented;       /* the line just read began with a blank */
    int have_prev_key;  /* inih's prev_name is set (a key since the last header) */
    const char *cur_key_section; /* section and key of the last key (for continuations) */
    char cur_key[64];
    sl_error *err;
    int failed;
    long fail_line;     /* line of the first error we found */
    long floor_line, name_line, elev_line, units_line, h2_line, desc_line, seed_line;
    unsigned long long seed;
    char *name, *description;
    double elevation_m;
    sl_unit units;
    raw_comp comp[SL_FLOOR_NCOMP];
} ctx;

static int fail(ctx *c, sl_status code, long line, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

static int fail(ctx *c, sl_status code, long line, const char *fmt, ...)
{
    if (c->failed)
        return 0;
    char msg[900];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    sl_error_set(c->err, code, c->path, line, "%s", msg);
    c->failed = 1;
    c->fail_line = line;
    return 0;
}

static int is_blank(char ch)
{
    return ch == ' ' || ch == '\t';
}

/* Section index for a name: 0 floor, 1 + comp, or -1. */
static int section_index(const char *s)
{
    if (!strcmp(s, "floor"))
        return 0;
    for (int k = 0; k < SL_FLOOR_NCOMP; k++)
        if (!strcmp(s, comp_names[k]))
            return 1 + k;
    return -1;
}

static long *section_line(ctx *c, int idx)
{
    return idx == 0 ? &c->floor_line : &c->comp[idx - 1].line;
}

/* Look at a section header the way inih will, to catch unknown, empty and
 * repeated sections with their line. */
static void see_section(ctx *c, const char *line)
{
    const char *p = line;
    while (is_blank(*p))
        p++;
    if (*p != '[')
        return;
    if (p > line && c->have_prev_key)
        return; /* inih reads an indented line after a key as a continuation */
    const char *end = strchr(p + 1, ']');
    if (!end)
        return; /* inih reports the syntax error */
    char name[128];
    size_t len = (size_t)(end - p - 1);
    if (len >= sizeof name)
        len = sizeof name - 1;
    memcpy(name, p + 1, len);
    name[len] = '\0';
    c->have_prev_key = 0;
    int idx = section_index(name);
    if (idx < 0) {
        fail(c, SL_EPARSE, c->lineno,
             "unknown section [%s] (expected [floor], [h1], [h2] or [v])", name);
        return;
    }
    long *sl = section_line(c, idx);
    if (*sl) {
        fail(c, SL_EPARSE, c->lineno, "section [%s] repeated (first at line %ld)", name, *sl);
        return;
    }
    *sl = c->lineno;
}

/* fgets-style reader for ini_parse_stream over the file in memory: whole
 * lines (at most num - 1 bytes with their line end) or an error. */
static char *reader(char *str, int num, void *stream)
{
    ctx *c = stream;
    if (c->failed)
        return NULL;
    const char *s;
    size_t len;
    size_t before = c->text.pos;
    if (!sl_text_next(&c->text, &s, &len))
        return NULL;
    c->lineno = c->text.lineno;
    size_t raw = c->text.pos - before; /* with the line end, as fgets sees it */
    if (raw < len + 1)
        raw = len + 1;
    if (num < 2 || raw > (size_t)num - 1) {
        fail(c, SL_EPARSE, c->lineno,
             "line longer than %d characters; continue long lists on indented lines",
             num - 3);
        return NULL;
    }
    memcpy(str, s, len);
    str[len] = '\n';
    str[len + 1] = '\0';
    c->indented = is_blank(str[0]);
    see_section(c, str);
    if (c->failed)
        return NULL;
    return str;
}

/* Strict number: the whole token, finite. */
static int parse_number(const char *tok, double *out)
{
    if (!*tok)
        return -1;
    char *end;
    errno = 0;
    double v = strtod(tok, &end);
    if (errno == ERANGE || *end || !isfinite(v))
        return -1;
    *out = v;
    return 0;
}

/* Append the numbers of one line (separated by commas and/or blanks) to a
 * list, checking each with `check` (may be NULL). */
typedef int (*num_check)(ctx *c, const numlist *l, double x, const char *key);

static int append_numbers(ctx *c, numlist *l, const char *value, const char *key,
                          num_check check)
{
    if (strchr(value, '=')) /* an indented "key = value" read as continuation */
        return fail(c, SL_EPARSE, c->lineno,
                    "'%s' is read as a continuation of '%s' because it is indented; "
                    "start a new key at the beginning of the line",
                    value, key);
    const char *p = value;
    int commas = 0;
    while (*p) {
        while (is_blank(*p) || *p == ',') {
            if (*p == ',' && ++commas > 1)
                return fail(c, SL_EPARSE, c->lineno, "%s: empty item between commas", key);
            p++;
        }
        if (!*p)
            break;
        commas = 0;
        char tok[128];
        size_t len = strcspn(p, ", \t");
        if (len >= sizeof tok)
            return fail(c, SL_EPARSE, c->lineno, "%s: token too long", key);
        memcpy(tok, p, len);
        tok[len] = '\0';
        p += len;
        double x;
        if (parse_number(tok, &x))
            return fail(c, SL_EPARSE, c->lineno, "%s: '%s' is not a finite number", key, tok);
        if (check && !check(c, l, x, key))
            return 0;
        if (numlist_push(l, x, c->lineno))
            return fail(c, SL_ENOMEM, c->lineno, "out of memory");
    }
    return 1;
}

static int check_frequency(ctx *c, const numlist *l, double x, const char *key)
{
    if (!(x > 0))
        return fail(c, SL_EINVAL, c->lineno, "%s: frequency %g must be positive", key, x);
    if (x < SL_FLOOR_F_MIN_HZ || x > SL_FLOOR_F_MAX_HZ)
        return fail(c, SL_EINVAL, c->lineno, "%s: frequency %g Hz outside %g-%g Hz", key, x,
                    SL_FLOOR_F_MIN_HZ, SL_FLOOR_F_MAX_HZ);
    if (l->n > 0 && !(x > l->v[l->n - 1]))
        return fail(c, SL_EINVAL, c->lineno,
                    "%s: frequencies must increase strictly: %g after %g", key, x,
                    l->v[l->n - 1]);
    return 1;
}

static int check_positive(ctx *c, const numlist *l, double x, const char *key)
{
    (void)l;
    if (!(x > 0))
        return fail(c, SL_EINVAL, c->lineno, "%s: value %g must be positive", key, x);
    return 1;
}

/* Keys of [floor], declared once (STYLE 9). */
typedef enum { FK_NAME, FK_ELEV, FK_UNITS, FK_H2, FK_DESC, FK_SEED, FK_COUNT } floor_key;
static const char *const floor_keys[FK_COUNT] = {
    [FK_NAME] = "name",         /* the floor's name (required) */
    [FK_ELEV] = "elevation_m",  /* elevation, m (optional) */
    [FK_UNITS] = "units",       /* units of all spectral values (required) */
    [FK_H2] = "h2",             /* 'same_as_h1' when there is no [h2] section */
    [FK_DESC] = "description",  /* free text (optional) */
    [FK_SEED] = "seed",         /* the floor's own seed, integer >= 0 (optional) */
};

static long *floor_key_line(ctx *c, floor_key k)
{
    switch (k) {
    case FK_NAME: return &c->name_line;
    case FK_ELEV: return &c->elev_line;
    case FK_UNITS: return &c->units_line;
    case FK_H2: return &c->h2_line;
    case FK_SEED: return &c->seed_line;
    default: return &c->desc_line;
    }
}

static int handle_floor(ctx *c, const char *name, const char *value)
{
    int k = -1;
    for (int i = 0; i < FK_COUNT; i++)
        if (!strcmp(name, floor_keys[i]))
            k = i;
    if (k < 0) {
        char known[256] = "";
        for (int i = 0; i < FK_COUNT; i++) {
            strncat(known, i ? ", " : "", sizeof known - strlen(known) - 1);
            strncat(known, floor_keys[i], sizeof known - strlen(known) - 1);
        }
        return fail(c, SL_EPARSE, c->lineno, "unknown key '%s' in [floor] (expected %s)", name,
                    known);
    }
    long *kl = floor_key_line(c, (floor_key)k);
    if (c->indented && *kl)
        return fail(c, SL_EPARSE, c->lineno,
                    "'%s' takes one value; this indented line would continue it", name);
    if (*kl)
        return fail(c, SL_EPARSE, c->lineno, "key '%s' repeated (first at line %ld)", name,
                    *kl);
    *kl = c->lineno;
    switch ((floor_key)k) {
    case FK_NAME:
        if (!*value)
            return fail(c, SL_EINVAL, c->lineno, "name is empty");
        if (!(c->name = strdup(value)))
            return fail(c, SL_ENOMEM, c->lineno, "out of memory");
        return 1;
    case FK_DESC:
        if (!(c->description = strdup(value)))
            return fail(c, SL_ENOMEM, c->lineno, "out of memory");
        return 1;
    case FK_SEED: {
        char *end;
        errno = 0;
        c->seed = strtoull(value, &end, 10);
        if (!*value || *value == '-' || *value == '+' || *end || errno)
            return fail(c, SL_EPARSE, c->lineno,
                        "seed: '%s' is not an integer from 0 to 18446744073709551615", value);
        return 1;
    }
    case FK_ELEV:
        if (parse_number(value, &c->elevation_m))
            return fail(c, SL_EPARSE, c->lineno, "elevation_m: '%s' is not a finite number",
                        value);
        return 1;
    case FK_UNITS:
        c->units = sl_unit_parse(value);
        if (c->units == SL_UNIT_NONE)
            return fail(c, SL_EINVAL, c->lineno,
                        "unknown units '%s' (expected g, m/s2, cm/s2, gal or mm/s2)", value);
        return 1;
    case FK_H2:
        if (strcmp(value, FLOOR_SAME_AS_H1))
            return fail(c, SL_EINVAL, c->lineno,
                        "h2 = '%s': the only value is '" FLOOR_SAME_AS_H1
                        "' (or give a [h2] section)",
                        value);
        return 1;
    default:
        return 1;
    }
}

static int handle_comp(ctx *c, raw_comp *rc, const char *sec, const char *name,
                       const char *value)
{
    int cont = c->indented && c->have_prev_key && c->cur_key_section == sec &&
               !strcmp(c->cur_key, name);
    if (!strcmp(name, "f_hz")) {
        if (!cont && rc->f_line)
            return fail(c, SL_EPARSE, c->lineno, "[%s] key 'f_hz' repeated (first at line %ld)",
                        sec, rc->f_line);
        if (!cont)
            rc->f_line = c->lineno;
        return append_numbers(c, &rc->f, value, "f_hz", check_frequency);
    }
    if (!strcmp(name, "zpa")) {
        if (cont)
            return fail(c, SL_EPARSE, c->lineno,
                        "'zpa' takes one value; this indented line would continue it");
        if (rc->zpa_line)
            return fail(c, SL_EPARSE, c->lineno, "[%s] key 'zpa' repeated (first at line %ld)",
                        sec, rc->zpa_line);
        rc->zpa_line = c->lineno;
        if (parse_number(value, &rc->zpa))
            return fail(c, SL_EPARSE, c->lineno, "zpa: '%s' is not a finite number", value);
        if (!(rc->zpa > 0))
            return fail(c, SL_EINVAL, c->lineno, "zpa: value %g must be positive", rc->zpa);
        return 1;
    }
    size_t plen = strlen(FLOOR_SA_PREFIX);
    if (!strncmp(name, FLOOR_SA_PREFIX, plen)) {
        double d;
        if (parse_number(name + plen, &d))
            return fail(c, SL_EPARSE, c->lineno,
                        "key '%s': expected sa_<damping ratio>, e.g. sa_0.05", name);
        if (!(d > 0 && d < 1))
            return fail(c, SL_EINVAL, c->lineno, "%s: damping %g outside (0, 1)", name, d);
        size_t k = 0;
        while (k < rc->nsa && fabs(rc->damping[k] - d) > SL_FLOOR_DAMPING_TOL)
            k++;
        if (k < rc->nsa && !cont)
            return fail(c, SL_EPARSE, c->lineno,
                        "[%s] damping %g given twice (first at line %ld)", sec, d,
                        rc->sa_line[k]);
        if (k == rc->nsa) {
            if (rc->nsa == SL_FLOOR_MAX_DAMPINGS)
                return fail(c, SL_EINVAL, c->lineno, "[%s] more than %d damping ratios", sec,
                            SL_FLOOR_MAX_DAMPINGS);
            rc->damping[k] = d;
            rc->sa_line[k] = c->lineno;
            rc->nsa++;
        }
        return append_numbers(c, &rc->sa[k], value, name, check_positive);
    }
    return fail(c, SL_EPARSE, c->lineno,
                "unknown key '%s' in [%s] (expected f_hz, sa_<damping>, zpa)", name, sec);
}

static int handler(void *user, const char *section, const char *name, const char *value)
{
    ctx *c = user;
    if (c->failed)
        return 0;
    int idx = section_index(section);
    if (!*section)
        return fail(c, SL_EPARSE, c->lineno, "key '%s' before any section", name);
    if (idx < 0) /* an indented header see_section() did not count */
        return fail(c, SL_EPARSE, c->lineno, "unknown section [%s]", section);
    int ok = idx == 0 ? handle_floor(c, name, value)
                      : handle_comp(c, &c->comp[idx - 1], comp_names[idx - 1], name, value);
    c->have_prev_key = 1;
    c->cur_key_section = idx == 0 ? "floor" : comp_names[idx - 1];
    snprintf(c->cur_key, sizeof c->cur_key, "%s", name);
    return ok;
}

static void ctx_free(ctx *c)
{
    sl_text_free(&c->text);
    free(c->name);
    free(c->description);
    for (int k = 0; k < SL_FLOOR_NCOMP; k++) {
        numlist_free(&c->comp[k].f);
        for (size_t d = 0; d < SL_FLOOR_MAX_DAMPINGS; d++)
            numlist_free(&c->comp[k].sa[d]);
    }
}

void sl_floor_free(sl_floor *fl)
{
    if (!fl)
        return;
    free(fl->path);
    free(fl->name);
    free(fl->description);
    for (int k = 0; k < SL_FLOOR_NCOMP; k++) {
        for (size_t d = 0; d < fl->comp[k].nspec; d++)
            sl_spectrum_clear(&fl->comp[k].spec[d]);
        free(fl->comp[k].spec);
    }
    free(fl);
}

/* Check what is missing after the whole file was read. */
static int check_complete(ctx *c)
{
    long eof = c->lineno > 0 ? c->lineno : 1;
    if (!c->floor_line)
        return fail(c, SL_EPARSE, eof, "missing section [floor]");
    if (!c->name_line)
        return fail(c, SL_EPARSE, c->floor_line, "[floor] has no 'name'");
    if (!c->units_line)
        return fail(c, SL_EPARSE, c->floor_line,
                    "[floor] has no 'units' (g, m/s2, cm/s2, gal or mm/s2)");
    raw_comp *h2 = &c->comp[SL_FLOOR_H2];
    if (c->h2_line && h2->line)
        return fail(c, SL_EPARSE, c->h2_line,
                    "'h2 = " FLOOR_SAME_AS_H1 "' and a [h2] section (line %ld): give one",
                    h2->line);
    if (!c->h2_line && !h2->line)
        return fail(c, SL_EPARSE, c->floor_line,
                    "H2 not given: add a [h2] section or declare 'h2 = " FLOOR_SAME_AS_H1
                    "' in [floor]");
    for (int k = 0; k < SL_FLOOR_NCOMP; k++) {
        raw_comp *rc = &c->comp[k];
        if (k == SL_FLOOR_H2 && c->h2_line)
            continue;
        if (!rc->line)
            return fail(c, SL_EPARSE, eof, "missing section [%s]", comp_names[k]);
        if (!rc->f_line)
            return fail(c, SL_EPARSE, rc->line, "[%s] has no 'f_hz'", comp_names[k]);
        if (rc->f.n < SL_FLOOR_MIN_POINTS)
            return fail(c, SL_EINVAL, rc->f_line, "[%s] f_hz has %zu value(s); at least %d",
                        comp_names[k], rc->f.n, SL_FLOOR_MIN_POINTS);
        if (rc->nsa == 0)
            return fail(c, SL_EPARSE, rc->line,
                        "[%s] has no spectrum (a key sa_<damping>, e.g. sa_0.05)",
                        comp_names[k]);
        for (size_t d = 0; d < rc->nsa; d++)
            if (rc->sa[d].n != rc->f.n)
                return fail(c, SL_EINVAL, rc->sa_line[d],
                            "[%s] sa_%g has %zu values but f_hz (line %ld) has %zu",
                            comp_names[k], rc->damping[d], rc->sa[d].n, rc->f_line, rc->f.n);
    }
    return 1;
}

/* Build component k of the floor from what was collected. */
static int build_comp(ctx *c, const raw_comp *rc, sl_floor_component *out, double to_si)
{
    out->spec = calloc(rc->nsa, sizeof *out->spec);
    if (!out->spec)
        return fail(c, SL_ENOMEM, 0, "out of memory");
    /* ascending damping */
    size_t order[SL_FLOOR_MAX_DAMPINGS];
    for (size_t d = 0; d < rc->nsa; d++) {
        size_t j = d;
        while (j > 0 && rc->damping[order[j - 1]] > rc->damping[d]) {
            order[j] = order[j - 1];
            j--;
        }
        order[j] = d;
    }
    size_t n = rc->f.n;
    double zpa_end = 0.0;
    for (size_t i = 0; i < rc->nsa; i++) {
        const numlist *sa = &rc->sa[order[i]];
        sl_spectrum *s = &out->spec[i];
        s->f_hz = malloc(n * sizeof *s->f_hz);
        s->sa_ms2 = malloc(n * sizeof *s->sa_ms2);
        out->nspec = i + 1;
        if (!s->f_hz || !s->sa_ms2)
            return fail(c, SL_ENOMEM, 0, "out of memory");
        s->n = n;
        s->damping = rc->damping[order[i]];
        memcpy(s->f_hz, rc->f.v, n * sizeof *s->f_hz);
        for (size_t j = 0; j < n; j++) {
            s->sa_ms2[j] = sa->v[j] * to_si;
            if (!isfinite(s->sa_ms2[j]) || s->sa_ms2[j] > SL_FLOOR_MAX_SA_G * SL_G)
                return fail(c, SL_EINVAL, sa->line[j], "sa_%g: value %g %s is above %g g "
                            "(overflows or is not a floor acceleration)", rc->damping[order[i]],
                            sa->v[j], sl_unit_name(c->units), SL_FLOOR_MAX_SA_G);
        }
        if (s->sa_ms2[n - 1] > zpa_end)
            zpa_end = s->sa_ms2[n - 1];
    }
    out->zpa_given = rc->zpa_line != 0;
    out->zpa_ms2 = out->zpa_given ? rc->zpa * to_si : zpa_end;
    if (!isfinite(out->zpa_ms2) || out->zpa_ms2 > SL_FLOOR_MAX_SA_G * SL_G)
        return fail(c, SL_EINVAL, rc->zpa_line, "zpa: value %g %s is above %g g", rc->zpa,
                    sl_unit_name(c->units), SL_FLOOR_MAX_SA_G);
    out->line = rc->line;
    return 1;
}

sl_floor *sl_floor_load(const char *path, sl_error *err)
{
    if (!path) {
        sl_error_set(err, SL_EINVAL, NULL, 0, "floor: no file name");
        return NULL;
    }
    ctx c;
    memset(&c, 0, sizeof c);
    c.path = path;
    c.err = err;
    c.elevation_m = NAN;
    const sl_text_opts to = {SL_FLOOR_MAX_BYTES, "a floor file", "SL_FLOOR_MAX_BYTES", 1};
    if (sl_text_load(path, &to, &c.text, err) != SL_OK)
        return NULL;
    int rc = ini_parse_stream(reader, &c, handler, &c);
    if (!c.failed && rc == -2) {
        fail(&c, SL_ENOMEM, 0, "out of memory");
    } else if (rc > 0 && (!c.failed || rc < c.fail_line)) {
        /* inih keeps going after a syntax error: report whichever came first */
        c.failed = 0;
        fail(&c, SL_EPARSE, rc,
             "syntax error: expected '[section]', 'key = value' or a comment");
    }
    if (!c.failed)
        check_complete(&c);
    sl_floor *fl = NULL;
    if (!c.failed) {
        fl = calloc(1, sizeof *fl);
        if (!fl) {
            fail(&c, SL_ENOMEM, 0, "out of memory");
        } else {
            fl->path = strdup(path);
            fl->name = c.name;
            fl->description = c.description ? c.description : strdup("");
            c.name = c.description = NULL;
            fl->elevation_m = c.elevation_m;
            fl->units = c.units;
            fl->units_line = c.units_line;
            fl->h2_same_as_h1 = c.h2_line != 0;
            fl->has_seed = c.seed_line != 0;
            fl->seed = (uint64_t)c.seed;
            if (!fl->path || !fl->description)
                fail(&c, SL_ENOMEM, 0, "out of memory");
            double to_si = sl_unit_to_ms2(c.units);
            for (int k = 0; k < SL_FLOOR_NCOMP && !c.failed; k++) {
                int src = (k == SL_FLOOR_H2 && fl->h2_same_as_h1) ? SL_FLOOR_H1 : k;
                build_comp(&c, &c.comp[src], &fl->comp[k], to_si);
            }
        }
    }
    ctx_free(&c);
    if (c.failed) {
        sl_floor_free(fl);
        return NULL;
    }
    return fl;
}

const sl_spectrum *sl_floor_spectrum(const sl_floor *fl, sl_floor_comp c, double damping)
{
    if (!fl || (unsigned)c >= SL_FLOOR_NCOMP)
        return NULL;
    const sl_floor_component *fc = &fl->comp[c];
    for (size_t d = 0; d < fc->nspec; d++)
        if (fabs(fc->spec[d].damping - damping) <= SL_FLOOR_DAMPING_TOL)
            return &fc->spec[d];
    return NULL;
}

const sl_spectrum *sl_floor_sa10(const sl_floor *fl, sl_floor_comp c)
{
    return sl_floor_spectrum(fl, c, SL_FLOOR_ASCE_DAMPING);
}

sl_status sl_floor_check_plausible(const sl_floor *fl, sl_error *err)
{
    double h = fmax(fl->comp[SL_FLOOR_H1].zpa_ms2, fl->comp[SL_FLOOR_H2].zpa_ms2) / SL_G;
    if (h < SL_FLOOR_ZPA_MIN_G || h > SL_FLOOR_ZPA_MAX_G)
        return sl_error_set(err, SL_EINVAL, fl->path, fl->units_line,
                            "units = %s gives a horizontal ZPA of %.4g g, outside the plausible "
                            "%g-%g g for a floor: check the units and the values",
                            sl_unit_name(fl->units), h, SL_FLOOR_ZPA_MIN_G, SL_FLOOR_ZPA_MAX_G);
    return SL_OK;
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
    char pat[4096];
    snprintf(pat, sizeof pat, "%s/*.ini", arg);
    glob_t g;
    memset(&g, 0, sizeof g);
    if (glob(pat, 0, NULL, &g) != 0) {
        globfree(&g);
        return sl_error_set(err, SL_EIO, arg, 0, "no floor files (*.ini) in this folder");
    }
    sl_status s = SL_OK;
    for (size_t i = 0; i < g.gl_pathc && !s; i++) {
        if (*n >= max)
            s = sl_error_set(err, SL_EINVAL, arg, 0, "more than %zu floor files", max);
        else if (!(paths[*n] = strdup(g.gl_pathv[i])))
            s = sl_error_set(err, SL_ENOMEM, arg, 0, "out of memory");
        else
            (*n)++;
    }
    globfree(&g);
    return s;
}
