/* components.c - the components table read and checked against the floor
 * tables of a run, one verdict per row, and components.csv; see
 * components.h (the workbook: components_book.c). */
#include "report/components.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <zlib.h>

#include "io/atomic.h"
#include "io/casefold.h"
#include "io/text.h"
#include "report/csvread.h"
#include "report/plant_book.h"
#include "report/sheets.h"

const char *const SL_COMP_COL_NAME[SL_COMP_NCOLS] = {"tag", "building", "floor", "mu", "base_m",
                                                     "cg_height_m", "clearance_mm"};
const char *const SL_COMP_OPT_NAME[SL_COMP_NOPT] = {"mu_max", "restitution", "orientation_deg"};
const char *const SL_COMP_MODE_NAME[SL_COMP_NMODES] = {"sliding", "rocking", "both"};
const char *const SL_COMP_VERDICT_NAME[SL_COMP_NVERDICTS] = {
    "ok", "marginal", "short", "rocking", "outside", "stands", "overturns"};
/* Room for the list of known buildings or floors in a message. */
#define KNOWN_MAX 600

static unsigned long file_crc(const char *buf, size_t len)
{
    uLong c = crc32(0L, Z_NULL, 0);
    for (size_t off = 0; off < len;) {
        size_t k = len - off > (1u << 30) ? (1u << 30) : len - off;
        c = crc32(c, (const Bytef *)buf + off, (uInt)k);
        off += k;
    }
    return c;
}

static char *dupstr(const char *s) { return sl_text_dup(s); }

int sl_comp_same_name(const char *a, const char *b) { return sl_casefold_same(a, b); }

/* ---- the components -------------------------------------------------------- */

double sl_comp_interp(const double *mu, const double *c, size_t n, double mu_at)
{
    if (n == 0 || !(mu_at >= mu[0]) || !(mu_at <= mu[n - 1]))
        return NAN;
    size_t k0 = 0; /* the last row at or below mu, as MATCH(mu, grid, 1) finds it */
    while (k0 + 1 < n && mu[k0 + 1] <= mu_at)
        k0++;
    size_t k1 = k0 + 1 < n ? k0 + 1 : k0;
    double mu0 = mu[k0], mu1 = mu[k1], c0 = c[k0], c1 = c[k1];
    /* the Lookup's formula, operation for operation (lookup_formula.c) */
    return mu1 == mu0 ? c0 : c0 + (mu_at - mu0) * (c1 - c0) / (mu1 - mu0);
}

int sl_comp_floor_at(const sl_comp_results *r, size_t fi, double mu, sl_comp_at *a)
{
    const sl_comp_floor *fl = &r->floors[fi];
    a->required_mm = sl_comp_interp(r->mu, fl->clearance_mm, r->n_mu, mu);
    a->se_mm = sl_comp_interp(r->mu, fl->se_mm, r->n_mu, mu);
    a->asce_mm = sl_comp_interp(r->mu, fl->asce_mm, r->n_mu, mu);
    a->k0 = a->k1 = 0;
    if (isnan(a->required_mm))
        return 0;
    while (a->k0 + 1 < r->n_mu && r->mu[a->k0 + 1] <= mu) /* as sl_comp_interp finds it */
        a->k0++;
    a->k1 = a->k0 + 1 < r->n_mu ? a->k0 + 1 : a->k0;
    return 1;
}

/* mu as the workbook's TEXT(x, "0.0##") shows it. */
static char *fmt_mu(double x, char *buf, size_t n)
{
    snprintf(buf, n, "%.3f", x);
    char *dot = strchr(buf, '.');
    if (dot) {
        char *e = buf + strlen(buf) - 1;
        while (e > dot + 1 && *e == '0')
            *e-- = '\0';
    }
    return buf;
}

/* The sliding check's reason, for verdict v. */
static void slide_reason(const sl_comp_results *r, const sl_comp_row *w, sl_comp_verdict v,
                         char *buf, size_t n)
{
    char a[48], b[48], se[48];
    switch (v) {
    case SL_COMP_ROCKING:
        snprintf(buf, n, "mu %s >= b/h %s: rocks before it slides; its rocking is computed by "
                 "seislide components", fmt_mu(w->mu, a, sizeof a),
                 fmt_mu(w->b_over_h, b, sizeof b));
        break;
    case SL_COMP_OUTSIDE: {
        char c[48];
        snprintf(buf, n, "mu %s outside the computed grid %s-%s: no clearance computed",
                 fmt_mu(w->mu, a, sizeof a), fmt_mu(r->mu[0], b, sizeof b),
                 fmt_mu(r->mu[r->n_mu - 1], c, sizeof c));
        break;
    }
    default:
        if (isfinite(w->se_mm))
            snprintf(se, sizeof se, "%.1f", w->se_mm);
        else
            snprintf(se, sizeof se, "-");
        if (v == SL_COMP_OK)
            snprintf(buf, n, "required %.1f mm (SE %s) <= available %.1f mm: margin %.1f mm",
                     w->required_mm, se, w->clearance_mm, w->margin_mm);
        else if (v == SL_COMP_MARGINAL)
            snprintf(buf, n, "required %.1f mm (SE %s) <= available %.1f mm: margin %.1f mm "
                     "< %g SE (%.1f mm), inside the noise of the motion sets", w->required_mm,
                     se, w->clearance_mm, w->margin_mm, SL_COMP_MARGIN_SE,
                     SL_COMP_MARGIN_SE * w->se_mm);
        else
            snprintf(buf, n, "required %.1f mm (SE %s) > available %.1f mm: %.1f mm short",
                     w->required_mm, se, w->clearance_mm, -w->margin_mm);
    }
}

