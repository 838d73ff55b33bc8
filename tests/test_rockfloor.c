/* test_rockfloor.c - rocking items over a floor's motion sets
 * (rock/rock_floor.h): the probabilities against the log-normal's closed
 * form, the uplift screen, invariances, threads and chunks, and the sets
 * made again against the run's own. */
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_randist.h>

#include "analysis.h"
#include "core/units.h"
#include "harness.h"
#include "io/floor.h"
#include "rock/rock_cache.h"
#include "rock/rock_floor.h"
#include "synth/synth.h"

#define FLOOR "floors/02-el12.ini"
#define N_STEP 6001
#define DT_STEP 0.005

/* A set whose H1 is a constant A (m/s^2) from t = 0.5 s on (a step), H2 and V
 * absent: a block uplifts iff eps L A > g tan(alpha), and then it
 * overturns (the tilted gravity of a constant acceleration has its
 * equilibrium past the corner). */
static sl_motion *step_motion(double a_ms2)
{
    double *x = calloc(N_STEP, sizeof *x);
    for (size_t i = 100; i < N_STEP; i++)
        x[i] = a_ms2;
    sl_motion *m = sl_motion_from_array(x, N_STEP, DT_STEP, "step");
    free(x);
    return m;
}

static sl_rockf_item item(double b_m, double h_m)
{
    sl_rockf_item it = {{b_m, h_m, -1.0}, NAN};
    return it;
}

static void run_items(const sl_set *sets, size_t n, const sl_rockf_item *items, size_t ni,
                      const sl_rockf_opts *o, sl_rockf_result *out)
{
    sl_error err;
    sl_error_clear(&err);
    sl_rockf_acc *acc = sl_rockf_acc_alloc(items, ni, n, o, &err);
    CHECK(acc != NULL, "%s", err.msg);
    if (!acc)
        return;
    CHECK(sl_rockf_acc_add(acc, sets, n, &err) == SL_OK, "%s", err.msg);
    CHECK(sl_rockf_acc_result(acc, out, &err) == SL_OK, "%s", err.msg);
    sl_rockf_acc_free(acc);
}

/* P(tip) of the step against the log-normal's closed form:
 * P(eps L A > g tan a) = Q((ln(g tan a / (L A)) + sigma^2/2) / sigma). The
 * grid of (F1) is within a grid cell's weight of it, and a fine grid
 * converges to it. */
static void test_step_probability(void)
{
    const double A = 0.25 * SL_G, sigma = 0.3;
    sl_motion *m = step_motion(A);
    sl_set set = {m, NULL, NULL};
    /* the last: P(tip) 0.7 % at 1.0 x, 13 % at 1.5 x (the design excursion from 1.5 x) */
    sl_rockf_item items[4] = {item(0.20, 1.0), item(0.25, 1.0), item(0.30, 1.2), item(0.5, 1.0)};
    for (int fine = 0; fine <= 1; fine++) {
        sl_rockf_opts o;
        sl_rockf_opts_default(&o);
        o.sigma_ln = sigma;
        if (fine) {
            o.dz = 0.01;
            o.zmin = -6;
            o.zmax = 6;
        }
        sl_rockf_result r[4];
        run_items(&set, 1, items, 4, &o, r);
        for (int i = 0; i < 4; i++) {
            for (int l = 0; l < SL_ROCKF_NLEVELS; l++) {
                double x = SL_G * items[i].block.b_m / items[i].block.h_m / (o.level[l] * A);
                double exact = gsl_cdf_ugaussian_Q((log(x) + 0.5 * sigma * sigma) / sigma);
                /* one grid cell's weight at most: phi(0) dz, plus the tails' */
                double tol = fine ? 0.005 : gsl_ran_ugaussian_pdf(0) * o.dz + 0.003;
                CHECK_CLOSE(r[i].level[l].p_tip, exact, tol, 0);
                CHECK_CLOSE(r[i].level[l].p_overturn, r[i].level[l].p_tip, 1e-15, 0);
                CHECK_CLOSE(r[i].level[l].p_uplift, r[i].level[l].p_tip, 1e-15, 0);
                CHECK(r[i].level[l].p_tip_se == 0, "one set: SE %g", r[i].level[l].p_tip_se);
                /* 84th percentile of theta/alpha: overturned (pi/2 / alpha) when
                 * P(overturn) > 16 %, else 0 (never uplifted) */
                double alpha = atan(items[i].block.b_m / items[i].block.h_m);
                double q = r[i].level[l].p_overturn > 1 - SL_ROCKF_THETA_Q + 1e-9
                               ? M_PI_2 / alpha : 0.0;
                if (fabs(r[i].level[l].p_overturn - (1 - SL_ROCKF_THETA_Q)) > 1e-6)
                    CHECK_CLOSE(r[i].level[l].theta_ratio_q, q, 1e-9, 1e-9);
                /* the excursion of a block that overturns is its height 2h; its
                 * (1 - target) quantile is 2h when P(overturn) exceeds the target */
                CHECK_CLOSE(r[i].level[l].excursion_mean_m,
                            r[i].level[l].p_overturn * 2 * items[i].block.h_m, 1e-9, 1e-9);
                double t = o.p_target[l];
                if (fabs(r[i].level[l].p_overturn - t) > 1e-6)
                    CHECK_CLOSE(r[i].level[l].excursion_q_m,
                                r[i].level[l].p_overturn > t ? 2 * items[i].block.h_m : 0.0, 1e-12,
                                0);
            }
            /* the design excursion: the larger of the two levels' */
            CHECK_CLOSE(r[i].excursion_m,
                        fmax(r[i].level[0].excursion_q_m, r[i].level[1].excursion_q_m), 0, 0);
        }
    }
    sl_motion_free(m);
}

