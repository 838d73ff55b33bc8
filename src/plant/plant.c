/* plant.c - a plant's floors, keys, costs and shards; see plant.h. */
#include "plant/plant.h"
#include "core/compare.h"

#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "core/units.h"
#include "method/scatter.h"
#include "plant/cache.h"
#include "plant/intensity.h"
#include "report/plant_book.h"
#include "report/components.h"

/* The non-hidden sub-folders of dir, sorted (malloc'd names into sub[]). */
static sl_status list_subdirs(const char *dir, char **sub, size_t *n, size_t max, sl_error *err)
{
    DIR *d = opendir(dir);
    *n = 0;
    if (!d)
        return SL_OK; /* not a folder: sl_floor_list says what it is */
    struct dirent *e;
    char path[4400];
    sl_status st = SL_OK;
    while (!st && (e = readdir(d)) != NULL) {
        struct stat s;
        if (e->d_name[0] == '.')
            continue;
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        if (stat(path, &s) != 0 || !S_ISDIR(s.st_mode))
            continue;
        if (*n >= max)
            st = sl_error_set(err, SL_EINVAL, dir, 0, "more than %zu buildings", max);
        else if (!(sub[(*n)++] = strdup(e->d_name)))
            st = sl_error_set(err, SL_ENOMEM, dir, 0, "out of memory");
    }
    closedir(d);
    if (st) { /* nothing half-listed goes back to the caller */
        for (size_t i = 0; i < *n; i++)
            free(sub[i]);
        *n = 0;
        return st;
    }
    qsort(sub, *n, sizeof *sub, sl_cmp_str);
    return SL_OK;
}

/* Does the folder hold floor files of its own (sl_floor_list finds some)? */
static int has_floor_files(const char *dir)
{
    char *paths[SL_DELIVER_MAX_FLOORS] = {NULL};
    size_t n = 0;
    sl_status st = sl_floor_list(dir, paths, &n, SL_DELIVER_MAX_FLOORS, NULL);
    for (size_t i = 0; i < n; i++)
        free(paths[i]);
    return st == SL_OK || n > 0;
}

static char *dup_or_empty(const char *s) { return strdup(s ? s : ""); }

static sl_status add_building(sl_plant *p, const char *id, const char *const *args, size_t nargs,
                              int force, char *warnings, size_t nw, sl_error *err)
{
    size_t b = p->n_buildings;
    char fa[SL_DELIVER_ID_MAX], fb[SL_DELIVER_ID_MAX];
    for (size_t j = 0; j < b; j++)
        if (!strcmp(sl_report_file_name(p->building[j], fa, sizeof fa),
                    sl_report_file_name(id, fb, sizeof fb)))
            return sl_error_set(err, SL_EINVAL, args[0], 0, "building '%s' gives the output "
                                "folder name '%s', as building '%s' does: rename one folder",
                                id, fb, p->building[j]);
    sl_deliver_inputs *in = calloc(1, sizeof *in);
    if (!in)
        return sl_error_set(err, SL_ENOMEM, args[0], 0, "out of memory");
    p->inputs[b] = in;
    snprintf(p->building[b], sizeof p->building[b], "%s", id);
    p->n_buildings++;
    size_t used = nw ? strlen(warnings) : 0;
    sl_status st = sl_deliver_inputs_load(in, args, nargs, force, warnings + used, nw - used,
                                          err);
    if (st)
        return st;
    if (p->n + in->n > SL_PLANT_MAX_FLOORS)
        return sl_error_set(err, SL_EINVAL, args[0], 0, "more than %d floors in the plant",
                            SL_PLANT_MAX_FLOORS);
    for (size_t i = 0; i < in->n; i++) {
        sl_plant_floor *f = &p->floors[p->n++];
        const sl_floor *fl = in->floors[i];
        sl_deliver_meta m;
        f->building = b;
        f->floor = fl;
        if ((st = sl_deliver_meta_of(fl, &m, err)))
            return st;
        f->id = strdup(in->idp[i]);
        f->name = dup_or_empty(m.name);
        f->path = dup_or_empty(m.path);
        f->description = dup_or_empty(m.description);
        f->units = dup_or_empty(m.units);
        f->elevation_m = m.elevation_m;
        f->crc32 = m.crc32;
        f->size_bytes = m.size_bytes;
        if (in->warn[i] && !(f->warnings = strdup(in->warn[i])))
            return sl_error_set(err, SL_ENOMEM, fl->path, 0, "out of memory");
        if (!f->id || !f->name || !f->path || !f->description || !f->units)
            return sl_error_set(err, SL_ENOMEM, fl->path, 0, "out of memory");
    }
    return SL_OK;
}

