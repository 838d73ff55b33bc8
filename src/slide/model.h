/*
 * model.h - the data of a sliding-block analysis, shared by the engine
 * (engine.c), the reference models (refmodel.c) and the dispatch above both
 * (slide.c): model choice, options, one result, one time history.
 * Equation of motion and units: slide.h.
 */
#ifndef SL_MODEL_H
#define SL_MODEL_H

#include <stddef.h>

#include "core/api.h"
#include "core/status.h"
#include "io/motion.h"

typedef enum sl_model {
    SL_MODEL_EXACT = 0, /* the engine: exact 1-D, projection 2-D */
    SL_MODEL_SMOOTH,    /* Wang-Wen/Park-Wen smoothed hysteretic model, GSL stiff ODE */
    SL_MODEL_PLASTIC    /* elastic-perfectly-plastic, Newmark average acceleration */
} sl_model;

/* Default accuracy of the engine: relative error of every reported peak
 * (the bound the 2-D error control aims at; the 1-D kernel is exact), and
 * the absolute error below which nothing is refined, m (a peak under 1 mm
 * is then held to 1 um). docs/integrators.md. */
#define SL_SLIDE_DEFAULT_RTOL 1e-3
#define SL_SLIDE_DEFAULT_ATOL_M 1e-6
/* The range of the engine's rtol (sl_slide_opts.rtol). */
#define SL_SLIDE_RTOL_MIN 1e-9
#define SL_SLIDE_RTOL_MAX 0.1
/* Default 2-D sub-steps per sample: 0 = error-controlled (rtol, atol_m). */
#define SL_SLIDE_DEFAULT_SUBSTEPS 0u

typedef struct sl_slide_opts {
    sl_model model;
    double g_ms2;        /* gravity, m/s^2 (SL_G) */
    double rtol;         /* 2-D: relative error of the peak (SL_SLIDE_DEFAULT_RTOL), in [1e-9, 0.1] */
    double atol_m;       /* 2-D: absolute error of the peak not worth refining, m (1e-6), > 0 */
    unsigned substeps;   /* 2-D: 0 (default) error control by rtol/atol_m; N >= 1 expert
                            override, N equal sub-steps per sample and no estimate */
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
SL_API void sl_slide_opts_default(sl_slide_opts *o);

/* Apply the accuracy a user asks for, one relative tolerance rtol and one
 * absolute tolerance atol_m (m), to the model o->model: for SL_MODEL_SMOOTH
 * the GSL ODE driver's eps_rel and eps_abs on u (smooth_rtol, smooth_atol;
 * refmodel.c, gsl_odeiv2_driver_alloc_scaled_new), for the engine the
 * bound its 2-D error control aims at, |error of a peak| <= max(rtol peak,
 * atol_m) (rtol, atol_m; docs/integrators.md). A value <= 0 keeps the
 * setting as it is. Returns SL_OK, or SL_EINVAL (err set, o unchanged) for
 * an engine rtol outside [SL_SLIDE_RTOL_MIN, SL_SLIDE_RTOL_MAX]. */
SL_API sl_status sl_slide_opts_set_tol(sl_slide_opts *o, double rtol, double atol_m, sl_error *err);

/* The model named "exact", "smooth" or "plastic"; -1 for any other name. */
SL_API int sl_model_parse(const char *name);
/* The smoothed model's solver (sl_slide_opts.smooth_solver) named "msbdf",
 * "rk4imp", "bsimp" or "rkf45": 0..3; -1 for any other name. */
SL_API int sl_smooth_solver_parse(const char *name);

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
    double err_est_m;     /* estimated absolute error of peak_m, m: 0 for the exact 1-D
                             kernel, NAN for fixed 2-D sub-steps and the reference models */
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
SL_API sl_history *sl_history_alloc(size_t cap, double dt_s);
/* Grow every array to hold cap samples. Returns 0, or -1 with the arrays
 * intact. */
SL_API int sl_history_reserve(sl_history *h, size_t cap);
SL_API void sl_history_free(sl_history *h);

/* Append one sample to a history that has room for it (library-internal). */
SL_API void sl_history_push(sl_history *h, double t, double ux, double uy, double vx, double vy,
                            double fx, double fy);

#endif