char *sl_comp_rock_prefix(const sl_comp_row *w, char *buf, size_t n)
{
    const sl_rockf_result *x = &w->rock;
    int k = snprintf(buf, n, "P(tip) %.1f %% (SE %.1f) at 1.0 x, %.1f %% (SE %.1f) at 1.5 x "
                     "(targets %g %%, %g %%)", 100 * x->level[0].p_tip,
                     100 * x->level[0].p_tip_se, 100 * x->level[1].p_tip,
                     100 * x->level[1].p_tip_se, 100 * SL_ROCKF_P_TARGET_1,
                     100 * SL_ROCKF_P_TARGET_2);
    if (k < 0 || (size_t)k >= n)
        return buf;
    if (w->rock_verdict == SL_COMP_OVERTURNS)
        snprintf(buf + k, n - (size_t)k, ": above its target");
    else if (w->rock_verdict == SL_COMP_MARGINAL)
        snprintf(buf + k, n - (size_t)k, ": within %g SE of its target after %zu sets",
                 SL_ROCKF_SE_DECIDE, x->n_sets);
    return buf;
}

/* The rocking check's reason: the prefix, then the excursion against the
 * available clearance (not for an item that overturns). */
static void rock_reason(const sl_comp_row *w, char *buf, size_t n)
{
    sl_comp_rock_prefix(w, buf, n);
    if (w->rock_verdict == SL_COMP_OVERTURNS)
        return;
    size_t k = strlen(buf);
    double e = 1000 * w->rock.excursion_m;
    if (w->rock_verdict == SL_COMP_SHORT)
        snprintf(buf + k, n - k, "; excursion %.1f mm > available %.1f mm: %.1f mm short", e,
                 w->clearance_mm, e - w->clearance_mm);
    else
        snprintf(buf + k, n - k, "; excursion %.1f mm <= available %.1f mm", e, w->clearance_mm);
}

char *sl_comp_reason(const sl_comp_results *r, const sl_comp_row *w, char *buf, size_t n)
{
    char a[48], b[48];
    if (w->mode == SL_COMP_MODE_SLIDING || (w->mode == SL_COMP_MODE_ROCKING && !w->has_rock)) {
        slide_reason(r, w, w->mode == SL_COMP_MODE_SLIDING ? w->verdict : SL_COMP_ROCKING, buf,
                     n);
    } else if (w->mode == SL_COMP_MODE_ROCKING) {
        rock_reason(w, buf, n);
    } else {
        char s1[600], s2[600];
        slide_reason(r, w, w->slide_verdict, s1, sizeof s1);
        if (w->has_rock)
            rock_reason(w, s2, sizeof s2);
        else
            snprintf(s2, sizeof s2, "mu_max %s >= b/h %s: its rocking is computed by seislide "
                     "components", fmt_mu(w->mu_max, a, sizeof a),
                     fmt_mu(w->b_over_h, b, sizeof b));
        snprintf(buf, n, "slides: %s; rocks: %s", s1, s2);
    }
    return buf;
}

/* A full list buf of n bytes ends in "...", cut at a character's start. */
static void ellipsis(char *buf, size_t n)
{
    size_t k = n - 4;
    while (k > 0 && ((unsigned char)buf[k] & 0xC0) == 0x80)
        k--;
    strcpy(buf + k, "...");
}

/* A name or tag of the components file for a message, as written: UTF-8
 * characters kept, a control byte or a byte that is not UTF-8 shown as
 * '?', whole characters up to NAME_SHOWN bytes. */
#define NAME_SHOWN 160
typedef struct shown_name {
    char s[NAME_SHOWN + 4];
} shown_name;

static shown_name as_written(const char *s)
{
    shown_name q;
    sl_text_quote_into(q.s, NAME_SHOWN, s, strlen(s));
    return q;
}

/* The known floors of building b (or the buildings) as a list for a message. */
static char *known_floors(const sl_comp_results *r, const char *b, char *buf, size_t n)
{
    size_t k = 0;
    buf[0] = '\0';
    for (size_t i = 0; i < r->n_floors && k + 1 < n; i++)
        if (!strcmp(r->floors[i].building, b))
            k += (size_t)snprintf(buf + k, n - k, "%s%s (%s)", k ? ", " : "", r->floors[i].id,
                                  r->floors[i].name);
    if (k >= n - 1 && n > 4)
        ellipsis(buf, n);
    return buf;
}

static char *known_buildings(const sl_comp_results *r, char *buf, size_t n)
{
    size_t k = 0;
    buf[0] = '\0';
    for (size_t b = 0; b < r->n_buildings && k + 1 < n; b++)
        k += (size_t)snprintf(buf + k, n - k, "%s%s", k ? ", " : "", r->buildings[b]);
    if (k >= n - 1 && n > 4)
        ellipsis(buf, n);
    return buf;
}