sl_status sl_plant_load(sl_plant *p, const char *const *args, size_t nargs, int force,
                        char *warnings, size_t nw, sl_error *err)
{
    if (nw)
        warnings[0] = '\0';
    p->building = calloc(SL_PLANT_MAX_BUILDINGS, sizeof *p->building);
    p->inputs = calloc(SL_PLANT_MAX_BUILDINGS, sizeof *p->inputs);
    p->floors = calloc(SL_PLANT_MAX_FLOORS, sizeof *p->floors);
    if (!p->building || !p->inputs || !p->floors)
        return sl_error_set(err, SL_ENOMEM, NULL, 0, "out of memory");
    char *sub[SL_PLANT_MAX_BUILDINGS];
    size_t ns = 0;
    sl_status st = SL_OK;
    if (nargs == 1 && (st = list_subdirs(args[0], sub, &ns, SL_PLANT_MAX_BUILDINGS, err)))
        return st;
    if (ns == 0 || has_floor_files(args[0])) { /* one building, as before */
        for (size_t i = 0; i < ns; i++)
            free(sub[i]);
        return add_building(p, "", args, nargs, force, warnings, nw, err);
    }
    p->is_plant = 1;
    char path[4400], id[SL_DELIVER_ID_MAX];
    for (size_t i = 0; i < ns; i++) {
        if (!st) {
            snprintf(path, sizeof path, "%s/%s", args[0], sub[i]);
            const char *one[1] = {path};
            sl_report_floor_id(sub[i], id, sizeof id);
            st = add_building(p, id, one, 1, force, warnings, nw, err);
        }
        free(sub[i]);
    }
    return st;
}

/* Append text to a floor's warnings ("; "-separated). */
static sl_status add_warning(sl_plant_floor *f, const char *text, sl_error *err)
{
    size_t had = f->warnings ? strlen(f->warnings) : 0, len = strlen(text);
    char *w = realloc(f->warnings, had + 2 + len + 1);
    if (!w)
        return sl_error_set(err, SL_ENOMEM, f->path, 0, "out of memory");
    snprintf(w + had, 2 + len + 1, "%s%s", had ? "; " : "", text);
    f->warnings = w;
    return SL_OK;
}

sl_status sl_plant_accept(sl_plant *p, const char *ref, sl_error *err)
{
    const char *slash = p->is_plant ? strrchr(ref, '/') : NULL;
    size_t blen = slash ? (size_t)(slash - ref) : 0, hits = 0, hit = 0;
    const char *id = slash ? slash + 1 : ref;
    char known[600] = "";
    size_t used = 0;
    for (size_t i = 0; i < p->n; i++) {
        const sl_plant_floor *f = &p->floors[i];
        const char *b = p->building[f->building];
        int w = snprintf(known + used, used < sizeof known ? sizeof known - used : 0, "%s%s%s%s",
                         used ? ", " : "", p->is_plant ? b : "", p->is_plant ? "/" : "", f->id);
        used += w > 0 ? (size_t)w : 0;
        if (strcasecmp(f->id, id) || (slash && (strlen(b) != blen || strncasecmp(b, ref, blen))))
            continue;
        hits++;
        hit = i;
    }
    if (used >= sizeof known)
        strcpy(known + sizeof known - 4, "...");
    if (hits == 1) {
        p->floors[hit].accepted = 1;
        return SL_OK;
    }
    if (hits)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "--accept-floor %s: %zu floors have that "
                            "id: give BUILDING/ID (the floors: %s)", ref, hits, known);
    return sl_error_set(err, SL_EINVAL, NULL, 0, "--accept-floor %s: no such floor (the floors: "
                        "%s)", ref, known);
}

