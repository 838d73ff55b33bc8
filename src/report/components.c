/* components.c - the components table read and checked against the floor
 * tables of a run, one verdict per row, and components.csv; see
 * components.h (the workbook: components_book.c). */
#include "report/components.h"

#include <ctype.h>
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <zlib.h>

#include "io/atomic.h"
#include "io/text.h"
#include "report/plant_book.h"
#include "report/sheets.h"

const char *const SL_COMP_COL_NAME[SL_COMP_NCOLS] = {"tag", "building", "floor", "mu", "base_m",
                                                     "cg_height_m", "clearance_mm"};
const char *const SL_COMP_VERDICT_NAME[SL_COMP_NVERDICTS] = {"ok", "short", "rocking",
                                                             "outside"};
/* Largest results CSV read, bytes (a floor table, floors.csv, plant.csv). */
#define RESULTS_MAX_BYTES (64L << 20)
/* Room for the list of known buildings or floors in a message. */
#define KNOWN_MAX 600

/* ---- RFC 4180 records ------------------------------------------------------ */

typedef struct csv_rd {
    const char *path, *buf;
    size_t len, pos;
    long line;               /* the line at pos */
} csv_rd;

typedef struct csv_rec {
    char **f;
    long *fline;             /* the line each field starts on */
    size_t n, cap;
    long line;               /* the line the record starts on */
} csv_rec;

static void rec_clear(csv_rec *r)
{
    for (size_t i = 0; i < r->n; i++)
        free(r->f[i]);
    r->n = 0;
}

static void rec_free(csv_rec *r)
{
    rec_clear(r);
    free(r->f);
    free(r->fline);
    memset(r, 0, sizeof *r);
}

static int rec_push(csv_rec *r, char *s, long line)
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
static int line_end(csv_rd *c)
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
static int next_record(csv_rd *c, csv_rec *r, sl_error *err)
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
                    if (nx != ',' && nx != '\r' && nx != '\n') {
                        free(s);
                        return -sl_error_set_at(err, SL_EPARSE, c->path, c->line,
                                                (long)r->n + 1, "text after the closing quote "
                                                "of a field (a quote inside a quoted field is "
                                                "written \"\")");
                    }
                    break;
                }
            } else if (!quoted && (ch == ',' || ch == '\r' || ch == '\n')) {
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
        if (c->pos < c->len && c->buf[c->pos] == ',') {
            c->pos++;
            continue;
        }
        line_end(c);
        return 1;
    }
}

/* Trimmed copy of a field for matching and numbers (into buf). */
static const char *trimmed(const char *s, char *buf, size_t n)
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

/* ---- the results of a run -------------------------------------------------- */

static char *dupstr(const char *s) { return sl_text_dup(s); }

/* "# key: value" of a comment line (the run's record); NULL otherwise. */
static const char *comment_value(const char *line, size_t n, const char *key, char *buf,
                                 size_t bn)
{
    size_t kl = strlen(key);
    if (n < kl + 4 || strncmp(line, "# ", 2) || strncmp(line + 2, key, kl) ||
        strncmp(line + 2 + kl, ": ", 2))
        return NULL;
    size_t v = n - kl - 4;
    if (v >= bn)
        v = bn - 1;
    memcpy(buf, line + kl + 4, v);
    buf[v] = '\0';
    return buf;
}

/* The column named `name` in a header record, or -1. */
static int header_col(const csv_rec *h, const char *name)
{
    char b[256];
    for (size_t i = 0; i < h->n; i++)
        if (!strcasecmp(trimmed(h->f[i], b, sizeof b), name))
            return (int)i;
    return -1;
}

static sl_status load_file(const char *path, long max, sl_text *t, sl_error *err)
{
    sl_text_opts o = {.max_bytes = max, .what = "a CSV table", .text_only = 1};
    return sl_text_load(path, &o, t, err);
}

/* A header record with the named columns (cols[k] set), after the comment
 * lines; *rd positioned at the first data row. */
static sl_status table_header(csv_rd *rd, csv_rec *h, const char *const *names, size_t nn,
                              int *cols, sl_error *err)
{
    int got = next_record(rd, h, err);
    if (got < 0)
        return (sl_status)-got;
    if (!got)
        return sl_error_set(err, SL_EPARSE, rd->path, rd->line, "no header row");
    for (size_t k = 0; k < nn; k++)
        if ((cols[k] = header_col(h, names[k])) < 0)
            return sl_error_set_at(err, SL_EPARSE, rd->path, h->line, 0,
                                   "no column '%s' in the header (not a table seislide run "
                                   "wrote)", names[k]);
    return SL_OK;
}