/* The building of a row: its index, or an error naming the known ones. */
static sl_status find_building(const sl_comp_results *r, const char *path, const sl_csvrec *w,
                               int col, size_t *bi, sl_error *err)
{
    char b[512], known[KNOWN_MAX];
    const char *s = sl_csv_trimmed(w->f[col], b, sizeof b);
    if (!r->is_plant) {
        if (!*s || (r->single && sl_comp_same_name(s, r->single))) {
            *bi = 0;
            return SL_OK;
        }
        return sl_error_set_at(err, SL_EINVAL, path, w->fline[col], col + 1,
                               "unknown building '%s': the results are one building (folder "
                               "'%s'): leave building empty", as_written(s).s,
                               r->single ? r->single : "");
    }
    if (!*s && r->n_buildings == 1) {
        *bi = 0;
        return SL_OK;
    }
    for (size_t k = 0; k < r->n_buildings; k++)
        if (sl_comp_same_name(s, r->buildings[k])) {
            *bi = k;
            return SL_OK;
        }
    return sl_error_set_at(err, SL_EINVAL, path, w->fline[col], col + 1,
                           *s ? "unknown building '%s'; the buildings: %s"
                              : "no building%s; the buildings: %s",
                           *s ? as_written(s).s : "",
                           known_buildings(r, known, sizeof known));
}

/* A floor of the results for a message: "roof (Ground slab, file roof.ini)". */
static char *floor_named(const sl_comp_floor *f, char *buf, size_t n)
{
    snprintf(buf, n, "%s (%s, file %s)", f->id, f->name, f->file ? f->file : "-");
    return buf;
}

/* The floor a row's reference names in building bi: the one floor of that
 * building whose id or name it is, compared without case as the workbook's
 * MATCH compares; a reference two floors answer to (one's id, another's
 * name) is refused naming both, never resolved by an order of preference. */
static sl_status find_floor(const sl_comp_results *r, const char *path, const sl_csvrec *w,
                            int col, size_t bi, size_t *fi, sl_error *err)
{
    char b[1024], known[KNOWN_MAX];
    const char *s = sl_csv_trimmed(w->f[col], b, sizeof b), *bld = r->buildings[bi];
    size_t hit = r->n_floors;
    for (size_t i = 0; i < r->n_floors; i++) {
        const sl_comp_floor *f = &r->floors[i];
        if (strcmp(f->building, bld) || !(sl_comp_same_name(s, f->id) || sl_comp_same_name(s, f->name)))
            continue;
        if (hit < r->n_floors) {
            char one[600], two[600];
            return sl_error_set_at(err, SL_EINVAL, path, w->fline[col], col + 1,
                                   "floor '%s' names two floors of the results: %s and %s (ids "
                                   "and names compared by the one name rule): rename one floor and "
                                   "rerun seislide run",
                                   as_written(s).s, floor_named(&r->floors[hit], one, sizeof one),
                                   floor_named(f, two, sizeof two));
        }
        hit = i;
    }
    if (hit < r->n_floors) {
        *fi = hit;
        return SL_OK;
    }
    char in[600] = "";
    if (r->is_plant)
        snprintf(in, sizeof in, " in building %s", bld);
    return sl_error_set_at(err, SL_EINVAL, path, w->fline[col], col + 1,
                           "unknown floor '%s'%s; its floors (id (name)): %s",
                           as_written(s).s, in,
                           known_floors(r, bld, known, sizeof known));
}

sl_status sl_comp_find(const sl_comp_results *r, const char *building, const char *floor,
                       size_t *fi, sl_error *err)
{
    /* a record of two fields, resolved as a row of the list is (no file, no line) */
    char *f[2] = {(char *)(building ? building : ""), (char *)(floor ? floor : "")};
    long fline[2] = {0, 0};
    const sl_csvrec w = {.f = f, .fline = fline, .n = 2};
    size_t bi = 0;
    sl_status st = find_building(r, NULL, &w, 0, &bi, err);
    return st ? st : find_floor(r, NULL, &w, 1, bi, fi, err);
}

/* A number of a row that must be > 0 (or >= 0 with nonneg); in a list
 * separated by ';' a decimal comma is a point (sl_text_decimal_comma). */
static sl_status row_num(const char *path, char sep, const sl_csvrec *w, int col, int nonneg,
                         double *v, sl_error *err)
{
    char b[SL_TEXT_TOKEN_MAX + 1], shown[SL_TEXT_TOKEN_MAX + 1];
    const char *s = sl_csv_trimmed(w->f[col], b, sizeof b);
    snprintf(shown, sizeof shown, "%s", s);
    if (!*s)
        return sl_error_set_at(err, SL_EPARSE, path, w->fline[col], col + 1, "empty value");
    if (sep == ';' && !sl_text_decimal_comma(b))
        return sl_error_set_at(err, SL_EPARSE, path, w->fline[col], col + 1, "'%s' mixes ',' "
                               "and '.' (or holds two commas): in a list separated by ';' write "
                               "numbers with one decimal comma and no thousands separator, e.g. "
                               "0,35", sl_text_quote(shown, strlen(shown)).s);
    sl_num_result nr = sl_text_parse_num(s, strlen(s), v);
    if (nr != SL_NUM_OK)
        return sl_error_set_at(err, nr == SL_NUM_BAD ? SL_EPARSE : SL_EINVAL, path,
                               w->fline[col], col + 1, "%s value '%s'",
                               nr == SL_NUM_BAD ? "non-numeric" : "non-finite",
                               sl_text_quote(shown, strlen(shown)).s);
    if (nonneg ? !(*v >= 0) : !(*v > 0))
        return sl_error_set_at(err, SL_EINVAL, path, w->fline[col], col + 1, "value %s must be "
                               "%s", shown, nonneg ? ">= 0" : "> 0");
    return SL_OK;
}

/* An optional number of a row: NAN when its column is absent or the field
 * empty; else as row_num (>= 0), then within [lo, hi]. */
