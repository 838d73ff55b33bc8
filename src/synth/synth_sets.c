/* synth_sets.c - whole sets in parallel with retries and the
 * correlation check, record-matching sets, AT2 output (docs/synthesis.md 3.4-3.6). */
#include "synth/synth_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <omp.h>

#include "io/atomic.h"
#include "core/units.h"

/* ------------------------------------------------------------------ */
/* Sets                                                                */
/* ------------------------------------------------------------------ */

/* The slot of component c in an sl_set. */
static sl_motion **set_slot(sl_set *st, sl_synth_comp c)
{
    return c == SL_SYNTH_H1 ? &st->h1 : c == SL_SYNTH_H2 ? &st->h2 : &st->v;
}

sl_motion *sl_synth_set_motion(const sl_synth_set *s, sl_synth_comp c)
{
    if (!s || (unsigned)c >= SL_SYNTH_NCOMP)
        return NULL;
    return *set_slot((sl_set *)&s->set, c);
}

void sl_synth_set_clear(sl_synth_set *set)
{
    if (!set)
        return;
    for (int c = 0; c < SL_SYNTH_NCOMP; c++)
        sl_motion_free(*set_slot(&set->set, (sl_synth_comp)c));
    memset(set, 0, sizeof *set);
}

/* One motion run: set, then iterate until the test passes or the cap. */
typedef struct job {
    size_t set;           /* index into out */
    sl_synth_comp comp;
    unsigned attempt;
    const double *rec;    /* record samples (match), else NULL */
    size_t rec_n;
    double *acc;          /* result, n samples (malloc'd) */
    sl_synth_check check;
    int psd_done;         /* check has the App. B PSD fields */
    const sl_spectrum *tspec; /* the target spectrum (borrowed) */
    sl_status st;
    sl_error err;
} job;

/* D5-75 of n samples of a at the plan's step (sl_motion_d5_75). */
static double d5_75_of(const sl_synth *s, const double *a)
{
    sl_motion tmp = {.path = NULL, .label = NULL, .n = s->n, .dt_s = s->dt, .acc_ms2 = (double *)a};
    return sl_motion_d5_75(&tmp);
}

static void run_job(const sl_synth *s, sl_synth_motion *m, const sl_synth_target *t,
                    uint64_t seed, size_t set_index, job *jb)
{
    sl_error_clear(&jb->err);
    jb->st = jb->rec ? sl_synth_set_record(m, t, jb->rec, jb->rec_n, &jb->err)
                     : sl_synth_set_random(m, t, seed, set_index, jb->comp, jb->attempt,
                                           &jb->err);
    /* Stagnation: an attempt whose best iterate has not improved for
     * SYNTH_STALL iterations is given up (the next attempt, with new
     * phases, is cheaper than the rest of the cap: CPU time of 20 RG 1.60
     * sets 3.6 s without, 3.1-3.3 s with 6-8; docs/synthesis.md 8). */
    /* D5-75 at the end of the coarse phase: an attempt (not the last, not a
     * record match) whose best coarse iterate already fails the D5-75 check
     * is given up there instead of after its full-accuracy iterations. The
     * strong-motion duration is set by the first corrections and moves
     * little afterwards: on floor and RG 1.60 targets (210 sets), 126 of
     * 886 attempts left the coarse phase below 6 s and 8 of them ended at
     * or above it (none from below 5 s); docs/synthesis.md 3.4. */
    const int last = jb->rec || jb->attempt + 1 >= s->p.max_attempts;
    while (!jb->st && !sl_synth_test(m) && sl_synth_iterations(m) < s->p.max_iter &&
           sl_synth_iterations(m) < m->best_iter + SYNTH_STALL) {
        const int was_coarse = m->coarse;
        jb->st = sl_synth_iterate(m, &jb->err);
        if (!jb->st && was_coarse && !m->coarse && !last &&
            d5_75_of(s, sl_synth_acc(m)) < s->p.min_d5_75_s)
            break;
    }
    /* An attempt given up in the coarse phase is redone, unless it is the
     * last: then its best iterate gets the full-accuracy spectrum, so that
     * what is reported is checked on it (a redone attempt's checks only
     * decide the redo, and a coarse failure is a failure either way). */
    if (!jb->st && m->coarse && (jb->rec || jb->attempt + 1 >= s->p.max_attempts))
        jb->st = sl_synth_end_coarse(m, &jb->err);
    if (jb->st)
        return;
    /* The App. B PSD (an FFT planned for each window length) is computed
     * here only when it decides a redo (psd_frac > 0); otherwise collect()
     * computes it for the motions kept. */
    sl_synth_check_motion_psd(m, &jb->check, s->p.psd_frac > 0);
    jb->psd_done = s->p.psd_frac > 0;
    jb->tspec = t->spec;
    jb->check.corr_record = jb->check.peaks_record = NAN;
    if (jb->rec) {
        jb->check.corr_record = sl_synth_corr(sl_synth_acc(m), jb->rec, jb->rec_n);
        jb->check.peaks_record =
            (double)sl_realism_peaks_above(jb->rec, jb->rec_n, SL_REALISM_PEAK_FRAC);
    }
    if (!jb->acc)
        jb->acc = malloc(s->n * sizeof *jb->acc);
    if (!jb->acc) {
        jb->st = sl_error_set(&jb->err, SL_ENOMEM, NULL, 0, "synth: out of memory");
        return;
    }
    memcpy(jb->acc, sl_synth_acc(m), s->n * sizeof *jb->acc);
}

