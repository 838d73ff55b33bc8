/* bench_rock.c - the rocking engine's cost per run against its error
 * (bench_rock.h). */
#include "study/bench_rock.h"

#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <string.h>

#include "core/clock.h"
#include "core/motion_set.h"
#include "core/units.h"
#include "io/floor.h"
#include "rock/rock.h"
#include "study/bench.h"
#include "synth/synth.h"

/* One synthesized set for the bench floor (or RG 1.60). */
static sl_status make_set(sl_bench_rock *b, sl_synth_set *set, sl_error *err)
{
    sl_synth_params sp;
    sl_synth_params_default(&sp);
    sp.psd_report = 0;
    sl_synth_target tgt[SL_SYNTH_NCOMP];
    sl_spectrum *spec[SL_SYNTH_NCOMP] = {NULL};
    sl_error fe;
    sl_floor *fl = sl_floor_load(SL_BENCH_ROCK_FLOOR, &fe);
    sl_status st;
    if (fl) {
        st = sl_synth_targets_floor(fl, 0.0, tgt, err);
        snprintf(b->source, sizeof b->source, "one set synthesized for %s (seed %u)",
                 SL_BENCH_ROCK_FLOOR, SL_BENCH_ROCK_SEED);
    } else {
        st = sl_synth_targets_rg160(SL_BENCH_SYNTH_PGA_G * SL_G, SL_SYNTH_DAMPING, &sp, spec, tgt,
                                    err);
        snprintf(b->source, sizeof b->source,
                 "one set synthesized for RG 1.60 at %.1f g (seed %u; %s not found)",
                 SL_BENCH_SYNTH_PGA_G, SL_BENCH_ROCK_SEED, SL_BENCH_ROCK_FLOOR);
    }
    const size_t n = (size_t)(SL_SYNTH_DURATION_S / SL_SYNTH_DT_S + 0.5) + 1;
    sl_synth *sy = st ? NULL : sl_synth_alloc(n, SL_SYNTH_DT_S, &sp, err);
    if (sy)
        st = sl_synth_make_set(sy, tgt, SL_BENCH_ROCK_SEED, 0, set, err);
    else if (!st)
        st = err ? err->code : SL_ENOMEM;
    sl_synth_free(sy);
    for (int c = 0; c < SL_SYNTH_NCOMP; c++)
        sl_spectrum_free(spec[c]);
    sl_floor_free(fl);
    return st;
}

/* Time, error and sensitivity of one block on a (n samples at dt). */
static sl_status measure(const double *a, size_t n, double dt, unsigned long repeat,
                         sl_bench_rock_case *c, sl_error *err)
{
    const sl_rock_block blk = {c->b_m, c->h_m, -1};
    sl_rock_opts o, oref;
    sl_rock_opts_default(&o);
    sl_rock_opts_default(&oref);
    oref.rtol = SL_BENCH_ROCK_REF_RTOL;
    sl_rock_result r, rr, rp;
    sl_status st = sl_rock_run(&blk, a, NULL, n, dt, 1, 1, &o, &r, err);
    if (!st)
        st = sl_rock_run(&blk, a, NULL, n, dt, 1, 1, &oref, &rr, err);
    if (st)
        return st;
    /* runs per batch: about 0.1 s */
    const size_t per = r.uplifted ? 200 : 20000;
    c->s_per_run = INFINITY;
    for (unsigned long q = 0; q < repeat; q++) {
        const double t0 = sl_clock_s();
        for (size_t k = 0; k < per; k++)
            sl_rock_run(&blk, a, NULL, n, dt, 1, 1, &o, &r, NULL);
        c->s_per_run = fmin(c->s_per_run, (sl_clock_s() - t0) / (double)per);
    }
    c->steps = r.steps;
    c->impacts = r.impacts;
    c->uplifted = r.uplifted;
    c->tipped = r.tipped;
    c->overturned = r.overturned;
    c->peak_over_alpha = r.peak_theta_over_alpha;
    c->err_rel = rr.peak_theta_rad > 0 ? fabs(r.peak_theta_rad / rr.peak_theta_rad - 1)
                                       : fabs(r.peak_theta_rad);
    c->sensitivity = 0;
    const double d[] = {1e-6, -1e-6, 1e-5, -1e-5};
    for (int k = 0; k < 4 && !st; k++) {
        st = sl_rock_run(&blk, a, NULL, n, dt, 1 + d[k], 1, &oref, &rp, err);
        if (rp.tipped != rr.tipped || rp.overturned != rr.overturned)
            c->sensitivity = INFINITY;
        else if (rr.peak_theta_rad > 0)
            c->sensitivity = fmax(c->sensitivity, fabs(rp.peak_theta_rad / rr.peak_theta_rad - 1));
    }
    snprintf(c->name, sizeof c->name, "%s",
             r.overturned ? "overturns" : r.tipped ? "tips" : r.uplifted ? "rocks"
                                                                         : "never uplifts");
    return st;
}

sl_status sl_bench_rock_run(unsigned long repeat, sl_bench_rock *b, sl_error *err)
{
    memset(b, 0, sizeof *b);
    sl_synth_set set;
    memset(&set, 0, sizeof set);
    sl_status st = make_set(b, &set, err);
    if (st)
        return st;
    const sl_motion *m = set.set.h1;
    b->n = m->n;
    b->dt_s = m->dt_s;
    b->pga_ms2 = sl_motion_pga(m);
    const double A = b->pga_ms2 / SL_G;
    const int saved = omp_get_max_threads();
    omp_set_num_threads(1);
    /* 0: never uplifts; 1: the first candidate that rocks without tipping;
     * 2: the first that tips */
    static const double rock_bh[] = {0.6, 0.75, 0.9}, tip_bh[] = {0.25, 0.35, 0.5};
    static const double rock_h[] = {1.0, 1.5, 2.0}, tip_h[] = {0.3, 0.5, 1.0};
    b->c[0].h_m = 1.0;
    b->c[0].b_m = 1.5 * A;
    st = measure(m->acc_ms2, m->n, m->dt_s, repeat, &b->c[0], err);
    for (int q = 0; q < 3 && !st; q++) {
        b->c[1].h_m = rock_h[q];
        b->c[1].b_m = rock_bh[q] * A * rock_h[q];
        st = measure(m->acc_ms2, m->n, m->dt_s, repeat, &b->c[1], err);
        if (b->c[1].uplifted && !b->c[1].tipped)
            break;
    }
    for (int q = 0; q < 3 && !st; q++) {
        b->c[2].h_m = tip_h[q];
        b->c[2].b_m = tip_bh[q] * A * tip_h[q];
        st = measure(m->acc_ms2, m->n, m->dt_s, repeat, &b->c[2], err);
        if (b->c[2].tipped)
            break;
    }
    omp_set_num_threads(saved);
    sl_synth_set_clear(&set);
    return st;
}