static sl_status opt_num(const char *path, char sep, const sl_csvrec *w, int col, double lo,
                         double hi, double *v, sl_error *err)
{
    char b[SL_TEXT_TOKEN_MAX + 1];
    *v = NAN;
    if (col < 0 || !*sl_csv_trimmed(w->f[col], b, sizeof b))
        return SL_OK;
    sl_status st = row_num(path, sep, w, col, lo >= 0, v, err);
    if (!st && !(*v >= lo && *v <= hi))
        st = sl_error_set_at(err, SL_EINVAL, path, w->fline[col], col + 1, "value %s outside "
                             "[%g, %g]", sl_csv_trimmed(w->f[col], b, sizeof b), lo, hi);
    if (st)
        *v = NAN;
    return st;
}

void sl_comp_table_free(sl_comp_table *t)
{
    if (!t)
        return;
    for (size_t i = 0; i < t->n; i++) {
        for (size_t c = 0; t->rows[i].field && c < t->n_cols; c++)
            free(t->rows[i].field[c]);
        free(t->rows[i].field);
    }
    for (size_t c = 0; t->header && c < t->n_cols; c++)
        free(t->header[c]);
    free(t->header);
    free(t->rows);
    free(t->path);
    memset(t, 0, sizeof *t);
}

/* Take the fields of record w (moved out of it). */
static char **take_fields(sl_csvrec *w)
{
    char **f = malloc((w->n ? w->n : 1) * sizeof *f);
    if (!f)
        return NULL;
    memcpy(f, w->f, w->n * sizeof *f);
    w->n = 0;
    return f;
}

/* Where the problems of a list go: into p (every one, up to the cap), or
 * the first into err and the reading stops (p NULL). */
typedef struct sink {
    sl_comp_problems *p;
    sl_error *err;
    size_t n;                /* problems so far */
    int stop;                /* 1: stop reading (p NULL, or a problem after which no row
                                can be read) */
    sl_status first;         /* the first problem's code */
} sink;

static void note(sink *k, const sl_error *e)
{
    if (!k->n++) {
        k->first = e->code;
        if (k->err)
            *k->err = *e;
    }
    if (!k->p) {
        k->stop = 1;
        return;
    }
    if (k->p->n < SL_COMP_MAX_PROBLEMS)
        k->p->e[k->p->n++] = *e;
    else
        k->p->n_more++;
}

/* A problem after which the reading stops (the header, a broken quote, no
 * memory, too many rows). */
static void fatal(sink *k, const sl_error *e)
{
    note(k, e);
    k->stop = 1;
}

static void no_memory(sink *k, const char *path)
{
    sl_error e;
    sl_error_set(&e, SL_ENOMEM, path, 0, "out of memory");
    fatal(k, &e);
}

static sl_status read_header(const char *path, sl_csvread *rd, sl_csvrec *h, sl_comp_table *t,
                             sl_error *err)
{
    sl_status st = sl_csvread_detect_sep(rd, err);
    if (st)
        return st;
    t->sep = rd->sep;
    int got = sl_csvread_next(rd, h, err);
    if (got < 0)
        return (sl_status)-got;
    if (!got)
        return sl_error_set(err, SL_EPARSE, path, rd->line, "no header row (tag, building, "
                            "floor, mu, base_m, cg_height_m, clearance_mm)");
    if (h->n > SL_COMP_MAX_COLS)
        return sl_error_set_at(err, SL_EPARSE, path, h->line, SL_COMP_MAX_COLS + 1,
                               "more than %d columns", SL_COMP_MAX_COLS);
    char b[256];
    for (int k = 0; k < SL_COMP_NCOLS; k++)
        t->col[k] = -1;
    for (int k = 0; k < SL_COMP_NOPT; k++)
        t->opt[k] = -1;
    for (size_t c = 0; c < h->n; c++) {
        const char *s = sl_csv_trimmed(h->f[c], b, sizeof b);
        if (!*s)
            return sl_error_set_at(err, SL_EPARSE, path, h->line, (long)c + 1, "empty column "
                                   "name");
        for (size_t e = 0; e < c; e++)
            if (sl_comp_same_name(s, h->f[e]))
                return sl_error_set_at(err, SL_EPARSE, path, h->line, (long)c + 1, "column "
                                       "'%s' again (column %zu)", sl_text_quote(s, strlen(s)).s,
                                       e + 1);
        for (int k = 0; k < SL_COMP_NCOLS; k++)
            if (sl_comp_same_name(s, SL_COMP_COL_NAME[k]))
                t->col[k] = (int)c;
        for (int k = 0; k < SL_COMP_NOPT; k++)
            if (sl_comp_same_name(s, SL_COMP_OPT_NAME[k]))
                t->opt[k] = (int)c;
    }
    for (int k = 0; k < SL_COMP_NCOLS; k++)
        if (t->col[k] < 0)
            return sl_error_set(err, SL_EPARSE, path, h->line, "no column '%s' in the header "
                                "(tag, building, floor, mu, base_m, cg_height_m, clearance_mm; "
                                "without case; the columns separated by ',', or all by ';')",
                                SL_COMP_COL_NAME[k]);
    t->n_cols = h->n;
    return (t->header = take_fields(h)) ? SL_OK
                                       : sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
}

