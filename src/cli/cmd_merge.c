/* cmd_merge.c - `seislide merge PARTS/K... -o OUT`: the results of the shards of
 * one plant run (`seislide run PLANT --shard K/N`, plant/shard.h) into exactly
 * the outputs of a single run (the recorded command line aside), and the
 * results into OUT's cache so that a later `seislide run PLANT -o OUT` reuses
 * them. Every shard 1..N must be given once; every result must pass its
 * checks (plant/cache.h). */
#include <errno.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "cli.h"
#include "outdir.h"
#include "plant/cache.h"
#include "plant/plant.h"
#include "plant/shard.h"
#include "report/deliver.h"
#include "report/plant_book.h"

#define VERSION_TEXT sl_build_id() /* the build's identity (core/version.h) */

typedef struct merge_args {
    const char *out;
    int quiet;
    double created;
} merge_args;

static const char merge_head[] =
    "usage: seislide merge SHARD_DIR... [-o DIR] [options]\n\nMerge the output folders of "
    "`seislide run PLANT --shard K/N -o SHARD_DIR` for\nK = 1..N into DIR: exactly the "
    "outputs of one `seislide run PLANT -o DIR` with the\nsame settings (the recorded command "
    "line aside), and DIR/.seislide-cache with every\nfloor's result (docs/plant.md).\n\n"
    "options:\n";
static const char merge_tail[] =
    "\nEvery shard 1..N must be given exactly once (a missing or repeated shard is an\n"
    "error naming it), all of one plant and one set of settings; every result is\n"
    "checked (key, CRC-32, counts) before it is used.\nExit status: 0 success, 1 bad or "
    "missing shard (the output folder unchanged),\n2 usage error.\n";

enum { O_CREATED = CLI_OPT_ID };
#define A(f) .off = offsetof(merge_args, f)
static const cli_opt opts[] = {
    {"output", 'o', "DIR", "output folder (default output/); written whole or not at all,\n"
     "as by run (not a shard folder)",
     .kind = CLI_STRING, A(out)},
    {"quiet", 'q', NULL, "no messages on stderr", .kind = CLI_FLAG, A(quiet)},
    CLI_OPT_CREATED(O_CREATED)};

static int take(void *dst, int key, const char *v)
{
    merge_args *a = dst;
    (void)key;
    if (cli_parse_created(v, &a->created))
        return cli_usage("merge", "bad value '%s' for --created", v);
    return CLI_EXIT_OK;
}

/* Copy a checked entry file into the output's cache (same bytes). */
static sl_status copy_entry(const char *from, const char *dir, const char *hash, sl_error *err)
{
    char to[4500];
    snprintf(to, sizeof to, "%s/%s" SL_CACHE_SUFFIX, dir, hash);
    FILE *in = fopen(from, "rb"), *out = in ? fopen(to, "wb") : NULL;
    char buf[65536];
    size_t k;
    int bad = !in || !out;
    while (!bad && (k = fread(buf, 1, sizeof buf, in)) > 0)
        bad = fwrite(buf, 1, k, out) != k;
    bad |= in && ferror(in);
    if (in)
        fclose(in);
    if (out)
        bad |= fclose(out) != 0;
    return bad ? sl_error_set(err, SL_EIO, to, 0, "cannot write: %s", strerror(errno)) : SL_OK;
}

/* Read the n shard folders: all of one plant, settings and version, every
 * shard 1..N once (by_k[K]: shard K's folder). */
static sl_status read_shards(char *const *dirs, size_t ns, sl_shard *sh, const char **by_k,
                             sl_error *err)
{
    for (size_t i = 0; i < ns; i++) {
        sl_status st = sl_shard_read(dirs[i], &sh[i], err);
        if (st)
            return st;
        if (sh[i].n != sh[0].n || sh[i].body_len != sh[0].body_len ||
            memcmp(sh[i].body, sh[0].body, sh[0].body_len) != 0)
            return sl_error_set(err, SL_EINVAL, dirs[i], 0, "shard %u/%u is not of the same plant "
                                "and settings as %s (shard %u/%u): every shard must come from the "
                                "same command but for --shard and -o", sh[i].k, sh[i].n, dirs[0],
                                sh[0].k, sh[0].n);
        if (by_k[sh[i].k])
            return sl_error_set(err, SL_EINVAL, dirs[i], 0, "shard %u/%u given twice: %s and %s",
                                sh[i].k, sh[i].n, by_k[sh[i].k], dirs[i]);
        by_k[sh[i].k] = dirs[i];
    }
    for (unsigned k = 1; k <= sh[0].n; k++)
        if (!by_k[k])
            return sl_error_set(err, SL_EINVAL, NULL, 0, "shard %u/%u missing (given: %zu of %u "
                                "shard folders)", k, sh[0].n, ns, sh[0].n);
    if (strcmp(sh[0].set.version, VERSION_TEXT) != 0)
        return sl_error_set(err, SL_EINVAL, dirs[0], 0, "the shards were computed by %s, this is "
                            "%s", sh[0].set.version, VERSION_TEXT);
    return SL_OK;
}

/* Every floor's result from its shard's folder, checked (dir0: the first
 * folder given, named when a floor is in no shard). */
