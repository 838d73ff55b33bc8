/* cmd_run.c - `seislide run`: floor response spectra in, the clearance workbook and CSV
 * tables out (analysis.h; report/deliver.h writes the folder), for one building or a
 * whole plant (plant/plant.h), every floor's result kept in a cache (plant/cache.h) and,
 * with --shard, one share of the floors for `seislide merge` (plant/shard.h). Options
 * and help: one table (run_opts.h); the floors computed or reused: run_floors.h; the
 * outputs written and swapped in: run_deliver.h; messages on stderr: run_report.h,
 * plant_progress.h. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis.h"
#include "cli.h"
#include "outdir.h"
#include "plant/cache.h"
#include "plant/plant.h"
#include "plant_progress.h"
#include "run_deliver.h"
#include "run_floors.h"
#include "run_opts.h"
#include "run_report.h"
#include "run_rocking.h"

#include "core/standards.h"

#define VERSION_TEXT sl_build_id() /* the build's identity (core/version.h) */

int cmd_run(int argc, char **argv)
{
    const char *dflt[] = {"floors"};
    char warn[16384], cache_dir[4400];
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
    sl_analysis_opts *ao = &a.ao; /* complete: run_parse */
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
    /* the floors of each building against each other (a units slip), but those
     * accepted in writing; an --accept-floor that names no floor is a usage error */
    for (size_t k = 0; k < a.n_accept; k++)
        if (sl_plant_accept(&plant, a.accept_floor[k], &err)) {
            rc = cli_usage("run", "%s", err.msg);
            goto done;
        }
    rc = CLI_EXIT_ERROR;
    if (sl_plant_check_intensity(&plant, &err))
        goto fail;
    for (size_t i = 0; i < plant.n; i++) /* an accepted floor's warning (the others: below) */
        if (plant.floors[i].accepted && plant.floors[i].warnings &&
            strstr(plant.floors[i].warnings, "accepted by --accept-floor"))
            cli_msg("run: warning: %s: %s", plant.floors[i].path,
                    strstr(plant.floors[i].warnings, "accepted by --accept-floor"));
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
    if (!a.no_cache) { /* in the output folder as resolved (one path for every step) */
        snprintf(cache_dir, sizeof cache_dir, "%s/%s", cli_outdir_path(), SL_CACHE_DIR_NAME);
        r.cache = a.cache ? a.cache : cache_dir;
        r.out = a.cache ? NULL : cli_outdir_path();
    }
    if (a.cache && run_cache_ready(&r, &err)) /* a cache given that cannot be used: before any work */
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
        cli_msg("run: reused %zu of %zu floors (cache %s%s)", r.pp.reused, n_mine,
                a.cache ? a.cache : a.out, a.cache ? "" : "/" SL_CACHE_DIR_NAME);
    /* motions that failed their checks stop the run before anything is written
     * (run_report_checks prints which, how often and where), unless accepted */
    for (size_t i = 0, k = 0; i < plant.n; i++)
        if (mine[i] && ++k && run_report_checks(k, n_mine, plant.floors[i].floor,
                                                 plant.floors[i].an, a.accept_failed))
            goto done;
    if (a.rocking_lookup &&
        run_rocking_lookup(&plant, mine, ao->seed, r.cache, a.quiet, &err))
        goto fail;
    if (run_deliver(&a, &plant, r.cache && !a.cache ? cache_dir : NULL, argc, argv, &out, &err))
        goto fail;
    rc = CLI_EXIT_OK;
    goto done;
fail:
    cli_outdir_error(&err);
done:
    free(a.mu.v);
    free(mine);
    sl_plant_free(&plant);
    cli_outdir_finish(out);
    return rc == CLI_OPT_HELP ? CLI_EXIT_OK : rc;
}