sl_status sl_plant_check_intensity(sl_plant *p, sl_error *err)
{
    sl_intensity_floor *f = calloc(p->n ? p->n : 1, sizeof *f);
    size_t *at = calloc(p->n ? p->n : 1, sizeof *at);
    char (*warn)[SL_INTENSITY_WARN_MAX] = calloc(p->n ? p->n : 1, sizeof *warn);
    sl_status st = SL_OK;
    if (!f || !at || !warn)
        st = sl_error_set(err, SL_ENOMEM, NULL, 0, "out of memory");
    for (size_t b = 0; !st && b < p->n_buildings; b++) {
        size_t n = 0;
        for (size_t i = 0; i < p->n; i++) {
            const sl_plant_floor *pf = &p->floors[i];
            if (pf->building != b || !pf->floor)
                continue;
            const sl_floor *fl = pf->floor;
            f[n] = (sl_intensity_floor){
                .id = pf->id, .name = pf->name, .path = pf->path, .units = fl->units,
                .units_text = fl->units_text,
                .zpa_h_ms2 = fmax(fl->comp[SL_FLOOR_H1].zpa_ms2, fl->comp[SL_FLOOR_H2].zpa_ms2),
                .elevation_m = fl->elevation_m, .accepted = pf->accepted};
            at[n++] = i;
        }
        st = sl_intensity_check(f, n, p->building[b], warn, err);
        for (size_t k = 0; !st && k < n; k++)
            if (warn[k][0])
                st = add_warning(&p->floors[at[k]], warn[k], err);
    }
    free(f);
    free(at);
    free(warn);
    return st;
}

/* Expected cost (plant.h, "Cost model"). */
static double floor_cost(const sl_floor *fl, const sl_analysis_opts *o)
{
    double zpa = fmax(fl->comp[SL_FLOOR_H1].zpa_ms2, fl->comp[SL_FLOOR_H2].zpa_ms2);
    double sigma = o->scatter < 0 ? sl_scatter_sigma_of_floor(fl) : o->scatter; /* the run's */
    double reach = zpa * exp(2 * (sigma > 0 ? sigma : 0));
    size_t m = 0;
    for (size_t k = 0; k < o->n_mu; k++)
        m += o->mu[k] * SL_G < reach;
    double sets = o->n_sets ? (double)o->n_sets : SL_PLANT_COST_SETS;
    return sets * (1.0 + (double)m);
}

sl_status sl_plant_keys(sl_plant *p, const sl_analysis_opts *o, const char *version,
                        sl_error *err)
{
    for (size_t i = 0; i < p->n; i++) {
        sl_status st = sl_entry_key_make(p->floors[i].floor, o, version, &p->floors[i].key, err);
        if (st)
            return st;
        p->floors[i].cost = floor_cost(p->floors[i].floor, o);
    }
    return SL_OK;
}

static const sl_plant *sort_plant;
static int by_cost(const void *a, const void *b)
{
    size_t i = *(const size_t *)a, j = *(const size_t *)b;
    double ci = sort_plant->floors[i].cost, cj = sort_plant->floors[j].cost;
    if (ci != cj)
        return ci > cj ? -1 : 1;
    return i < j ? -1 : i > j;
}

void sl_plant_assign(sl_plant *p, unsigned n_shards)
{
    size_t *order = malloc((p->n ? p->n : 1) * sizeof *order);
    double *load = calloc(n_shards ? n_shards : 1, sizeof *load);
    if (!order || !load) { /* cannot sort: deal round-robin in plant order (still deterministic) */
        for (size_t i = 0; i < p->n; i++)
            p->floors[i].shard = (unsigned)(i % n_shards) + 1;
        free(order);
        free(load);
        return;
    }
    for (size_t i = 0; i < p->n; i++)
        order[i] = i;
    sort_plant = p;
    qsort(order, p->n, sizeof *order, by_cost);
    for (size_t r = 0; r < p->n; r++) {
        unsigned best = 0;
        for (unsigned k = 1; k < n_shards; k++)
            if (load[k] < load[best])
                best = k;
        load[best] += p->floors[order[r]].cost;
        p->floors[order[r]].shard = best + 1;
    }
    free(order);
    free(load);
}

