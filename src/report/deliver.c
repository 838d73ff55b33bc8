/* deliver.c - the output folder of `seislide run`; see deliver.h. */
#include "report/deliver.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <zlib.h>

#include "method/asce.h"
#include "method/scatter.h"
#include "synth/synth.h"

sl_status sl_deliver_file_crc(const char *path, unsigned long *crc, long *size, sl_error *err)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return sl_error_set(err, SL_EIO, path, 0, "cannot read: %s", strerror(errno));
    uLong c = crc32(0L, Z_NULL, 0);
    unsigned char buf[65536];
    size_t k;
    long total = 0;
    while ((k = fread(buf, 1, sizeof buf, f)) > 0) {
        c = crc32(c, buf, (uInt)k);
        total += (long)k;
    }
    int bad = ferror(f);
    fclose(f);
    *crc = c;
    *size = total;
    return bad ? sl_error_set(err, SL_EIO, path, 0, "cannot read") : SL_OK;
}

static sl_status write_motions(const char *dir, size_t n, const sl_deliver_meta *floors,
                               const char *const *ids, const sl_analysis *const *an,
                               uint64_t seed, sl_error *err)
{
    static const char *const cn[SL_SYNTH_NCOMP] = {"h1", "h2", "v"};
    char sub[4096], path[4400], title[512], file[SL_DELIVER_ID_MAX];
    snprintf(sub, sizeof sub, "%s/motions", dir);
    if (mkdir(sub, 0777) != 0)
        return sl_error_set(err, SL_EIO, sub, 0, "cannot create: %s", strerror(errno));
    for (size_t i = 0; i < n; i++) {
        snprintf(sub, sizeof sub, "%s/motions/%s", dir,
                 sl_report_file_name(ids[i], file, sizeof file));
        if (mkdir(sub, 0777) != 0)
            return sl_error_set(err, SL_EIO, sub, 0, "cannot create: %s", strerror(errno));
        for (size_t s = 0; s < an[i]->n_sets; s++)
            for (int c = 0; c < SL_SYNTH_NCOMP; c++) {
                snprintf(path, sizeof path, "%s/set%02zu_%s.AT2", sub, s + 1, cn[c]);
                snprintf(title, sizeof title, "%s, set %zu, %s, seed %llu", floors[i].name,
                         s + 1, cn[c], (unsigned long long)seed);
                if (sl_synth_write_at2(path, sl_synth_set_motion(&an[i]->sets[s], (sl_synth_comp)c), title, err))
                    return err ? err->code : SL_EIO;
            }
    }
    return SL_OK;
}

sl_status sl_deliver_meta_of(const sl_floor *fl, sl_deliver_meta *m, sl_error *err)
{
    *m = (sl_deliver_meta){.name = fl->name, .path = fl->path, .description = fl->description,
                           .units = sl_unit_name(fl->units), .elevation_m = fl->elevation_m};
    return sl_deliver_file_crc(fl->path, &m->crc32, &m->size_bytes, err);
}

sl_status sl_deliver_write(const char *dir, size_t n, const sl_floor *const *floors,
                           const char *const *ids, const sl_analysis *const *an,
                           const sl_deliver_opts *o, sl_error *err)
{
    sl_deliver_meta *m = calloc(n ? n : 1, sizeof *m);
    if (!m)
        return sl_error_set(err, SL_ENOMEM, dir, 0, "out of memory");
    sl_status st = SL_OK;
    for (size_t i = 0; i < n && !st; i++)
        st = sl_deliver_meta_of(floors[i], &m[i], err);
    if (!st)
        st = sl_deliver_write_meta(dir, n, m, ids, an, o, err);
    free(m);
    return st;
}