/* Without scatter a set is tipped or not: the step below and above its
 * threshold. */
static void test_no_scatter(void)
{
    sl_motion *lo = step_motion(0.19 * SL_G), *hi = step_motion(0.21 * SL_G);
    sl_set sets[2] = {{lo, NULL, NULL}, {hi, NULL, NULL}};
    sl_rockf_item it = item(0.2, 1.0); /* tan(alpha) = 0.2 */
    sl_rockf_opts o;
    sl_rockf_opts_default(&o);
    o.sigma_ln = 0;
    sl_rockf_result r;
    run_items(sets, 2, &it, 1, &o, &r);
    CHECK_CLOSE(r.level[0].p_tip, 0.5, 1e-15, 0);
    /* sd of (0, 1) is 1/sqrt(2): SE = 1/2 */
    CHECK_CLOSE(r.level[0].p_tip_se, 0.5, 1e-12, 0);
    CHECK_CLOSE(r.level[1].p_tip, 1.0, 1e-15, 0); /* 1.5 x 0.19 g > 0.2 g */
    CHECK(r.n_sets == 2 && r.n_orient == 12, "%zu sets, %zu orientations", r.n_sets,
          r.n_orient);
    sl_motion_free(lo);
    sl_motion_free(hi);
}

/* The stopping rule (F6): an item that never uplifts and one that always
 * overturns take the first batch only; one whose p_tip at 1.5 x is near its
 * 10 % target takes every set. */
static void test_stopping_rule(void)
{
    enum { NS = 40 };
    const double tan_a = 0.25, x = 1.404; /* Q((ln x + s^2/2) / s) ~ 0.10 at sigma 0.3 */
    sl_synth_set ss[NS];
    memset(ss, 0, sizeof ss);
    for (int s = 0; s < NS; s++) /* amplitudes spread by +-10 %, in no order */
        ss[s].set.h1 = step_motion(SL_G * tan_a / (1.5 * x) * (0.9 + 0.005 * ((7 * s) % NS)));
    sl_rockf_item items[3] = {item(0.5, 1.0), item(0.05, 1.0), item(0.25, 1.0)};
    sl_rockf_opts o;
    sl_rockf_opts_default(&o);
    o.sigma_ln = 0.3; /* x above is for 0.3 */
    sl_rockf_result r[3];
    sl_error err;
    CHECK(sl_rockf_floor_run(NULL, 1, NS, ss, items, 3, &o, r, &err) == SL_OK, "%s", err.msg);
    CHECK(r[0].n_sets == SL_ROCKF_MIN_SETS && r[0].level[1].p_uplift == 0,
          "squat: %zu sets, p_uplift %g", r[0].n_sets, r[0].level[1].p_uplift);
    CHECK(r[1].n_sets == SL_ROCKF_MIN_SETS && r[1].level[0].p_overturn > 0.9,
          "slender: %zu sets, p_overturn %g", r[1].n_sets, r[1].level[0].p_overturn);
    CHECK(r[2].n_sets == NS && fabs(r[2].level[1].p_tip - 0.10) < 0.05 &&
              r[2].level[1].p_tip_se > 0,
          "near the target: %zu sets, p_tip(1.5 x) %g (SE %g)", r[2].n_sets,
          r[2].level[1].p_tip, r[2].level[1].p_tip_se);
    for (int s = 0; s < NS; s++)
        sl_motion_free(ss[s].set.h1);
}

