/* test_analysis.c - the per-floor study (analysis.h): seed independence from
 * the floor's name, results independent of batch sizes and threads, the
 * stopping rule, and the stated standard error of the design value against
 * its scatter over independent seeds (brute force, light version; the heavy
 * one is tests/converge-bruteforce.sh). Runs from the repository root. */
#include <omp.h>

#include <math.h>

#include "analysis.h"
#include "core/clock.h"
#include "harness.h"
#include "signal/spectrum.h"
#include "slide/slide.h"

#define ROOF "floors/04-roof36.ini"

static const double mu3[] = {0.1, 0.3, 0.5};

/* Copy src to dst replacing the line that starts with `key` by `line`
 * (appended after [floor] when key is absent from src). */
static int copy_with(const char *src, const char *dst, const char *key, const char *line)
{
    FILE *in = fopen(src, "r"), *out = fopen(dst, "w");
    if (!in || !out) {
        if (in)
            fclose(in);
        if (out)
            fclose(out);
        return -1;
    }
    char buf[1024];
    int done = 0;
    while (fgets(buf, sizeof buf, in)) {
        if (!done && key && !strncmp(buf, key, strlen(key))) {
            fprintf(out, "%s\n", line);
            done = 1;
        } else {
            fputs(buf, out);
            if (!done && !strncmp(buf, "[floor]", 7) && key && !strcmp(key, "seed")) {
                fprintf(out, "%s\n", line);
                done = 1;
            }
        }
    }
    fclose(in);
    fclose(out);
    return done ? 0 : -1;
}

static sl_floor *load(const char *path)
{
    sl_error e;
    sl_floor *fl = sl_floor_load(path, &e);
    char buf[2200];
    CHECK(fl != NULL, "%s", sl_error_format(&e, buf, sizeof buf));
    return fl;
}

/* A floor's seed depends on its numbers (or its `seed =`), never on its name
 * or description; a changed number changes it. */
static void test_seed_from_content(void)
{
    char tmp[] = "/tmp/sl_test_analysisXXXXXX";
    if (!mkdtemp(tmp))
        SKIP("no temporary folder");
    char p1[300], p2[300], p3[300], p4[300];
    snprintf(p1, sizeof p1, "%s/renamed.ini", tmp);
    snprintf(p2, sizeof p2, "%s/number.ini", tmp);
    snprintf(p3, sizeof p3, "%s/seed.ini", tmp);
    snprintf(p4, sizeof p4, "%s/seed-number.ini", tmp);
    CHECK(!copy_with(ROOF, p1, "name", "name = Something else entirely"), "copy 1");
    /* the ZPA of [h1] changed in its last digit */
    CHECK(!copy_with(ROOF, p2, "zpa", "zpa = 0.6300001"), "copy 2");
    CHECK(!copy_with(ROOF, p3, "seed", "seed = 77"), "copy 3");
    CHECK(!copy_with(p2, p4, "seed", "seed = 77"), "copy 4");
    sl_floor *a = load(ROOF), *b = load(p1), *c = load(p2), *d = load(p3), *e = load(p4);
    if (a && b && c && d && e) {
        CHECK(strcmp(a->name, b->name) != 0, "renamed");
        CHECK(sl_analysis_floor_seed(1, a) == sl_analysis_floor_seed(1, b), "name changes seed");
        CHECK(sl_analysis_floor_seed(1, a) != sl_analysis_floor_seed(1, c), "number ignored");
        CHECK(sl_analysis_floor_seed(1, a) != sl_analysis_floor_seed(2, a), "run seed ignored");
        CHECK(d->has_seed && d->seed == 77, "seed key %d %llu", d->has_seed,
              (unsigned long long)d->seed);
        CHECK(sl_analysis_floor_seed(1, d) == sl_analysis_floor_seed(1, e),
              "explicit seed: numbers must not matter");
        CHECK(sl_analysis_floor_seed(1, d) != sl_analysis_floor_seed(1, a), "explicit seed unused");
        CHECK(sl_analysis_floor_seed(1, d) != sl_analysis_floor_seed(3, d), "explicit: run seed");
        /* every number counts: one spectral value of H1, one frequency of V */
        uint64_t s0 = sl_analysis_floor_seed(1, a);
        a->comp[SL_FLOOR_H1].spec[0].sa_ms2[3] *= 1.0 + 1e-12;
        CHECK(sl_analysis_floor_seed(1, a) != s0, "a spectral value is ignored");
        a->comp[SL_FLOOR_H1].spec[0].sa_ms2[3] /= 1.0 + 1e-12;
        a->comp[SL_FLOOR_V].spec[0].f_hz[1] *= 1.0 + 1e-12;
        CHECK(sl_analysis_floor_seed(1, a) != s0, "a frequency is ignored");
    }
    sl_floor_free(a);
    sl_floor_free(b);
    sl_floor_free(c);
    sl_floor_free(d);
    sl_floor_free(e);
    remove(p1);
    remove(p2);
    remove(p3);
    remove(p4);
    rmdir(tmp);
}

