/* synth_sets.c - whole sets in parallel (a flow of OpenMP tasks) with
 * retries and the correlation check, record-matching sets, AT2 output (docs/synthesis.md 3.4-3.6). */
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

/* Per-thread motion workspaces kept across the attempts of one call (their
 * spectrum and FFTW plans are made once per thread, not once per task). */
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

/* The App. B PSD of the motions of one set kept, where run_job left it out. */
static void set_psd(const sl_synth *s, job *jb3)
{
    for (int c = 0; c < SL_SYNTH_NCOMP; c++) {
        job *jb = &jb3[c];
        if (jb->acc && !jb->psd_done && !jb->st && s->p.psd_report) {
            sl_synth_check_psd(jb->acc, s->n, s->dt, jb->tspec, s->p.psd_frac, &jb->check);
            jb->psd_done = 1;
        }
    }
}

/* Fill *o, set k of the call, from its jobs jb3 (motions copied into
 * sl_motion; o cleared on failure). Returns SL_OK or SL_ENOMEM. */
static sl_status collect_set(const sl_synth *s, job *jb3, size_t k, const char *prefix,
                             size_t first_set, sl_synth_set *o, sl_error *err)
{
    memset(o, 0, sizeof *o);
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
            sl_synth_set_clear(o);
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
    return SL_OK;
}

static void free_jobs(job *jobs, size_t nj)
{
    if (!jobs)
        return;
    for (size_t i = 0; i < nj; i++)
        free(jobs[i].acc);
    free(jobs);
}

/* The redo decisions of one set whose components have all run: every
 * component that failed its spectral, D5-75, PGA, peaks or PSD checks, and
 * the later component of the set's worst correlated pair, while attempts
 * remain (each gets its next attempt). Functions of the set's results only,
 * so the same for any thread count, order or batch split. Returns the
 * number of components to redo, their comps in redo[]. */
static int set_redo(const sl_synth *s, job *jb3, sl_synth_comp redo_c[SL_SYNTH_NCOMP])
{
    int redo[SL_SYNTH_NCOMP] = {0, 0, 0}, nredo = 0;
    for (int c = 0; c < SL_SYNTH_NCOMP; c++) {
        const sl_synth_check *ck = &jb3[c].check;
        redo[c] = !(ck->ok_below && ck->ok_above && ck->ok_run && ck->ok_d5_75 && ck->ok_pga &&
                    ck->ok_peaks && ck->ok_psd);
    }
    double corr[SL_SYNTH_NPAIR];
    int q = set_corr(s, jb3, corr);
    if (q >= 0 && !redo[synth_pairs[q][0]])
        redo[synth_pairs[q][1]] = 1;
    for (int c = 0; c < SL_SYNTH_NCOMP; c++)
        if (redo[c] && jb3[c].attempt + 1 < s->p.max_attempts) {
            jb3[c].attempt++;
            redo_c[nredo++] = (sl_synth_comp)c;
        }
    return nredo;
}

/* One call of sl_synth_make_sets_then as a flow of OpenMP tasks: a task per
 * component attempt; the task that ends the last running component of a set
 * makes the set's redo decisions (set_redo) and spawns its redone
 * components, or, when none is left, fills out[k] and hands the set to
 * `ready`. No thread waits for a round of other sets. */
typedef struct flow {
    const sl_synth *s;
    const sl_synth_target *tgt;
    uint64_t seed;
    size_t first_set, count;
    job *jobs;               /* count x SL_SYNTH_NCOMP */
    unsigned *pending;       /* per set: components still running */
    sl_status *set_st;       /* per set: the failure of collect_set or ready */
    sl_error *set_err;
    int *filled;             /* per set: out[k] filled */
    sl_synth_set *out;
    size_t done, total;      /* motion runs finished and planned (progress) */
    sl_synth_progress progress;
    void *ctx;
    sl_synth_ready ready;
    void *ready_ctx;
    workspaces *ws;
    int stop;                /* a failure: no new work is started */
} flow;

static int flow_stopped(flow *f)
{
    int stop;
#pragma omp atomic read
    stop = f->stop;
    return stop;
}

static void flow_fail(flow *f)
{
#pragma omp atomic write
    f->stop = 1;
}

static void flow_job(flow *f, size_t i);

/* Set k has no component running: redo some, or hand it on. */
static void flow_set(flow *f, size_t k)
{
    job *jb3 = &f->jobs[k * SL_SYNTH_NCOMP];
    for (int c = 0; c < SL_SYNTH_NCOMP; c++)
        if (jb3[c].st) {
            flow_fail(f);
            return;
        }
    if (flow_stopped(f))
        return;
    sl_synth_comp redo[SL_SYNTH_NCOMP];
    int nredo = set_redo(f->s, jb3, redo);
    if (nredo > 0) {
        f->pending[k] = (unsigned)nredo; /* visible to the tasks: task creation flushes */
#pragma omp critical(sl_synth_progress)
        f->total += (size_t)nredo;
        /* the last redone component goes on here, at once: a set's redos
         * come before the work queued behind them (the NLTHA of the sets
         * already final), which then fills the flow's end */
        for (int q = 0; q + 1 < nredo; q++) {
            size_t i = k * SL_SYNTH_NCOMP + (size_t)redo[q];
#pragma omp task default(none) firstprivate(f, i) /* f by value: this frame may be gone */
            flow_job(f, i);
        }
        flow_job(f, k * SL_SYNTH_NCOMP + (size_t)redo[nredo - 1]);
        return;
    }
    set_psd(f->s, jb3);
    sl_status st = collect_set(f->s, jb3, k, NULL, f->first_set, &f->out[k], &f->set_err[k]);
    for (int c = 0; c < SL_SYNTH_NCOMP; c++) { /* copied into out[k] (or failed) */
        free(jb3[c].acc);
        jb3[c].acc = NULL;
    }
    f->filled[k] = !st;
    if (!st && f->ready)
        st = f->ready(f->ready_ctx, k, &f->set_err[k]);
    if (st) {
        f->set_st[k] = st;
        flow_fail(f);
    }
}