/* The example floor's first sets, made as the run makes them. */
static size_t floor_sets(sl_floor **fl, sl_synth_set *out, size_t n)
{
    sl_error err;
    sl_error_clear(&err);
    *fl = sl_floor_load(FLOOR, &err);
    CHECK(*fl != NULL, "%s", err.msg);
    if (!*fl)
        return 0;
    sl_analysis_opts ao;
    sl_analysis_opts_default(&ao);
    CHECK(sl_analysis_make_sets(*fl, &ao, 0, n, out, &err) == SL_OK, "%s", err.msg);
    return n;
}

static int same_result(const sl_rockf_result *a, const sl_rockf_result *b)
{
    return memcmp(a->level, b->level, sizeof a->level) == 0 &&
           memcmp(&a->excursion_m, &b->excursion_m, sizeof a->excursion_m) == 0;
}

/* Slender blocks of several sizes on the example floor el. 12 m. */
static const sl_rockf_item floor_items[] = {
    {{0.10, 0.50, -1}, NAN}, {{0.15, 0.75, -1}, NAN}, {{0.20, 1.00, -1}, NAN},
    {{0.25, 1.00, 0.9}, NAN}, {{0.30, 1.20, -1}, 30.0}, {{0.05, 0.40, -1}, NAN}};
#define N_FI (sizeof floor_items / sizeof *floor_items)
#define N_FS 4

/* The uplift screen changes nothing: every realisation integrated gives the
 * same bits; so do one or two threads, chunks of one set, and a set given
 * with its motions and the same set made again, and H1 and H2 swapped (the
 * orientation grid maps onto itself, phi to 90 - phi, and the projection is
 * exact under it: rock.h, sl_rock_project). */
static void test_floor_invariance(void)
{
    sl_floor *fl = NULL;
    sl_synth_set ss[N_FS];
    memset(ss, 0, sizeof ss);
    if (floor_sets(&fl, ss, N_FS) != N_FS)
        goto done;
    sl_set sets[N_FS], swapped[N_FS];
    for (int s = 0; s < N_FS; s++) {
        sets[s] = ss[s].set;
        swapped[s] = ss[s].set;
        swapped[s].h1 = ss[s].set.h2;
        swapped[s].h2 = ss[s].set.h1;
    }
    sl_rockf_opts o;
    sl_rockf_opts_default(&o);
    sl_rockf_result ref[N_FI], r[N_FI];
    run_items(sets, N_FS, floor_items, N_FI, &o, ref);
    size_t tipping = 0, uplifting = 0;
    for (size_t i = 0; i < N_FI; i++) {
        tipping += ref[i].level[1].p_tip > 0 && ref[i].level[1].p_tip < 1;
        uplifting += ref[i].level[0].p_uplift > 0;
    }
    CHECK(tipping >= 2 && uplifting >= 4, "the items span the cases: %zu tip partly, %zu uplift",
          tipping, uplifting);
    o.no_screen = 1;
    run_items(sets, N_FS, floor_items, N_FI, &o, r);
    for (size_t i = 0; i < N_FI; i++)
        CHECK(same_result(&ref[i], &r[i]), "screen: item %zu differs", i);
    o.no_screen = 0;
    int saved = omp_get_max_threads();
    omp_set_num_threads(1);
    run_items(sets, N_FS, floor_items, N_FI, &o, r);
    omp_set_num_threads(saved);
    for (size_t i = 0; i < N_FI; i++)
        CHECK(same_result(&ref[i], &r[i]), "1 thread: item %zu differs", i);
    sl_error err;
    sl_error_clear(&err);
    sl_rockf_acc *acc = sl_rockf_acc_alloc(floor_items, N_FI, N_FS, &o, &err);
    for (int s = 0; acc && s < N_FS; s++)
        CHECK(sl_rockf_acc_add(acc, &sets[s], 1, &err) == SL_OK, "%s", err.msg);
    CHECK(acc && sl_rockf_acc_result(acc, r, &err) == SL_OK, "%s", err.msg);
    for (size_t i = 0; i < N_FI; i++)
        CHECK(same_result(&ref[i], &r[i]), "chunks: item %zu differs", i);
    CHECK(acc && sl_rockf_acc_add(acc, sets, 1, &err) == SL_EINVAL, "a set past max_sets");
    sl_rockf_acc_free(acc);
    run_items(swapped, N_FS, floor_items, N_FI, &o, r);
    for (size_t i = 0; i < N_FI; i++)
        if (isnan(floor_items[i].orientation_deg))
            CHECK(same_result(&ref[i], &r[i]), "H1 and H2 swapped: item %zu differs", i);
    CHECK(sl_rockf_floor_run(fl, 1, N_FS, ss, floor_items, N_FI, &o, r, &err) == SL_OK, "%s",
          err.msg);
    for (size_t i = 0; i < N_FI; i++)
        CHECK(same_result(&ref[i], &r[i]), "given sets: item %zu differs", i);
    CHECK(sl_rockf_floor_run(fl, 1, N_FS, NULL, floor_items, N_FI, &o, r, &err) == SL_OK, "%s",
          err.msg);
    for (size_t i = 0; i < N_FI; i++)
        CHECK(same_result(&ref[i], &r[i]), "sets made again: item %zu differs", i);
done:
    for (int s = 0; s < N_FS; s++)
        sl_synth_set_clear(&ss[s]);
    sl_floor_free(fl);
}