static sl_status num_field(const csv_rd *rd, const csv_rec *w, int col, double *v, int empty_nan,
                           sl_error *err)
{
    char b[SL_TEXT_TOKEN_MAX + 1];
    const char *s = (size_t)col < w->n ? trimmed(w->f[col], b, sizeof b) : "";
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

/* floor_<id>.csv of a building: the grid, clearance and SE; the floor file's
 * record and (first floor) the run's record. */
static sl_status load_floor(sl_comp_results *r, sl_comp_floor *fl, const char *bdir,
                            sl_error *err)
{
    char path[4400], b[1200];
    snprintf(path, sizeof path, "%s/floor_%s.csv", bdir, fl->id);
    sl_text t;
    sl_status st = load_file(path, RESULTS_MAX_BYTES, &t, err);
    if (st)
        return st;
    /* the record: comment lines before the header */
    const char *s;
    size_t n;
    int first = !r->program;
    while (sl_text_next(&t, &s, &n) && n && s[0] == '#') {
        const char *v;
        if ((v = comment_value(s, n, "floor_file_crc32", b, sizeof b))) {
            char *end;
            fl->crc32 = strtoul(v, &end, 16);
            const char *p = strchr(end, '('), *q = strrchr(end, ',');
            if (p && q && q > p) {
                free(fl->file);
                fl->file = sl_text_dup_mem(p + 1, (size_t)(q - p - 1));
                fl->size_bytes = strtol(q + 1, NULL, 10);
            }
        }
        static const char *const keys[] = {"program", "command", "created", "seed", "project",
                                           "document", "revision"};
        char **dst[] = {&r->program, &r->command, &r->created, &r->seed, &r->project,
                        &r->document, &r->revision};
        for (size_t k = 0; first && k < sizeof keys / sizeof keys[0]; k++)
            if (!*dst[k] && (v = comment_value(s, n, keys[k], b, sizeof b)))
                *dst[k] = dupstr(v);
    }
    csv_rd rd = {.path = path, .buf = t.buf, .len = t.len, .line = 1};
    csv_rec h = {0}, w = {0};
    static const char *const names[] = {"mu", "clearance_mm", "nltha_design_se_mm"};
    int col[3];
    size_t k = 0;
    st = table_header(&rd, &h, names, 3, col, err);
    if (!st && !(fl->clearance_mm = calloc(r->n_mu ? r->n_mu : 64, sizeof(double))))
        st = sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
    if (!st && !(fl->se_mm = calloc(r->n_mu ? r->n_mu : 64, sizeof(double))))
        st = sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
    int first_floor = !r->mu;
    double *mu = first_floor ? calloc(64, sizeof *mu) : NULL;
    size_t cap = 64;
    if (!st && first_floor && !mu)
        st = sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
    for (int got; !st && (got = next_record(&rd, &w, err)) != 0; k++) {
        if (got < 0) {
            st = (sl_status)-got;
            break;
        }
        double m, c, e;
        if ((st = num_field(&rd, &w, col[0], &m, 0, err)) ||
            (st = num_field(&rd, &w, col[1], &c, 0, err)) ||
            (st = num_field(&rd, &w, col[2], &e, 1, err)))
            break;
        if (first_floor) {
            if (k == cap) {
                double *g[3] = {realloc(mu, 2 * cap * sizeof *mu), NULL, NULL};
                if (g[0])
                    mu = g[0];
                g[1] = realloc(fl->clearance_mm, 2 * cap * sizeof *mu);
                if (g[1])
                    fl->clearance_mm = g[1];
                g[2] = realloc(fl->se_mm, 2 * cap * sizeof *mu);
                if (g[2])
                    fl->se_mm = g[2];
                if (!g[0] || !g[1] || !g[2]) {
                    st = sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
                    break;
                }
                cap *= 2;
            }
            if (k && !(m > mu[k - 1])) {
                st = sl_error_set_at(err, SL_EPARSE, path, w.line, col[0] + 1, "mu %g is not "
                                     "above the row before (%g)", m, mu[k - 1]);
                break;
            }
            mu[k] = m;
        } else if (k >= r->n_mu || m != r->mu[k]) {
            st = sl_error_set_at(err, SL_EINVAL, path, w.line, col[0] + 1, "mu %g: this floor's "
                                 "grid is not the other floors' (one run gives every floor the "
                                 "same grid)", m);
            break;
        }
        fl->clearance_mm[k] = c;
        fl->se_mm[k] = e;
    }
    if (!st && k == 0)
        st = sl_error_set(err, SL_EPARSE, path, rd.line, "no rows under the header");
    if (!st && !first_floor && k != r->n_mu)
        st = sl_error_set(err, SL_EINVAL, path, rd.line, "%zu rows: the other floors have %zu "
                          "(one run gives every floor the same grid)", k, r->n_mu);
    if (!st && first_floor) {
        r->mu = mu;
        r->n_mu = k;
        mu = NULL;
    }
    free(mu);
    rec_free(&h);
    rec_free(&w);
    sl_text_free(&t);
    return st;
}

/* floors.csv of the building folder bdir: its floors appended to r. */
static sl_status load_building(sl_comp_results *r, const char *building, const char *bdir,
                               sl_error *err)
{
    char path[4400];
    snprintf(path, sizeof path, "%s/floors.csv", bdir);
    sl_text t;
    sl_status st = load_file(path, RESULTS_MAX_BYTES, &t, err);
    if (st)
        return st;
    csv_rd rd = {.path = path, .buf = t.buf, .len = t.len, .line = 1};
    csv_rec h = {0}, w = {0};
    static const char *const names[] = {"floor_id", "floor"};
    int col[2];
    st = table_header(&rd, &h, names, 2, col, err);
    for (int got; !st && (got = next_record(&rd, &w, err)) != 0;) {
        if (got < 0) {
            st = (sl_status)-got;
            break;
        }
        if ((size_t)col[0] >= w.n || (size_t)col[1] >= w.n || !*w.f[col[0]]) {
            st = sl_error_set(err, SL_EPARSE, path, w.line, "a row without its floor id or name");
            break;
        }
        sl_comp_floor *g = realloc(r->floors, (r->n_floors + 1) * sizeof *g);
        if (!g) {
            st = sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
            break;
        }
        r->floors = g;
        sl_comp_floor *fl = &r->floors[r->n_floors++];
        memset(fl, 0, sizeof *fl);
        fl->building = dupstr(building);
        fl->id = dupstr(w.f[col[0]]);
        fl->name = dupstr(w.f[col[1]]);
        if (!fl->building || !fl->id || !fl->name)
            st = sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
        else
            st = load_floor(r, fl, bdir, err);
    }
    if (!st && !r->n_floors)
        st = sl_error_set(err, SL_EPARSE, path, rd.line, "no floors listed");
    rec_free(&h);
    rec_free(&w);
    sl_text_free(&t);
    return st;
}

static int is_file(const char *path)
{
    struct stat sb;
    return stat(path, &sb) == 0 && S_ISREG(sb.st_mode);
}

static sl_status add_building(sl_comp_results *r, const char *id, sl_error *err)
{
    for (size_t b = 0; b < r->n_buildings; b++)
        if (!strcmp(r->buildings[b], id))
            return SL_OK;
    char **g = realloc(r->buildings, (r->n_buildings + 1) * sizeof *g);
    if (!g || !(g[r->n_buildings] = dupstr(id))) {
        if (g)
            r->buildings = g;
        return sl_error_set(err, SL_ENOMEM, r->dir, 0, "out of memory");
    }
    r->buildings = g;
    r->n_buildings++;
    return SL_OK;
}

static int cmp_str(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* A plant: the buildings in plant.csv's order, then any other sub-folder
 * holding floors.csv (sorted). */
static sl_status plant_buildings(sl_comp_results *r, const char *pcsv, sl_error *err)
{
    char path[4400];
    sl_text t;
    sl_status st = load_file(pcsv, RESULTS_MAX_BYTES, &t, err);
    if (st)
        return st;
    csv_rd rd = {.path = pcsv, .buf = t.buf, .len = t.len, .line = 1};
    csv_rec h = {0}, w = {0};
    static const char *const names[] = {"building"};
    int col[1];
    st = table_header(&rd, &h, names, 1, col, err);
    for (int got; !st && (got = next_record(&rd, &w, err)) != 0;) {
        if (got < 0) {
            st = (sl_status)-got;
            break;
        }
        if ((size_t)col[0] >= w.n)
            continue;
        snprintf(path, sizeof path, "%s/%s/floors.csv", r->dir, w.f[col[0]]);
        if (is_file(path))
            st = add_building(r, w.f[col[0]], err);
    }
    rec_free(&h);
    rec_free(&w);
    sl_text_free(&t);
    DIR *d = st ? NULL : opendir(r->dir);
    if (!st && !d)
        return sl_error_set(err, SL_EIO, r->dir, 0, "cannot read the folder");
    size_t n0 = r->n_buildings;
    for (struct dirent *e; d && !st && (e = readdir(d));) {
        if (e->d_name[0] == '.')
            continue;
        snprintf(path, sizeof path, "%s/%s/floors.csv", r->dir, e->d_name);
        if (is_file(path))
            st = add_building(r, e->d_name, err);
    }
    if (d)
        closedir(d);
    if (!st && r->n_buildings > n0)
        qsort(r->buildings + n0, r->n_buildings - n0, sizeof *r->buildings, cmp_str);
    return st;
}

void sl_comp_results_free(sl_comp_results *r)
{
    if (!r)
        return;
    for (size_t i = 0; i < r->n_floors; i++) {
        sl_comp_floor *f = &r->floors[i];
        free(f->building);
        free(f->id);
        free(f->name);
        free(f->file);
        free(f->clearance_mm);
        free(f->se_mm);
    }
    for (size_t b = 0; b < r->n_buildings; b++)
        free(r->buildings[b]);
    free(r->buildings);
    free(r->floors);
    free(r->mu);
    free(r->dir);
    free(r->single);
    char **s[] = {&r->program, &r->command, &r->created, &r->seed, &r->project, &r->document,
                  &r->revision};
    for (size_t k = 0; k < sizeof s / sizeof s[0]; k++)
        free(*s[k]);
    memset(r, 0, sizeof *r);
}

/* The last part of a path (its trailing slashes left out), malloc'd. */
static char *last_part(const char *dir)
{
    size_t k = strlen(dir);
    while (k > 1 && dir[k - 1] == '/')
        k--;
    size_t s = k;
    while (s && dir[s - 1] != '/')
        s--;
    return sl_text_dup_mem(dir + s, k - s);
}

sl_status sl_comp_results_shown(sl_comp_results *r, const char *shown, sl_error *err)
{
    char *d = dupstr(shown), *s = r->is_plant ? NULL : last_part(shown);
    if (!d || (!r->is_plant && !s)) {
        free(d);
        free(s);
        return sl_error_set(err, SL_ENOMEM, shown, 0, "out of memory");
    }
    free(r->dir);
    free(r->single);
    r->dir = d;
    r->single = s;
    return SL_OK;
}

sl_status sl_comp_results_load(const char *dir, sl_comp_results *r, sl_error *err)
{
    memset(r, 0, sizeof *r);
    char path[4400];
    sl_status st = SL_OK;
    if (!(r->dir = dupstr(dir)))
        return sl_error_set(err, SL_ENOMEM, dir, 0, "out of memory");
    snprintf(path, sizeof path, "%s/%s", dir, SL_PLANT_BOOK_CSV);
    if (is_file(path)) {
        r->is_plant = 1;
        st = plant_buildings(r, path, err);
        if (!st && !r->n_buildings)
            st = sl_error_set(err, SL_EIO, dir, 0, "a plant's results without a building "
                              "folder (<building>/floors.csv)");
        for (size_t b = 0; !st && b < r->n_buildings; b++) {
            snprintf(path, sizeof path, "%s/%s", dir, r->buildings[b]);
            st = load_building(r, r->buildings[b], path, err);
        }
    } else {
        snprintf(path, sizeof path, "%s/floors.csv", dir);
        if (!is_file(path))
            st = sl_error_set(err, SL_EIO, dir, 0, "not the output folder of seislide run: "
                              "neither %s nor floors.csv in it", SL_PLANT_BOOK_CSV);
        else
            st = add_building(r, "", err);
        if (!st) {
            /* the folder's own name: a row may name it as its building */
            if (!(r->single = last_part(dir)))
                st = sl_error_set(err, SL_ENOMEM, dir, 0, "out of memory");
        }
        if (!st)
            st = load_building(r, "", dir, err);
    }
    char **s[] = {&r->program, &r->command, &r->created, &r->seed, &r->project, &r->document,
                  &r->revision};
    for (size_t k = 0; !st && k < sizeof s / sizeof s[0]; k++)
        if (!*s[k] && !(*s[k] = dupstr("-")))
            st = sl_error_set(err, SL_ENOMEM, dir, 0, "out of memory");
    if (st)
        sl_comp_results_free(r);
    return st;
}

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
        strcpy(buf + n - 4, "...");
    return buf;
}

static char *known_buildings(const sl_comp_results *r, char *buf, size_t n)
{
    size_t k = 0;
    buf[0] = '\0';
    for (size_t b = 0; b < r->n_buildings && k + 1 < n; b++)
        k += (size_t)snprintf(buf + k, n - k, "%s%s", k ? ", " : "", r->buildings[b]);
    if (k >= n - 1 && n > 4)
        strcpy(buf + n - 4, "...");
    return buf;
}

/* The building of a row: its index, or an error naming the known ones. */
static sl_status find_building(const sl_comp_results *r, const char *path, const csv_rec *w,
                               int col, size_t *bi, sl_error *err)
{
    char b[512], known[KNOWN_MAX];
    const char *s = trimmed(w->f[col], b, sizeof b);
    if (!r->is_plant) {
        if (!*s || (r->single && !strcasecmp(s, r->single))) {
            *bi = 0;
            return SL_OK;
        }
        return sl_error_set_at(err, SL_EINVAL, path, w->fline[col], col + 1,
                               "unknown building '%s': the results are one building (folder "
                               "'%s'): leave building empty", sl_text_quote(s, strlen(s)).s,
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
                           *s ? sl_text_quote(s, strlen(s)).s : "",
                           known_buildings(r, known, sizeof known));
}

static sl_status find_floor(const sl_comp_results *r, const char *path, const csv_rec *w,
                            int col, size_t bi, size_t *fi, sl_error *err)
{
    char b[1024], known[KNOWN_MAX];
    const char *s = trimmed(w->f[col], b, sizeof b), *bld = r->buildings[bi];
    for (int by_name = 0; by_name < 2; by_name++)
        for (size_t i = 0; i < r->n_floors; i++)
            if (!strcmp(r->floors[i].building, bld) &&
                !strcasecmp(s, by_name ? r->floors[i].name : r->floors[i].id)) {
                *fi = i;
                return SL_OK;
            }
    char in[600] = "";
    if (r->is_plant)
        snprintf(in, sizeof in, " in building %s", bld);
    return sl_error_set_at(err, SL_EINVAL, path, w->fline[col], col + 1,
                           "unknown floor '%s'%s; its floors (id (name)): %s",
                           sl_text_quote(s, strlen(s)).s, in,
                           known_floors(r, bld, known, sizeof known));
}

/* A number of a row that must be > 0 (or >= 0 with nonneg). */
static sl_status row_num(const char *path, const csv_rec *w, int col, int nonneg, double *v,
                         sl_error *err)
{
    char b[SL_TEXT_TOKEN_MAX + 1];
    const char *s = trimmed(w->f[col], b, sizeof b);
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
static char **take_fields(csv_rec *w)
{
    char **f = malloc((w->n ? w->n : 1) * sizeof *f);
    if (!f)
        return NULL;
    memcpy(f, w->f, w->n * sizeof *f);
    w->n = 0;
    return f;
}

static sl_status read_header(const char *path, csv_rd *rd, csv_rec *h, sl_comp_table *t,
                             sl_error *err)
{
    int got = next_record(rd, h, err);
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
        const char *s = trimmed(h->f[c], b, sizeof b);
        if (!*s)
            return sl_error_set_at(err, SL_EPARSE, path, h->line, (long)c + 1, "empty column "
                                   "name");
        for (size_t e = 0; e < c; e++) {
            char b2[256];
            if (!strcasecmp(s, trimmed(h->f[e], b2, sizeof b2)))
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
static sl_status read_row(const sl_comp_results *r, sl_comp_table *t, csv_rec *w,
                          sl_comp_row *x, sl_error *err)
{
    const char *path = t->path;
    const int *col = t->col;
    if (w->n != t->n_cols)
        return sl_error_set_at(err, SL_EPARSE, path, w->line, (long)(w->n < t->n_cols ? w->n + 1
                               : t->n_cols + 1), "%zu fields; the header has %zu", w->n,
                               t->n_cols);
    char b[512];
    if (!*trimmed(w->f[col[SL_COMP_TAG]], b, sizeof b))
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
    sl_status st = load_file(path, SL_COMP_MAX_BYTES, &txt, err);
    if (st)
        return st;
    csv_rd rd = {.path = path, .buf = txt.buf, .len = txt.len, .line = 1};
    csv_rec h = {0}, w = {0};
    t->crc32 = file_crc(txt.mem, strlen(txt.mem));
    t->size_bytes = (long)strlen(txt.mem);
    if (!(t->path = dupstr(path)))
        st = sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
    if (!st)
        st = read_header(path, &rd, &h, t, err);
    size_t cap = 0;
    for (int got; !st && (got = next_record(&rd, &w, err)) != 0;) {
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
            blank = !*trimmed(w.f[c], bb, sizeof bb);
        if (blank)
            continue;
        sl_comp_row *x = &t->rows[t->n];
        memset(x, 0, sizeof *x);
        if ((st = read_row(r, t, &w, x, err)))
            break;
        t->n++;
        /* a repeated tag (without case, as the workbook's COUNTIF compares) */
        char b1[512], b2[512];
        const char *tag = trimmed(x->field[t->col[SL_COMP_TAG]], b1, sizeof b1);
        for (size_t i = 0; i + 1 < t->n; i++)
            if (!strcasecmp(tag, trimmed(t->rows[i].field[t->col[SL_COMP_TAG]], b2, sizeof b2))) {
                st = sl_error_set_at(err, SL_EINVAL, path, x->line, t->col[SL_COMP_TAG] + 1,
                                     "tag '%s' again: first on line %ld",
                                     sl_text_quote(tag, strlen(tag)).s, t->rows[i].line);
                break;
            }
        if (!st)
            t->count[x->verdict]++;
    }
    if (!st && t->n == 0)
        st = sl_error_set(err, SL_EPARSE, path, rd.line, "no components under the header");
    rec_free(&h);
    rec_free(&w);
    sl_text_free(&txt);
    if (st)
        sl_comp_table_free(t);
    return st;
}

/* ---- components.csv -------------------------------------------------------- */

int sl_comp_owns_name(const char *name)
{
    return !strcmp(name, SL_COMP_CSV) || !strcmp(name, SL_COMP_XLSX);
}

static void csv_num(FILE *f, double v, const char *fmt)
{
    if (isfinite(v))
        fprintf(f, fmt, v);
}

/* The run's record as the shared CSV head reads it; floors named
 * BUILDING/ID in a plant (as plant.csv names them). */
static sl_status shared_report(const sl_comp_results *r, const sl_comp_opts *o, sl_report *rep,
                               sl_report_floor **floors, char (**ids)[2 * SL_RPT_ID_MAX + 2],
                               sl_error *err)
{
    sl_report_init(rep);
    rep->version = o->version;
    rep->command_line = o->command_line;
    rep->seed = r->seed;
    rep->created = o->created;
    rep->project.project = strcmp(r->project, "-") ? r->project : NULL;
    rep->project.document = strcmp(r->document, "-") ? r->document : NULL;
    rep->project.revision = strcmp(r->revision, "-") ? r->revision : NULL;
    *floors = calloc(r->n_floors, sizeof **floors);
    *ids = calloc(r->n_floors, sizeof **ids);
    if (!*floors || !*ids) {
        free(*floors);
        free(*ids);
        return sl_error_set(err, SL_ENOMEM, NULL, 0, "out of memory");
    }
    for (size_t i = 0; i < r->n_floors; i++) {
        const sl_comp_floor *fl = &r->floors[i];
        snprintf((*ids)[i], sizeof (*ids)[i], "%s%s%s", fl->building, r->is_plant ? "/" : "",
                 fl->id);
        (*floors)[i] = (sl_report_floor){.id = (*ids)[i], .name = fl->name,
                                         .path = fl->file ? fl->file : "-", .crc32 = fl->crc32,
                                         .size_bytes = fl->size_bytes};
    }
    rep->n_floors = r->n_floors;
    rep->floors = *floors;
    return SL_OK;
}

static sl_status write_csv(const sl_comp_results *r, const sl_comp_table *t, const char *dir,
                           const sl_comp_opts *o, sl_error *err)
{
    char path[4400], buf[2400];
    snprintf(path, sizeof path, "%s/%s", dir, SL_COMP_CSV);
    sl_report rep;
    sl_report_floor *floors;
    char (*ids)[2 * SL_RPT_ID_MAX + 2];
    if (shared_report(r, o, &rep, &floors, &ids, err))
        return err ? err->code : SL_ENOMEM;
    sl_atomic *a = sl_atomic_open(path, err);
    if (!a) {
        free(floors);
        free(ids);
        return err ? err->code : SL_EIO;
    }
    FILE *f = sl_atomic_file(a);
    sl_rpt_csv_head(f, &rep, "one row per component: its columns as given, then the required "
                    "clearance at its mu on its floor, the margin and the verdict");
    free(floors);
    free(ids);
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