static int same_rows(const sl_analysis *x, const sl_analysis *y)
{
    if (x->design->n != y->design->n || x->n_sets != y->n_sets)
        return 0;
    for (size_t k = 0; k < x->design->n; k++) {
        const sl_design_row *p = &x->design->rows[k], *q = &y->design->rows[k];
        if (p->nltha_mean_m != q->nltha_mean_m || p->nltha_sd_m != q->nltha_sd_m ||
            p->clearance_m != q->clearance_m || x->conv[k].design_se_m != y->conv[k].design_se_m ||
            x->conv[k].design_lo_m != y->conv[k].design_lo_m)
            return 0;
    }
    return 1;
}

/* Set i is always the same motions: an adaptive run that ends at 5 sets in
 * batches of 2, 4, 5 equals a fixed run of 5, bit for bit, and so does the
 * fixed run on one thread. */
static void test_batches_and_threads(void)
{
    sl_floor *fl = load(ROOF);
    if (!fl)
        return;
    sl_analysis_opts o;
    sl_analysis_opts_default(&o);
    o.mu = mu3;
    o.n_mu = 3;
    o.first_batch = 2;
    o.min_batch = 2;
    o.plan_growth = 2; /* 2, 4, 5 */
    o.max_sets = 5;
    o.rel_se = 1e-9; /* never converges: runs to max_sets */
    o.abs_se_m = 0;
    o.boot_resamples = 200;
    sl_error err;
    sl_analysis *ad = sl_analysis_run(fl, &o, &err);
    o.n_sets = 5;
    double t_fx = sl_clock_s();
    sl_analysis *fx = sl_analysis_run(fl, &o, &err);
    t_fx = sl_clock_s() - t_fx;
    int saved = omp_get_max_threads();
    omp_set_num_threads(1);
    sl_analysis *one = sl_analysis_run(fl, &o, &err);
    omp_set_num_threads(saved);
    CHECK(ad && fx && one, "runs");
    if (ad && fx && one) {
        CHECK(ad->stop == SL_ANALYSIS_STOP_MAX_SETS && ad->n_sets == 5 && ad->n_batches == 3,
              "adaptive: stop %s, %zu sets, %zu batches", sl_analysis_stop_name(ad->stop),
              ad->n_sets, ad->n_batches);
        CHECK(strstr(ad->note, "not converged") != NULL, "note '%s'", ad->note);
        CHECK(fx->stop == SL_ANALYSIS_STOP_FIXED && fx->n_batches == 1, "fixed");
        CHECK(same_rows(ad, fx), "batches change the result");
        CHECK(same_rows(fx, one), "threads change the result");
        /* every other damping of the file (2 %, 10 % per component), the set
         * mean over all 5 sets whatever the batches (2, 4, 5): the adaptive
         * run equals the fixed one; the mean of S/T lies between the sets'
         * own lowest and highest; the verdict is the limits' */
        CHECK(ad->n_dampings == 6 && fx->n_dampings == 6, "dampings %zu %zu", ad->n_dampings,
              fx->n_dampings);
        for (size_t q = 0; q < fx->n_dampings && q < ad->n_dampings; q++) {
            const sl_analysis_damping *x = &ad->dampings[q], *y = &fx->dampings[q];
            CHECK(x->set_min == y->set_min && x->set_max == y->set_max && x->ok == y->ok,
                  "damping %zu: adaptive %g-%g, fixed %g-%g", q, x->set_min, x->set_max,
                  y->set_min, y->set_max);
            CHECK((int)y->comp == (int)(q / 2) && y->damping == (q % 2 ? 0.10 : 0.02),
                  "damping %zu: comp %d, %g", q, (int)y->comp, y->damping);
            double lo = INFINITY, hi = -INFINITY;
            for (size_t k = 0; k < fx->n_sets; k++) {
                const sl_synth_other *ot = &fx->sets[k].check[y->comp].other[q % 2];
                lo = fmin(lo, ot->min_ratio);
                hi = fmax(hi, ot->max_ratio);
            }
            CHECK(lo <= y->set_min && y->set_min <= y->set_max && y->set_max <= hi &&
                      y->set_min > 0.5 && y->set_max < 2,
                  "damping %zu: set mean %g-%g, motions %g-%g", q, y->set_min, y->set_max, lo, hi);
            CHECK(y->ok == (y->set_min >= fx->damping_lim_lo && y->set_max <= fx->damping_lim_hi),
                  "damping %zu: verdict", q);
        }
        CHECK(fx->damping_lim_lo == 0.9 && fx->damping_lim_hi == 1.3, "limits %g %g",
              fx->damping_lim_lo, fx->damping_lim_hi);
        /* the extra synthesis attempts the run reports: every motion's own
         * attempt number, summed; the same over the batches (2, 4, 5) */
        size_t extra = 0;
        for (size_t k = 0; k < fx->n_sets; k++)
            for (int c = 0; c < SL_SYNTH_NCOMP; c++)
                extra += fx->sets[k].check[c].attempt;
        /* the App. B PSD (reported only) is not computed by a run */
        CHECK(isnan(fx->sets[0].check[0].psd_min_ratio) && fx->sets[0].check[0].ok_psd,
              "run: PSD %g", fx->sets[0].check[0].psd_min_ratio);
        CHECK(fx->n_extra_attempts == extra && ad->n_extra_attempts == extra,
              "extra attempts: fixed %zu, adaptive %zu, the motions' %zu", fx->n_extra_attempts,
              ad->n_extra_attempts, extra);
        /* thread time: at most the run's wall time x threads */
        CHECK(fx->time_checks_s >= 0 && fx->time_checks_s <= fx->time_synth_s &&
                  fx->time_synth_s <= t_fx * (double)saved,
              "checks %g s of synthesis %g s, the run %g s x %d threads", fx->time_checks_s,
              fx->time_synth_s, t_fx, saved);
        /* the set mean is over every set: the same call on all 5 sets of the
         * run (a plan as analysis.c makes it) gives the stored values */
        sl_synth_params sp;
        sl_synth_params_default(&sp);
        sl_synth *plan = sl_synth_alloc((size_t)(SL_SYNTH_DURATION_S / SL_SYNTH_DT_S + 0.5) + 1,
                                        SL_SYNTH_DT_S, &sp, &err);
        CHECK(plan && !sl_synth_check_dampings(plan, fl, fx->sets, fx->n_sets, &err),
              "check_dampings: %s", err.msg);
        for (size_t q = 0; plan && q < fx->n_dampings; q++) {
            const sl_analysis_damping *y = &fx->dampings[q];
            const sl_synth_other *ot = &fx->sets[0].check[y->comp].other[q % 2];
            CHECK(ot->set_min == y->set_min && ot->set_max == y->set_max,
                  "damping %zu: stored %g-%g, all sets %g-%g", q, y->set_min, y->set_max,
                  ot->set_min, ot->set_max);
        }
        sl_synth_free(plan);
        for (size_t k = 0; k < 3; k++) {
            const sl_analysis_conv *c = &fx->conv[k];
            const sl_design_row *r = &fx->design->rows[k];
            CHECK(c->design_m == r->nltha_design_m && c->n_sets == 5, "conv row %zu", k);
            /* uncapped: SE of the design = FS x sd / sqrt(n) (stats.h) */
            if (!(r->flags & SL_DESIGN_NLTHA_CAPPED))
                CHECK_CLOSE(c->design_se_m, SL_NLTHA_FS * r->nltha_sd_m / sqrt(5.0), 0, 1e-12);
            CHECK(c->design_lo_m <= c->design_m && c->design_m <= c->design_hi_m,
                  "band %g %g %g", c->design_lo_m, c->design_m, c->design_hi_m);
        }
    }
    sl_analysis_free(ad);
    sl_analysis_free(fx);
    sl_analysis_free(one);
    sl_floor_free(fl);
}

