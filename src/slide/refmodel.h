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
 *
 * Unlike the engine, every mu is integrated (no SL_SLIDE_SKIPPED shortcut).
 * path_m, episodes and t_rest_s count the slip (the motion not stored in
 * the elastic spring), so the ringing of a stuck block on a spring of
 * stiffness mu N / U_y adds neither path nor episodes. After the record the
 * block is at rest when its elastic orbit can no longer reach the friction
 * limit; the extension is capped at 60 s + v/(mu g) (then NEVER_STOPS).
 * The plastic model needs plastic_substeps >= 2 dt sqrt(mu g / U_y) to
 * resolve the elastic period; it is not raised automatically.
 * Equations, sources and measured accuracy: docs/refmodels.md.
 */
#ifndef SL_REFMODEL_H
#define SL_REFMODEL_H

#include "slide/model.h"

/* Run one (set, mu) with opts->model SMOOTH or PLASTIC. hist may be NULL.
 * A solver failure is an error with context (time, step), never a silent
 * result. */
sl_status sl_refmodel_run(const sl_set *set, double mu, const sl_slide_opts *opts,
                          sl_slide_result *res, sl_history **hist, sl_error *err);

#endif