/* The sets made again are the run's own, bit for bit. */
static void test_sets_made_again(void)
{
    sl_error err;
    sl_error_clear(&err);
    sl_floor *fl = sl_floor_load(FLOOR, &err);
    CHECK(fl != NULL, "%s", err.msg);
    if (!fl)
        return;
    sl_analysis_opts ao;
    sl_analysis_opts_default(&ao);
    double mu[2] = {0.2, 0.4};
    ao.mu = mu;
    ao.n_mu = 2;
    ao.n_sets = 3;
    ao.seed = 7;
    sl_analysis *a = sl_analysis_run(fl, &ao, &err);
    CHECK(a != NULL, "%s", err.msg);
    sl_synth_set ss[2];
    memset(ss, 0, sizeof ss);
    CHECK(sl_analysis_make_sets(fl, &ao, 1, 2, ss, &err) == SL_OK, "%s", err.msg);
    for (int s = 0; a && s < 2; s++)
        for (int c = 0; c < SL_SYNTH_NCOMP; c++) {
            const sl_motion *x = sl_synth_set_motion(&a->sets[s + 1], (sl_synth_comp)c);
            const sl_motion *y = sl_synth_set_motion(&ss[s], (sl_synth_comp)c);
            CHECK(x && y && x->n == y->n &&
                      memcmp(x->acc_ms2, y->acc_ms2, x->n * sizeof *x->acc_ms2) == 0,
                  "set %d component %d differs", s + 1, c);
        }
    for (int s = 0; s < 2; s++)
        sl_synth_set_clear(&ss[s]);
    sl_analysis_free(a);
    sl_floor_free(fl);
}

/* The cache (rock_cache.h): what is written reads back bit for bit; another
 * item, seed or set count is another key; a damaged byte is a miss. */
static void test_cache(void)
{
    sl_error err;
    sl_floor *fl = sl_floor_load(FLOOR, &err);
    CHECK(fl != NULL, "%s", err.msg);
    if (!fl)
        return;
    char dir[] = "/tmp/seislide-rockc-XXXXXX";
    CHECK(mkdtemp(dir) != NULL, "mkdtemp");
    sl_rockf_opts o;
    sl_rockf_opts_default(&o);
    sl_rockf_item items[2] = {item(0.2, 1.0), item(0.3, 0.5)};
    sl_rockf_result out[2], back[2];
    memset(out, 0, sizeof out);
    for (int i = 0; i < 2; i++) {
        out[i].n_sets = 20 + (size_t)i;
        out[i].n_orient = 12;
        out[i].level[1].p_tip = 0.1 * (i + 1);
        out[i].level[0].theta_ratio_q = 1.0 / 3.0;
        out[i].excursion_m = 0.0123 + i;
    }
    sl_rockc_key k, k2;
    CHECK(sl_rockc_key_make(fl, 1, 60, &o, items, 2, &k, &err) == SL_OK, "%s", err.msg);
    CHECK(!sl_rockc_read(dir, &k, back, 2), "empty folder: a miss");
    CHECK(sl_rockc_write(dir, &k, out, 2, &err) == SL_OK, "%s", err.msg);
    CHECK(sl_rockc_read(dir, &k, back, 2) && !memcmp(out, back, sizeof out), "read back");
    CHECK(!sl_rockc_read(dir, &k, back, 1), "another count");
    items[1].block.h_m = 0.51;
    CHECK(sl_rockc_key_make(fl, 1, 60, &o, items, 2, &k2, &err) == SL_OK, "%s", err.msg);
    CHECK(strcmp(k.hash, k2.hash) && !sl_rockc_read(dir, &k2, back, 2), "another item");
    sl_rockc_key_free(&k2);
    CHECK(sl_rockc_key_make(fl, 2, 60, &o, items, 2, &k2, &err) == SL_OK, "%s", err.msg);
    CHECK(!sl_rockc_read(dir, &k2, back, 2), "another seed");
    sl_rockc_key_free(&k2);
    char path[256];
    snprintf(path, sizeof path, "%s/%s%s", dir, k.hash, SL_ROCKC_SUFFIX);
    FILE *f = fopen(path, "r+b");
    CHECK(f != NULL, "%s", path);
    if (f) {
        fseek(f, 200, SEEK_SET);
        int c = fgetc(f);
        fseek(f, 200, SEEK_SET);
        fputc(c ^ 1, f);
        fclose(f);
    }
    CHECK(!sl_rockc_read(dir, &k, back, 2), "one bit flipped: a miss");
    remove(path);
    rmdir(dir);
    sl_rockc_key_free(&k);
    sl_floor_free(fl);
}

