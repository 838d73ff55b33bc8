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

int cmd_synth(int argc, char **argv)
{
    synth_run o;
    int rc = synth_parse(argc, argv, &o);
    if (rc)
        return rc < 0 ? CLI_EXIT_OK : rc;

    /* the output folder apart from the floor file and the records (exit 2) */
    if ((rc = cli_outdir_apart("synth", "output folder", o.outdir, &o.floor_path, 1)) ||
        (rc = cli_outdir_apart("synth", "output folder", o.outdir, o.match, o.nmatch)))
        return rc;
    sl_error err;
    sl_error_clear(&err);
    sl_atomic_dir *outd = NULL;
    sl_floor *fl = NULL;
    sl_spectrum *own[SL_SYNTH_NCOMP] = {NULL, NULL, NULL};
    sl_motion *rec[SL_SYNTH_NCOMP] = {NULL, NULL, NULL};
    sl_synth *plan = NULL;
    sl_synth_set *sets = NULL;
    size_t nsets = 0;
    sl_synth_target tgt[SL_SYNTH_NCOMP];
    char desc[SL_SYNTH_NCOMP][512];
    rc = CLI_EXIT_ERROR;

    /* Targets. */
    if (o.floor_path) {
        fl = sl_floor_load(o.floor_path, &err);
        if (!fl || sl_synth_targets_floor(fl, o.damping, tgt, &err)) {
            cli_print_error(&err);
            goto done;
        }
    } else {
        double z = o.damping > 0 ? o.damping : SL_SYNTH_DAMPING;
        if (!(z >= SL_RG160_ZETA_MIN && z <= SL_RG160_ZETA_MAX)) {
            rc = cli_usage("synth", "--damping %g outside RG 1.60's range [%g, %g]", z,
                           SL_RG160_ZETA_MIN, SL_RG160_ZETA_MAX);
            goto done;
        }
        if (sl_synth_targets_rg160(o.rg_pga_g * SL_G, z, &o.p, own, tgt, &err)) {
            cli_print_error(&err);
            goto done;
        }
    }
    synth_describe_targets(fl, o.rg_pga_g, tgt, desc);

    /* Plan and motions. */
    double dt = o.dt_s > 0 ? o.dt_s : SL_SYNTH_DT_S;
    size_t n;
    if (o.nmatch > 0) {
        if ((rc = synth_read_records(&o, rec, &dt)) != CLI_EXIT_OK)
            goto done;
        rc = CLI_EXIT_ERROR;
        n = 0;
        for (size_t i = 0; i < o.nmatch; i++)
            n = rec[i]->n > n ? rec[i]->n : n;
    } else {
        n = (size_t)llround(o.duration_s / dt) + 1;
    }
    plan = sl_synth_alloc(n, dt, &o.p, &err);
    if (!plan) { /* bad settings (not memory) are the options' doing: a usage error */
        if (err.code == SL_EINVAL)
            rc = cli_usage("synth", "%s (%zu samples of --dt %g s, --fmin %g Hz)", err.msg, n,
                           dt, o.p.fmin_hz);
        else
            cli_print_error(&err);
        goto done;
    }
    if (!(outd = cli_outdir_open(o.outdir, "seislide " SEISLIDE_VERSION, NULL, &err))) {
        cli_print_error(&err);
        goto done;
    }
    nsets = o.nmatch > 0 ? 1 : (size_t)o.count;
    sets = calloc(nsets, sizeof *sets);
    if (!sets) {
        cli_msg("out of memory");
        goto done;
    }
    int show = !o.quiet && isatty(STDERR_FILENO);
    sl_status st;
    if (o.nmatch > 0) {
        const sl_motion *r3[SL_SYNTH_NCOMP] = {rec[0], rec[1], rec[2]};
        st = sl_synth_match_set(plan, tgt, r3, sets, &err);
    } else {
        st = sl_synth_make_sets(plan, tgt, (uint64_t)o.seed, 0, nsets, sets,
                                show ? progress_cb : NULL, NULL, &err);
    }
    if (st && st != SL_ENOCONV) {
        cli_print_error(&err);
        goto done;
    }
    /* every other damping the floor file gives, on the motions' own spectra */
    if (fl && sl_synth_check_dampings(plan, fl, sets, nsets, &err)) {
        cli_print_error(&err);
        goto done;
    }
    /* every file into the fresh folder, swapped in whole (outdir.h) */
    cli_outdir_writing();
    synth_output out = {sl_atomic_dir_path(outd), o.csv, o.seed, o.nmatch > 0 ? o.match : NULL,
                        (const char(*)[512])desc, &o.p};
    if (synth_write_outputs(&out, sets, nsets) != CLI_EXIT_OK)
        goto done;
    if (cli_outdir_commit(&outd, &err)) {
        if (!cli_outdir_interrupted())
            cli_print_error(&err);
        goto done;
    }
    if (fl && !o.quiet)
        synth_print_dampings(sets, nsets, &o.p);
    size_t total = 0, failed = 0;
    for (size_t k = 0; k < nsets; k++)
        for (int c = 0; c < SL_SYNTH_NCOMP; c++)
            if (sl_synth_set_motion(&sets[k], (sl_synth_comp)c)) {
                total++;
                failed += !sets[k].check[c].pass;
            }
    if (failed) {
        cli_msg("synth: %zu of %zu motions failed a check (see %s/report.csv)", failed, total,
                o.outdir);
        goto done;
    }
    if (!o.quiet) {
        if (o.nmatch > 0)
            cli_msg("synth: %zu motions matched, every check passed; %s/report.csv", total,
                    o.outdir);
        else
            cli_msg("synth: %zu motions, every check passed (seed %llu); %s/report.csv", total,
                    o.seed, o.outdir);
    }
    rc = CLI_EXIT_OK;
done:
    for (size_t k = 0; sets && k < nsets; k++)
        sl_synth_set_clear(&sets[k]);
    free(sets);
    sl_synth_free(plan);
    for (int c = 0; c < SL_SYNTH_NCOMP; c++) {
        sl_spectrum_free(own[c]);
        sl_motion_free(rec[c]);
    }
    sl_floor_free(fl);
    cli_outdir_finish(outd);
    return rc;
}
