/*
 * slide.c - the public entry points of the sliding analysis (slide.h): check
 * the input, dispatch to the engine (engine.h) or to a reference model
 * (refmodel.h), and run many sets in parallel.
 */
#include "slide/slide.h"

#include <math.h>
#include <omp.h>

#include "slide/engine.h"
#include "slide/refmodel.h"

static sl_status check_opts(const sl_set *set, const double *mu, size_t n_mu,
                            const sl_slide_opts *o, sl_error *err)
{
    if (!set || !set->h1 || !set->h1->acc_ms2 || set->h1->n < 1)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "slide: no H1 motion");
    if (!(set->h1->dt_s > 0.0))
        return sl_error_set(err, SL_EINVAL, NULL, 0, "slide: dt %g must be > 0", set->h1->dt_s);
    if ((set->h2 && set->h2->n != set->h1->n) || (set->v && set->v->n != set->h1->n))
        return sl_error_set(err, SL_EINVAL, NULL, 0,
                            "slide: components differ in length (check the set first)");
    if (!(o->g_ms2 > 0.0))
        return sl_error_set(err, SL_EINVAL, NULL, 0, "slide: gravity %g must be > 0", o->g_ms2);
    if (!(o->rtol >= 1e-9 && o->rtol <= 0.1))
        return sl_error_set(err, SL_EINVAL, NULL, 0, "slide: rtol %g must be in [1e-9, 0.1]",
                            o->rtol);
    if (!(o->atol_m > 0.0) || !isfinite(o->atol_m))
        return sl_error_set(err, SL_EINVAL, NULL, 0, "slide: atol %g m must be > 0", o->atol_m);
    if (!(o->up_ratio > 0.0))
        return sl_error_set(err, SL_EINVAL, NULL, 0, "slide: up_ratio %g must be > 0",
                            o->up_ratio);
    if (set->h2 && o->up_ratio != 1.0)
        return sl_error_set(err, SL_EINVAL, NULL, 0,
                            "slide: asymmetric or one-way resistance is 1-D only (no H2)");
    for (size_t k = 0; k < n_mu; k++)
        if (!(mu[k] >= 0.0) || !isfinite(mu[k]))
            return sl_error_set(err, SL_EINVAL, NULL, 0,
                                "slide: friction coefficient %g must be finite and >= 0", mu[k]);
    return SL_OK;
}

double sl_slide_mu_threshold(const sl_set *set, const sl_slide_opts *opts)
{
    sl_slide_opts def;
    if (!opts) {
        sl_slide_opts_default(&def);
        opts = &def;
    }
    return sl_engine_threshold(set, opts);
}

static sl_status run_any(const sl_set *set, const double *mu, size_t n_mu,
                         const sl_slide_opts *opts, sl_slide_result *res,
                         sl_history **hist, sl_error *err)
{
    sl_slide_opts def;
    if (!opts) {
        sl_slide_opts_default(&def);
        opts = &def;
    }
    sl_status st = check_opts(set, mu, n_mu, opts, err);
    if (st)
        return st;
    if (opts->model != SL_MODEL_EXACT) {
        for (size_t k = 0; k < n_mu; k++) {
            st = sl_refmodel_run(set, mu[k], opts, &res[k], hist, err);
            if (st)
                return st;
            res[k].err_est_m = NAN; /* the reference models do not estimate */
        }
        return SL_OK;
    }
    return sl_engine_run(set, mu, n_mu, opts, res, hist, err);
}

sl_status sl_slide_run(const sl_set *set, const double *mu, size_t n_mu,
                       const sl_slide_opts *opts, sl_slide_result *res, sl_error *err)
{
    return run_any(set, mu, n_mu, opts, res, NULL, err);
}

sl_status sl_slide_history(const sl_set *set, double mu, const sl_slide_opts *opts,
                           sl_slide_result *res, sl_history **hist, sl_error *err)
{
    if (hist)
        *hist = NULL;
    return run_any(set, &mu, 1, opts, res, hist, err);
}

sl_status sl_slide_batch(const sl_set *sets, size_t n_sets, const double *mu, size_t n_mu,
                         const sl_slide_opts *opts, sl_slide_result *res, sl_error *err)
{
    /* Work items: (set, chunk of mu). Every (set, mu) is computed the same
     * way whatever the chunking, so results do not depend on threads. */
    const size_t chunk = SL_SLIDE_BATCH_CHUNK;
    const size_t per_set = (n_mu + chunk - 1) / chunk;
    const long items = (long)(n_sets * per_set);
    sl_status first = SL_OK;
    long first_item = -1;
    sl_error first_err;
    sl_error_clear(&first_err);
#pragma omp parallel for schedule(dynamic, 1)
    for (long it = 0; it < items; it++) {
        size_t s = (size_t)it / per_set, c = (size_t)it % per_set;
        size_t k0 = c * chunk, kn = (k0 + chunk <= n_mu) ? chunk : n_mu - k0;
        sl_error e;
        sl_error_clear(&e);
        sl_status st = sl_slide_run(&sets[s], mu + k0, kn, opts, res + s * n_mu + k0, &e);
        if (st) {
#pragma omp critical(sl_slide_batch_err)
            {
                if (first_item < 0 || it < first_item) { /* report the first, deterministically */
                    first_item = it;
                    first = st;
                    first_err = e;
                }
            }
        }
    }
    if (first && err)
        *err = first_err;
    return first;
}