/* The verdict of a computed row (components.h: in this order). */
static sl_comp_verdict verdict(const sl_comp_row *x)
{
    if (x->mu >= x->b_over_h)
        return SL_COMP_ROCKING;
    if (isnan(x->required_mm))
        return SL_COMP_OUTSIDE;
    if (x->margin_mm < 0)
        return SL_COMP_SHORT;
    double se = isfinite(x->se_mm) ? x->se_mm : 0; /* an empty SE counts as 0 */
    if (x->margin_mm < SL_COMP_MARGIN_SE * se)
        return SL_COMP_MARGINAL;
    return SL_COMP_OK;
}

/* The tags seen: a hash set of their keys (sl_casefold_key) with the line
 * of each one's first row, so that a repeated tag is found in one pass. */
typedef struct tag_set {
    char **key;
    long *line;
    size_t cap, n;
} tag_set;

static size_t tag_hash(const char *s)
{
    size_t h = 14695981039346656037ULL & (size_t)-1; /* FNV-1a */
    for (; *s; s++)
        h = (h ^ (unsigned char)*s) * (size_t)1099511628211ULL;
    return h;
}

static void tag_set_free(tag_set *s)
{
    for (size_t i = 0; i < s->cap; i++)
        free(s->key[i]);
    free(s->key);
    free(s->line);
    memset(s, 0, sizeof *s);
}

/* The tag's first line when it was seen before, else 0 (and it is added);
 * -1 on no memory. */
static long tag_seen(tag_set *s, const char *tag, long line)
{
    if (2 * (s->n + 1) > s->cap) {
        tag_set g = {calloc(s->cap ? 2 * s->cap : 256, sizeof(char *)),
                     calloc(s->cap ? 2 * s->cap : 256, sizeof(long)), s->cap ? 2 * s->cap : 256,
                     s->n};
        if (!g.key || !g.line) {
            free(g.key);
            free(g.line);
            return -1;
        }
        for (size_t i = 0; i < s->cap; i++)
            if (s->key[i]) {
                size_t j = tag_hash(s->key[i]) & (g.cap - 1);
                while (g.key[j])
                    j = (j + 1) & (g.cap - 1);
                g.key[j] = s->key[i];
                g.line[j] = s->line[i];
            }
        free(s->key);
        free(s->line);
        *s = g;
    }
    char *key = malloc(2 * strlen(tag) + 1);
    if (!key)
        return -1;
    sl_casefold_key(tag, key, 2 * strlen(tag) + 1);
    size_t j = tag_hash(key) & (s->cap - 1);
    for (; s->key[j]; j = (j + 1) & (s->cap - 1))
        if (!strcmp(s->key[j], key)) {
            free(key);
            return s->line[j];
        }
    s->key[j] = key;
    s->line[j] = line;
    s->n++;
    return 0;
}

/* One data record w checked and computed into row x: every field checked
 * (a repeated tag against the set of tags), each problem noted in the
 * order of the fields; 1 when the row is good. */
static int read_row(const sl_comp_results *r, sl_comp_table *t, sl_csvrec *w, sl_comp_row *x,
                    tag_set *tags, sink *k)
{
    const char *path = t->path;
    const int *col = t->col;
    sl_error e;
    size_t n0 = k->n;
    if (w->n != t->n_cols) { /* the fields cannot be told apart: one problem for the row */
        sl_error_set_at(&e, SL_EPARSE, path, w->line, (long)(w->n < t->n_cols ? w->n + 1
                        : t->n_cols + 1), "%zu fields; the header has %zu", w->n, t->n_cols);
        note(k, &e);
        return 0;
    }
    char b[512];
    const char *tag = sl_csv_trimmed(w->f[col[SL_COMP_TAG]], b, sizeof b);
    long first = *tag ? tag_seen(tags, tag, w->line) : 0;
    if (!*tag)
        sl_error_set_at(&e, SL_EPARSE, path, w->fline[col[SL_COMP_TAG]], col[SL_COMP_TAG] + 1,
                        "empty tag");
    else if (first > 0) /* without case, as the workbook's COUNTIF compares */
        sl_error_set_at(&e, SL_EINVAL, path, w->fline[col[SL_COMP_TAG]], col[SL_COMP_TAG] + 1,
                        "tag '%s' again: first on line %ld", as_written(tag).s, first);
    else if (first < 0)
        sl_error_set(&e, SL_ENOMEM, path, 0, "out of memory");
    if (first < 0)
        fatal(k, &e);
    else if (!*tag || first)
        note(k, &e);
    size_t bi = 0;
    if (!k->stop && find_building(r, path, w, col[SL_COMP_BUILDING], &bi, &e))
        note(k, &e);
    else if (!k->stop && find_floor(r, path, w, col[SL_COMP_FLOOR], bi, &x->floor, &e))
        note(k, &e);
    const struct { int c, nonneg; double *v; } num[] = {
        {SL_COMP_MU, 0, &x->mu}, {SL_COMP_BASE, 0, &x->base_m}, {SL_COMP_CG, 0, &x->cg_height_m},
        {SL_COMP_CLEARANCE, 1, &x->clearance_mm}};
    for (size_t q = 0; q < sizeof num / sizeof num[0] && !k->stop; q++)
        if (row_num(path, t->sep, w, col[num[q].c], num[q].nonneg, num[q].v, &e))
            note(k, &e);
    /* the optional columns: mu_max >= mu, r in [0, 1], any finite orientation */
    const struct { int c; double lo, hi; double *v; } opt[] = {
        {SL_COMP_MU_MAX, 0, INFINITY, &x->mu_max}, {SL_COMP_RESTITUTION, 0, 1, &x->restitution},
        {SL_COMP_ORIENTATION, -INFINITY, INFINITY, &x->orientation_deg}};
    for (size_t q = 0; q < sizeof opt / sizeof opt[0] && !k->stop; q++)
        if (opt_num(path, t->sep, w, t->opt[opt[q].c], opt[q].lo, opt[q].hi, opt[q].v, &e))
            note(k, &e);
    if (!k->stop && !isnan(x->mu_max) && isfinite(x->mu) && !(x->mu_max >= x->mu)) {
        int c = t->opt[SL_COMP_MU_MAX];
        sl_error_set_at(&e, SL_EINVAL, path, w->fline[c], c + 1, "mu_max %g below mu %g",
                        x->mu_max, x->mu);
        note(k, &e);
    }
    if (k->n != n0)
        return 0;
    x->line = w->line;
    /* Shenton (1996): a rigid block slides before it rocks when mu < b/h */
    x->b_over_h = x->base_m / (2 * x->cg_height_m);
    sl_comp_at at;
    sl_comp_floor_at(r, x->floor, x->mu, &at);
    x->required_mm = at.required_mm;
    x->se_mm = at.se_mm;
    x->asce_mm = at.asce_mm;
    x->margin_mm = x->clearance_mm - x->required_mm;
    x->slide_verdict = verdict(x);
    x->mode = x->mu >= x->b_over_h ? SL_COMP_MODE_ROCKING
              : !isnan(x->mu_max) && x->mu_max >= x->b_over_h ? SL_COMP_MODE_BOTH
                                                              : SL_COMP_MODE_SLIDING;
    x->rock_verdict = SL_COMP_ROCKING; /* until sl_comp_set_rocking */
    x->verdict = x->mode == SL_COMP_MODE_SLIDING ? x->slide_verdict : SL_COMP_ROCKING;
    return 1;
}

