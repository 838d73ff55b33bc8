/*
 * rock.h - nonlinear time-history analysis of a rigid rectangular block
 * rocking on a rigid floor (Housner 1963, "The behavior of inverted pendulum
 * structures during earthquakes", BSSA 53(2)); docs/model.md, "Rocking".
 *
 * The block: uniform mass, base width 2b, centre of mass at height h (total
 * height 2h), so that
 *
 *     R = sqrt(b^2 + h^2),  alpha = atan(b / h),  p^2 = 3 g / (4 R)     (K1)
 *
 * (I_O = (4/3) m R^2 about a base corner). Planar rocking about a base
 * corner, theta > 0 about one corner, theta < 0 about the other:
 *
 *     theta'' = -p^2 [ (1 + a_v/g) sin(alpha sgn(theta) - theta)
 *                      + (a_h/g) cos(alpha sgn(theta) - theta) ]        (K2)
 *
 * with a_h the floor's horizontal acceleration along the block's weak axis
 * and a_v its vertical acceleration (up positive), both piecewise linear
 * between samples; after the last sample the floor is at rest and the
 * block rocks on until it comes to rest or overturns.
 *
 * Contact. At rest (theta = theta' = 0) the block uplifts when
 *
 *     |a_h| > (g + a_v) tan(alpha)                                     (K3)
 *
 * (theta > 0 when a_h < 0), the instant located exactly (a_h and a_v are
 * linear within a sample). Impact at theta = 0: theta' <- r theta' with,
 * unless the caller gives r, Housner's value from the angular momentum
 * about the new corner,
 *
 *     r = 1 - (3/2) sin^2(alpha).                                      (K4)
 *
 * A cascade of impacts that would bring the block to rest in finite time
 * is ended at rest: after an impact, when the net acceleration at theta = 0
 * pushes the block back (a_r > 0) and its rebound theta'^2 / (2 a_r) is
 * below rest_fraction alpha (SL_ROCK_REST_FRACTION); r = 0 rests at once.
 * Uplift is then checked again by (K3) (rock.c, docs/model.md).
 *
 * Tipping and overturning: the block has tipped when |theta| reaches alpha
 * (past its balance point under gravity alone; the run goes on) and has
 * overturned when |theta| reaches pi/2 (lying on its side); the run stops
 * there. Every event instant is located on the integrator's own step to
 * round-off (rock.c).
 *
 * Excursion: rocking about a corner carries the top corner on that side
 * 2 h sin|theta| beyond the footprint (the clearance a rocking item needs);
 * excursion_m is its largest value, 2 h sin(peak |theta|) (2h once
 * overturned).
 *
 * Units: SI (m, s, m/s^2, rad).
 */
#ifndef SL_ROCK_H
#define SL_ROCK_H

#include <stddef.h>

#include "core/api.h"
#include "core/status.h"

/* The block. */
typedef struct sl_rock_block {
    double b_m;           /* half the base width along the rocking axis, m (> 0) */
    double h_m;           /* height of the centre of mass, m (> 0) */
    double restitution;   /* r of the impact rule, in [0, 1]; a negative value or NAN:
                             Housner's (K4) */
} sl_rock_block;

/* Settings of the integrator (sl_rock_opts_default).
 *
 * Between events the block is integrated by the 3-stage, fourth-order
 * Runge-Kutta-Nystrom method for theta'' = f(t, theta) on sub-steps aligned
 * with the samples (the forcing is linear within a step), at most
 * H(rtol) / omega_s long, omega_s = p ((1 + a_v/g)^2 + (a_h/g)^2)^(1/4)
 * the largest frequency of the linearised (K2) over the sample and
 * H(rtol) = SL_ROCK_H_COEF rtol^(1/4) (docs/integrators.md, "Rocking",
 * has the measured accuracy). */
typedef struct sl_rock_opts {
    double rtol;          /* relative accuracy aimed at for the peak rotation */
    unsigned substeps;    /* > 0: fixed sub-steps per sample (no error control) */
    double rest_fraction; /* the rest rule's threshold: after an impact the block is set at
                             rest when the excursion it can reach is below rest_fraction
                             alpha (rock.c, docs/model.md); default SL_ROCK_REST_FRACTION */
    double theta0_rad;    /* initial state (default 0, 0: at rest); |theta0| < pi/2 */
    double omega0_rad_s;
} sl_rock_opts;

/* Default rtol: keeps the peak rotation of non-chaotic cases within 0.1 %
 * of a converged reference (docs/integrators.md, "Rocking"). */
#define SL_ROCK_DEFAULT_RTOL 1e-4
#define SL_ROCK_RTOL_MIN 1e-12
#define SL_ROCK_RTOL_MAX 1e-2
/* H(rtol) = SL_ROCK_H_COEF rtol^(1/4): the step's share of a radian of the
 * block's fastest linearised motion (0.5 at rtol 1, 0.05 at rtol 1e-4). */
#define SL_ROCK_H_COEF 0.5
#define SL_ROCK_SUBSTEPS_MAX 100000u
/* The rest rule: a rebound that cannot reach this fraction of alpha ends
 * the cascade at rest. */
#define SL_ROCK_REST_FRACTION 1e-6
/* The free rocking after the record is followed at most SL_ROCK_TAIL_MAX_P / p s
 * (it ends at its first peak, within a few 1/p). */
#define SL_ROCK_TAIL_MAX_P 1e4