/* Per-thread motion workspaces kept across the rounds of one call (their
 * spectrum and FFTW plans are made once, not once per round). */
typedef struct workspaces {
    sl_synth_motion **m;
    size_t n;
} workspaces;

static void workspaces_free(workspaces *w)
{
    for (size_t i = 0; i < w->n; i++)
        sl_synth_motion_free(w->m[i]);
    free(w->m);
    w->m = NULL;
    w->n = 0;
}

/* Run jobs[idx[0..nidx-1]] in parallel; each thread has its own workspace
 * (ws->m[thread], made on first use). Returns the first failure in index
 * order (err filled). */
static sl_status run_jobs(const sl_synth *s, const sl_synth_target tgt[SL_SYNTH_NCOMP],
                          uint64_t seed, size_t first_set, job *jobs, const size_t *idx,
                          size_t nidx, size_t *done, size_t total, sl_synth_progress progress,
                          void *ctx, workspaces *ws, sl_error *err)
{
    long long nj = (long long)nidx;
#pragma omp parallel
    {
        sl_error e;
        size_t tid = (size_t)omp_get_thread_num();
        sl_synth_motion *own = NULL, **slot = tid < ws->n ? &ws->m[tid] : &own;
        if (!*slot)
            *slot = sl_synth_motion_alloc(s, &e);
        sl_synth_motion *m = *slot;
#pragma omp for schedule(dynamic, 1)
        for (long long q = 0; q < nj; q++) {
            job *jb = &jobs[idx[q]];
            if (!m) {
                jb->st = sl_error_set(&jb->err, SL_ENOMEM, NULL, 0, "synth: out of memory");
                continue;
            }
            run_job(s, m, &tgt[jb->comp], seed, first_set + jb->set, jb);
#pragma omp critical(sl_synth_progress)
            {
                (*done)++;
                if (progress)
                    progress(ctx, *done, total);
            }
        }
        sl_synth_motion_free(own);
    }
    for (size_t q = 0; q < nidx; q++) {
        job *jb = &jobs[idx[q]];
        if (jb->st)
            return sl_error_set(err, jb->st, NULL, 0, "%s", jb->err.msg);
    }
    return SL_OK;
}

static const int synth_pairs[SL_SYNTH_NPAIR][2] = {
    {SL_SYNTH_H1, SL_SYNTH_H2}, {SL_SYNTH_H1, SL_SYNTH_V}, {SL_SYNTH_H2, SL_SYNTH_V}};

/* Correlations of set `k` (jobs k*3 + c); returns the pair with the largest
 * |rho| above the limit, or -1. */
static int set_corr(const sl_synth *s, job *jb3, double corr[SL_SYNTH_NPAIR])
{
    int worst = -1;
    double worst_r = s->p.max_corr;
    for (int q = 0; q < SL_SYNTH_NPAIR; q++) {
        job *a = &jb3[synth_pairs[q][0]], *b = &jb3[synth_pairs[q][1]];
        if (!a->acc || !b->acc) {
            corr[q] = NAN;
            continue;
        }
        size_t n = s->n;
        if (a->rec && b->rec)
            n = a->rec_n < b->rec_n ? a->rec_n : b->rec_n;
        corr[q] = sl_synth_corr(a->acc, b->acc, n);
        if (fabs(corr[q]) > worst_r) {
            worst_r = fabs(corr[q]);
            worst = q;
        }
    }
    return worst;
}

