/* rock_floor.c - rocking items on a floor over its motion sets (rock_floor.h). */
#include "rock/rock_floor.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_math.h>
#include <gsl/gsl_randist.h>

#include "core/units.h"

/* What one realisation (set, level, eps_j), worst over orientations, gave. */
enum { F_UPLIFT = 1, F_TIP = 2, F_OVERTURN = 4 };

struct sl_rockf_acc {
    sl_rockf_opts o;
    size_t n_items, max_sets, n_sets;
    sl_rockf_item *items;
    size_t *n_item_sets;      /* per item: the sets it was run on (a prefix of the floor's) */
    unsigned char *active;    /* per item: still taking sets (sl_rockf_acc_add) */
    size_t nz;                /* intensity points (F1) */
    double *eps, *w;          /* nz each */
    size_t n_orient;          /* the grid of (F2) */
    double *orient_deg;
    /* per (item, level, set, j): index ((i * NLEVELS + l) * max_sets + s) * nz + j */
    double *ratio, *exc_m;
    unsigned char *flags;
    size_t *runs;             /* per (item, set): block runs integrated */
};

void sl_rockf_opts_default(sl_rockf_opts *o)
{
    memset(o, 0, sizeof *o);
    o->sigma_ln = SL_ROCKF_SCATTER;
    o->level[0] = SL_ROCKF_LEVEL_1;
    o->level[1] = SL_ROCKF_LEVEL_2;
    o->p_target[0] = SL_ROCKF_P_TARGET_1;
    o->p_target[1] = SL_ROCKF_P_TARGET_2;
    o->zmin = SL_ROCKF_ZMIN;
    o->zmax = SL_ROCKF_ZMAX;
    o->dz = SL_ROCKF_DZ;
    o->orient_step_deg = SL_ROCKF_ORIENT_STEP_DEG;
    o->min_sets = SL_ROCKF_MIN_SETS;
    sl_rock_opts_default(&o->engine);
}

static sl_status check_opts(const sl_rockf_opts *o, sl_error *err)
{
    if (!(o->sigma_ln >= 0 && o->sigma_ln <= 1.0))
        return sl_error_set(err, SL_EINVAL, NULL, 0, "rocking: intensity scatter %g outside "
                            "[0, 1]", o->sigma_ln);
    for (int l = 0; l < SL_ROCKF_NLEVELS; l++)
        if (!(o->level[l] > 0 && isfinite(o->level[l])) ||
            !(o->p_target[l] > 0 && o->p_target[l] < 1))
            return sl_error_set(err, SL_EINVAL, NULL, 0, "rocking: level %g or target "
                                "probability %g out of range", o->level[l], o->p_target[l]);
    if (o->sigma_ln > 0 && !(o->dz > 0 && o->zmin < o->zmax && isfinite(o->zmin) &&
                             isfinite(o->zmax) && (o->zmax - o->zmin) / o->dz <= 10000))
        return sl_error_set(err, SL_EINVAL, NULL, 0, "rocking: bad intensity grid %g:%g:%g",
                            o->zmin, o->dz, o->zmax);
    if (!(o->orient_step_deg > 0 && o->orient_step_deg <= 180))
        return sl_error_set(err, SL_EINVAL, NULL, 0, "rocking: orientation step %g outside "
                            "(0, 180] degrees", o->orient_step_deg);
    return SL_OK;
}

/* The intensity points and weights of (F1): trapezoid weights of the
 * normal density, the tails given to the end points, scaled to sum 1. */
static sl_status make_grid(sl_rockf_acc *a, sl_error *err)
{
    const sl_rockf_opts *o = &a->o;
    a->nz = o->sigma_ln > 0 ? (size_t)floor((o->zmax - o->zmin) / o->dz + 1e-9) + 1 : 1;
    a->eps = malloc(a->nz * sizeof *a->eps);
    a->w = malloc(a->nz * sizeof *a->w);
    if (!a->eps || !a->w)
        return sl_error_set(err, SL_ENOMEM, NULL, 0, "rocking: out of memory");
    if (a->nz == 1) {
        a->eps[0] = 1.0;
        a->w[0] = 1.0;
        return SL_OK;
    }
    double sum = 0;
    for (size_t j = 0; j < a->nz; j++) {
        double z = o->zmin + (double)j * o->dz;
        a->eps[j] = exp(o->sigma_ln * z - 0.5 * o->sigma_ln * o->sigma_ln);
        double w = gsl_ran_ugaussian_pdf(z) * o->dz;
        if (j == 0)
            w = 0.5 * w + gsl_cdf_ugaussian_P(z);
        else if (j == a->nz - 1)
            w = 0.5 * w + gsl_cdf_ugaussian_Q(z);
        a->w[j] = w;
        sum += w;
    }
    for (size_t j = 0; j < a->nz; j++)
        a->w[j] /= sum;
    return SL_OK;
}