/* The stopping rule: converged means SE <= max(rel value, abs) at every mu,
 * and the previous batch was not converged (it would have stopped). */
static void test_stopping_rule(void)
{
    sl_floor *fl = load(ROOF);
    if (!fl)
        return;
    sl_analysis_opts o;
    sl_analysis_opts_default(&o);
    o.mu = mu3;
    o.n_mu = 3;
    o.rel_se = 0.2;
    o.abs_se_m = 0.002;
    o.first_batch = 3;
    o.boot_resamples = 100;
    sl_error err;
    sl_analysis *a = sl_analysis_run(fl, &o, &err);
    CHECK(a != NULL, "run");
    if (a) {
        CHECK(a->stop == SL_ANALYSIS_STOP_CONVERGED && a->n_unconverged == 0, "stop %s",
              sl_analysis_stop_name(a->stop));
        for (size_t k = 0; k < 3; k++) {
            const sl_analysis_conv *c = &a->conv[k];
            CHECK(c->converged && c->design_se_m <= fmax(0.2 * c->design_m, 0.002),
                  "mu %g: SE %g, design %g", mu3[k], c->design_se_m, c->design_m);
        }
        if (a->n_batches > 1) {
            /* the first batch alone: not converged somewhere */
            o.n_sets = 3;
            sl_analysis *b = sl_analysis_run(fl, &o, &err);
            int any = 0;
            for (size_t k = 0; b && k < 3; k++)
                any |= !b->conv[k].converged;
            CHECK(b && any, "the first batch was already converged");
            sl_analysis_free(b);
        }
    }
    sl_analysis_free(a);
    sl_floor_free(fl);
}

