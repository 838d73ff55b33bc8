/* components_results.c - the floor tables of a run read back from its CSV
 * files (floors.csv, floor_<id>.csv; plant.csv and one folder per building
 * for a plant), with the run's record; see components.h. */
#include "report/components.h"
#include "core/compare.h"

#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "report/csvread.h"
#include "report/plant_book.h"
#include "report/report.h"
#include "report/sheets.h"

/* Largest results CSV read, bytes (a floor table, floors.csv, plant.csv). */
#define RESULTS_MAX_BYTES (64L << 20)

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





/* floor_<id>.csv of a building (the id made a file name, as report/csv.c
 * names it): the grid, clearance and SE; the floor file's record and (first
 * floor) the run's record. */
static sl_status load_floor(sl_comp_results *r, sl_comp_floor *fl, const char *bdir,
                            sl_error *err)
{
    char path[4400], b[1200], file[4 * SL_RPT_ID_MAX + 1];
    snprintf(path, sizeof path, "%s/floor_%s.csv", bdir,
             sl_report_file_name(fl->id, file, sizeof file));
    sl_text t;
    sl_status st = sl_csv_load(path, RESULTS_MAX_BYTES, &t, err);
    if (st)
        return st;
    /* the record: comment lines before the header */
    const char *s;
    size_t n;
    int first = !r->program;
    while (sl_text_next(&t, &s, &n) && n && s[0] == '#') {
        const char *v;
        if ((v = comment_value(s, n, "horizontal_zpa_g", b, sizeof b)))
            fl->zpa_g = strtod(v, NULL);
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
                                           "document", "revision", "clearance_policy"};
        char **dst[] = {&r->program, &r->command, &r->created, &r->seed, &r->project,
                        &r->document, &r->revision, &r->policy};
        for (size_t k = 0; first && k < sizeof keys / sizeof keys[0]; k++)
            if (!*dst[k] && (v = comment_value(s, n, keys[k], b, sizeof b)))
                *dst[k] = dupstr(v);
    }
    sl_csvread rd = {.path = path, .buf = t.buf, .len = t.len, .line = 1};
    sl_csvrec h = {0}, w = {0};
    static const char *const names[] = {"mu", "clearance_mm", "nltha_design_se_mm"};
    int col[3];
    size_t k = 0;
    st = sl_csv_header(&rd, &h, names, 3, col, err);
    /* the ASCE design value beside it (a table without the column: empty) */
    int col_asce = st ? -1 : sl_csv_header_col(&h, "asce_design_mm");
    int col_flags = st ? -1 : sl_csv_header_col(&h, "flags");
    if (!st && !(fl->clearance_mm = calloc(r->n_mu ? r->n_mu : 64, sizeof(double))))
        st = sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
    if (!st && !(fl->se_mm = calloc(r->n_mu ? r->n_mu : 64, sizeof(double))))
        st = sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
    if (!st && !(fl->asce_mm = calloc(r->n_mu ? r->n_mu : 64, sizeof(double))))
        st = sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
    if (!st && !(fl->flags = calloc(r->n_mu ? r->n_mu : 64, sizeof(char *))))
        st = sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
    int first_floor = !r->mu;
    double *mu = first_floor ? calloc(64, sizeof *mu) : NULL;
    size_t cap = 64;
    if (!st && first_floor && !mu)
        st = sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
    for (int got; !st && (got = sl_csvread_next(&rd, &w, err)) != 0; k++) {
        if (got < 0) {
            st = (sl_status)-got;
            break;
        }
        double m, c, e, a = NAN;
        if ((st = sl_csv_num(&rd, &w, col[0], &m, 0, err)) ||
            (st = sl_csv_num(&rd, &w, col[1], &c, 0, err)) ||
            (st = sl_csv_num(&rd, &w, col[2], &e, 1, err)) ||
            (col_asce >= 0 && (st = sl_csv_num(&rd, &w, col_asce, &a, 1, err))))
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
                double *ga = realloc(fl->asce_mm, 2 * cap * sizeof *mu);
                if (ga)
                    fl->asce_mm = ga;
                char **gf = realloc(fl->flags, 2 * cap * sizeof *gf);
                if (gf) {
                    fl->flags = gf;
                    memset(gf + cap, 0, cap * sizeof *gf);
                }
                if (!g[0] || !g[1] || !g[2] || !ga || !gf) {
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
        fl->asce_mm[k] = a;
        char fb[600];
        if (!(fl->flags[k] = dupstr(col_flags >= 0 && (size_t)col_flags < w.n
                                    ? sl_csv_trimmed(w.f[col_flags], fb, sizeof fb) : ""))) {
            st = sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
            break;
        }
        fl->n_flags = k + 1;
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
    sl_csvrec_free(&h);
    sl_csvrec_free(&w);
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
    sl_csvread rd;
    sl_status st = sl_csv_open(path, RESULTS_MAX_BYTES, &t, &rd, err);
    if (st)
        return st;
    sl_csvrec h = {0}, w = {0};
    static const char *const names[] = {"floor_id", "floor"};
    int col[2];
    const size_t first = r->n_floors;
    st = sl_csv_header(&rd, &h, names, 2, col, err);
    /* what a floor's Lookup says besides its numbers (absent columns: empty) */
    int c_sets = st ? -1 : sl_csv_header_col(&h, "n_sets"),
        c_stop = st ? -1 : sl_csv_header_col(&h, "sets_stop"),
        c_note = st ? -1 : sl_csv_header_col(&h, "note"),
        c_warn = st ? -1 : sl_csv_header_col(&h, "warnings");
    for (int got; !st && (got = sl_csvread_next(&rd, &w, err)) != 0;) {
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
        fl->zpa_g = NAN;
        fl->n_sets = c_sets >= 0 && (size_t)c_sets < w.n && *w.f[c_sets]
                     ? strtol(w.f[c_sets], NULL, 10) : -1;
        fl->sets_stop = dupstr(c_stop >= 0 && (size_t)c_stop < w.n ? w.f[c_stop] : "");
        fl->note = dupstr(c_note >= 0 && (size_t)c_note < w.n ? w.f[c_note] : "");
        fl->warnings = dupstr(c_warn >= 0 && (size_t)c_warn < w.n ? w.f[c_warn] : "");
        if (!fl->building || !fl->id || !fl->name || !fl->sets_stop || !fl->note ||
            !fl->warnings)
            st = sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
        else
            st = load_floor(r, fl, bdir, err);
    }
    if (!st && !r->n_floors)
        st = sl_error_set(err, SL_EPARSE, path, rd.line, "no floors listed");
    /* every reference names one floor (report.h, sl_report_check_floors), so that a
     * row and the workbook's formulas, which try ids before names, find the same */
    for (size_t i = first; !st && i < r->n_floors; i++)
        for (size_t j = first; !st && j < i; j++) {
            const sl_comp_floor *a = &r->floors[j], *b = &r->floors[i];
            if (sl_report_floor_refs_clash(a->id, a->name, b->id, b->name))
                st = sl_error_set(err, SL_EINVAL, path, 0,
                                  "floors %s ('%s', file %s) and %s ('%s', file %s) share a "
                                  "reference (ids and names compared without case), so a "
                                  "component's floor could name either: rename one floor and "
                                  "rerun seislide run",
                                  a->id, a->name, a->file ? a->file : "-", b->id, b->name,
                                  b->file ? b->file : "-");
        }
    sl_csvrec_free(&h);
    sl_csvrec_free(&w);
    sl_text_free(&t);
    return st;
}

static int is_file(const char *path)
{
    struct stat sb;
    return stat(path, &sb) == 0 && S_ISREG(sb.st_mode);
}

/* A building named as written, its results in the folder dir/folder (a
 * folder already listed is not added twice). */
static sl_status add_building(sl_comp_results *r, const char *name, const char *folder,
                              sl_error *err)
{
    for (size_t b = 0; b < r->n_buildings; b++)
        if (!strcmp(r->folders[b], folder))
            return SL_OK;
    char **g = realloc(r->buildings, (r->n_buildings + 1) * sizeof *g);
    if (g)
        r->buildings = g;
    char **h = g ? realloc(r->folders, (r->n_buildings + 1) * sizeof *h) : NULL;
    if (h)
        r->folders = h;
    if (!g || !h || !(g[r->n_buildings] = dupstr(name)))
        return sl_error_set(err, SL_ENOMEM, r->dir, 0, "out of memory");
    if (!(h[r->n_buildings] = dupstr(folder))) {
        free(g[r->n_buildings]);
        return sl_error_set(err, SL_ENOMEM, r->dir, 0, "out of memory");
    }
    r->n_buildings++;
    return SL_OK;
}

/* A plant: the buildings of plant.csv, named as written there, in its
 * order (each in the folder its name makes, sl_report_file_name, as
 * plant/plant.c names it), then any other sub-folder holding floors.csv
 * (sorted, named by the folder). */
static sl_status plant_buildings(sl_comp_results *r, const char *pcsv, sl_error *err)
{
    char path[4400], folder[4 * SL_RPT_ID_MAX + 1];
    sl_text t;
    sl_csvread rd;
    sl_status st = sl_csv_open(pcsv, RESULTS_MAX_BYTES, &t, &rd, err);
    if (st)
        return st;
    sl_csvrec h = {0}, w = {0};
    static const char *const names[] = {"building"};
    int col[1];
    st = sl_csv_header(&rd, &h, names, 1, col, err);
    for (int got; !st && (got = sl_csvread_next(&rd, &w, err)) != 0;) {
        if (got < 0) {
            st = (sl_status)-got;
            break;
        }
        if ((size_t)col[0] >= w.n)
            continue;
        sl_report_file_name(w.f[col[0]], folder, sizeof folder);
        snprintf(path, sizeof path, "%s/%s/floors.csv", r->dir, folder);
        if (is_file(path))
            st = add_building(r, w.f[col[0]], folder, err);
    }
    sl_csvrec_free(&h);
    sl_csvrec_free(&w);
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
            st = add_building(r, e->d_name, e->d_name, err);
    }
    if (d)
        closedir(d);
    if (!st && r->n_buildings > n0) { /* here each name is its folder's */
        qsort(r->buildings + n0, r->n_buildings - n0, sizeof *r->buildings, sl_cmp_str);
        for (size_t b = n0; b < r->n_buildings; b++) {
            char *c = dupstr(r->buildings[b]);
            if (!c)
                return sl_error_set(err, SL_ENOMEM, r->dir, 0, "out of memory");
            free(r->folders[b]);
            r->folders[b] = c;
        }
    }
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
        free(f->asce_mm);
        for (size_t k = 0; f->flags && k < f->n_flags; k++)
            free(f->flags[k]);
        free(f->flags);
        free(f->sets_stop);
        free(f->note);
        free(f->warnings);
    }
    for (size_t b = 0; b < r->n_buildings; b++) {
        free(r->buildings[b]);
        free(r->folders[b]);
    }
    free(r->buildings);
    free(r->folders);
    free(r->floors);
    free(r->mu);
    free(r->dir);
    free(r->single);
    char **s[] = {&r->program, &r->command, &r->created, &r->seed, &r->project, &r->document,
                  &r->revision, &r->policy};
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
            snprintf(path, sizeof path, "%s/%s", dir, r->folders[b]);
            st = load_building(r, r->buildings[b], path, err);
        }
    } else {
        snprintf(path, sizeof path, "%s/floors.csv", dir);
        if (!is_file(path))
            st = sl_error_set(err, SL_EIO, dir, 0, "not the output folder of seislide run: "
                              "neither %s nor floors.csv in it", SL_PLANT_BOOK_CSV);
        else
            st = add_building(r, "", "", err);
        if (!st) {
            /* the folder's own name: a row may name it as its building */
            if (!(r->single = last_part(dir)))
                st = sl_error_set(err, SL_ENOMEM, dir, 0, "out of memory");
        }
        if (!st)
            st = load_building(r, "", dir, err);
    }
    char **s[] = {&r->program, &r->command, &r->created, &r->seed, &r->project, &r->document,
                  &r->revision, &r->policy};
    for (size_t k = 0; !st && k < sizeof s / sizeof s[0]; k++)
        if (!*s[k] && !(*s[k] = dupstr("-")))
            st = sl_error_set(err, SL_ENOMEM, dir, 0, "out of memory");
    if (st)
        sl_comp_results_free(r);
    return st;
}
