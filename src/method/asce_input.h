/*
 * asce_input.h - the input of the ASCE/SEI 43-05 method (asce.h), assembled
 * in one place from whichever source it comes from:
 *
 *   source        H1, H2 spectra (10 %)        A_v               ZPA_h                 PGD (cap)
 *   floor file    its sa_0.10 of H1 and H2     V zpa             max(H1 zpa, H2 zpa)   unknown
 *                 (or the caller's fallback)
 *   motion set    PSA of H1 and H2 on the      peak |a_V|        max(PGA_H1, PGA_H2)   100-40 of the
 *                 default grid (spectrum.h)    (0 without V)     (sl_set_pga_h)        horizontals
 *   RG 1.60       horizontal spectrum at PGA   PGA (vertical     PGA                   1.4 x 36 in x PGA
 *                 for H1 and H2                ZPA = PGA)                              (100-40 of two equal)
 *
 * ZPA_h is the LARGER horizontal peak (ASCE/SEI 43-05 A.1: no sliding when
 * mu_e g >= the horizontal peak acceleration). Damping: SL_ASCE_DAMPING
 * (core/standards.h).
 *
 * Memory: an sl_asce_source owns the spectra it computed (own[]); the
 * input's h1/h2 point into own[] or into the floor (borrowed: the floor
 * must outlive the source). Free with sl_asce_source_free().
 */
#ifndef SL_ASCE_INPUT_H
#define SL_ASCE_INPUT_H

#include "core/api.h"
#include "core/status.h"
#include "io/floor.h"
#include "io/motion.h"
#include "method/asce.h"

typedef struct sl_asce_source {
    sl_asce_input in;     /* ready for sl_asce_alloc(); fs = SL_ASCE_FS, g = SL_G */
    sl_spectrum *own[2];  /* spectra made here (NULL when borrowed) */
} sl_asce_source;

/* The floor's horizontal ZPA: the larger of the H1 and H2 zpa, m/s^2. */
SL_API double sl_asce_floor_zpa_h(const sl_floor *fl);

/* From a floor file. The spectra are the floor's 10 %-damped H1 and H2
 * (sl_floor_sa10); when the floor lacks one and `fallback` is not NULL,
 * fallback[0] and fallback[1] (borrowed, 10 %-damped) are used instead.
 * Returns SL_OK, or SL_EUNSUPPORTED naming the file, line and component
 * when a spectrum is missing and there is no fallback. */
SL_API sl_status sl_asce_input_from_floor(const sl_floor *fl, const sl_spectrum *const *fallback,
                                          sl_asce_source *src, sl_error *err);

/* From a checked motion set (H1 and H2 required, V optional): the 10 %
 * PSA of H1 and H2 on the default grid (SL_SPECTRUM_FMIN_HZ ..
 * SL_SPECTRUM_FMAX_HZ, SL_SPECTRUM_PER_DECADE per decade). Returns SL_OK,
 * SL_EINVAL (no H2), SL_ENOMEM, or the spectrum's error. */
SL_API sl_status sl_asce_input_from_set(const sl_set *set, sl_asce_source *src, sl_error *err);

/* From Regulatory Guide 1.60 at PGA pga_g (g, > 0): the horizontal
 * spectrum for both horizontals on its own grid (sl_rg160_grid over the
 * default range), A_v = ZPA_h = PGA, PGD = each horizontal's 36 in per g
 * combined 100-40. Returns SL_OK, SL_EINVAL or SL_ENOMEM. */
SL_API sl_status sl_asce_input_from_rg160(double pga_g, sl_asce_source *src, sl_error *err);

/* Free the owned spectra and zero the source; harmless on NULL. */
SL_API void sl_asce_source_free(sl_asce_source *src);

#endif