/* Brute force (light): 20 independent seeds of 4 sets each; the RMS of the
 * stated SE of the design value matches the standard deviation of the
 * design value over the seeds within a factor 1.5, at each mu. */
static void test_stated_se(void)
{
    enum { NSEED = 20, NSETS = 4 };
    sl_floor *fl = load(ROOF);
    if (!fl)
        return;
    sl_analysis_opts o;
    sl_analysis_opts_default(&o);
    o.mu = mu3;
    o.n_mu = 3;
    o.n_sets = NSETS;
    o.boot_resamples = 0;
    o.substeps = 2; /* the scatter is the quantity, not the peak's 1e-3 accuracy */
    double d[NSEED][3], se2[3] = {0, 0, 0};
    int ok = 1;
    for (int s = 0; s < NSEED && ok; s++) {
        o.seed = 1000 + (uint64_t)s;
        sl_error err;
        sl_analysis *a = sl_analysis_run(fl, &o, &err);
        ok = a != NULL;
        for (size_t k = 0; a && k < 3; k++) {
            d[s][k] = a->conv[k].design_m;
            se2[k] += a->conv[k].design_se_m * a->conv[k].design_se_m / NSEED;
        }
        sl_analysis_free(a);
    }
    CHECK(ok, "runs");
    for (size_t k = 0; ok && k < 3; k++) {
        double m = 0, v = 0;
        for (int s = 0; s < NSEED; s++)
            m += d[s][k] / NSEED;
        for (int s = 0; s < NSEED; s++)
            v += (d[s][k] - m) * (d[s][k] - m) / (NSEED - 1);
        double ratio = sqrt(se2[k]) / sqrt(v);
        if (getenv("SEISLIDE_TEST_VERBOSE"))
            fprintf(stderr, "    mu %g: design %.4f m, stated SE %.4f, scatter %.4f, ratio %.3f\n",
                    mu3[k], m, sqrt(se2[k]), sqrt(v), ratio);
        CHECK(ratio > 1 / 1.5 && ratio < 1.5, "mu %g: stated SE %g, scatter %g", mu3[k],
              sqrt(se2[k]), sqrt(v));
    }
    sl_floor_free(fl);
}