/* The verdict rules (rock_floor.h). */
static void test_verdict(void)
{
    sl_rockf_result r;
    memset(&r, 0, sizeof r);
    const double t[2] = {0.01, 0.10};
    r.excursion_m = 0.05;
    CHECK(sl_rockf_verdict_of(&r, t, 0.06) == SL_ROCKF_STANDS, "stands");
    CHECK(sl_rockf_verdict_of(&r, t, NAN) == SL_ROCKF_STANDS, "no clearance given");
    CHECK(sl_rockf_verdict_of(&r, t, 0.04) == SL_ROCKF_SHORT, "short");
    r.level[0].p_tip = 0.011;
    CHECK(sl_rockf_verdict_of(&r, t, 0.06) == SL_ROCKF_OVERTURNS, "1 %% at 1.0 x");
    r.level[0].p_tip = 0.01;
    CHECK(sl_rockf_verdict_of(&r, t, 0.06) == SL_ROCKF_MARGINAL, "at the target, SE 0");
    r.level[0].p_tip = 0.005;
    CHECK(sl_rockf_verdict_of(&r, t, 0.06) == SL_ROCKF_MARGINAL, "between 0 and 1, SE 0");
    r.level[0].p_tip = 0.01;
    r.level[0].p_tip_se = 0.002;
    CHECK(sl_rockf_verdict_of(&r, t, 0.06) == SL_ROCKF_MARGINAL, "at the target, SE > 0");
    r.level[0].p_tip = 0.0065;
    CHECK(sl_rockf_verdict_of(&r, t, 0.06) == SL_ROCKF_MARGINAL, "1.75 SE below");
    CHECK(sl_rockf_verdict_of(&r, t, 0.04) == SL_ROCKF_SHORT, "short before marginal");
    r.level[0].p_tip = 0.0059;
    CHECK(sl_rockf_verdict_of(&r, t, 0.06) == SL_ROCKF_STANDS, "2.05 SE below: decided");
    r.level[1].p_tip = 0.11;
    CHECK(sl_rockf_verdict_of(&r, t, 0.06) == SL_ROCKF_OVERTURNS, "10 %% at 1.5 x");
    CHECK(!strcmp(sl_rockf_verdict_name(SL_ROCKF_OVERTURNS), "overturns"), "name");
}

/* Bad input is refused, naming what. */
static void test_bad_input(void)
{
    sl_error err;
    sl_rockf_opts o;
    sl_rockf_opts_default(&o);
    sl_rockf_item bad = item(-0.1, 1.0);
    CHECK(!sl_rockf_acc_alloc(&bad, 1, 1, &o, &err) && err.code == SL_EINVAL, "b < 0");
    sl_rockf_item good = item(0.1, 1.0);
    o.sigma_ln = 2;
    CHECK(!sl_rockf_acc_alloc(&good, 1, 1, &o, &err) && err.code == SL_EINVAL, "sigma 2");
    sl_rockf_opts_default(&o);
    sl_rockf_acc *acc = sl_rockf_acc_alloc(&good, 1, 1, &o, &err);
    sl_rockf_result r;
    CHECK(acc && sl_rockf_acc_result(acc, &r, &err) == SL_EINVAL, "no sets");
    sl_set none = {NULL, NULL, NULL};
    CHECK(acc && sl_rockf_acc_add(acc, &none, 1, &err) == SL_EINVAL, "no H1");
    sl_rockf_acc_free(acc);
}

int main(void)
{
    RUN(test_step_probability);
    RUN(test_no_scatter);
    RUN(test_verdict);
    RUN(test_stopping_rule);
    RUN(test_cache);
    RUN(test_bad_input);
    RUN(test_sets_made_again);
    RUN(test_floor_invariance);
    return HARNESS_END("test_rockfloor");
}