sl_rockf_item sl_comp_rock_item(const sl_comp_row *w)
{
    sl_rockf_item it = {{w->base_m / 2, w->cg_height_m,
                         isnan(w->restitution) ? -1.0 : w->restitution},
                        w->orientation_deg};
    return it;
}

/* How bad a verdict is, for a row checked both ways (components.h). */
static int badness(sl_comp_verdict v)
{
    switch (v) {
    case SL_COMP_OVERTURNS: return 6;
    case SL_COMP_SHORT: return 5;
    case SL_COMP_ROCKING: return 4; /* not computed: no verdict yet */
    case SL_COMP_OUTSIDE: return 3;
    case SL_COMP_MARGINAL: return 2;
    default: return 1; /* ok, stands */
    }
}

void sl_comp_set_rocking(sl_comp_table *t, size_t i, const sl_rockf_result *res)
{
    sl_comp_row *w = &t->rows[i];
    if (w->mode == SL_COMP_MODE_SLIDING)
        return;
    static const sl_comp_verdict of[] = {SL_COMP_STANDS, SL_COMP_MARGINAL, SL_COMP_SHORT,
                                         SL_COMP_OVERTURNS};
    const double target[SL_ROCKF_NLEVELS] = {SL_ROCKF_P_TARGET_1, SL_ROCKF_P_TARGET_2};
    w->rock = *res;
    w->has_rock = 1;
    w->rock_verdict = of[sl_rockf_verdict_of(res, target, w->clearance_mm / 1000.0)];
    sl_comp_verdict v = w->rock_verdict;
    if (w->mode == SL_COMP_MODE_BOTH && badness(w->slide_verdict) >= badness(v))
        v = w->slide_verdict; /* equal: the sliding word (ok rather than stands) */
    t->count[w->verdict]--;
    w->verdict = v;
    t->count[v]++;
}

sl_status sl_comp_table_read(const char *path, const sl_comp_results *r, sl_comp_table *t,
                             sl_comp_problems *p, sl_error *err)
{
    memset(t, 0, sizeof *t);
    if (p)
        memset(p, 0, sizeof *p);
    sink k = {.p = p, .err = err};
    sl_text txt;
    sl_csvread rd;
    sl_error e;
    sl_status st = sl_csv_open(path, SL_COMP_MAX_BYTES, &txt, &rd, err);
    if (st)
        return st;
    sl_csvrec h = {0}, w = {0};
    tag_set tags = {0};
    t->crc32 = file_crc(txt.mem, strlen(txt.mem));
    t->size_bytes = (long)strlen(txt.mem);
    if (!(t->path = dupstr(path)))
        no_memory(&k, path);
    else if (read_header(path, &rd, &h, t, &e))
        fatal(&k, &e);
    size_t cap = 0;
    for (int got; !k.stop && (got = sl_csvread_next(&rd, &w, &e)) != 0;) {
        if (got < 0) {
            fatal(&k, &e);
            break;
        }
        int blank = 1; /* a row of empty fields (",,,,": spreadsheets export them) */
        char bb[64];
        for (size_t c = 0; c < w.n && blank; c++)
            blank = !*sl_csv_trimmed(w.f[c], bb, sizeof bb);
        if (blank)
            continue;
        if (p)
            p->n_rows++;
        if (p ? p->n_rows > SL_COMP_MAX_ROWS : t->n == SL_COMP_MAX_ROWS) {
            sl_error_set(&e, SL_EINVAL, path, w.line, "more than %d components",
                         SL_COMP_MAX_ROWS);
            fatal(&k, &e);
            break;
        }
        if (t->n == cap) {
            sl_comp_row *g = realloc(t->rows, (cap = cap ? 2 * cap : 64) * sizeof *g);
            if (!g) {
                no_memory(&k, path);
                break;
            }
            t->rows = g;
        }
        size_t n0 = k.n;
        sl_comp_row *x = &t->rows[t->n];
        memset(x, 0, sizeof *x);
        int good = read_row(r, t, &w, x, &tags, &k);
        if (p && k.n != n0)
            p->n_bad_rows++;
        if (!good || k.n)
            continue; /* once a row is refused only the problems are gathered */
        if (!(x->field = take_fields(&w))) {
            no_memory(&k, path);
            break;
        }
        t->n++;
        t->count[x->verdict]++;
    }
    if (!k.n && t->n == 0) {
        sl_error_set(&e, SL_EPARSE, path, rd.line, "no components under the header");
        fatal(&k, &e);
    }
    sl_csvrec_free(&h);
    sl_csvrec_free(&w);
    sl_text_free(&txt);
    tag_set_free(&tags);
    if (!k.n)
        return SL_OK;
    if (p && k.n > 1)
        sl_error_set(err, k.first, path, 0, "%zu of %zu rows refused (%zu problems)",
                     p->n_bad_rows, p->n_rows, k.n);
    sl_comp_table_free(t);
    return k.first;
}

