/* cmd_run.c - `seislide run`: floor response spectra in, the clearance workbook and CSV
 * tables out (analysis.h; report/deliver.h writes the folder), for one building or a
 * whole plant (plant/plant.h), every floor's result kept in a cache (plant/cache.h) and,
 * with --shard, one share of the floors for `seislide merge` (plant/shard.h). Options
 * and help: one table (run_opts.h); messages on stderr: run_report.h, plant_progress.h. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "analysis.h"
#include "cli.h"
#include "components_out.h"
#include "outdir.h"
#include "plant/cache.h"
#include "plant/plant.h"
#include "plant/shard.h"
#include "plant_progress.h"
#include "report/deliver.h"
#include "report/plant_book.h"
#include "run_opts.h"
#include "run_report.h"

#include "core/standards.h"

#define VERSION_TEXT "seislide " SEISLIDE_VERSION

/* "building/floor" in a plant, the floor's name otherwise. */
static const char *label(const sl_plant *p, const sl_plant_floor *f, char *buf, size_t n)
{
    if (!p->is_plant)
        return f->name;
    snprintf(buf, n, "%s/%s", p->building[f->building], f->id);
    return buf;
}

typedef struct runner {
    const sl_plant *p;
    sl_analysis_opts *ao;
    const char *cache;      /* NULL: no cache */
    int cache_ready, read_cache;
    const char *out;        /* the final output folder (made when the default cache needs it) */
    plant_progress pp;
    size_t n_mu;
} runner;

