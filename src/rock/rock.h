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
 * is ended at rest (the rule and its threshold: rock.c, docs/model.md);
 * uplift is then checked again by (K3).
 *
 * Tipping and overturning: the block has tipped when |theta| reaches alpha
 * (past its balance point under gravity alone) and has overturned when
 * |theta| reaches pi/2 (lying on its side); the run stops there.
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

/* Settings of the integrator (sl_rock_opts_default). */
typedef struct sl_rock_opts {
    double rtol;          /* relative accuracy aimed at for the peak rotation */
    unsigned substeps;    /* > 0: fixed sub-steps per sample (no error control) */
} sl_rock_opts;

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
} sl_rock_result;

/* Housner's restitution (K4) of a block with half base b_m and centre of
 * mass at h_m. */
SL_API double sl_rock_housner_r(double b_m, double h_m);

/* Run the block on a_h (n samples at dt_s, m/s^2) and a_v (n samples, or
 * NULL: no vertical), each multiplied by its scale (a_h by scale_h, a_v by
 * scale_v) on the fly. SL_EINVAL (bad block, n < 2, dt <= 0, a sample not
 * finite), SL_ENOMEM. The block starts at rest. Reentrant; allocates
 * nothing on the way. */
SL_API sl_status sl_rock_run(const sl_rock_block *blk, const double *a_h_ms2,
                             const double *a_v_ms2, size_t n, double dt_s, double scale_h,
                             double scale_v, const sl_rock_opts *o, sl_rock_result *out,
                             sl_error *err);

/* The weak-axis history of a set at orientation theta_deg from H1:
 * out[i] = cos(phi) h1[i] + sin(phi) h2[i] (h2 NULL: cos(phi) h1[i]). */
SL_API void sl_rock_project(const double *h1, const double *h2, size_t n, double phi_deg,
                            double *out);

/* Optional history of a run (sl_rock_run_history): theta and theta' at
 * every sample, and every event. */
typedef struct sl_rock_history {
    size_t n;
    double *t_s, *theta_rad, *omega_rad_s;  /* n each, at the samples */
} sl_rock_history;

/* As sl_rock_run, also filling h (allocated here; free with
 * sl_rock_history_free). After an overturn the history holds pi/2 sgn. */
SL_API sl_status sl_rock_run_history(const sl_rock_block *blk, const double *a_h_ms2,
                                     const double *a_v_ms2, size_t n, double dt_s,
                                     double scale_h, double scale_v, const sl_rock_opts *o,
                                     sl_rock_result *out, sl_rock_history *h, sl_error *err);
SL_API void sl_rock_history_free(sl_rock_history *h);

#endif