/* ---- components.csv -------------------------------------------------------- */

static void csv_num(FILE *f, double v, const char *fmt)
{
    if (isfinite(v))
        fprintf(f, fmt, v);
}

void sl_comp_report(const sl_comp_results *r, const sl_comp_opts *o, sl_report *rep)
{
    sl_report_init(rep);
    rep->version = o->version;
    rep->command_line = o->command_line;
    rep->seed = r->seed;
    rep->created = o->created;
    rep->project.project = strcmp(r->project, "-") ? r->project : NULL;
    rep->project.document = strcmp(r->document, "-") ? r->document : NULL;
    rep->project.revision = strcmp(r->revision, "-") ? r->revision : NULL;
    rep->project.date = o->date; /* the check's own date, as a run's title block */
}

/* The run's record as the shared CSV head reads it; floors named
 * BUILDING/ID in a plant (as plant.csv names them). */
static sl_status shared_report(const sl_comp_results *r, const sl_comp_opts *o, sl_report *rep,
                               sl_rpt_floors *floors, sl_error *err)
{
    sl_comp_report(r, o, rep);
    if (sl_rpt_floors_alloc(floors, rep, r->n_floors, NULL, err))
        return err ? err->code : SL_ENOMEM;
    for (size_t i = 0; i < r->n_floors; i++) {
        const sl_comp_floor *fl = &r->floors[i];
        sl_rpt_floors_set(floors, i, fl->building, r->is_plant ? "/" : "", fl->id,
                          (sl_report_floor){.name = fl->name, .path = fl->file ? fl->file : "-",
                                            .crc32 = fl->crc32, .size_bytes = fl->size_bytes});
    }
    return SL_OK;
}