void sl_rockf_acc_free(sl_rockf_acc *a)
{
    if (!a)
        return;
    free(a->items);
    free(a->n_item_sets);
    free(a->active);
    free(a->eps);
    free(a->w);
    free(a->orient_deg);
    free(a->ratio);
    free(a->exc_m);
    free(a->flags);
    free(a->runs);
    free(a);
}

sl_rockf_acc *sl_rockf_acc_alloc(const sl_rockf_item *items, size_t n_items, size_t max_sets,
                                 const sl_rockf_opts *o, sl_error *err)
{
    if (check_opts(o, err))
        return NULL;
    if (n_items == 0 || max_sets == 0) {
        sl_error_set(err, SL_EINVAL, NULL, 0, "rocking: no items or no sets");
        return NULL;
    }
    for (size_t i = 0; i < n_items; i++) {
        const sl_rock_block *b = &items[i].block;
        if (!(b->b_m > 0 && b->h_m > 0 && isfinite(b->b_m) && isfinite(b->h_m)) ||
            b->restitution > 1 || !(isnan(items[i].orientation_deg) ||
                                    isfinite(items[i].orientation_deg))) {
            sl_error_set(err, SL_EINVAL, NULL, 0, "rocking: item %zu: bad block (b %g m, h %g m, "
                         "r %g, orientation %g deg)", i + 1, b->b_m, b->h_m, b->restitution,
                         items[i].orientation_deg);
            return NULL;
        }
    }
    sl_rockf_acc *a = calloc(1, sizeof *a);
    if (!a) {
        sl_error_set(err, SL_ENOMEM, NULL, 0, "rocking: out of memory");
        return NULL;
    }
    a->o = *o;
    a->n_items = n_items;
    a->max_sets = max_sets;
    if (make_grid(a, err)) {
        sl_rockf_acc_free(a);
        return NULL;
    }
    a->n_orient = (size_t)ceil(180.0 / o->orient_step_deg - 1e-9);
    const size_t cells = n_items * SL_ROCKF_NLEVELS * max_sets * a->nz;
    a->items = malloc(n_items * sizeof *a->items);
    a->orient_deg = malloc(a->n_orient * sizeof *a->orient_deg);
    a->ratio = calloc(cells, sizeof *a->ratio);
    a->exc_m = calloc(cells, sizeof *a->exc_m);
    a->flags = calloc(cells, 1);
    a->runs = calloc(n_items * max_sets, sizeof *a->runs);
    a->n_item_sets = calloc(n_items, sizeof *a->n_item_sets);
    a->active = malloc(n_items);
    if (!a->items || !a->orient_deg || !a->ratio || !a->exc_m || !a->flags || !a->runs ||
        !a->n_item_sets || !a->active) {
        sl_error_set(err, SL_ENOMEM, NULL, 0, "rocking: out of memory");
        sl_rockf_acc_free(a);
        return NULL;
    }
    memcpy(a->items, items, n_items * sizeof *items);
    memset(a->active, 1, n_items);
    for (size_t k = 0; k < a->n_orient; k++)
        a->orient_deg[k] = (double)k * o->orient_step_deg;
    return a;
}

size_t sl_rockf_acc_n_sets(const sl_rockf_acc *a)
{
    return a ? a->n_sets : 0;
}

/* c = min over samples of (g + L a_v) / (L |a_h|): uplift at eps needs
 * eps > tan(alpha) c (the screen of rock_floor.h). -INFINITY when g + L a_v
 * <= 0 where a_h is not zero (the block is weightless there). */
