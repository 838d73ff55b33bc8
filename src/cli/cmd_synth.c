/* cmd_synth.c - `seislide synth`: spectrum-compatible three-component sets
 * (or recorded motions matched to a target), their files and a match report
 * with every acceptance check. Library: synth.h; method: docs/synthesis.md. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "io/floor.h"
#include "io/motion.h"
#include "outdir.h"
#include "signal/rg160.h"
#include "synth/synth.h"
#include "synth_opts.h"
#include "synth_output.h"

/* ---- Progress --------------------------------------------------------- */

static void progress_cb(void *ctx, size_t done, size_t total)
{
    (void)ctx;
    fprintf(stderr, "\rseislide: synth: %zu/%zu motions", done, total);
    if (done >= total)
        fputc('\n', stderr);
    fflush(stderr);
}

/* ---- The command ------------------------------------------------------ */

/* One run: its options, targets, plan and sets (freed by job_free). */
typedef struct synth_job {
    synth_run o;
    sl_floor *fl;
    sl_spectrum *own[SL_SYNTH_NCOMP];   /* RG 1.60 targets' spectra */
    sl_motion *rec[SL_SYNTH_NCOMP];     /* --match records */
    sl_synth *plan;
    sl_synth_set *sets;
    size_t nsets;
    sl_atomic_dir *outd;                /* the fresh output folder (outdir.h) */
    sl_synth_target tgt[SL_SYNTH_NCOMP];
    char desc[SL_SYNTH_NCOMP][512];
    sl_error err;
} synth_job;

static void job_free(synth_job *j)
{
    for (size_t k = 0; j->sets && k < j->nsets; k++)
        sl_synth_set_clear(&j->sets[k]);
    free(j->sets);
    sl_synth_free(j->plan);
    for (int c = 0; c < SL_SYNTH_NCOMP; c++) {
        sl_spectrum_free(j->own[c]);
        sl_motion_free(j->rec[c]);
    }
    sl_floor_free(j->fl);
    cli_outdir_finish(j->outd);
}

/* The targets: the floor file's spectra or RG 1.60 at --rg160 PGA. */
static int job_targets(synth_job *j)
{
    const synth_run *o = &j->o;
    if (o->floor_path) {
        j->fl = sl_floor_load(o->floor_path, &j->err);
        if (!j->fl || sl_synth_targets_floor(j->fl, o->damping, j->tgt, &j->err)) {
            cli_print_error(&j->err);
            return CLI_EXIT_ERROR;
        }
    } else {
        double z = o->damping > 0 ? o->damping : SL_SYNTH_DAMPING;
        if (!(z >= SL_RG160_ZETA_MIN && z <= SL_RG160_ZETA_MAX))
            return cli_usage("synth", "--damping %g outside RG 1.60's range [%g, %g]", z,
                             SL_RG160_ZETA_MIN, SL_RG160_ZETA_MAX);
        if (sl_synth_targets_rg160(o->rg_pga_g * SL_G, z, &o->p, j->own, j->tgt, &j->err)) {
            cli_print_error(&j->err);
            return CLI_EXIT_ERROR;
        }
    }
    synth_describe_targets(j->fl, o->rg_pga_g, j->tgt, j->desc);
    return CLI_EXIT_OK;
}

/* The plan: --duration at --dt, or the longest --match record at its dt. */
static int job_plan(synth_job *j)
{
    const synth_run *o = &j->o;
    double dt = o->dt_s > 0 ? o->dt_s : SL_SYNTH_DT_S;
    size_t n = 0;
    if (o->nmatch > 0) {
        int rc = synth_read_records(o, j->rec, &dt);
        if (rc != CLI_EXIT_OK)
            return rc;
        for (size_t i = 0; i < o->nmatch; i++)
            n = j->rec[i]->n > n ? j->rec[i]->n : n;
    } else {
        n = (size_t)llround(o->duration_s / dt) + 1;
    }
    j->plan = sl_synth_alloc(n, dt, &o->p, &j->err);
    if (!j->plan) { /* bad settings (not memory) are the options' doing: a usage error */
        if (j->err.code == SL_EINVAL)
            return cli_usage("synth", "%s (%zu samples of --dt %g s, --fmin %g Hz)", j->err.msg,
                             n, dt, o->p.fmin_hz);
        cli_print_error(&j->err);
        return CLI_EXIT_ERROR;
    }
    return CLI_EXIT_OK;
}