/* Where the cap governs (mu 0.005 on the roof: the block barely moves, the
 * floor slides under it, 3 x mean > 1.5 x mean PGD), the design value is the
 * cap and its standard error is the cap's, 1.5 sd(PGD) / sqrt(n), not 0;
 * the plain array handed to the report (design_se_m) is the same. */
static void test_cap_se(void)
{
    static const double mu2[] = {0.005, 0.05};
    sl_floor *fl = load(ROOF);
    if (!fl)
        return;
    sl_analysis_opts o;
    sl_analysis_opts_default(&o);
    o.mu = mu2;
    o.n_mu = 2;
    o.n_sets = 8;
    o.boot_resamples = 200;
    o.substeps = 2;
    sl_error err;
    sl_analysis *a = sl_analysis_run(fl, &o, &err);
    CHECK(a != NULL, "run");
    if (a) {
        const sl_design_row *r = &a->design->rows[0];
        const sl_analysis_conv *c = &a->conv[0];
        double m = 0, v = 0;
        for (size_t s = 0; s < a->n_sets; s++)
            m += a->pgd_m[s] / (double)a->n_sets;
        for (size_t s = 0; s < a->n_sets; s++)
            v += (a->pgd_m[s] - m) * (a->pgd_m[s] - m) / (double)(a->n_sets - 1);
        CHECK((r->flags & SL_DESIGN_NLTHA_CAPPED) && c->design_m == r->cap_m, "mu 0.005 capped: "
              "design %g, cap %g", c->design_m, r->cap_m);
        CHECK_CLOSE(c->design_se_m, SL_DESIGN_CAP_FACTOR * sqrt(v / (double)a->n_sets), 0, 1e-12);
        CHECK(a->design_se_m[0] == c->design_se_m && a->design_se_m[1] == a->conv[1].design_se_m,
              "design_se_m array");
        CHECK(!(a->design->rows[1].flags & SL_DESIGN_NLTHA_CAPPED), "mu 0.05 capped");
        CHECK(c->design_lo_m <= c->design_m && c->design_m <= c->design_hi_m &&
                  c->design_hi_m > c->design_lo_m,
              "band %g %g %g", c->design_lo_m, c->design_m, c->design_hi_m);
    }
    sl_analysis_free(a);
    sl_floor_free(fl);
}

/* The variance-reduction diagnostic (analysis.h vr_*): recomputed here
 * from the run's own sets by another path (peaks from sl_slide_run one set
 * at a time, spectra from sl_spectrum_compute one motion at a time, the
 * correlation from its definition), and 1 - max rho^2. */