static double screen_c(const double *ah, const double *av, size_t n, double level)
{
    double c = INFINITY;
    for (size_t i = 0; i < n; i++) {
        double h = fabs(ah[i]) * level;
        double v = SL_G + (av ? level * av[i] : 0.0);
        if (h == 0)
            continue;
        if (v <= 0)
            return -INFINITY;
        double q = v / h;
        if (q < c)
            c = q;
    }
    return c;
}

/* Working memory of one thread: the weak-axis histories of the grid
 * orientations and one more, and their screens. */
typedef struct work {
    size_t n;                /* samples a slot holds (the longest set so far) */
    double *proj;            /* (n_orient + 1) slots, each the set's samples */
    double *c;               /* (n_orient + 1) x NLEVELS */
} work;

static size_t cell(const sl_rockf_acc *a, size_t i, int l, size_t s, size_t j)
{
    return ((i * SL_ROCKF_NLEVELS + (size_t)l) * a->max_sets + s) * a->nz + j;
}

/* Slot k of the work: the horizontals projected on the weak axis at phi
 * degrees from H1, and the screen value of each level. */
static void fill_slot(const sl_rockf_acc *a, const sl_set *set, double phi, size_t k, work *wk)
{
    const size_t n = set->h1->n;
    sl_rock_project(set->h1->acc_ms2, set->h2 ? set->h2->acc_ms2 : NULL, n, phi, wk->proj + k * n);
    for (int l = 0; l < SL_ROCKF_NLEVELS; l++)
        wk->c[k * SL_ROCKF_NLEVELS + (size_t)l] =
            screen_c(wk->proj + k * n, set->v ? set->v->acc_ms2 : NULL, n, a->o.level[l]);
}

/* Set s (its index among the acc's sets): every item, level and intensity. */
static sl_status one_set(sl_rockf_acc *a, const sl_set *set, size_t s, work *wk, sl_error *err)
{
    const size_t n = set->h1->n, no = a->n_orient;
    const double dt = set->h1->dt_s;
    const double *av = set->v ? set->v->acc_ms2 : NULL;
    for (size_t k = 0; k < no; k++)
        fill_slot(a, set, a->orient_deg[k], k, wk);
    for (size_t i = 0; i < a->n_items; i++) {
        if (!a->active[i])
            continue;
        const sl_rockf_item *it = &a->items[i];
        size_t runs = 0;
        const double tan_a = it->block.b_m / it->block.h_m;
        /* the orientations of this item: the grid, or its own (slot no) */
        size_t k0 = 0, k1 = no;
        if (!isnan(it->orientation_deg)) {
            k0 = no;
            k1 = no + 1;
            fill_slot(a, set, it->orientation_deg, no, wk);
        }
        for (int l = 0; l < SL_ROCKF_NLEVELS; l++) {
            const double L = a->o.level[l];
            for (size_t j = 0; j < a->nz; j++) {
                double ratio = 0, exc = 0;
                unsigned char fl = 0;
                for (size_t k = k0; k < k1; k++) {
                    if (!a->o.no_screen &&
                        !(a->eps[j] > tan_a * wk->c[k * SL_ROCKF_NLEVELS + (size_t)l]))
                        continue; /* cannot uplift: at rest throughout */
                    sl_rock_result r;
                    sl_status st = sl_rock_run(&it->block, wk->proj + k * n, av, n, dt,
                                               L * a->eps[j], L, &a->o.engine, &r, err);
                    if (st)
                        return st;
                    runs++;
                    fl |= (unsigned char)((r.uplifted ? F_UPLIFT : 0) | (r.tipped ? F_TIP : 0) |
                                          (r.overturned ? F_OVERTURN : 0));
                    ratio = fmax(ratio, r.peak_theta_over_alpha);
                    exc = fmax(exc, r.excursion_m);
                    if (r.overturned)
                        break; /* no orientation can give more */
                }
                size_t c = cell(a, i, l, s, j);
                a->ratio[c] = ratio;
                a->exc_m[c] = exc;
                a->flags[c] = fl;
            }
        }
        a->runs[i * a->max_sets + s] = runs;
    }
    return SL_OK;
}