sl_status sl_deliver_write_meta(const char *dir, size_t n, const sl_deliver_meta *floors,
                                const char *const *ids, const sl_analysis *const *an,
                                const sl_deliver_opts *o, sl_error *err)
{
    if (n == 0)
        return sl_error_set(err, SL_EINVAL, dir, 0, "no floors to write");
    size_t nq = 0;
    for (size_t i = 0; i < n; i++)
        nq += an[i]->n_sets * SL_SYNTH_NCOMP;
    sl_report_floor *rf = calloc(n, sizeof *rf);
    sl_report_quality *rq = calloc(nq ? nq : 1, sizeof *rq);
    char (*why)[160] = calloc(nq ? nq : 1, sizeof *why);
    char (*damp)[1024] = calloc(n, sizeof *damp);
    sl_status st = SL_OK;
    if (!rf || !rq || !why || !damp) {
        st = sl_error_set(err, SL_ENOMEM, dir, 0, "out of memory");
        goto done;
    }
    static const char *const comp[SL_SYNTH_NCOMP] = {"H1", "H2", "V"};
    size_t q = 0;
    for (size_t i = 0; i < n && !st; i++) {
        const sl_deliver_meta *fl = &floors[i];
        rf[i] = (sl_report_floor){.id = ids[i], .name = fl->name, .path = fl->path,
                                  .description = fl->description, .elevation_m = fl->elevation_m,
                                  .units = fl->units, .crc32 = fl->crc32,
                                  .size_bytes = fl->size_bytes, .zpa_h_ms2 = an[i]->zpa_h_ms2,
                                  .design = an[i]->design, .note = an[i]->note,
                                  .n_mu_skipped = an[i]->n_mu_skipped,
                                  .design_lo_m = an[i]->design_lo_m,
                                  .design_hi_m = an[i]->design_hi_m,
                                  .design_se_m = an[i]->design_se_m,
                                  .err_est_m = an[i]->err_est_m,
                                  .sets_stop = sl_analysis_stop_name(an[i]->stop),
                                  .scatter = an[i]->scatter,
                                  .dampings = sl_analysis_dampings_text(an[i], damp[i],
                                                                        sizeof damp[i]),
                                  .dampings_min = NAN, .dampings_max = NAN,
                                  .dampings_ok = an[i]->dampings_ok,
                                  .n_failed_motions = an[i]->n_failed_motions,
                                  .sa10_fallback = an[i]->sa10_fallback,
                                  .warnings = fl->warnings ? fl->warnings : "",
                                  .accepted = fl->accepted,
                                  .rock_lookup = an[i]->rock_lookup};
        for (size_t k = 0; k < an[i]->n_dampings; k++) {
            const sl_analysis_damping *dk = &an[i]->dampings[k];
            rf[i].dampings_min = isnan(rf[i].dampings_min) ? dk->set_min
                                                           : fmin(rf[i].dampings_min, dk->set_min);
            rf[i].dampings_max = isnan(rf[i].dampings_max) ? dk->set_max
                                                           : fmax(rf[i].dampings_max, dk->set_max);
        }
        for (size_t s = 0; s < an[i]->n_sets; s++)
            for (int c = 0; c < SL_SYNTH_NCOMP; c++, q++) {
                const sl_synth_check *k = &an[i]->sets[s].check[c];
                snprintf(why[q], sizeof why[q], "%s%s%s%s%s%s%s%s", k->ok_below ? "" : "below ",
                         k->ok_above ? "" : "above ", k->ok_run ? "" : "run_below ",
                         k->ok_d5_75 ? "" : "d5_75 ", k->ok_duration ? "" : "duration ",
                         k->ok_end ? "" : "end_v_d ", k->ok_pga ? "" : "pga ",
                         k->ok_corr ? "" : "correlation");
                rq[q] = (sl_report_quality){.floor = ids[i], .set = (int)s + 1,
                                            .component = comp[c], .pga_g = k->pga_ms2 / SL_G,
                                            .d5_75_s = k->d5_75_s, .min_ratio = k->min_ratio,
                                            .max_ratio = k->max_ratio,
                                            .max_run_below = (int)k->run_below,
                                            .max_corr = k->max_corr,
                                            .v_end_ms = sl_synth_end_residual(k->v_end_ms,
                                                                              k->pgv_ms),
                                            .d_end_m = sl_synth_end_residual(k->d_end_m,
                                                                             k->pgd_m),
                                            .pass = k->pass,
                                            .why = why[q]};
            }
    }
    if (st)
        goto done;
    const sl_design *d0 = an[0]->design;
    char s_sets[1024], s_seed[32], s_mu[96], s_sub[64], s_fs[160], s_synth[160], s_scat[1400],
        s_acc[1024] = "none";
    /* the floors accepted in writing out of line with their building */
    size_t used = 0;
    for (size_t i = 0; i < n && used + 20 < sizeof s_acc; i++)
        if (floors[i].accepted) {
            int w = snprintf(s_acc + used, sizeof s_acc - 20 - used, "%s%s", used ? ", " : "",
                             ids[i]);
            used += w > 0 ? (size_t)w : 0;
        }
    if (used)
        snprintf(s_acc + used, sizeof s_acc - used, " (--accept-floor)");
    /* per floor: the sets it needed and why it stopped */
    used = 0;
    for (size_t i = 0; i < n && used < sizeof s_sets; i++) {
        int w = snprintf(s_sets + used, sizeof s_sets - used, "%s%s: %zu (%s)", i ? "; " : "",
                         ids[i], an[i]->n_sets, sl_analysis_stop_name(an[i]->stop));
        used += w > 0 ? (size_t)w : 0;
    }
    snprintf(s_seed, sizeof s_seed, "%llu", (unsigned long long)o->seed);
    snprintf(s_mu, sizeof s_mu, "%zu values, %g to %g", d0->n, d0->rows[0].mu, d0->rows[d0->n - 1].mu);
    if (o->substeps) /* fixed sub-steps (expert), else the engine's error control */
        snprintf(s_sub, sizeof s_sub, "%u per sample (fixed)", o->substeps);
    else
        snprintf(s_sub, sizeof s_sub, "error-controlled, relative error %g", o->accuracy);
    snprintf(s_fs, sizeof s_fs, "NLTHA %g x mean; ASCE %g x best estimate; cap %g x mean peak "
             "floor displacement",
             d0->fs_nltha, d0->fs_asce, d0->cap_factor);
    snprintf(s_synth, sizeof s_synth, "%g s at %g s, matched at %g %% damping (SRP 3.7.1 checks)",
             SL_SYNTH_DURATION_S, SL_SYNTH_DT_S, 100 * SL_SYNTH_DAMPING);
    /* every floor's own sigma (each floor's by default, docs/run.md (R4)) */
    char s_sig[900] = "";
    used = 0;
    int any = 0;
    for (size_t i = 0; i < n && used < sizeof s_sig; i++) {
        int w = snprintf(s_sig + used, sizeof s_sig - used, "%s%s %.3g (%zu values)",
                         i ? "; " : "", ids[i], an[i]->scatter, an[i]->n_nltha_mu);
        used += w > 0 ? (size_t)w : 0;
        any |= an[i]->scatter > 0;
    }
    if (any)
        snprintf(s_scat, sizeof s_scat, "log standard deviation of the horizontal intensity, "
                 "mean 1, averaged exactly over each set: each set's NLTHA runs at log-spaced "
                 "friction values (%d a decade, every mu / intensity of the average), from "
                 "which its peak on the %zu values of the friction grid is computed; per floor: "
                 "%s", SL_SCATTER_PER_DECADE, d0->n, s_sig);
    else
        snprintf(s_scat, sizeof s_scat, "none: the sets as synthesized");
    const sl_report_setting settings[] = {
        {"motion sets per floor", s_sets}, {"seed", s_seed}, {"friction grid", s_mu},
        {"2-D sub-steps", s_sub}, {"factors", s_fs}, {"synthetic motions", s_synth},
        {"record-to-record intensity scatter", s_scat},
        {"clearance policy", sl_clearance_policy_name(d0->policy)},
        {"accepted floors", s_acc},
        {"units", "displacements in mm; accelerations in g; SI inside"}};
    sl_report rep;
    sl_report_init(&rep);
    rep.version = o->version;
    rep.command_line = o->command_line;
    rep.seed = s_seed;
    rep.created = o->created;
    rep.project = o->project;
    rep.building = o->building;
    rep.n_floors = n;
    rep.floors = rf;
    rep.n_quality = q;
    rep.quality = rq;
    rep.n_settings = sizeof settings / sizeof settings[0];
    rep.settings = settings;
    char wb[4096];
    snprintf(wb, sizeof wb, "%s/%s", dir, SL_DELIVER_WORKBOOK);
    if (!(st = sl_report_check_floors(&rep, err)) && !(st = sl_report_write_csv(&rep, dir, err)) &&
        !(st = sl_report_write_xlsx(&rep, wb, err)) && o->write_motions)
        st = write_motions(dir, n, floors, ids, an, o->seed, err);
done:
    free(rf);
    free(rq);
    free(why);
    free(damp);
    return st;
}

