/* test_threads.c - the library called from two POSIX threads at once
 * (seislide.h, "Threads"): synthesized sets, their PSD checks (FFTW plans
 * made per call) and multirate spectrum plans (FFTW plans), on record
 * lengths that differ per task so that FFTW's planner is entered from both
 * threads at the same time; the targets are shared read-only. Each task's
 * digest from the two threads equals, bit for bit, the one of the same task
 * run alone. Without the planner lock (core/fftw_safe.c) the test crashed
 * or differed in 10 runs of 10 (1200 PSD checks a task; 400 gave 5 of 6). */
#include <omp.h>
#include <pthread.h>

#include "harness.h"
#include "core/units.h"
#include "signal/realism.h"
#include "signal/rg160.h"
#include "signal/spectrum.h"
#include "synth/synth.h"

#define NTASK 6
#define DT 0.005

static sl_spectrum *g_sp[SL_SYNTH_NCOMP];
static sl_synth_target g_tgt[SL_SYNTH_NCOMP];

typedef struct task {
    double digest;   /* sums of the motions, PSD ratios and spectra */
    sl_status st;
    char msg[1024];
} task;

/* One task: a set, its PSD checks and a multirate spectrum of H1. */
static void run_task(size_t k, task *out)
{
    sl_error e;
    sl_error_clear(&e);
    const size_t n = 2400 + 97 * k;
    double d = 0;
    sl_synth *s = sl_synth_alloc(n, DT, NULL, &e);
    sl_synth_set set;
    memset(&set, 0, sizeof set);
    sl_status st = s ? sl_synth_make_set(s, g_tgt, 11 + k, 0, &set, &e) : e.code;
    if (st == SL_ENOCONV)
        st = SL_OK; /* a set that misses a check is still a deterministic result */
    for (int c = 0; st == SL_OK && c < SL_SYNTH_NCOMP; c++) {
        const sl_motion *m = sl_synth_set_motion(&set, (sl_synth_comp)c);
        for (size_t i = 0; i < m->n; i++)
            d += m->acc_ms2[i];
        sl_psd_check pc;
        st = sl_psd_check_motion(m->acc_ms2, m->n, m->dt_s, g_tgt[c].spec, 0, SL_PSD_FMIN_HZ,
                                 SL_PSD_FMAX_HZ, &pc, &e);
        d += pc.min_ratio;
    }
    /* the planner entered many times: PSD checks of the first m samples of
     * H1, m different each time (a plan per length) */
    const sl_motion *h1 = st == SL_OK ? sl_synth_set_motion(&set, SL_SYNTH_H1) : NULL;
    for (size_t j = 0; st == SL_OK && j < 1200; j++) {
        sl_psd_check pc;
        st = sl_psd_check_motion(h1->acc_ms2, 1000 + (3 * j + k) % 1300, DT, g_tgt[0].spec, 0,
                                 SL_PSD_FMIN_HZ, SL_PSD_FMAX_HZ, &pc, &e);
        d += pc.min_ratio;
    }
    size_t nf = 0;
    double *f = sl_spectrum_grid(0.2, 40.0, 40, &nf);
    sl_spectrum_plan *p = st == SL_OK && f
                              ? sl_spectrum_plan_alloc(n, DT, f, nf, 0.05, NULL, 20.0, &e)
                              : NULL;
    double *psa = f ? malloc(nf * sizeof *psa) : NULL;
    if (st == SL_OK && (!p || !psa))
        st = p ? SL_ENOMEM : e.code;
    if (st == SL_OK)
        st = sl_spectrum_plan_compute(p, sl_synth_set_motion(&set, SL_SYNTH_H1)->acc_ms2, psa,
                                      NULL, NULL, &e);
    for (size_t j = 0; st == SL_OK && j < nf; j++)
        d += psa[j];
    free(psa);
    free(f);
    sl_spectrum_plan_free(p);
    sl_synth_set_clear(&set);
    sl_synth_free(s);
    out->digest = d;
    out->st = st;
    snprintf(out->msg, sizeof out->msg, "%s", st ? e.msg : "");
}

typedef struct worker {
    size_t first;  /* tasks first, first + 2, ... */
    task *res;
} worker;

static void *work(void *arg)
{
    worker *w = arg;
    omp_set_num_threads(1); /* two threads in all on a two-core machine */
    for (size_t k = w->first; k < NTASK; k += 2)
        run_task(k, &w->res[k]);
    return NULL;
}

static void test_two_threads_equal_sequential(void)
{
    task seq[NTASK], par[NTASK];
    omp_set_num_threads(1);
    for (size_t k = 0; k < NTASK; k++) {
        run_task(k, &seq[k]);
        CHECK(seq[k].st == SL_OK, "task %zu alone: status %d %s", k, seq[k].st, seq[k].msg);
    }
    worker w[2] = {{0, par}, {1, par}};
    pthread_t th[2];
    int made[2];
    for (int i = 0; i < 2; i++)
        made[i] = pthread_create(&th[i], NULL, work, &w[i]) == 0;
    for (int i = 0; i < 2; i++)
        if (made[i])
            pthread_join(th[i], NULL);
        else
            work(&w[i]);
    CHECK(made[0] && made[1], "pthread_create failed");
    for (size_t k = 0; k < NTASK; k++) {
        CHECK(par[k].st == SL_OK, "task %zu in a thread: status %d %s", k, par[k].st, par[k].msg);
        CHECK(par[k].digest == seq[k].digest && isfinite(seq[k].digest),
              "task %zu: %.17g in a thread, %.17g alone", k, par[k].digest, seq[k].digest);
    }
}

int main(void)
{
    sl_error e;
    if (sl_synth_targets_rg160(0.3 * SL_G, SL_SYNTH_DAMPING, NULL, g_sp, g_tgt, &e)) {
        fprintf(stderr, "targets: %s\n", e.msg);
        return 1;
    }
    RUN(test_two_threads_equal_sequential);
    for (int c = 0; c < SL_SYNTH_NCOMP; c++)
        sl_spectrum_free(g_sp[c]);
    return HARNESS_END("threads");
}
