/* run_floors.c - the floors of one `seislide run` (run_floors.h): each from
 * the cache or computed under its lock, the locked ones waited for. */
#include "run_floors.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "plant/cache.h"
#include "report/deliver.h"

/* "building/floor" in a plant, the floor's name otherwise. */
static const char *label(const sl_plant *p, const sl_plant_floor *f, char *buf, size_t n)
{
    if (!p->is_plant)
        return f->name;
    snprintf(buf, n, "%s/%s", p->building[f->building], f->id);
    return buf;
}

sl_status run_cache_ready(runner *r, sl_error *err)
{
    if (r->cache_ready)
        return SL_OK;
    if (r->out && mkdir(r->out, 0777) != 0 && errno != EEXIST)
        return sl_error_set(err, SL_EIO, r->out, 0, "cannot create: %s", strerror(errno));
    sl_status st = sl_cache_open(r->cache, err);
    r->cache_ready = !st;
    return st;
}

/* Try the cache for floor i: 1 taken from it, 0 not there (or damaged: said). */
static int try_cache(runner *r, size_t i, const char *lab)
{
    sl_plant_floor *f = &r->p->floors[i];
    char why[256];
    if (!r->cache || !r->read_cache)
        return 0;
    sl_cache_read_result c = sl_cache_read(r->cache, &f->key, r->n_mu, &f->an, why, sizeof why);
    if (c == SL_CACHE_DAMAGED)
        plant_progress_msg(&r->pp, "run: cache entry %s/%s%s failed its check (%s): floor '%s' "
                           "recomputed", r->cache, f->key.hash, SL_CACHE_SUFFIX, why, lab);
    if (c != SL_CACHE_HIT)
        return 0;
    f->reused = 1;
    size_t seq = r->pp.done + 1; /* the floor's place in this run's sequence */
    plant_progress_floor(&r->pp, seq, lab, f->cost);
    plant_progress_done(&r->pp, seq, lab, f->an, 1, r->n_mu);
    return 1;
}

/* Compute floor i (its lock held, when there is a cache) and store it. */
static sl_status compute(runner *r, size_t i, const char *lab, sl_error *err)
{
    sl_plant_floor *f = &r->p->floors[i];
    size_t seq = r->pp.done + 1; /* the floor's place in this run's sequence */
    plant_progress_floor(&r->pp, seq, lab, f->cost);
    r->pp.cache_dir = r->cache;
    r->pp.lock_hash = r->cache ? f->key.hash : NULL;
    f->an = sl_analysis_run(f->floor, r->ao, err);
    r->pp.lock_hash = NULL;
    if (!f->an)
        return err ? err->code : SL_EINVAL;
    sl_status st = r->cache ? sl_cache_write(r->cache, &f->key, f->an, err) : SL_OK;
    if (!st)
        plant_progress_done(&r->pp, seq, lab, f->an, 0, r->n_mu);
    return st;
}

/* Every floor of this run: from the cache, else computed; a floor another
 * run is computing (locked) is left for later and then waited for. */
sl_status run_floors(runner *r, const unsigned char *mine, sl_error *err)
{
    const sl_plant *p = r->p;
    char lab[2 * SL_DELIVER_ID_MAX + 2];
    unsigned char *later = calloc(p->n ? p->n : 1, 1);
    if (!later)
        return sl_error_set(err, SL_ENOMEM, NULL, 0, "out of memory");
    /* the cache opened first: an unwritable one stops the run before any work, and
     * what killed runs left in it goes even when every floor is reused */
    sl_status st = r->cache ? run_cache_ready(r, err) : SL_OK;
    size_t n_later = 0;
    for (int pass = 0; !st && (pass == 0 || n_later); pass++) {
        int progressed = 0;
        for (size_t i = 0; !st && i < p->n; i++) {
            if (!mine[i] || p->floors[i].an || (pass && !later[i]))
                continue;
            const char *lb = label(p, &p->floors[i], lab, sizeof lab);
            if (try_cache(r, i, lb)) {
                n_later -= later[i];
                later[i] = 0;
                progressed = 1;
                continue;
            }
            if (r->cache) {
                if ((st = run_cache_ready(r, err)))
                    break;
                sl_cache_lock_result lk = sl_cache_lock(r->cache, p->floors[i].key.hash, err);
                if (lk == SL_CACHE_LOCK_ERROR) {
                    st = err ? err->code : SL_EIO;
                    break;
                }
                if (lk == SL_CACHE_BUSY) {
                    if (!later[i]) {
                        later[i] = 1;
                        n_later++;
                        plant_progress_msg(&r->pp, "run: floor '%s' is being computed by another "
                                           "run (lock %s/%s.lock): left for later", lb, r->cache,
                                           p->floors[i].key.hash);
                    }
                    continue;
                }
                /* locked: another run may have finished it just now */
                if (r->read_cache && try_cache(r, i, lb)) {
                    sl_cache_unlock(r->cache, p->floors[i].key.hash);
                    n_later -= later[i];
                    later[i] = 0;
                    progressed = 1;
                    continue;
                }
            }
            st = compute(r, i, lb, err);
            if (r->cache)
                sl_cache_unlock(r->cache, p->floors[i].key.hash);
            n_later -= later[i];
            later[i] = 0;
            progressed = 1;
        }
        if (!st && n_later && !progressed)
            sleep(1);
    }
    free(later);
    return st;
}