SL_API void sl_rock_opts_default(sl_rock_opts *o);

/* What one run gives. Times NAN when the event did not happen. */
typedef struct sl_rock_result {
    double alpha_rad;          /* atan(b / h) */
    double p_rad_s;            /* frequency parameter p of (K1), rad/s */
    double restitution;        /* r used */
    double peak_theta_rad;     /* largest |theta| (pi/2 once overturned) */
    double peak_theta_over_alpha;
    double t_peak_s;
    double excursion_m;        /* 2 h sin(peak |theta|) */
    int uplifted;              /* the block left rest at least once */
    int tipped;                /* |theta| reached alpha */
    int overturned;            /* |theta| reached pi/2 */
    double t_uplift_s, t_tip_s, t_overturn_s; /* first uplift, tip, overturn */
    size_t impacts;            /* impacts at theta = 0 */
    size_t uplifts;            /* times the block left rest */
    size_t rests;              /* impact cascades ended by the rest rule */
    size_t liftoff_samples;    /* samples with g + a_v < 0: (K3) holds whatever a_h; the
                                  block would leave the floor, which the model does not
                                  describe (docs/model.md): treat the result as flagged */
    double t_end_s;            /* where the integration ended: the last sample when the
                                  block is at rest there; else the first peak of the free
                                  rocking after the record (all later peaks are lower), a
                                  rest, or the overturn */
    size_t steps;              /* integrator steps taken (cost) */
} sl_rock_result;

/* Housner's restitution (K4) of a block with half base b_m and centre of
 * mass at h_m: 1 - (3/2) b^2/(b^2 + h^2), and 0 where that is negative (a
 * block wider than about 1.4 times its height does not rebound). */
SL_API double sl_rock_housner_r(double b_m, double h_m);

/* Run the block on a_h (n samples at dt_s, m/s^2) and a_v (n samples, or
 * NULL: no vertical), each multiplied by its scale (a_h by scale_h, a_v by
 * scale_v) on the fly. SL_EINVAL (bad block, bad options, n < 2, dt <= 0,
 * a scale or a sample not finite), SL_ENOMEM, SL_ENOCONV (the free rocking
 * after the record did not end within SL_ROCK_TAIL_MAX_P / p s: not seen).
 * The block starts at rest (or in the state of o->theta0_rad,
 * o->omega0_rad_s); o NULL: the defaults. Reentrant; allocates nothing on
 * the way. */
SL_API sl_status sl_rock_run(const sl_rock_block *blk, const double *a_h_ms2,
                             const double *a_v_ms2, size_t n, double dt_s, double scale_h,
                             double scale_v, const sl_rock_opts *o, sl_rock_result *out,
                             sl_error *err);

/* The weak-axis history of a set at orientation phi_deg from H1:
 * out[i] = cos(phi) h1[i] + sin(phi) h2[i] (h2 NULL: cos(phi) h1[i]). Exact
 * under the symmetries of the orientation grid: quarter turns are exact, and
 * H1 and H2 exchanged at 90 - phi give the same bits as at phi. */
SL_API void sl_rock_project(const double *h1, const double *h2, size_t n, double phi_deg,
                            double *out);

/* The events of a run (sl_rock_history). */
typedef enum sl_rock_event_kind {
    SL_ROCK_EV_UPLIFT = 0, /* left rest: (K3) */
    SL_ROCK_EV_IMPACT,     /* theta = 0: omega_before -> omega = r omega_before */
    SL_ROCK_EV_PEAK,       /* a local largest |theta| (theta' = 0) */
    SL_ROCK_EV_TIP,        /* |theta| = alpha, the first time */
    SL_ROCK_EV_OVERTURN,   /* |theta| = pi/2: the run stops */
    SL_ROCK_EV_REST,       /* a cascade ended at rest by the rest rule (or r = 0) */
    SL_ROCK_EV_END,        /* the integration ends (t_end_s) */
    SL_ROCK_EV_COUNT
} sl_rock_event_kind;

typedef struct sl_rock_event {
    sl_rock_event_kind kind;
    double t_s, theta_rad, omega_rad_s; /* the state after the event */
    double omega_before_rad_s;          /* an impact's omega before it (else = omega) */
} sl_rock_event;

/* "uplift", "impact", "peak", "tip", "overturn", "rest", "end". */
SL_API const char *sl_rock_event_name(sl_rock_event_kind k);

/* Optional history of a run (sl_rock_run_history): theta and theta' at
 * every sample of the record (rows 0 .. n_record - 1, t = i dt), then on
 * through the free rocking after it at the same dt, and a last row at
 * t_end_s; and every event in time order. */
typedef struct sl_rock_history {
    size_t n;                               /* rows */
    double *t_s, *theta_rad, *omega_rad_s;  /* n each */
    size_t n_events;
    sl_rock_event *events;                  /* n_events */
} sl_rock_history;

/* As sl_rock_run, also filling h (allocated here; free with
 * sl_rock_history_free). After an overturn the history holds pi/2 sgn
 * to the end of the record. */
SL_API sl_status sl_rock_run_history(const sl_rock_block *blk, const double *a_h_ms2,
                                     const double *a_v_ms2, size_t n, double dt_s,
                                     double scale_h, double scale_v, const sl_rock_opts *o,
                                     sl_rock_result *out, sl_rock_history *h, sl_error *err);
SL_API void sl_rock_history_free(sl_rock_history *h);

#endif
