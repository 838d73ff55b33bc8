/*
 * design.h - design sliding spectra of one floor, the ASCE/NLTHA crossover
 * and the required clearance.
 *
 * From the peak vector sliding displacements of N motion sets (NLTHA, the
 * engine) and the ASCE/SEI 43-05 best estimates over the same friction grid:
 *
 *   NLTHA best estimate   m(mu)  = mean over sets of peak |u|
 *   NLTHA design          D_N    = min(FS_N m, cap),   FS_N = 3.0 (ASCE 43-05
 *                                  A.1: 3.0 x the mean of >= 5 analyses)
 *   ASCE design           D_A    = min(FS_A delta_s, cap), FS_A = 2.0
 *   cap                   1.5 x the mean over sets of the peak floor
 *                         displacement by the 100-40 rule (the study's cap)
 *   x                     = mu g / ZPA_h (the floor's horizontal ZPA)
 *
 * The crossover (the source study's quantity) is the x below which ASCE is
 * unconservative: when D_A < D_N at the lowest mu of the grid, the x where
 * D_A - D_N first becomes non-negative, interpolated linearly in x; when
 * ASCE is conservative at the lowest mu there is no crossover in the grid.
 * Every range of x where D_A < D_N is listed, wherever it lies (e.g. at
 * high x, where ASCE's "no sliding" rule ignores the vector sum of the
 * horizontals and the vertical, and NLTHA still gives millimetres). The required clearance is D_N
 * by default (ASCE 43-05 permits NLTHA everywhere), or D_A, or max(D_N, D_A).
 *
 * Units: SI (m, m/s^2); mu dimensionless. Plain data; the caller owns every
 * array it passes; sl_design_free() frees what sl_design_compute() made.
 */
#ifndef SL_DESIGN_H
#define SL_DESIGN_H

#include <stddef.h>

#include "core/api.h"
#include "core/standards.h"
#include "core/status.h"

/* ASCE/SEI 43-05 factor on the mean of the nonlinear analyses. */
#define SL_NLTHA_FS 3.0
/* The study's cap: the design value need not exceed 1.5 x the input's
 * peak displacement (100-40 combination of the horizontals). */
#define SL_DESIGN_CAP_FACTOR SL_CAP_FACTOR /* core/standards.h */
/* ASCE 43-05 minimum number of NLTHA motions. */
#define SL_NLTHA_MIN_SETS 5

typedef enum sl_clearance_policy {
    SL_CLEARANCE_NLTHA = 0, /* D_N (default) */
    SL_CLEARANCE_ASCE,      /* D_A */
    SL_CLEARANCE_ENVELOPE   /* max(D_N, D_A) */
} sl_clearance_policy;

/* Name of a policy ("nltha", "asce", "envelope") and its parser (-1 if
 * unknown). */
SL_API const char *sl_clearance_policy_name(sl_clearance_policy p);
SL_API int sl_clearance_policy_parse(const char *s);

enum {
    SL_DESIGN_NO_SLIDING = 1,     /* mu g at or above every set's demand: NLTHA not run, 0 */
    SL_DESIGN_NLTHA_CAPPED = 2,   /* D_N = cap */
    SL_DESIGN_ASCE_CAPPED = 4,    /* D_A = cap */
    SL_DESIGN_UNCONSERVATIVE = 8, /* D_A < D_N */
    SL_DESIGN_ASCE_UNDEFINED = 16 /* ASCE gave no value (e.g. no crossing): D_A = NAN */
};

typedef struct sl_design_row {
    double mu;
    double x;             /* mu g / ZPA_h */
    double nltha_mean_m;  /* mean over sets */
    double nltha_sd_m;    /* sample standard deviation over sets */
    double nltha_design_m;
    double asce_best_m;   /* delta_s (NAN when undefined) */
    double asce_design_m;
    double cap_m;
    double clearance_m;   /* by the policy */
    unsigned flags;       /* SL_DESIGN_* */
} sl_design_row;

typedef struct sl_design_range {
    double x_from, x_to;  /* a range of mu g/ZPA where ASCE < NLTHA (grid points) */
    /* The same range with its ends where D_A - D_N changes sign, linearly
     * interpolated between the grid rows on either side; an end that
     * reaches the first or last row of the grid (open_lo, open_hi = 1)
     * stays at that row: the grid does not say where the range ends. */
    double mu_lo, mu_hi, x_lo, x_hi;
    int open_lo, open_hi;
} sl_design_range;

typedef struct sl_design {
    size_t n;              /* rows = friction values */
    sl_design_row *rows;
    double zpa_h_ms2;
    double cap_m;
    sl_clearance_policy policy;
    size_t n_sets;         /* motion sets behind the NLTHA mean */
    double fs_nltha, fs_asce, cap_factor; /* the factors used */
    int has_crossover;     /* 1 when ASCE is unconservative at the lowest mu and
                              becomes conservative within the grid */
    double crossover_x;    /* mu g / ZPA there (NAN if none) */
    double crossover_mu;   /* the same as mu */
    size_t n_ranges;       /* ranges where ASCE < NLTHA */
    sl_design_range *ranges;
} sl_design;

/* Inputs: n_mu friction values (increasing), n_sets motion sets,
 * peak_m[s * n_mu + k] the peak of set s at mu[k] (0 when not integrated),
 * no_slide[k] nonzero when mu[k] g is at or above every set's demand,
 * asce_best_m[k] the ASCE best estimate (NAN when undefined), pgd_m[s] the
 * 100-40 peak displacement of set s, zpa_h_ms2 > 0. */
typedef struct sl_design_input {
    size_t n_mu, n_sets;
    const double *mu;
    const double *peak_m;
    const int *no_slide;
    const double *asce_best_m;
    const double *pgd_m;
    double zpa_h_ms2;
    double g_ms2;
    double fs_nltha;       /* SL_NLTHA_FS */
    double fs_asce;        /* SL_ASCE_FS */
    double cap_factor;     /* SL_DESIGN_CAP_FACTOR */
    sl_clearance_policy policy;
} sl_design_input;

/* Defaults for the factors, g and the policy; the caller sets the rest. */
SL_API void sl_design_input_default(sl_design_input *in);

/* Compute the design spectra, crossover and clearance. Returns NULL and
 * fills err on bad input (n_mu == 0, n_sets == 0, mu not increasing,
 * ZPA <= 0, negative or non-finite peaks). */
SL_API sl_design *sl_design_compute(const sl_design_input *in, sl_error *err);

SL_API void sl_design_free(sl_design *d);

/* The required clearance at an arbitrary mu, m: linear interpolation in mu
 * between the grid rows k and k + 1 with mu_k <= mu <= mu_k+1,
 *   c(mu) = c_k + (mu - mu_k) (c_k+1 - c_k) / (mu_k+1 - mu_k),
 * exact at grid points; NAN outside [mu_0, mu_n-1] or for a NAN mu. This is
 * the one definition: the workbook's Lookup formula is its visible twin
 * (report.c writes it; tests/test_lookup.c recalculates it with
 * LibreOffice and compares). */
SL_API double sl_design_clearance_at(const sl_design *d, double mu);

#endif