/* Fill out[k] from the jobs (motions copied into sl_motion). */
static sl_status collect(const sl_synth *s, job *jobs, size_t count, const char *prefix,
                         size_t first_set, sl_synth_set *out, sl_error *err)
{
    /* The App. B PSD of the motions kept, where run_job left it out. */
    long long nj = (long long)(count * SL_SYNTH_NCOMP);
#pragma omp parallel for schedule(dynamic, 1)
    for (long long i = 0; i < nj; i++) {
        job *jb = &jobs[i];
        if (jb->acc && !jb->psd_done && !jb->st && s->p.psd_report) {
            sl_synth_check_psd(jb->acc, s->n, s->dt, jb->tspec, s->p.psd_frac, &jb->check);
            jb->psd_done = 1;
        }
    }
    int all_pass = 1;
    for (size_t k = 0; k < count; k++) {
        sl_synth_set *o = &out[k];
        memset(o, 0, sizeof *o);
        job *jb3 = &jobs[k * SL_SYNTH_NCOMP];
        set_corr(s, jb3, o->corr);
        o->pass = 1;
        for (int c = 0; c < SL_SYNTH_NCOMP; c++) {
            job *jb = &jb3[c];
            if (!jb->acc)
                continue;
            char label[64];
            if (prefix)
                snprintf(label, sizeof label, "%s_%s", prefix, sl_synth_comp_name((sl_synth_comp)c));
            else
                snprintf(label, sizeof label, "set%02zu_%s", first_set + k + 1,
                         sl_synth_comp_name((sl_synth_comp)c));
            sl_motion **slot = set_slot(&o->set, (sl_synth_comp)c);
            *slot = sl_motion_from_array(jb->acc, s->n, s->dt, label);
            if (!*slot) {
                for (size_t q = 0; q <= k; q++)
                    sl_synth_set_clear(&out[q]);
                return sl_error_set(err, SL_ENOMEM, NULL, 0, "synth: out of memory");
            }
            o->check[c] = jb->check;
            double mc = NAN;
            for (int q = 0; q < SL_SYNTH_NPAIR; q++)
                if ((synth_pairs[q][0] == c || synth_pairs[q][1] == c) && !isnan(o->corr[q]))
                    mc = isnan(mc) || fabs(o->corr[q]) > mc ? fabs(o->corr[q]) : mc;
            o->check[c].max_corr = mc;
            o->check[c].ok_corr = isnan(mc) || mc <= s->p.max_corr;
            o->check[c].pass = o->check[c].pass && o->check[c].ok_corr;
            o->pass = o->pass && o->check[c].pass;
        }
        all_pass = all_pass && o->pass;
    }
    return all_pass ? SL_OK : SL_ENOCONV;
}

static void free_jobs(job *jobs, size_t nj)
{
    if (!jobs)
        return;
    for (size_t i = 0; i < nj; i++)
        free(jobs[i].acc);
    free(jobs);
}

sl_status sl_synth_make_sets(const sl_synth *s, const sl_synth_target tgt[SL_SYNTH_NCOMP],
                             uint64_t seed, size_t first_set, size_t count,
                             sl_synth_set *out, sl_synth_progress progress, void *ctx,
                             sl_error *err)
{
    if (count == 0)
        return SL_OK;
    for (int c = 0; c < SL_SYNTH_NCOMP; c++)
        if (sl_synth_check_target(&tgt[c], err))
            return SL_EINVAL;
    size_t nj = count * SL_SYNTH_NCOMP;
    job *jobs = calloc(nj, sizeof *jobs);
    size_t *idx = malloc(nj * sizeof *idx);
    if (!jobs || !idx) {
        free(jobs);
        free(idx);
        return sl_error_set(err, SL_ENOMEM, NULL, 0, "synth: out of memory");
    }
    for (size_t i = 0; i < nj; i++) {
        jobs[i].set = i / SL_SYNTH_NCOMP;
        jobs[i].comp = (sl_synth_comp)(i % SL_SYNTH_NCOMP);
        idx[i] = i;
    }
    size_t done = 0, total = nj, nidx = nj;
    sl_status st = SL_OK;
    workspaces ws = {calloc((size_t)omp_get_max_threads(), sizeof(sl_synth_motion *)),
                     (size_t)omp_get_max_threads()};
    if (!ws.m)
        ws.n = 0; /* every thread then makes its own */
    /* Rounds: run the pending jobs, then redo (next attempt) every component
     * that failed its spectral or D5-75 checks and the later component of each set's
     * worst correlated pair, while attempts remain. Every decision depends
     * only on results, so the rounds are the same for any thread count. */
    while (nidx > 0) {
        st = run_jobs(s, tgt, seed, first_set, jobs, idx, nidx, &done, total, progress, ctx,
                      &ws, err);
        if (st)
            break;
        nidx = 0;
        for (size_t k = 0; k < count; k++) {
            job *jb3 = &jobs[k * SL_SYNTH_NCOMP];
            int redo[SL_SYNTH_NCOMP] = {0, 0, 0};
            for (int c = 0; c < SL_SYNTH_NCOMP; c++) {
                const sl_synth_check *ck = &jb3[c].check;
                redo[c] = !(ck->ok_below && ck->ok_above && ck->ok_run && ck->ok_d5_75 &&
                            ck->ok_pga && ck->ok_peaks && ck->ok_psd);
            }
            double corr[SL_SYNTH_NPAIR];
            int q = set_corr(s, jb3, corr);
            if (q >= 0 && !redo[synth_pairs[q][0]])
                redo[synth_pairs[q][1]] = 1;
            for (int c = 0; c < SL_SYNTH_NCOMP; c++)
                if (redo[c] && jb3[c].attempt + 1 < s->p.max_attempts) {
                    jb3[c].attempt++;
                    idx[nidx++] = k * SL_SYNTH_NCOMP + (size_t)c;
                }
        }
        total += nidx;
    }
    workspaces_free(&ws);
    if (!st)
        st = collect(s, jobs, count, NULL, first_set, out, err);
    free_jobs(jobs, nj);
    free(idx);
    return st;
}

