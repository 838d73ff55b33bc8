/*
 * standards.h - the factors of the standards and of the source study,
 * declared once, each with its source (the standard's section, or the source
 * study: docs/validation.md). Every
 * module that needs one includes this header; none retypes the number.
 */
#ifndef SL_STANDARDS_H
#define SL_STANDARDS_H

#include <stddef.h>

#include "core/api.h"

/* Damping ratio of the spectra of the ASCE/SEI 43-05 method (Appendix A.1,
 * step 3: 10 %-damped pseudo-accelerations); the source study also matched
 * its ground set to RG 1.60 at this damping (docs/validation.md). */
#define SL_ASCE_DAMPING 0.10

/* The study's cap: a design sliding displacement need not exceed 1.5 x the
 * peak displacement of the input (the source study; ASCE/SEI 43-05 A.1
 * as it applied it, step 7). */
#define SL_CAP_FACTOR 1.5

/* The 100-40 combination of the two horizontal peak displacements,
 * max(D1 + 0.4 D2, D2 + 0.4 D1) (ASCE 4-98 3.2.7.1, as the source study). */
#define SL_COMB_100_40 0.4

/* The default friction grid: mu = 0.05 to 0.80 step 0.01, 76 values (the
 * source study's range for the real sets, on a finer step). */
#define SL_MU_GRID_FROM 0.05
#define SL_MU_GRID_TO 0.80
#define SL_MU_GRID_STEP 0.01
#define SL_MU_GRID_N 76
#define SL_MU_GRID_TEXT "0.05:0.80:0.01" /* the same, as --mu-range takes it */

/* Fill mu[0 .. SL_MU_GRID_N - 1] with the default grid, each value
 * computed from its index (from + k step, no accumulated round-off). */
SL_API void sl_mu_grid_default(double mu[SL_MU_GRID_N]);

#endif