/* The sets (or the matched records) and, with a floor file, every other
 * damping it gives on the motions' own spectra. */
static int job_motions(synth_job *j)
{
    const synth_run *o = &j->o;
    if (!(j->outd = cli_outdir_open(o->outdir, sl_build_id(), NULL, &j->err))) {
        cli_print_error(&j->err);
        return CLI_EXIT_ERROR;
    }
    j->nsets = o->nmatch > 0 ? 1 : (size_t)o->count;
    if (!(j->sets = calloc(j->nsets, sizeof *j->sets))) {
        cli_msg("out of memory");
        return CLI_EXIT_ERROR;
    }
    int show = !o->quiet && isatty(STDERR_FILENO);
    sl_status st;
    if (o->nmatch > 0) {
        const sl_motion *r3[SL_SYNTH_NCOMP] = {j->rec[0], j->rec[1], j->rec[2]};
        st = sl_synth_match_set(j->plan, j->tgt, r3, j->sets, &j->err);
    } else {
        st = sl_synth_make_sets(j->plan, j->tgt, (uint64_t)o->seed, 0, j->nsets, j->sets,
                                show ? progress_cb : NULL, NULL, &j->err);
    }
    if ((st && st != SL_ENOCONV) ||
        (j->fl && sl_synth_check_dampings(j->plan, j->fl, j->sets, j->nsets, &j->err))) {
        cli_print_error(&j->err);
        return CLI_EXIT_ERROR;
    }
    return CLI_EXIT_OK;
}

/* The files and the verdict: 1 (error) when a motion failed a check. */
static int job_write(synth_job *j)
{
    const synth_run *o = &j->o;
    /* every file into the fresh folder, swapped in whole (outdir.h) */
    cli_outdir_writing();
    synth_output out = {sl_atomic_dir_path(j->outd), o->csv, o->seed,
                        o->nmatch > 0 ? o->match : NULL, (const char(*)[512])j->desc, &o->p};
    if (synth_write_outputs(&out, j->sets, j->nsets) != CLI_EXIT_OK)
        return CLI_EXIT_ERROR;
    if (cli_outdir_commit(&j->outd, &j->err)) {
        cli_outdir_error(&j->err);
        return CLI_EXIT_ERROR;
    }
    if (j->fl && !o->quiet)
        synth_print_dampings(j->sets, j->nsets, &o->p);
    size_t total = 0, failed = 0;
    for (size_t k = 0; k < j->nsets; k++)
        for (int c = 0; c < SL_SYNTH_NCOMP; c++)
            if (sl_synth_set_motion(&j->sets[k], (sl_synth_comp)c)) {
                total++;
                failed += !j->sets[k].check[c].pass;
            }
    if (failed) {
        cli_msg("synth: %zu of %zu motions failed a check (see %s/report.csv)", failed, total,
                o->outdir);
        return CLI_EXIT_ERROR;
    }
    if (!o->quiet && o->nmatch > 0)
        cli_msg("synth: %zu motions matched, every check passed; %s/report.csv", total,
                o->outdir);
    else if (!o->quiet)
        cli_msg("synth: %zu motions, every check passed (seed %llu); %s/report.csv", total,
                o->seed, o->outdir);
    return CLI_EXIT_OK;
}

int cmd_synth(int argc, char **argv)
{
    synth_job j = {0};
    int rc = synth_parse(argc, argv, &j.o);
    if (rc)
        return rc < 0 ? CLI_EXIT_OK : rc;
    /* the output folder apart from the floor file and the records (exit 2) */
    if ((rc = cli_outdir_apart("synth", "output folder", j.o.outdir, &j.o.floor_path, 1)) ||
        (rc = cli_outdir_apart("synth", "output folder", j.o.outdir, j.o.match, j.o.nmatch)))
        return rc;
    sl_error_clear(&j.err);
    rc = job_targets(&j);
    if (rc == CLI_EXIT_OK)
        rc = job_plan(&j);
    if (rc == CLI_EXIT_OK)
        rc = job_motions(&j);
    if (rc == CLI_EXIT_OK)
        rc = job_write(&j);
    job_free(&j);
    return rc;
}
