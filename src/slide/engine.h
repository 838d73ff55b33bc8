/*
 * engine.h - the Coulomb sliding engine (library-internal; callers use
 * slide.h): the exact 1-D kernel and the error-controlled 2-D kernel,
 * all friction coefficients of one motion advancing together.
 */
#ifndef SL_ENGINE_H
#define SL_ENGINE_H

#include "slide/model.h"

/* sl_slide_mu_threshold for a set already checked by slide.c. */
double sl_engine_threshold(const sl_set *set, const sl_slide_opts *opts);

/* sl_slide_run / sl_slide_history with opts->model == SL_MODEL_EXACT, on a
 * set and options already checked by slide.c. hist_out may be NULL; with a
 * history, n_mu must be 1. */
sl_status sl_engine_run(const sl_set *set, const double *mu, size_t n_mu,
                        const sl_slide_opts *opts, sl_slide_result *res, sl_history **hist_out,
                        sl_error *err);

#endif