sl_status sl_synth_make_set(const sl_synth *s, const sl_synth_target tgt[SL_SYNTH_NCOMP],
                            uint64_t seed, size_t set, sl_synth_set *out, sl_error *err)
{
    return sl_synth_make_sets(s, tgt, seed, set, 1, out, NULL, NULL, err);
}

sl_status sl_synth_match_set(const sl_synth *s, const sl_synth_target tgt[SL_SYNTH_NCOMP],
                             const sl_motion *const rec[SL_SYNTH_NCOMP], sl_synth_set *out,
                             sl_error *err)
{
    job jobs[SL_SYNTH_NCOMP];
    size_t idx[SL_SYNTH_NCOMP], nidx = 0;
    memset(jobs, 0, sizeof jobs);
    for (int c = 0; c < SL_SYNTH_NCOMP; c++) {
        jobs[c].comp = (sl_synth_comp)c;
        if (!rec[c])
            continue;
        if (fabs(rec[c]->dt_s - s->dt) > 1e-9 * s->dt || rec[c]->n > s->n)
            return sl_error_set(err, SL_EINVAL, rec[c]->path, 0,
                                "synth: record (%zu samples at %g s) does not fit the plan "
                                "(%zu at %g s)",
                                rec[c]->n, rec[c]->dt_s, s->n, s->dt);
        if (sl_synth_check_target(&tgt[c], err))
            return SL_EINVAL;
        jobs[c].rec = rec[c]->acc_ms2;
        jobs[c].rec_n = rec[c]->n;
        idx[nidx++] = (size_t)c;
    }
    if (nidx == 0)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "synth: no record to match");
    size_t done = 0;
    workspaces ws = {NULL, 0};
    sl_status st = run_jobs(s, tgt, 0, 0, jobs, idx, nidx, &done, nidx, NULL, NULL, &ws, err);
    if (!st)
        st = collect(s, jobs, 1, "match", 0, out, err);
    for (int c = 0; c < SL_SYNTH_NCOMP; c++)
        free(jobs[c].acc);
    return st;
}

sl_status sl_synth_write_at2(const char *path, const sl_motion *m, const char *title,
                             sl_error *err)
{
    sl_atomic *a = sl_atomic_open(path, err);
    if (!a)
        return err ? err->code : SL_EIO;
    FILE *f = sl_atomic_file(a);
    fprintf(f, "SEISLIDE SYNTHETIC MOTION\n%s\nACCELERATION TIME SERIES IN UNITS OF G\n",
            title && *title ? title : (m->label ? m->label : ""));
    fprintf(f, "NPTS= %zu, DT= %.10g SEC\n", m->n, m->dt_s);
    /* Values per line in the PEER layout. */
    enum { PER_LINE = 5 };
    for (size_t i = 0; i < m->n; i++) {
        fprintf(f, " %16.9E", m->acc_ms2[i] / SL_G);
        if ((i + 1) % PER_LINE == 0 || i + 1 == m->n)
            fputc('\n', f);
    }
    return sl_atomic_commit(a, err);
}
