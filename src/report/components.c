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
#include "io/text.h"
#include "report/csvread.h"
#include "report/plant_book.h"
#include "report/sheets.h"

const char *const SL_COMP_COL_NAME[SL_COMP_NCOLS] = {"tag", "building", "floor", "mu", "base_m",
                                                     "cg_height_m", "clearance_mm"};
const char *const SL_COMP_VERDICT_NAME[SL_COMP_NVERDICTS] = {"ok", "short", "rocking",
                                                             "outside"};
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

char *sl_comp_reason(const sl_comp_results *r, const sl_comp_row *w, char *buf, size_t n)
{
    char a[48], b[48], se[48];
    switch (w->verdict) {
    case SL_COMP_ROCKING:
        snprintf(buf, n, "mu %s >= b/h %s: rocks before it slides, check rocking (ASCE 43-05)",
                 fmt_mu(w->mu, a, sizeof a), fmt_mu(w->b_over_h, b, sizeof b));
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
        if (w->verdict == SL_COMP_OK)
            snprintf(buf, n, "required %.1f mm (SE %s) <= available %.1f mm: margin %.1f mm",
                     w->required_mm, se, w->clearance_mm, w->margin_mm);
        else
            snprintf(buf, n, "required %.1f mm (SE %s) > available %.1f mm: %.1f mm short",
                     w->required_mm, se, w->clearance_mm, -w->margin_mm);
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
        if (!*s || (r->single && !strcasecmp(s, r->single))) {
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
        if (!strcasecmp(s, r->buildings[k])) {
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
        if (strcmp(f->building, bld) || (strcasecmp(s, f->id) && strcasecmp(s, f->name)))
            continue;
        if (hit < r->n_floors) {
            char one[600], two[600];
            return sl_error_set_at(err, SL_EINVAL, path, w->fline[col], col + 1,
                                   "floor '%s' names two floors of the results: %s and %s (ids "
                                   "and names compared without case): rename one floor and "
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

/* A number of a row that must be > 0 (or >= 0 with nonneg). */
static sl_status row_num(const char *path, const sl_csvrec *w, int col, int nonneg, double *v,
                         sl_error *err)
{
    char b[SL_TEXT_TOKEN_MAX + 1];
    const char *s = sl_csv_trimmed(w->f[col], b, sizeof b);
    sl_num_result nr = sl_text_parse_num(s, strlen(s), v);
    if (!*s)
        return sl_error_set_at(err, SL_EPARSE, path, w->fline[col], col + 1, "empty value");
    if (nr != SL_NUM_OK)
        return sl_error_set_at(err, nr == SL_NUM_BAD ? SL_EPARSE : SL_EINVAL, path,
                               w->fline[col], col + 1, "%s value '%s'",
                               nr == SL_NUM_BAD ? "non-numeric" : "non-finite",
                               sl_text_quote(s, strlen(s)).s);
    if (nonneg ? !(*v >= 0) : !(*v > 0))
        return sl_error_set_at(err, SL_EINVAL, path, w->fline[col], col + 1, "value %s must be "
                               "%s", s, nonneg ? ">= 0" : "> 0");
    return SL_OK;
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

static sl_status read_header(const char *path, sl_csvread *rd, sl_csvrec *h, sl_comp_table *t,
                             sl_error *err)
{
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
    for (size_t c = 0; c < h->n; c++) {
        const char *s = sl_csv_trimmed(h->f[c], b, sizeof b);
        if (!*s)
            return sl_error_set_at(err, SL_EPARSE, path, h->line, (long)c + 1, "empty column "
                                   "name");
        for (size_t e = 0; e < c; e++) {
            char b2[256];
            if (!strcasecmp(s, sl_csv_trimmed(h->f[e], b2, sizeof b2)))
                return sl_error_set_at(err, SL_EPARSE, path, h->line, (long)c + 1, "column "
                                       "'%s' again (column %zu)", sl_text_quote(s, strlen(s)).s,
                                       e + 1);
        }
        for (int k = 0; k < SL_COMP_NCOLS; k++)
            if (!strcasecmp(s, SL_COMP_COL_NAME[k]))
                t->col[k] = (int)c;
    }
    for (int k = 0; k < SL_COMP_NCOLS; k++)
        if (t->col[k] < 0)
            return sl_error_set(err, SL_EPARSE, path, h->line, "no column '%s' in the header "
                                "(tag, building, floor, mu, base_m, cg_height_m, clearance_mm; "
                                "without case)", SL_COMP_COL_NAME[k]);
    t->n_cols = h->n;
    return (t->header = take_fields(h)) ? SL_OK
                                       : sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
}

/* One data record w checked and computed into row x. */
static sl_status read_row(const sl_comp_results *r, sl_comp_table *t, sl_csvrec *w,
                          sl_comp_row *x, sl_error *err)
{
    const char *path = t->path;
    const int *col = t->col;
    if (w->n != t->n_cols)
        return sl_error_set_at(err, SL_EPARSE, path, w->line, (long)(w->n < t->n_cols ? w->n + 1
                               : t->n_cols + 1), "%zu fields; the header has %zu", w->n,
                               t->n_cols);
    char b[512];
    if (!*sl_csv_trimmed(w->f[col[SL_COMP_TAG]], b, sizeof b))
        return sl_error_set_at(err, SL_EPARSE, path, w->fline[col[SL_COMP_TAG]],
                               col[SL_COMP_TAG] + 1, "empty tag");
    size_t bi = 0;
    sl_status st;
    if ((st = find_building(r, path, w, col[SL_COMP_BUILDING], &bi, err)) ||
        (st = find_floor(r, path, w, col[SL_COMP_FLOOR], bi, &x->floor, err)) ||
        (st = row_num(path, w, col[SL_COMP_MU], 0, &x->mu, err)) ||
        (st = row_num(path, w, col[SL_COMP_BASE], 0, &x->base_m, err)) ||
        (st = row_num(path, w, col[SL_COMP_CG], 0, &x->cg_height_m, err)) ||
        (st = row_num(path, w, col[SL_COMP_CLEARANCE], 1, &x->clearance_mm, err)))
        return st;
    x->line = w->line;
    const sl_comp_floor *fl = &r->floors[x->floor];
    /* Shenton (1996): a rigid block slides before it rocks when mu < b/h */
    x->b_over_h = x->base_m / (2 * x->cg_height_m);
    x->required_mm = sl_comp_interp(r->mu, fl->clearance_mm, r->n_mu, x->mu);
    x->se_mm = sl_comp_interp(r->mu, fl->se_mm, r->n_mu, x->mu);
    x->margin_mm = x->clearance_mm - x->required_mm;
    if (x->mu >= x->b_over_h)
        x->verdict = SL_COMP_ROCKING;
    else if (isnan(x->required_mm))
        x->verdict = SL_COMP_OUTSIDE;
    else if (x->margin_mm >= 0)
        x->verdict = SL_COMP_OK;
    else
        x->verdict = SL_COMP_SHORT;
    if (!(x->field = take_fields(w)))
        return sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
    return SL_OK;
}

sl_status sl_comp_table_read(const char *path, const sl_comp_results *r, sl_comp_table *t,
                             sl_error *err)
{
    memset(t, 0, sizeof *t);
    sl_text txt;
    sl_csvread rd;
    sl_status st = sl_csv_open(path, SL_COMP_MAX_BYTES, &txt, &rd, err);
    if (st)
        return st;
    sl_csvrec h = {0}, w = {0};
    t->crc32 = file_crc(txt.mem, strlen(txt.mem));
    t->size_bytes = (long)strlen(txt.mem);
    if (!(t->path = dupstr(path)))
        st = sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
    if (!st)
        st = read_header(path, &rd, &h, t, err);
    size_t cap = 0;
    for (int got; !st && (got = sl_csvread_next(&rd, &w, err)) != 0;) {
        if (got < 0) {
            st = (sl_status)-got;
            break;
        }
        if (t->n == SL_COMP_MAX_ROWS) {
            st = sl_error_set(err, SL_EINVAL, path, w.line, "more than %d components",
                              SL_COMP_MAX_ROWS);
            break;
        }
        if (t->n == cap) {
            sl_comp_row *g = realloc(t->rows, (cap = cap ? 2 * cap : 64) * sizeof *g);
            if (!g) {
                st = sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
                break;
            }
            t->rows = g;
        }
        int blank = 1; /* a row of empty fields (",,,,": spreadsheets export them) */
        char bb[64];
        for (size_t c = 0; c < w.n && blank; c++)
            blank = !*sl_csv_trimmed(w.f[c], bb, sizeof bb);
        if (blank)
            continue;
        sl_comp_row *x = &t->rows[t->n];
        memset(x, 0, sizeof *x);
        if ((st = read_row(r, t, &w, x, err)))
            break;
        t->n++;
        /* a repeated tag (without case, as the workbook's COUNTIF compares) */
        char b1[512], b2[512];
        const char *tag = sl_csv_trimmed(x->field[t->col[SL_COMP_TAG]], b1, sizeof b1);
        for (size_t i = 0; i + 1 < t->n; i++)
            if (!strcasecmp(tag, sl_csv_trimmed(t->rows[i].field[t->col[SL_COMP_TAG]], b2, sizeof b2))) {
                st = sl_error_set_at(err, SL_EINVAL, path, x->line, t->col[SL_COMP_TAG] + 1,
                                     "tag '%s' again: first on line %ld",
                                     as_written(tag).s, t->rows[i].line);
                break;
            }
        if (!st)
            t->count[x->verdict]++;
    }
    if (!st && t->n == 0)
        st = sl_error_set(err, SL_EPARSE, path, rd.line, "no components under the header");
    sl_csvrec_free(&h);
    sl_csvrec_free(&w);
    sl_text_free(&txt);
    if (st)
        sl_comp_table_free(t);
    return st;
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
    sl_rpt_csv_comment(f, "required_clearance_mm", "the floor's required clearance (clearance_mm "
                       "of its floor table) at mu, linear interpolation between the grid rows "
                       "around it, as the workbook's Lookup; empty off the grid");
    sl_rpt_csv_comment(f, "required_clearance_se_mm", "the standard error of the NLTHA design "
                       "value, interpolated the same way");
    sl_rpt_csv_comment(f, "verdict", "rocking when mu >= b_over_h = base_m / (2 cg_height_m) (a "
                       "rigid block rocks before it slides, Shenton 1996: check rocking, ASCE/SEI "
                       "43-05); else outside when mu is off the grid; else ok when margin_mm = "
                       "clearance_mm - required_clearance_mm >= 0; else short");
    for (size_t c = 0; c < t->n_cols; c++) {
        sl_rpt_csv_field(f, t->header[c]);
        fputc(',', f);
    }
    fputs("b_over_h,required_clearance_mm,required_clearance_se_mm,margin_mm,verdict,reason\r\n",
          f);
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
        csv_num(f, w->margin_mm, "%.1f");
        fprintf(f, ",%s,", SL_COMP_VERDICT_NAME[w->verdict]);
        sl_rpt_csv_field(f, sl_comp_reason(r, w, buf, sizeof buf));
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