/* Component attempt jobs[i] on this thread's workspace (made on its first
 * job; a task runs on one thread and reaches no scheduling point while it
 * uses the workspace). */
static void flow_job(flow *f, size_t i)
{
    job *jb = &f->jobs[i];
    const size_t k = jb->set;
    if (flow_stopped(f))
        return;
    size_t tid = (size_t)omp_get_thread_num();
    sl_synth_motion **slot = &f->ws->m[tid < f->ws->n ? tid : 0];
    if (!*slot)
        *slot = sl_synth_motion_alloc(f->s, &jb->err);
    if (!*slot)
        jb->st = sl_error_set(&jb->err, SL_ENOMEM, NULL, 0, "synth: out of memory");
    else
        run_job(f->s, *slot, &f->tgt[jb->comp], f->seed, f->first_set + k, jb);
    if (jb->st)
        flow_fail(f);
    unsigned left;
#pragma omp critical(sl_synth_progress)
    {
        f->done++;
        if (f->progress)
            f->progress(f->ctx, f->done, f->total);
        left = --f->pending[k];
    }
    if (left == 0)
        flow_set(f, k);
}

sl_status sl_synth_make_sets_then(const sl_synth *s, const sl_synth_target tgt[SL_SYNTH_NCOMP],
                                  uint64_t seed, size_t first_set, size_t count,
                                  sl_synth_set *out, sl_synth_progress progress, void *ctx,
                                  sl_synth_ready ready, void *ready_ctx, sl_error *err)
{
    if (count == 0)
        return SL_OK;
    for (int c = 0; c < SL_SYNTH_NCOMP; c++)
        if (sl_synth_check_target(&tgt[c], err))
            return SL_EINVAL;
    const size_t nj = count * SL_SYNTH_NCOMP, nth = (size_t)omp_get_max_threads();
    flow f = {.s = s, .tgt = tgt, .seed = seed, .first_set = first_set, .count = count,
              .out = out, .total = nj, .progress = progress, .ctx = ctx, .ready = ready,
              .ready_ctx = ready_ctx};
    workspaces ws = {calloc(nth, sizeof(sl_synth_motion *)), nth};
    f.ws = &ws;
    f.jobs = calloc(nj, sizeof *f.jobs);
    f.pending = malloc(count * sizeof *f.pending);
    f.set_st = calloc(count, sizeof *f.set_st);
    f.set_err = calloc(count, sizeof *f.set_err);
    f.filled = calloc(count, sizeof *f.filled);
    sl_status st = SL_OK;
    if (!ws.m || !f.jobs || !f.pending || !f.set_st || !f.set_err || !f.filled) {
        st = sl_error_set(err, SL_ENOMEM, NULL, 0, "synth: out of memory");
        goto done;
    }
    for (size_t i = 0; i < nj; i++) {
        f.jobs[i].set = i / SL_SYNTH_NCOMP;
        f.jobs[i].comp = (sl_synth_comp)(i % SL_SYNTH_NCOMP);
    }
    for (size_t k = 0; k < count; k++)
        f.pending[k] = SL_SYNTH_NCOMP;
    /* the first attempts in set order; the rest is spawned as sets decide */
#pragma omp parallel
#pragma omp single
    for (size_t i = 0; i < nj; i++) {
#pragma omp task default(none) shared(f) firstprivate(i) /* f outlives the region */
        flow_job(&f, i);
    }
    /* the first failure in job order, then in set order */
    for (size_t i = 0; i < nj && !st; i++)
        if (f.jobs[i].st)
            st = sl_error_set(err, f.jobs[i].st, NULL, 0, "%s", f.jobs[i].err.msg);
    for (size_t k = 0; k < count && !st; k++)
        if (f.set_st[k]) {
            st = f.set_st[k];
            if (err)
                *err = f.set_err[k];
        }
    for (size_t k = 0; k < count && !st; k++)
        if (!out[k].pass)
            st = SL_ENOCONV;
done:
    if (st && st != SL_ENOCONV && f.filled)
        for (size_t k = 0; k < count; k++)
            if (f.filled[k])
                sl_synth_set_clear(&out[k]);
    workspaces_free(&ws);
    free_jobs(f.jobs, f.jobs ? nj : 0);
    free(f.pending);
    free(f.set_st);
    free(f.set_err);
    free(f.filled);
    return st;
}

sl_status sl_synth_make_sets(const sl_synth *s, const sl_synth_target tgt[SL_SYNTH_NCOMP],
                             uint64_t seed, size_t first_set, size_t count,
                             sl_synth_set *out, sl_synth_progress progress, void *ctx,
                             sl_error *err)
{
    return sl_synth_make_sets_then(s, tgt, seed, first_set, count, out, progress, ctx, NULL,
                                   NULL, err);
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
    if (!st) {
        set_psd(s, jobs);
        st = collect_set(s, jobs, 0, "match", 0, out, err);
    }
    if (!st && !out->pass)
        st = SL_ENOCONV;
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
