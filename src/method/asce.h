/*
 * asce.h - the approximate sliding displacement of ASCE/SEI 43-05,
 * Appendix A.1 (as applied in the source study; docs/spectra.md section 3),
 * and Newmark's (1965) rigid-block estimates for comparison.
 *
 * Steps, for a friction coefficient mu:
 *   1. mu_e = mu (1 - 0.4 A_v/g)               A_v: peak vertical acceleration
 *   2. c_s  = 2 mu_e g                          m/s^2
 *   3. SA_vH(f) = sqrt(SA_H1(f)^2 + 0.16 SA_H2(f)^2), 10 %-damped PSA,
 *      H1 the larger of the two at each frequency
 *   4. f_es = the lowest frequency where SA_vH = c_s: scanning upward from the
 *      lowest frequency, the first interval [f_i, f_i+1] with
 *      SA_vH(f_i) < c_s <= SA_vH(f_i+1), log-log interpolation in it
 *   5. delta_best = c_s/(2 pi f_es)^2           m
 *   6. delta_design = FS x delta_best            FS = SL_ASCE_FS (2.0)
 *   7. delta_design <= 1.5 x peak input displacement (100-40 combination of
 *      the horizontals) when it is known (the study's cap)
 *
 * Edge cases (engineering rules; each shown as a status flag, never as a
 * silent zero; docs/spectra.md):
 *   - no_sliding:  mu_e g >= the peak horizontal acceleration (the larger
 *     horizontal ZPA): delta_best = delta_design = 0, f_es = NAN.
 *   - below_fmin:  SA_vH(f_min) >= c_s (so the upward scan starts above
 *     c_s). The spectrum is extended below f_min at constant spectral
 *     displacement, SA = SA_vH(f_min) (f/f_min)^2, which crosses c_s at
 *     f_es = f_min sqrt(c_s/SA_vH(f_min)) and gives
 *     delta_best = SA_vH(f_min)/(2 pi f_min)^2 = SD_vH(f_min). (When
 *     mu_e <= 0, c_s = 0 and f_es = 0; delta is the same limit.)
 *   - no_crossing: SA_vH < c_s over the whole spectrum although mu_e g is
 *     below the horizontal ZPA: the method has no answer; f_es and both
 *     deltas are NAN.
 *   - capped:      delta_design was reduced to the cap.
 *
 * Units: SI (m, m/s^2, Hz). Memory: sl_asce_alloc() copies what it needs;
 * free with sl_asce_free().
 */
#ifndef SL_ASCE_H
#define SL_ASCE_H

#include <stddef.h>

#include "core/api.h"
#include "signal/spectrum.h"
#include "core/standards.h"
#include "core/status.h"

/* The constants of the method (ASCE/SEI 43-05 A.1 and the study). */
#define SL_ASCE_VERTICAL_COEF 0.4  /* mu_e = mu (1 - 0.4 A_v/g) */
#define SL_ASCE_CS_COEF 2.0        /* c_s = 2 mu_e g */
#define SL_ASCE_H2_COEF 0.4        /* SA_vH = sqrt(SA_H1^2 + (0.4 SA_H2)^2) */
#define SL_ASCE_FS 2.0             /* design = FS x best estimate */
/* SL_ASCE_DAMPING (10 %), SL_CAP_FACTOR (1.5) and SL_COMB_100_40 (0.4):
 * core/standards.h. */

/* Status flags of one result (0 = ok). */
enum {
    SL_ASCE_CAPPED = 1,
    SL_ASCE_NO_SLIDING = 2,
    SL_ASCE_NO_CROSSING = 4,
    SL_ASCE_BELOW_FMIN = 8
};

/* What the method needs. Zero-initialise, or use sl_asce_input_default(). */
typedef struct sl_asce_input {
    const sl_spectrum *h1;  /* horizontal PSA at 10 % damping, m/s^2 (required) */
    const sl_spectrum *h2;  /* the other horizontal (required; may be h1 itself) */
    double av_ms2;          /* peak vertical acceleration A_v, m/s^2, >= 0 */
    double zpa_h_ms2;       /* peak horizontal acceleration (larger of the two), m/s^2,
                               > 0: the no-sliding threshold */
    double pgd_m;           /* peak input displacement, 100-40 combination, m;
                               NAN (or <= 0) when unknown: no cap */
    double fs;              /* factor of safety (SL_ASCE_FS) */
    double g_ms2;           /* gravity (SL_G) */
} sl_asce_input;

/* One result. NAN where a quantity does not exist (see the edge cases). */
typedef struct sl_asce_result {
    double mu;              /* friction coefficient */
    double mu_e;            /* effective friction coefficient, step 1 */
    double cs_ms2;          /* c_s, m/s^2 */
    double fes_hz;          /* f_es, Hz */
    double delta_best_m;    /* best estimate, m */
    double delta_design_m;  /* design value (after the cap), m */
    double cap_m;           /* the cap, m (NAN when unknown) */
    unsigned flags;         /* SL_ASCE_* */
} sl_asce_result;

/* Defaults: fs = SL_ASCE_FS, g = SL_G, pgd_m = NAN, the rest zero/NULL. */
SL_API void sl_asce_input_default(sl_asce_input *in);

/* Opaque: the combined spectrum SA_vH and the input, prepared once for
 * many mu ("plan once, execute many"). */
typedef struct sl_asce sl_asce;

/* Prepare the method: checks the input (spectra with >= 2 positive,
 * strictly increasing frequencies and positive values; A_v >= 0; ZPA > 0;
 * FS > 0), and forms SA_vH (step 3) on the union of the two spectra's
 * frequencies inside their common range, each spectrum interpolated
 * log-log. Returns NULL and fills err (SL_EINVAL, SL_ENOMEM) on failure. */
SL_API sl_asce *sl_asce_alloc(const sl_asce_input *in, sl_error *err);

/* Free; harmless on NULL. */
SL_API void sl_asce_free(sl_asce *a);

/* The combined spectrum: its length, frequencies (Hz) and SA_vH (m/s^2).
 * Borrowed pointers, valid until sl_asce_free(). */
SL_API size_t sl_asce_combined(const sl_asce *a, const double **f_hz, const double **savh_ms2);

/* Steps 1-7 for one mu (>= 0, finite) into *res. Returns SL_OK or
 * SL_EINVAL. */
SL_API sl_status sl_asce_eval(const sl_asce *a, double mu, sl_asce_result *res, sl_error *err);

/* The status as text: "ok", or the flags joined by '+' in the order
 * no_sliding, no_crossing, below_fmin, capped (e.g. "below_fmin+capped").
 * Writes into buf (size n) and returns it. */
SL_API const char *sl_asce_status_name(unsigned flags, char *buf, size_t n);

/* Newmark (1965), rigid block with resistance mu g under a single
 * rectangular acceleration pulse of peak A (pga_ms2) and velocity V
 * (pgv_ms):
 *   symmetric resistance ("Newmark I"):  U = V^2/(2 mu g) (1 - mu g/A)
 *   asymmetric, one-way ("Newmark II"):  U = (2 V^2/(mu g)) (1 - mu g/A)^2
 * Both return 0 when mu g >= A; NAN when mu <= 0, A <= 0, V < 0 or an
 * input is not finite. Metres. */
SL_API double sl_asce_newmark_sym(double pgv_ms, double pga_ms2, double mu, double g_ms2);
SL_API double sl_asce_newmark_asym(double pgv_ms, double pga_ms2, double mu, double g_ms2);

#endif