static sl_status write_csv(const sl_comp_results *r, const sl_comp_table *t, const char *dir,
                           const sl_comp_opts *o, sl_error *err)
{
    char path[4400], buf[2400];
    snprintf(path, sizeof path, "%s/%s", dir, SL_COMP_CSV);
    sl_report rep;
    sl_rpt_floors floors;
    if (shared_report(r, o, &rep, &floors, err))
        return err ? err->code : SL_ENOMEM;
    sl_atomic *a = sl_atomic_open(path, err);
    if (!a) {
        sl_rpt_floors_free(&floors);
        return err ? err->code : SL_EIO;
    }
    FILE *f = sl_atomic_file(a);
    sl_rpt_csv_head(f, &rep, "one row per component: its columns as given, then the required "
                    "clearance at its mu on its floor, the margin and the verdict");
    sl_rpt_floors_free(&floors);
    snprintf(buf, sizeof buf, "%s (%08lx, %ld bytes)", t->path, t->crc32 & 0xffffffffUL,
             t->size_bytes);
    sl_rpt_csv_comment(f, "components_file", buf);
    snprintf(buf, sizeof buf, "%s (%s; created %s; command %s)", r->dir,
             r->is_plant ? "a plant" : "one building", r->created, r->command);
    sl_rpt_csv_comment(f, "results", buf);
    sl_rpt_csv_comment(f, "units", "base_m and cg_height_m in m; clearances and margin in mm; mu "
                       "and b_over_h dimensionless");
    snprintf(buf, sizeof buf, "%s (the run's; required_clearance_mm is %s)", r->policy,
             !strcmp(r->policy, "asce") ? "the ASCE/SEI 43-05 design value"
             : !strcmp(r->policy, "envelope") ? "the larger of the NLTHA and ASCE design values"
             : "the NLTHA design value");
    sl_rpt_csv_comment(f, "clearance_policy", buf);
    sl_rpt_csv_comment(f, "required_clearance_mm", "the floor's required clearance (clearance_mm "
                       "of its floor table) at mu, linear interpolation between the grid rows "
                       "around it, as the workbook's Lookup; empty off the grid");
    sl_rpt_csv_comment(f, "required_clearance_se_mm", "the standard error of the NLTHA design "
                       "value, interpolated the same way");
    sl_rpt_csv_comment(f, "asce_design_mm", "the ASCE/SEI 43-05 design value at mu "
                       "(asce_design_mm of the floor table), interpolated the same way, beside "
                       "the required clearance");
    sl_rpt_csv_comment(f, "mode", "sliding when mu (mu_max when given) < b_over_h = base_m / "
                       "(2 cg_height_m); rocking when mu >= b_over_h (a rigid block rocks before "
                       "it slides, Shenton 1996); both when mu < b_over_h <= mu_max: both checks, "
                       "the worse verdict governs (overturns, short, outside, marginal, ok)");
    snprintf(buf, sizeof buf, "sliding: outside when mu is off the grid; else, with margin_mm = "
             "clearance_mm - required_clearance_mm: short when margin_mm < 0; marginal when "
             "margin_mm < %g x required_clearance_se_mm (inside the noise of the motion sets: "
             "more sets or more gap decide it); else ok. Rocking (ASCE/SEI 43-05 section 1.3 "
             "targets, tipping as unacceptable performance): overturns when p_tip > %g or "
             "p_tip_15 > %g; short when excursion_mm > clearance_mm; marginal when a p_tip is "
             "within %g standard errors of its target; else stands", SL_COMP_MARGIN_SE,
             SL_ROCKF_P_TARGET_1, SL_ROCKF_P_TARGET_2, SL_ROCKF_SE_DECIDE);
    sl_rpt_csv_comment(f, "verdict", buf);
    snprintf(buf, sizeof buf, "NLTHA of the rocking block (Housner 1963) on the floor's own "
             "synthesized sets (rocking_sets of them: %d, then %d more while the verdict is "
             "within %g SE of a target), the horizontals scaled by a log-normal intensity "
             "factor of log standard deviation %.2f (mean 1; %g-point quadrature), the weak "
             "axis the worst of every %g degrees (or orientation_deg); p_uplift, p_tip "
             "(|theta| reaches alpha), p_overturn (pi/2): fractions at the floor motion, _15 "
             "at 1.5 x it, each with its standard error over sets; theta_over_alpha: peak "
             "rotation over alpha, mean and 84th percentile; excursion_mm: 2 h sin(peak "
             "theta), the larger of its %g %% exceedance value at 1.0 x and %g %% at 1.5 x "
             "(docs/rocking.md)", SL_ROCKF_MIN_SETS, SL_ROCKF_CHUNK, SL_ROCKF_SE_DECIDE,
             SL_ROCKF_SCATTER, (SL_ROCKF_ZMAX - SL_ROCKF_ZMIN) / SL_ROCKF_DZ + 1,
             SL_ROCKF_ORIENT_STEP_DEG, 100 * SL_ROCKF_P_TARGET_1, 100 * SL_ROCKF_P_TARGET_2);
    sl_rpt_csv_comment(f, "rocking", buf);
    for (size_t c = 0; c < t->n_cols; c++) {
        sl_rpt_csv_field(f, t->header[c]);
        fputc(',', f);
    }
    fputs("b_over_h,required_clearance_mm,required_clearance_se_mm,asce_design_mm,margin_mm,"
          "verdict,reason,mode,sliding_verdict,rocking_verdict,rocking_sets,p_uplift,p_tip,"
          "p_tip_se,p_tip_15,p_tip_15_se,p_overturn,p_overturn_15,theta_over_alpha_mean,"
          "theta_over_alpha_p84,excursion_mm\r\n", f);
    for (size_t i = 0; i < t->n; i++) {
        const sl_comp_row *w = &t->rows[i];
        for (size_t c = 0; c < t->n_cols; c++) {
            sl_rpt_csv_field(f, w->field[c]);
            fputc(',', f);
        }
        csv_num(f, w->b_over_h, "%.4g");
        fputc(',', f);
        csv_num(f, w->required_mm, "%.1f");
        fputc(',', f);
        csv_num(f, w->se_mm, "%.1f");
        fputc(',', f);
        csv_num(f, w->asce_mm, "%.1f");
        fputc(',', f);
        csv_num(f, w->margin_mm, "%.1f");
        fprintf(f, ",%s,", SL_COMP_VERDICT_NAME[w->verdict]);
        sl_rpt_csv_field(f, sl_comp_reason(r, w, buf, sizeof buf));
        fprintf(f, ",%s,%s,%s", SL_COMP_MODE_NAME[w->mode],
                w->mode != SL_COMP_MODE_ROCKING ? SL_COMP_VERDICT_NAME[w->slide_verdict] : "",
                w->mode != SL_COMP_MODE_SLIDING ? SL_COMP_VERDICT_NAME[w->rock_verdict] : "");
        if (w->has_rock) {
            const sl_rockf_result *x = &w->rock;
            fprintf(f, ",%zu,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.3f,%.3f,%.1f", x->n_sets,
                    x->level[0].p_uplift, x->level[0].p_tip, x->level[0].p_tip_se,
                    x->level[1].p_tip, x->level[1].p_tip_se, x->level[0].p_overturn,
                    x->level[1].p_overturn, x->level[0].theta_ratio_mean,
                    x->level[0].theta_ratio_q, 1000 * x->excursion_m);
        } else {
            fputs(",,,,,,,,,,,", f);
        }
        fputs("\r\n", f);
    }
    return sl_atomic_commit(a, err);
}

sl_status sl_comp_write(const sl_comp_results *r, const sl_comp_table *t, const char *dir,
                        const sl_comp_opts *o, sl_error *err)
{
    char path[4400];
    if (write_csv(r, t, dir, o, err))
        return err ? err->code : SL_EIO;
    snprintf(path, sizeof path, "%s/%s", dir, SL_COMP_XLSX);
    return sl_comp_write_xlsx(r, t, path, o, err);
}
