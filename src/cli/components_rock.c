/* components_rock.c - the rocking check of a components table's slender rows
 * (components_out.h): per floor, its rocking items over the floor's own
 * motion sets (rock/rock_floor.h), from the cache when it holds them
 * (rock/rock_cache.h), else computed and kept there. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli.h"
#include "components_out.h"
#include "core/clock.h"
#include "io/floor.h"
#include "report/deliver.h"
#include "rock/rock_cache.h"
#include "rock/rock_floor.h"

/* The floor of results floor fi: the run's own (plant given: its floor, its
 * sets when they still hold their motions), else its file read again, which
 * must be the bytes the run read (its CRC-32). */
static sl_status floor_of(const sl_comp_results *r, size_t fi, const sl_plant *plant,
                          const sl_floor **fl, sl_floor **owned, const sl_synth_set **sets,
                          size_t *n_sets, sl_error *err)
{
    const sl_comp_floor *cf = &r->floors[fi];
    *owned = NULL;
    *sets = NULL;
    for (size_t i = 0; plant && i < plant->n; i++) {
        const sl_plant_floor *pf = &plant->floors[i];
        if (!pf->floor || !pf->an || strcmp(pf->id, cf->id) ||
            (plant->is_plant && strcmp(plant->building[pf->building], cf->building)))
            continue;
        *fl = pf->floor;
        *n_sets = pf->an->n_sets;
        if (pf->an->n_sets && pf->an->sets && pf->an->sets[0].set.h1)
            *sets = pf->an->sets;
        return SL_OK;
    }
    if (cf->n_sets < 1)
        return sl_error_set(err, SL_EINVAL, r->dir, 0, "floor '%s': the results give no set "
                            "count (floors.csv n_sets): rerun seislide run", cf->id);
    *n_sets = (size_t)cf->n_sets;
    unsigned long crc;
    long size;
    sl_error e;
    if (!cf->file || !*cf->file || sl_deliver_file_crc(cf->file, &crc, &size, &e))
        return sl_error_set(err, SL_EIO, cf->file, 0, "floor '%s': the rocking check makes the "
                            "floor's motion sets again from the floor file the run read, and "
                            "it cannot be read here (%s): run seislide components from the "
                            "folder the run was started in, or use seislide run --components",
                            cf->id, cf->file && *cf->file ? e.msg : "no file recorded");
    if ((crc & 0xffffffffUL) != (cf->crc32 & 0xffffffffUL))
        return sl_error_set(err, SL_EINVAL, cf->file, 0, "floor '%s': the floor file changed "
                            "since the run (CRC-32 %08lx, the run read %08lx): rerun seislide "
                            "run", cf->id, crc & 0xffffffffUL, cf->crc32 & 0xffffffffUL);
    if (!(*owned = sl_floor_load(cf->file, err)))
        return err ? err->code : SL_EIO;
    *fl = *owned;
    return SL_OK;
}

sl_status components_rock(const sl_comp_results *r, sl_comp_table *t, const sl_plant *plant,
                          const char *cache, int quiet, sl_error *err)
{
    size_t n_rock = 0;
    for (size_t i = 0; i < t->n; i++)
        n_rock += t->rows[i].mode != SL_COMP_MODE_SLIDING;
    if (!n_rock)
        return SL_OK;
    char *end = NULL;
    errno = 0;
    uint64_t seed = strtoull(r->seed, &end, 10);
    if (errno || end == r->seed || *end)
        return sl_error_set(err, SL_EINVAL, r->dir, 0, "the results record no seed ('%s'): "
                            "the rocking check needs it to make the floors' motion sets "
                            "again", r->seed);
    struct stat sb;
    if (cache && (stat(cache, &sb) != 0 || !S_ISDIR(sb.st_mode)))
        cache = NULL;
    sl_rockf_opts o;
    sl_rockf_opts_default(&o);
    size_t *rows = malloc(t->n * sizeof *rows);
    sl_rockf_item *items = malloc(t->n * sizeof *items);
    sl_rockf_result *res = malloc(t->n * sizeof *res);
    sl_status st = rows && items && res ? SL_OK
                                        : sl_error_set(err, SL_ENOMEM, NULL, 0, "out of memory");
    for (size_t fi = 0; !st && fi < r->n_floors; fi++) {
        size_t n = 0;
        for (size_t i = 0; i < t->n; i++)
            if (t->rows[i].mode != SL_COMP_MODE_SLIDING && t->rows[i].floor == fi) {
                rows[n] = i;
                items[n++] = sl_comp_rock_item(&t->rows[i]);
            }
        if (!n)
            continue;
        const sl_floor *fl = NULL;
        sl_floor *owned = NULL;
        const sl_synth_set *sets = NULL;
        size_t n_sets = 0;
        if ((st = floor_of(r, fi, plant, &fl, &owned, &sets, &n_sets, err)))
            break;
        sl_rockc_key key = {0};
        const char *lab = r->floors[fi].id;
        char where[600];
        snprintf(where, sizeof where, "%s%s%s", r->is_plant ? r->floors[fi].building : "",
                 r->is_plant ? "/" : "", lab);
        int hit = 0;
        if (cache) {
            if ((st = sl_rockc_key_make(fl, seed, n_sets, &o, items, n, &key, err))) {
                sl_floor_free(owned);
                break;
            }
            hit = sl_rockc_read(cache, &key, res, n);
        }
        if (!hit) {
            double t0 = sl_clock_s();
            st = sl_rockf_floor_run(fl, seed, n_sets, sets, items, n, &o, res, err);
            if (!st && !quiet) {
                size_t used = 0;
                for (size_t k = 0; k < n; k++)
                    used = res[k].n_sets > used ? res[k].n_sets : used;
                cli_msg("components: rocking of %zu item(s) on floor '%s': up to %zu of its %zu "
                        "sets, %.1f s", n, where, used, n_sets, sl_clock_s() - t0);
            }
            if (!st && cache) {
                sl_error e;
                if (sl_rockc_write(cache, &key, res, n, &e))
                    cli_msg("components: warning: the rocking results of floor '%s' are not "
                            "kept in the cache: %s: %s", where, e.file, e.msg);
            }
        } else if (!quiet) {
            cli_msg("components: rocking of %zu item(s) on floor '%s' reused from the cache",
                    n, where);
        }
        sl_rockc_key_free(&key);
        sl_floor_free(owned);
        for (size_t k = 0; !st && k < n; k++)
            sl_comp_set_rocking(t, rows[k], &res[k]);
    }
    free(rows);
    free(items);
    free(res);
    return st;
}