sl_status sl_rockf_acc_add(sl_rockf_acc *a, const sl_set *sets, size_t count, sl_error *err)
{
    if (a->n_sets + count > a->max_sets)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "rocking: %zu sets, at most %zu",
                            a->n_sets + count, a->max_sets);
    for (size_t s = 0; s < count; s++) {
        const sl_set *x = &sets[s];
        if (!x->h1 || x->h1->n < 2 || (x->h2 && x->h2->n != x->h1->n) ||
            (x->v && x->v->n != x->h1->n))
            return sl_error_set(err, SL_EINVAL, NULL, 0, "rocking: set %zu: no H1, or "
                                "components of different lengths", a->n_sets + s + 1);
    }
    sl_status st = SL_OK;
    size_t first_bad = (size_t)-1;
    sl_error e_bad;
    sl_error_clear(&e_bad);
#pragma omp parallel default(none) shared(a, sets, count, st, first_bad, e_bad)
    {
        work wk = {0};
        sl_error e;
        sl_error_clear(&e);
#pragma omp for schedule(dynamic, 1)
        for (size_t s = 0; s < count; s++) {
            const size_t n = sets[s].h1->n;
            sl_status my = SL_OK;
            if (wk.n < n) { /* grows to the longest set: n samples a slot */
                free(wk.proj);
                wk.proj = malloc((a->n_orient + 1) * n * sizeof *wk.proj);
                wk.n = wk.proj ? n : 0;
            }
            if (!wk.c)
                wk.c = malloc((a->n_orient + 1) * SL_ROCKF_NLEVELS * sizeof *wk.c);
            if (!wk.proj || !wk.c)
                my = sl_error_set(&e, SL_ENOMEM, NULL, 0, "rocking: out of memory");
            if (!my)
                my = one_set(a, &sets[s], a->n_sets + s, &wk, &e);
            if (my) {
#pragma omp critical(sl_rockf_err)
                if (s < first_bad) { /* the first failing set, whatever the threads */
                    first_bad = s;
                    st = my;
                    e_bad = e;
                }
            }
        }
        free(wk.proj);
        free(wk.c);
    }
    if (st) {
        if (err)
            *err = e_bad;
        return st;
    }
    a->n_sets += count;
    for (size_t i = 0; i < a->n_items; i++)
        if (a->active[i])
            a->n_item_sets[i] = a->n_sets;
    return SL_OK;
}

/* Mean and standard error over sets of P_s = sum_j w_j [flags & bit] (F3). */
static void prob(const sl_rockf_acc *a, size_t i, int l, unsigned char bit, double *p,
                 double *se)
{
    const size_t n = a->n_item_sets[i];
    double sum = 0, sum2 = 0;
    for (size_t s = 0; s < n; s++) {
        double ps = 0;
        for (size_t j = 0; j < a->nz; j++)
            ps += (a->flags[cell(a, i, l, s, j)] & bit) ? a->w[j] : 0.0;
        sum += ps;
        sum2 += ps * ps;
    }
    double m = sum / (double)n;
    double var = n > 1 ? (sum2 - (double)n * m * m) / (double)(n - 1) : 0.0;
    *p = m;
    *se = n > 1 && var > 0 ? sqrt(var / (double)n) : 0.0;
}

typedef struct wv {
    double v, w;
} wv;

static int by_value(const void *x, const void *y)
{
    double a = ((const wv *)x)->v, b = ((const wv *)y)->v;
    return (a > b) - (a < b);
}

/* The weighted mean and the q quantile (the smallest value whose
 * cumulative weight reaches q) of values[s, j] with weights w_j / n (F4). */
static void wstats(const sl_rockf_acc *a, const double *values, size_t i, int l, double q,
                   wv *buf, double *mean, double *quant)
{
    const size_t n = a->n_item_sets[i];
    size_t m = 0;
    double sum = 0;
    for (size_t s = 0; s < n; s++)
        for (size_t j = 0; j < a->nz; j++) {
            double v = values[cell(a, i, l, s, j)];
            buf[m].v = v;
            buf[m].w = a->w[j] / (double)n;
            sum += buf[m].w * v;
            m++;
        }
    qsort(buf, m, sizeof *buf, by_value);
    double cum = 0;
    *quant = m ? buf[m - 1].v : 0.0;
    for (size_t k = 0; k < m; k++) {
        cum += buf[k].w;
        if (cum >= q * (1 - 1e-12)) {
            *quant = buf[k].v;
            break;
        }
    }
    *mean = sum;
}

