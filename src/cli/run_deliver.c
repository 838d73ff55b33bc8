/* run_deliver.c - the outputs of `seislide run` into its output folder,
 * whole or not at all (run_deliver.h). */
#include "run_deliver.h"

#include <stdio.h>
#include <errno.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "cli.h"
#include "components_out.h"
#include "outdir.h"
#include "plant/cache.h"
#include "plant/shard.h"
#include "report/deliver.h"
#include "report/plant_book.h"

#define VERSION_TEXT sl_build_id() /* the build's identity (core/version.h) */

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

sl_status run_deliver(const run_args *a, const sl_plant *plant, const char *default_cache,
                      int argc, char **argv, sl_atomic_dir **out, sl_error *err)
{
    char cmdline[8192], date[32];
    const sl_analysis_opts *ao = &a->ao;
    cli_command_line(cmdline, sizeof cmdline, argc, argv);
    sl_deliver_opts dop = a->dop; /* version, write_motions, project: set by run_parse */
    sl_shard_settings ss = {VERSION_TEXT, ao->seed, ao->substeps, ao->rtol, dop.project,
                            a->mu.n, a->mu.v};
    dop.command_line = cmdline;
    dop.created = (time_t)a->created;
    dop.seed = ao->seed;
    dop.substeps = ao->substeps;
    dop.accuracy = ao->rtol;
    if (!dop.project.date && strftime(date, sizeof date, "%Y-%m-%d", gmtime(&dop.created)))
        dop.project.date = date;
    cli_outdir_writing(); /* a signal now is noted, and the fresh folder dropped */
    const char *fresh = sl_atomic_dir_path(*out);
    sl_status st = a->shard_n ? write_shard(plant, fresh, a, &ss, err)
                              : sl_plant_deliver(plant, fresh, &dop, err);
    if (st)
        return st;
    if (a->components &&
        (st = components_write(fresh, a->out, a->components, fresh, cmdline, dop.created, plant,
                               default_cache ? default_cache : a->cache, a->quiet, err)))
        return st;
    /* the default cache travels with the outputs across the swap; any failure of
     * the commit (or a signal) puts it back (atomic.h: sl_atomic_dir_take) */
    if (default_cache && (st = sl_atomic_dir_take(*out, SL_CACHE_DIR_NAME, err)))
        return st;
    if ((st = cli_outdir_commit(out, err)))
        return st;
    if (!a->quiet)
        cli_msg("run: wrote %s/%s", a->out, a->shard_n ? SL_SHARD_MANIFEST " and the shard's results"
                : plant->is_plant ? "<building>/ for each building, " SL_PLANT_BOOK_CSV " and "
                  SL_PLANT_BOOK_XLSX : SL_DELIVER_WORKBOOK " and the CSV files");
    return SL_OK;
}
