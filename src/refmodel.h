/*
 * refmodel.h - reference models for the sliding block, kept out of the fast
 * path: same inputs and outputs as the engine (slide.h).
 *
 *  - SL_MODEL_SMOOTH: the smoothed biaxial hysteretic model (Park-Wen /
 *    Wang-Wen variables Z_x, Z_y; A = 1, beta = gamma = 0.5) integrated with
 *    GSL's stiff ODE drivers at controlled tolerances.
 *  - SL_MODEL_PLASTIC: elastic-perfectly-plastic spring with a high initial
 *    stiffness, Newmark average acceleration with return mapping (what
 *    OpenSees' flat slider bearing does).
 */
#ifndef SL_REFMODEL_H
#define SL_REFMODEL_H

#include "slide.h"

/* Run one (set, mu) with opts->model SMOOTH or PLASTIC. hist may be NULL.
 * A solver failure is an error with context (time, step), never a silent
 * result. */
sl_status sl_refmodel_run(const sl_set *set, double mu, const sl_slide_opts *opts,
                          sl_slide_result *res, sl_history **hist, sl_error *err);

#endif