sl_status sl_rockf_acc_result(const sl_rockf_acc *a, sl_rockf_result *out, sl_error *err)
{
    if (a->n_sets == 0)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "rocking: no sets added");
    wv *buf = malloc(a->n_sets * a->nz * sizeof *buf);
    if (!buf)
        return sl_error_set(err, SL_ENOMEM, NULL, 0, "rocking: out of memory");
    for (size_t i = 0; i < a->n_items; i++) {
        sl_rockf_result *r = &out[i];
        memset(r, 0, sizeof *r);
        r->n_sets = a->n_item_sets[i];
        r->n_orient = isnan(a->items[i].orientation_deg) ? a->n_orient : 1;
        for (size_t s = 0; s < r->n_sets; s++)
            r->n_runs += a->runs[i * a->max_sets + s];
        for (int l = 0; l < SL_ROCKF_NLEVELS; l++) {
            sl_rockf_level *v = &r->level[l];
            prob(a, i, l, F_UPLIFT, &v->p_uplift, &v->p_uplift_se);
            prob(a, i, l, F_TIP, &v->p_tip, &v->p_tip_se);
            prob(a, i, l, F_OVERTURN, &v->p_overturn, &v->p_overturn_se);
            wstats(a, a->ratio, i, l, SL_ROCKF_THETA_Q, buf, &v->theta_ratio_mean,
                   &v->theta_ratio_q);
            wstats(a, a->exc_m, i, l, 1 - a->o.p_target[l], buf, &v->excursion_mean_m,
                   &v->excursion_q_m);
        }
        r->excursion_m = fmax(r->level[0].excursion_q_m, r->level[1].excursion_q_m);
    }
    free(buf);
    return SL_OK;
}

/* Is p decided against target t (F6)? Every set tips everywhere or nowhere
 * (p 1 or 0: the sets agree, SE 0), or p is more than SL_ROCKF_SE_DECIDE
 * standard errors from t; an SE of 0 at another p (sets that happen to agree
 * on a share) decides nothing. */
static int level_decided(double p, double se, double t)
{
    if (p == 0 || p == 1)
        return 1;
    return se > 0 && fabs(p - t) > SL_ROCKF_SE_DECIDE * se;
}

/* (F6): item i is decided when some level's p_tip is above its target and
 * decided there, or every level's is at or below it and decided. */
static int decided(const sl_rockf_acc *a, size_t i)
{
    int all_below = 1;
    for (int l = 0; l < SL_ROCKF_NLEVELS; l++) {
        double p, se;
        prob(a, i, l, F_TIP, &p, &se);
        const double t = a->o.p_target[l];
        if (p > t && level_decided(p, se, t))
            return 1;
        if (!(p <= t && level_decided(p, se, t)))
            all_below = 0;
    }
    return all_below;
}

size_t sl_rockf_acc_update(sl_rockf_acc *a)
{
    size_t n_active = 0;
    for (size_t i = 0; i < a->n_items; i++) {
        if (a->active[i] && a->n_item_sets[i] >= a->o.min_sets && decided(a, i))
            a->active[i] = 0;
        n_active += a->active[i];
    }
    return n_active;
}

sl_rockf_verdict sl_rockf_verdict_of(const sl_rockf_result *r,
                                     const double p_target[SL_ROCKF_NLEVELS], double clearance_m)
{
    int near = 0;
    for (int l = 0; l < SL_ROCKF_NLEVELS; l++) {
        const sl_rockf_level *v = &r->level[l];
        if (v->p_tip > p_target[l])
            return SL_ROCKF_OVERTURNS;
        near |= !level_decided(v->p_tip, v->p_tip_se, p_target[l]);
    }
    if (!isnan(clearance_m) && r->excursion_m > clearance_m)
        return SL_ROCKF_SHORT;
    return near ? SL_ROCKF_MARGINAL : SL_ROCKF_STANDS;
}

const char *sl_rockf_verdict_name(sl_rockf_verdict v)
{
    static const char *const names[] = {"stands", "marginal", "short", "overturns"};
    return (unsigned)v < sizeof names / sizeof *names ? names[v] : "?";
}