static sl_status read_results(const sl_shard *sh0, sl_plant *p, const char *const *by_k,
                              const char *dir0, sl_error *err)
{
    char path[4400], why[256];
    for (size_t i = 0; i < p->n; i++) {
        sl_plant_floor *f = &p->floors[i];
        const char *dir = f->shard ? by_k[f->shard] : NULL;
        if (!dir)
            return sl_error_set(err, SL_EINVAL, dir0, 0, "floor '%s' is in no shard", f->id);
        snprintf(path, sizeof path, "%s/%s/%s" SL_CACHE_SUFFIX, dir, SL_SHARD_RESULTS, f->key.hash);
        sl_cache_read_result c = sl_cache_read_path(path, f->key.hash, sh0->set.n_mu, &f->an,
                                                    why, sizeof why);
        if (c != SL_CACHE_HIT)
            return sl_error_set(err, SL_EINVAL, path, 0, "the result of floor '%s%s%s' (shard "
                                "%u/%u) %s%s: rerun that shard",
                                p->is_plant ? p->building[f->building] : "",
                                p->is_plant ? "/" : "", f->id, f->shard, sh0->n,
                                c == SL_CACHE_MISS ? "is missing" : "failed its check: ",
                                c == SL_CACHE_MISS ? "" : why);
    }
    return SL_OK;
}

/* The outputs of one run, and every result in the cache, into the fresh
 * folder (argc, argv: the recorded command line); from the first write on a
 * signal is only noted (outdir.h). */
static sl_status write_outputs(const sl_shard *sh0, const char *const *by_k, const char *fresh,
                               const merge_args *a, int argc, char **argv, sl_error *err)
{
    const sl_plant *p = &sh0->plant;
    char cmdline[8192], date[32], path[4400];
    cli_command_line(cmdline, sizeof cmdline, argc, argv);
    sl_deliver_opts dop = {.version = VERSION_TEXT, .command_line = cmdline,
                           .created = (time_t)a->created, .project = sh0->set.project,
                           .seed = sh0->set.seed, .substeps = sh0->set.substeps,
                           .accuracy = sh0->set.accuracy};
    if (!dop.project.date && strftime(date, sizeof date, "%Y-%m-%d", gmtime(&dop.created)))
        dop.project.date = date;
    cli_outdir_writing(); /* a signal now is noted, and the fresh folder dropped */
    sl_status st = sl_plant_deliver(p, fresh, &dop, err);
    if (st)
        return st;
    char cache[4400];
    snprintf(cache, sizeof cache, "%s/%s", fresh, SL_CACHE_DIR_NAME);
    if (mkdir(cache, 0777) != 0)
        return sl_error_set(err, SL_EIO, cache, 0, "cannot create: %s", strerror(errno));
    for (size_t i = 0; i < p->n; i++) {
        const sl_plant_floor *f = &p->floors[i];
        snprintf(path, sizeof path, "%s/%s/%s" SL_CACHE_SUFFIX, by_k[f->shard], SL_SHARD_RESULTS,
                 f->key.hash);
        if ((st = copy_entry(path, cache, f->key.hash, err)))
            return st;
    }
    return SL_OK;
}

int cmd_merge(int argc, char **argv)
{
    static const cli_command cmd = {"merge", merge_head, merge_tail, opts, CLI_NOPTS(opts), 20,
                                    take, NULL, 1};
    merge_args a = {.out = "output", .created = cli_created_default()};
    int rc = cli_command_parse(&cmd, argc, argv, &a);
    if (rc)
        return rc == CLI_OPT_HELP ? CLI_EXIT_OK : rc;
    size_t ns = (size_t)(argc - optind);
    if (ns == 0)
        return cli_usage("merge", "give the shard folders (seislide merge PARTS/* -o DIR)");
    if (ns > SL_PLANT_MAX_SHARDS)
        return cli_usage("merge", "more than %d shard folders", SL_PLANT_MAX_SHARDS);
    char *const *dirs = argv + optind;
    if ((rc = cli_outdir_apart("merge", "output folder", a.out, (const char *const *)dirs, ns)))
        return rc;
    sl_shard *sh = calloc(ns, sizeof *sh);
    const char **by_k = calloc(SL_PLANT_MAX_SHARDS + 1, sizeof *by_k);
    sl_atomic_dir *out = NULL;
    sl_error err;
    sl_error_clear(&err);
    rc = CLI_EXIT_ERROR;
    if (!sh || !by_k) {
        sl_error_set(&err, SL_ENOMEM, NULL, 0, "out of memory");
        goto fail;
    }
    if (read_shards(dirs, ns, sh, by_k, &err))
        goto fail;
    sl_plant *p = &sh[0].plant;
    for (size_t i = 0; i < p->n; i++) /* the floor files the shards were computed from */
        if ((rc = cli_outdir_apart_floor("merge", a.out, p->floors[i].path, p->is_plant)))
            goto done;
    rc = CLI_EXIT_ERROR;
    if (!(out = cli_outdir_open(a.out, VERSION_TEXT, NULL, &err)))
        goto fail;
    if (read_results(&sh[0], p, by_k, dirs[0], &err))
        goto fail;
    if (write_outputs(&sh[0], by_k, sl_atomic_dir_path(out), &a, argc, argv, &err))
        goto fail;
    if (cli_outdir_commit(&out, &err))
        goto fail;
    if (!a.quiet)
        cli_msg("merge: %u shards, %zu floors%s: wrote %s", sh[0].n, p->n,
                p->is_plant ? " of the plant" : "", a.out);
    rc = CLI_EXIT_OK;
    goto done;
fail:
    cli_outdir_error(&err);
done:
    for (size_t i = 0; sh && i < ns; i++)
        sl_shard_free(&sh[i]);
    free(sh);
    free(by_k);
    cli_outdir_finish(out);
    return rc;
}