void sl_plant_free(sl_plant *p)
{
    for (size_t i = 0; p->floors && i < p->n; i++) {
        sl_plant_floor *f = &p->floors[i];
        free(f->id);
        free(f->name);
        free(f->path);
        free(f->description);
        free(f->units);
        free(f->warnings);
        sl_entry_key_free(&f->key);
        sl_analysis_free(f->an);
    }
    for (size_t b = 0; p->inputs && b < p->n_buildings; b++) {
        if (p->inputs[b])
            sl_deliver_inputs_free(p->inputs[b]);
        free(p->inputs[b]);
    }
    free(p->floors);
    free(p->inputs);
    free(p->building);
    memset(p, 0, sizeof *p);
}

/* The outputs of building b into folder dir. */
static sl_status deliver_building(const sl_plant *p, size_t b, const char *dir,
                                  const sl_deliver_opts *o, sl_error *err)
{
    size_t n = 0;
    sl_deliver_meta *m = calloc(p->n ? p->n : 1, sizeof *m);
    const char **ids = calloc(p->n ? p->n : 1, sizeof *ids);
    const sl_analysis **an = calloc(p->n ? p->n : 1, sizeof *an);
    sl_status st = SL_OK;
    if (!m || !ids || !an)
        st = sl_error_set(err, SL_ENOMEM, dir, 0, "out of memory");
    for (size_t i = 0; !st && i < p->n; i++) {
        const sl_plant_floor *f = &p->floors[i];
        if (f->building != b)
            continue;
        m[n] = (sl_deliver_meta){f->name,        f->path,       f->description,
                                 f->units,       f->elevation_m, f->crc32,
                                 f->size_bytes,  f->warnings,    f->accepted};
        ids[n] = f->id;
        an[n++] = f->an;
    }
    if (!st)
        st = sl_deliver_write_meta(dir, n, m, ids, an, o, err);
    free(m);
    free(ids);
    free(an);
    return st;
}

sl_status sl_plant_deliver(const sl_plant *p, const char *dir, const sl_deliver_opts *o,
                           sl_error *err)
{
    if (!p->is_plant)
        return deliver_building(p, 0, dir, o, err);
    char sub[4400], file[SL_DELIVER_ID_MAX];
    for (size_t b = 0; b < p->n_buildings; b++) {
        snprintf(sub, sizeof sub, "%s/%s", dir,
                 sl_report_file_name(p->building[b], file, sizeof file));
        if (mkdir(sub, 0777) != 0)
            return sl_error_set(err, SL_EIO, sub, 0, "cannot create: %s", strerror(errno));
        sl_deliver_opts ob = *o; /* the building named on every page of its workbook */
        ob.building = p->building[b];
        sl_status st = deliver_building(p, b, sub, &ob, err);
        if (st)
            return st;
    }
    sl_plant_book_row *rows = calloc(p->n ? p->n : 1, sizeof *rows);
    if (!rows)
        return sl_error_set(err, SL_ENOMEM, dir, 0, "out of memory");
    for (size_t i = 0; i < p->n; i++) {
        const sl_plant_floor *f = &p->floors[i];
        rows[i] = (sl_plant_book_row){.building = p->building[f->building], .id = f->id,
                                      .name = f->name, .elevation_m = f->elevation_m,
                                      .zpa_h_ms2 = f->an->zpa_h_ms2, .n_sets = f->an->n_sets,
                                      .stop = sl_analysis_stop_name(f->an->stop),
                                      .design = f->an->design, .path = f->path,
                                      .crc32 = f->crc32, .size_bytes = f->size_bytes,
                                      .n_failed_motions = f->an->n_failed_motions,
                                      .design_se_m = f->an->design_se_m,
                                      .warnings = f->warnings};
    }
    char seed[32]; /* as the building CSVs record it (deliver.c) */
    snprintf(seed, sizeof seed, "%llu", (unsigned long long)o->seed);
    sl_plant_book book = {.version = o->version, .command_line = o->command_line, .seed = seed,
                          .created = o->created, .project = o->project, .n = p->n,
                          .rows = rows, .lookup_mu = SL_REPORT_LOOKUP_MU};
    sl_status st = sl_plant_book_write_csv(&book, dir, err);
    if (!st)
        st = sl_plant_book_write_xlsx(&book, dir, err);
    free(rows);
    return st;
}
