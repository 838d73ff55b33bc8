/*
 * slide.h - nonlinear time-history analysis (NLTHA) of a rigid block sliding
 * on a level floor with isotropic Coulomb friction (static = kinetic).
 *
 * Equation of motion (../shared/docs/REFERENCE.md section 1), u = block
 * displacement relative to the floor, a_g = horizontal floor acceleration
 * (1-D or 2-D), a_v = vertical floor acceleration (up positive):
 *
 *     u'' = -a_g(t) - mu N(t) s,   N = max(g + a_v, 0)              (1)
 *     s = u'/|u'| while sliding,   |s| <= 1 while stuck.
 *
 * N <= 0 is lift-off: no friction (the instants are counted). The input is
 * taken as piecewise linear between samples; after the last sample the floor
 * is at rest (a_g = a_v = 0) and the block slides on until it stops, so the
 * peak is never cut off.
 *
 * Integrators (docs/model.md, docs/integrators.md):
 *  - 1-D (H1 only): exact for piecewise-linear input. Within a step the
 *    relative velocity is a quadratic in time; stop, start and lift-off
 *    instants are roots of quadratics or linear functions.
 *  - 2-D (H1 and H2): `substeps` sub-steps per input step; implicit
 *    midpoint friction while sliding on, a split step at stops and
 *    reversals, the implicit velocity projection onto the friction disk
 *    (Moreau-Jean) from rest; forcing integrated exactly. Observed order
 *    about 2 in the sub-step (1.5-2 on real records); error of the peak
 *    about 1e-3 at the default 8 sub-steps; docs/integrators.md.
 *  - Asymmetric 1-D: friction mu against sliding toward -x ("downslope",
 *    where a positive floor acceleration pushes the block) and mu*up_ratio
 *    toward +x; up_ratio = INFINITY is one-way sliding as in Newmark's
 *    asymmetric case and SLAMMER's rigid-block analysis.
 *
 * Units: SI throughout (m, s, m/s^2); mu dimensionless.
 */
#ifndef SL_SLIDE_H
#define SL_SLIDE_H

#include <stddef.h>

#include "io/motion.h"
#include "core/status.h"

typedef enum sl_model {
    SL_MODEL_EXACT = 0, /* the engine: exact 1-D, projection 2-D */
    SL_MODEL_SMOOTH,    /* Wang-Wen/Park-Wen smoothed hysteretic model, GSL stiff ODE */
    SL_MODEL_PLASTIC    /* elastic-perfectly-plastic, Newmark average acceleration */
} sl_model;

/* Default number of 2-D projection sub-steps per input step. */
#define SL_SLIDE_DEFAULT_SUBSTEPS 8u

typedef struct sl_slide_opts {
    sl_model model;
    double g_ms2;        /* gravity, m/s^2 (SL_G) */
    unsigned substeps;   /* 2-D sub-steps per input sample (>= 1) */
    double up_ratio;     /* 1-D: resistance toward +x = mu * up_ratio (1 = symmetric,
                            INFINITY = one-way); must be 1 in 2-D */
    int invert;          /* 1: multiply the horizontal records by -1 (SLAMMER "inverted") */
    /* Smoothed model (SL_MODEL_SMOOTH): Z' = (A - |Z|^eta (beta sgn + gamma)) u'/U_y */
    double smooth_eta;   /* exponent eta, 2..20 (5) */
    double smooth_uy_m;  /* yield displacement U_y, m (1e-4) */
    double smooth_rtol;  /* solver relative tolerance (1e-6) */
    double smooth_atol;  /* solver absolute tolerance on u, m (1e-9) */
    int smooth_solver;   /* 0 msbdf, 1 rk4imp, 2 bsimp, 3 rkf45 (see refmodel.h) */
    /* Elastic-plastic model (SL_MODEL_PLASTIC): initial stiffness k = mu N / U_y */
    double plastic_uy_m;    /* yield displacement, m (1e-4) */
    unsigned plastic_substeps; /* sub-steps per input step (>= 1) (8) */
    int keep_going;      /* 1 (default): after the record, integrate until rest */
} sl_slide_opts;