static sl_status cache_ready(runner *r, sl_error *err)
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
static sl_status run_floors(runner *r, const unsigned char *mine, sl_error *err)
{
    const sl_plant *p = r->p;
    char lab[2 * SL_DELIVER_ID_MAX + 2];
    unsigned char *later = calloc(p->n ? p->n : 1, 1);
    if (!later)
        return sl_error_set(err, SL_ENOMEM, NULL, 0, "out of memory");
    /* the cache opened first: an unwritable one stops the run before any work, and
     * what killed runs left in it goes even when every floor is reused */
    sl_status st = r->cache ? cache_ready(r, err) : SL_OK;
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
                if ((st = cache_ready(r, err)))
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

/* Write every result of shard K into the fresh folder, with the manifest. */
static sl_status write_shard(const sl_plant *p, const char *dir, const run_args *a,
                             const sl_shard_settings *s, sl_error *err)
{
    char res[4400];
    snprintf(res, sizeof res, "%s/%s", dir, SL_SHARD_RESULTS);
    if (mkdir(res, 0777) != 0)
        return sl_error_set(err, SL_EIO, res, 0, "cannot create: %s", strerror(errno));
    for (size_t i = 0; i < p->n; i++)
        if (p->floors[i].shard == a->shard_k) {
            sl_status st = sl_cache_write(res, &p->floors[i].key, p->floors[i].an, err);
            if (st)
                return st;
        }
    return sl_shard_write_manifest(dir, a->shard_k, a->shard_n, p, s, err);
}

int cmd_run(int argc, char **argv)
{
    const char *dflt[] = {"floors"};
    char cmdline[8192], date[32], warn[16384], cache_dir[4400];
    static sl_plant plant; /* large: not on the stack */
    unsigned char *mine = NULL;
    sl_atomic_dir *out = NULL;
    sl_error err;
    sl_error_clear(&err);
    run_args a;
    int rc = run_parse(argc, argv, &a);
    if (rc)
        goto done;
    rc = CLI_EXIT_ERROR;
    sl_analysis_opts *ao = &a.ao; /* rel_se, rtol, seed, policy: set by the options */
    ao->substeps = (unsigned)a.substeps; /* 0: error-controlled by rtol (docs/integrators.md) */
    ao->n_sets = a.sets; /* 0: adaptive */
    ao->abs_se_m = 1e-3 * a.abs_se_mm;
    ao->max_sets = a.max_sets;
    ao->mu = a.mu.v;
    ao->n_mu = a.mu.n;
    /* every floor read and checked, and the output folder made, before any long work;
     * the output folder apart from every input (exit 2) */
    int nargs = optind < argc ? argc - optind : 1;
    const char *const *ops = optind < argc ? (const char *const *)argv + optind : dflt;
    if ((rc = cli_outdir_apart("run", "output folder", a.out, ops, (size_t)nargs)) ||
        (rc = cli_outdir_apart("run", "output folder", a.out, &a.cache, 1)) ||
        (rc = cli_outdir_apart("run", "output folder", a.out, &a.components, 1)))
        goto done;
    rc = CLI_EXIT_ERROR;
    if (sl_plant_load(&plant, ops, (size_t)nargs, a.force, warn, sizeof warn, &err) ||
        sl_plant_keys(&plant, ao, VERSION_TEXT, &err))
        goto fail;
    for (size_t i = 0; i < plant.n; i++) /* what the operands reach through a link */
        if ((rc = cli_outdir_apart_floor("run", a.out, plant.floors[i].path, plant.is_plant)))
            goto done;
    rc = CLI_EXIT_ERROR;
    for (const char *w = warn; *w;) { /* one line each: file:line: text */
        size_t len = strcspn(w, "\n");
        cli_msg("run: warning: %.*s", (int)len, w);
        w += len + (w[len] == '\n');
    }
    if (a.shard_n)
        sl_plant_assign(&plant, a.shard_n);
    /* a run killed just before its swap left the cache in its fresh folder */
    if (!(out = cli_outdir_open(a.out, VERSION_TEXT, !a.no_cache && !a.cache ? SL_CACHE_DIR_NAME
                                                                           : NULL, &err)))
        goto fail;
    if (a.sets > 0 && a.sets < SL_NLTHA_MIN_SETS && !a.quiet)
        cli_msg("run: warning: %lu motion sets per floor; ASCE/SEI 43-05 asks for at least %d",
                a.sets, SL_NLTHA_MIN_SETS);
    runner r = {.p = &plant, .ao = ao, .n_mu = a.mu.n, .read_cache = !a.dop.write_motions};
    if (!a.no_cache) {
        snprintf(cache_dir, sizeof cache_dir, "%s/%s", a.out, SL_CACHE_DIR_NAME);
        r.cache = a.cache ? a.cache : cache_dir;
        r.out = a.cache ? NULL : a.out;
    }
    if (a.cache && cache_ready(&r, &err)) /* a cache given that cannot be used: before any work */
        goto fail;
    if (!(mine = calloc(plant.n ? plant.n : 1, 1))) {
        sl_error_set(&err, SL_ENOMEM, NULL, 0, "out of memory");
        goto fail;
    }
    size_t n_mine = 0;
    double cost = 0;
    for (size_t i = 0; i < plant.n; i++) {
        mine[i] = !a.shard_n || plant.floors[i].shard == a.shard_k;
        n_mine += mine[i];
        cost += mine[i] ? plant.floors[i].cost : 0;
    }
    plant_progress_start(&r.pp, a.quiet, n_mine, cost);
    ao->progress = plant_progress_cb;
    ao->progress_ctx = &r.pp;
    sl_status st = run_floors(&r, mine, &err);
    plant_progress_end(&r.pp);
    if (st)
        goto fail;
    if (!a.quiet && r.cache)
        cli_msg("run: reused %zu of %zu floors (cache %s)", r.pp.reused, n_mine, r.cache);
    /* motions that failed their checks stop the run before anything is written
     * (run_report_checks prints which, how often and where), unless accepted */
    for (size_t i = 0, k = 0; i < plant.n; i++)
        if (mine[i] && ++k && run_report_checks(k, n_mine, plant.floors[i].floor,
                                                 plant.floors[i].an, a.accept_failed))
            goto done;
    cli_command_line(cmdline, sizeof cmdline, argc, argv);
    sl_deliver_opts *dop = &a.dop; /* version, write_motions, project: set by run_parse */
    sl_shard_settings ss = {VERSION_TEXT, ao->seed, ao->substeps, ao->rtol, dop->project,
                            a.mu.n, a.mu.v};
    dop->command_line = cmdline;
    dop->created = (time_t)a.created;
    dop->seed = ao->seed;
    dop->substeps = ao->substeps;
    dop->accuracy = ao->rtol;
    if (!dop->project.date && strftime(date, sizeof date, "%Y-%m-%d", gmtime(&dop->created)))
        dop->project.date = date;
    cli_outdir_writing(); /* a signal now is noted, and the fresh folder dropped */
    const char *fresh = sl_atomic_dir_path(out);
    if (a.shard_n ? write_shard(&plant, fresh, &a, &ss, &err)
                  : sl_plant_deliver(&plant, fresh, dop, &err))
        goto fail;
    if (a.components &&
        components_write(fresh, a.out, a.components, fresh, cmdline, dop->created, &err))
        goto fail;
    /* the default cache travels with the outputs across the swap */
    char moved[4400] = "";
    struct stat sb;
    if (r.cache && !a.cache && stat(cache_dir, &sb) == 0) {
        snprintf(moved, sizeof moved, "%s/%s", fresh, SL_CACHE_DIR_NAME);
        if (rename(cache_dir, moved) != 0) {
            sl_error_set(&err, SL_EIO, cache_dir, 0, "cannot carry the cache over: %s",
                         strerror(errno));
            goto fail;
        }
    }
    if (cli_outdir_commit(&out, &err)) {
        if (moved[0] && out) /* not swapped (interrupted): the cache goes back */
            rename(moved, cache_dir);
        goto fail;
    }
    if (!a.quiet)
        cli_msg("run: wrote %s/%s", a.out, a.shard_n ? SL_SHARD_MANIFEST " and the shard's results"
                : plant.is_plant ? "<building>/ for each building, " SL_PLANT_BOOK_CSV " and "
                  SL_PLANT_BOOK_XLSX : SL_DELIVER_WORKBOOK " and the CSV files");
    rc = CLI_EXIT_OK;
    goto done;
fail:
    if (!cli_outdir_interrupted())
        cli_print_error(&err);
done:
    free(a.mu.v);
    free(mine);
    sl_plant_free(&plant);
    cli_outdir_finish(out);
    return rc == CLI_OPT_HELP ? CLI_EXIT_OK : rc;
}