static void test_vr_diagnostic(void)
{
    sl_floor *fl = load(ROOF);
    if (!fl)
        return;
    sl_analysis_opts o;
    sl_analysis_opts_default(&o);
    o.mu = mu3;
    o.n_mu = 3;
    o.n_sets = 12;
    o.scatter = 0; /* peaks are one NLTHA each */
    o.boot_resamples = 0;
    sl_error err;
    /* one thread: the steps' times are then disjoint parts of the wall time, and a
     * step timed twice (even the diagnostic, under a millisecond) exceeds it */
    int saved = omp_get_max_threads();
    omp_set_num_threads(1);
    double t0 = sl_clock_s();
    sl_analysis *a = sl_analysis_run(fl, &o, &err);
    double wall = sl_clock_s() - t0;
    omp_set_num_threads(saved);
    CHECK(a != NULL, "run");
    if (!a) {
        sl_floor_free(fl);
        return;
    }
    /* each step timed once: the four times are disjoint parts of the run */
    double steps = a->time_synth_s + a->time_nltha_s + a->time_stats_s + a->time_asce_s;
    double room = wall;
    CHECK(steps <= room, "steps %.6f s > the run's wall time %.6f s (synth %.6f "
          "nltha %.6f stats %.6f asce %.6f)", steps, room, a->time_synth_s, a->time_nltha_s,
          a->time_stats_s, a->time_asce_s);
    const size_t n = a->n_sets;
    sl_slide_opts so;
    sl_slide_opts_default(&so);
    double pk[12][3], ysa[12], ypgv[12];
    for (size_t s = 0; s < n; s++) {
        sl_slide_result r[3];
        CHECK(sl_slide_run(&a->sets[s].set, mu3, 3, &so, r, &err) == SL_OK, "slide %zu", s);
        for (int k = 0; k < 3; k++)
            pk[s][k] = r[k].peak_m;
        ypgv[s] = a->sets[s].check[SL_SYNTH_H1].pgv_ms + a->sets[s].check[SL_SYNTH_H2].pgv_ms;
    }
    for (int k = 0; k < 3; k++) {
        double f = a->vr_f_hz[k];
        CHECK(isfinite(f) && f > 0, "mu %g: f_es %g", mu3[k], f);
        for (size_t s = 0; s < n; s++) {
            const sl_motion *h[2] = {a->sets[s].set.h1, a->sets[s].set.h2};
            double p[2];
            for (int c = 0; c < 2; c++)
                sl_spectrum_compute(h[c]->acc_ms2, h[c]->n, h[c]->dt_s, &f, 1, 0.10, &p[c], NULL,
                                    NULL, &err);
            ysa[s] = sqrt(p[0] * p[1]);
        }
        double rho[2];
        for (int q = 0; q < 2; q++) {
            const double *y = q ? ypgv : ysa;
            double mx = 0, my = 0, sxy = 0, sxx = 0, syy = 0;
            for (size_t s = 0; s < n; s++) {
                mx += pk[s][k] / (double)n;
                my += y[s] / (double)n;
            }
            for (size_t s = 0; s < n; s++) {
                sxy += (pk[s][k] - mx) * (y[s] - my);
                sxx += (pk[s][k] - mx) * (pk[s][k] - mx);
                syy += (y[s] - my) * (y[s] - my);
            }
            rho[q] = sxy / sqrt(sxx * syy);
        }
        CHECK_CLOSE(a->vr_corr_sa[k], rho[0], 1e-9, 0);
        CHECK_CLOSE(a->vr_corr_pgv[k], rho[1], 1e-9, 0);
        CHECK_CLOSE(a->vr_factor[k], 1 - fmax(rho[0] * rho[0], rho[1] * rho[1]), 1e-9, 0);
    }
    sl_analysis_free(a);
    sl_floor_free(fl);
}

static void test_bad_options(void)
{
    sl_floor *fl = load(ROOF);
    if (!fl)
        return;
    sl_analysis_opts o;
    sl_analysis_opts_default(&o);
    o.mu = mu3;
    o.n_mu = 3;
    o.rel_se = 0;
    o.abs_se_m = 0;
    sl_error err;
    sl_error_clear(&err);
    CHECK(sl_analysis_run(fl, &o, &err) == NULL && err.code == SL_EINVAL &&
              strstr(err.file, "roof36"),
          "no target: %s", err.msg);
    sl_analysis_opts_default(&o);
    o.mu = mu3;
    o.n_mu = 3;
    o.max_sets = 1;
    CHECK(sl_analysis_run(fl, &o, &err) == NULL && err.code == SL_EINVAL, "max_sets 1");
    CHECK(!strcmp(sl_analysis_stop_name(SL_ANALYSIS_STOP_CONVERGED), "converged") &&
              !strcmp(sl_analysis_stop_name(SL_ANALYSIS_STOP_MAX_SETS), "max_sets") &&
              !strcmp(sl_analysis_stop_name(SL_ANALYSIS_STOP_FIXED), "fixed"),
          "stop names");
    /* the defaults are the documented ones (docs/run.md, "Convergence") */
    sl_analysis_opts_default(&o);
    CHECK(o.band_method == SL_STATS_BAND_STUDENT && o.plan_margin == 1.1 &&
              o.plan_growth == 2.0 && o.first_batch == 10 && o.band_level == 0.90,
          "defaults: band %d, margin %g, growth %g", (int)o.band_method, o.plan_margin,
          o.plan_growth);
    o.mu = mu3;
    o.n_mu = 3;
    o.plan_margin = 0.9;
    CHECK(sl_analysis_run(fl, &o, &err) == NULL && err.code == SL_EINVAL, "margin 0.9");
    sl_floor_free(fl);
}

int main(void)
{
    RUN(test_seed_from_content);
    RUN(test_bad_options);
    RUN(test_batches_and_threads);
    RUN(test_stopping_rule);
    RUN(test_stated_se);
    RUN(test_cap_se);
    RUN(test_vr_diagnostic);
    return HARNESS_END("analysis");
}