/* Fill defaults (documented next to each field). */
void sl_slide_opts_default(sl_slide_opts *o);

/* Status flags of one result. */
enum {
    SL_SLIDE_SKIPPED = 1,     /* mu g >= the most the motion can demand: no sliding, not integrated */
    SL_SLIDE_NEVER_STOPS = 2, /* mu = 0 (or lift-off at the end): block still moving at record end */
    SL_SLIDE_LIFTOFF = 4      /* at least one sample had a_v <= -g */
};

/* What one (motion, mu) analysis returns. Displacements in m. */
typedef struct sl_slide_result {
    double mu;
    double peak_m;        /* max over time of |u| (vector), the quantity spectra use */
    double peak_x_m;      /* max |u_x| */
    double peak_y_m;      /* max |u_y| (0 in 1-D) */
    double t_peak_s;      /* time of peak_m */
    double residual_m;    /* |u| at rest */
    double residual_x_m;  /* u_x at rest (signed) */
    double residual_y_m;  /* u_y at rest (signed) */
    double path_m;        /* sliding path length, integral of |u'| dt */
    double max_speed_ms;  /* max |u'| */
    double t_rest_s;      /* time the block came to rest for good */
    double slide_time_s;  /* total time spent sliding (2-D: to the sub-step) */
    long episodes;        /* number of stick-to-slip transitions */
    long liftoff_samples; /* samples with a_v <= -g */
    int flags;            /* SL_SLIDE_* */
} sl_slide_result;

/* Time history of one analysis, sampled at the record's dt, extended past
 * the record until rest. F/W is the friction force on the block divided by
 * its weight (= absolute block acceleration / g), per axis. */
typedef struct sl_history {
    size_t n;
    double dt_s;
    double *t_s, *ux_m, *uy_m, *vx_ms, *vy_ms, *fx_w, *fy_w;
} sl_history;

/* Allocate a history with room for cap samples (n = 0); NULL on failure.
 * Free with sl_history_free(). */
sl_history *sl_history_alloc(size_t cap, double dt_s);
/* Grow every array to hold cap samples. Returns 0, or -1 with the arrays
 * intact. */
int sl_history_reserve(sl_history *h, size_t cap);
void sl_history_free(sl_history *h);

/* The smallest mu at which the block can never slide:
 * max_i |a_h(t_i)| / N(t_i) over samples (INFINITY with lift-off). Exact for
 * piecewise-linear input since |a_h| is convex and N linear on each step.
 * With up_ratio != 1 this is the threshold for the downslope resistance. */
double sl_slide_mu_threshold(const sl_set *set, const sl_slide_opts *opts);

/* Analyse one checked set for n_mu friction coefficients (each >= 0) at
 * once; res[k] is for mu[k]. mu at or above the threshold is not
 * integrated (flag SL_SLIDE_SKIPPED, zero displacement). Returns SL_OK or an
 * error (bad mu, bad options, solver failure for the reference models). */
sl_status sl_slide_run(const sl_set *set, const double *mu, size_t n_mu,
                       const sl_slide_opts *opts, sl_slide_result *res,
                       sl_error *err);

/* As sl_slide_run for one mu, also returning the history (*hist, caller
 * frees with sl_history_free). */
sl_status sl_slide_history(const sl_set *set, double mu, const sl_slide_opts *opts,
                           sl_slide_result *res, sl_history **hist, sl_error *err);

/* Many sets: res[i * n_mu + k] for set i and mu[k]; runs the sets in
 * parallel with OpenMP. Results do not depend on the thread count. */
sl_status sl_slide_batch(const sl_set *sets, size_t n_sets, const double *mu,
                         size_t n_mu, const sl_slide_opts *opts,
                         sl_slide_result *res, sl_error *err);

#endif