sl_status sl_deliver_inputs_load(sl_deliver_inputs *in, const char *const *args, size_t nargs,
                                 int force, char *warnings, size_t nw, sl_error *err)
{
    sl_status st = SL_OK;
    if (nw)
        warnings[0] = '\0';
    for (size_t i = 0; i < nargs && !st; i++)
        st = sl_floor_list(args[i], in->paths, &in->n, SL_DELIVER_MAX_FLOORS, err);
    sl_report_floor rf[SL_DELIVER_MAX_FLOORS];
    for (size_t i = 0; i < in->n && !st; i++) {
        if (!(in->floors[i] = sl_floor_load(in->paths[i], err)))
            return err ? err->code : SL_EINVAL;
        sl_error w;
        char zw[600];
        if ((st = sl_floor_check_plausible(in->floors[i], force ? &w : err)) && force) {
            size_t used = strlen(warnings);
            snprintf(warnings + used, nw - used, "%s:%ld: %s; run anyway (--force)\n", w.file,
                     w.line, w.msg);
            char fw[sizeof w.msg + 40];
            snprintf(fw, sizeof fw, "%s; run anyway (--force)", w.msg);
            in->warn[i] = strdup(fw);
            st = in->warn[i] ? SL_OK : sl_error_set(err, SL_ENOMEM, w.file, 0, "out of memory");
        } else if (!st && sl_floor_zpa_warning(in->floors[i], zw, sizeof zw)) {
            size_t used = nw ? strlen(warnings) : 0;
            if (nw)
                snprintf(warnings + used, nw - used, "%s:%ld: %s\n", in->floors[i]->path,
                         in->floors[i]->units_line, zw);
            if (!(in->warn[i] = strdup(zw)))
                st = sl_error_set(err, SL_ENOMEM, in->paths[i], 0, "out of memory");
        }
        in->idp[i] = sl_report_floor_id(in->paths[i], in->ids[i], sizeof in->ids[i]);
        rf[i] = (sl_report_floor){.id = in->idp[i], .name = in->floors[i]->name,
                                  .path = in->paths[i]};
    }
    if (st)
        return st;
    sl_report chk;
    sl_report_init(&chk);
    chk.n_floors = in->n;
    chk.floors = rf;
    return sl_report_check_floors(&chk, err);
}

void sl_deliver_inputs_free(sl_deliver_inputs *in)
{
    for (size_t i = 0; i < in->n; i++) {
        sl_floor_free(in->floors[i]);
        free(in->paths[i]);
        free(in->warn[i]);
    }
    memset(in, 0, sizeof *in);
}
