/*
 * spectrum_type.h - a response spectrum at one damping as plain data
 * (sl_spectrum), its allocation and its log-log interpolation. The type sits
 * below both signal/ (which computes spectra, signal/spectrum.h) and io/
 * (which reads floor spectra, io/floor.h), so neither includes the other
 * for it.
 *
 * Units: Hz and m/s^2; damping as a ratio of critical.
 */
#ifndef SL_SPECTRUM_TYPE_H
#define SL_SPECTRUM_TYPE_H

#include <stddef.h>

#include "core/api.h"

/* A spectrum at one damping: plain data. Each struct owns its two arrays
 * (free with sl_spectrum_free). */
typedef struct sl_spectrum {
    size_t n;        /* number of frequencies */
    double damping;  /* ratio of critical damping */
    double *f_hz;    /* n frequencies, Hz, strictly increasing, > 0 */
    double *sa_ms2;  /* n pseudo-spectral accelerations, m/s^2 */
} sl_spectrum;

/* Allocate a spectrum of n points (arrays zeroed), damping set. Returns NULL
 * on n == 0 or allocation failure. Free with sl_spectrum_free(). */
SL_API sl_spectrum *sl_spectrum_alloc(size_t n, double damping);

/* Free a spectrum and its arrays; harmless on NULL. */
SL_API void sl_spectrum_free(sl_spectrum *s);

/* Free only the arrays of a spectrum embedded in another struct (sets them
 * to NULL and n to 0); harmless on NULL. */
SL_API void sl_spectrum_clear(sl_spectrum *s);

/* Log-log interpolation of a spectrum at f_hz (power law between points):
 * SA(f) = SA_i (f/f_i)^p, p = ln(SA_{i+1}/SA_i)/ln(f_{i+1}/f_i).
 * Outside [f_0, f_{n-1}] returns NAN. Values must be positive. */
SL_API double sl_spectrum_interp(const sl_spectrum *s, double f_hz);

#endif
