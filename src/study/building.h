/*
 * building.h - a linear multi-storey building that turns ground motions into
 * physical floor motions (for validating synthesized floor motions against
 * the motions behind a floor spectrum; docs/synthesis.md section 10).
 *
 * Model. Per direction (H1, H2, V) an independent uniform shear chain of
 * N equal storeys (mass m, storey stiffness k, fixed base, free top). Its
 * modes are closed-form (e.g. Chopra, Dynamics of Structures, uniform shear
 * building):
 *     omega_r = 2 sqrt(k/m) sin((2r - 1) pi / (2 (2N + 1))),        (B1)
 *     phi_r(j) = sin((2r - 1) j pi / (2N + 1)),   j = 1..N floors,   (B2)
 *     Gamma_r = sum_j phi_r(j) / sum_j phi_r(j)^2,                  (B3)
 * so sqrt(k/m) follows from the fundamental frequency f1 of the direction.
 * Each mode is a 5 %-damped oscillator driven by the ground acceleration
 * a_g (modal superposition):
 *     q_r'' + 2 zeta w_r q_r' + w_r^2 q_r = -a_g(t),                (B4)
 * and the absolute acceleration of floor j is
 *     a_j(t) = sum_r Gamma_r phi_r(j) (-(2 zeta w_r q_r' + w_r^2 q_r)),  (B5)
 * which uses sum_r Gamma_r phi_r(j) = 1 (complete modal set: a rigid
 * building moves with the ground). q, q' are computed by the exact
 * piecewise-linear recurrence of spectrum.h (sl_spectrum_history).
 * Horizontal directions have their modes a few Hz apart (N = 3: f1, 2.80
 * f1, 4.05 f1); the vertical direction is stiff (f1 of 10-20 Hz).
 *
 * Units: SI. Library code: no printing.
 */
#ifndef SL_BUILDING_H
#define SL_BUILDING_H

#include <stddef.h>

#include "core/status.h"
#include "io/motion.h"

/* Most storeys handled. */
#define SL_BUILDING_MAX_STOREYS 20

typedef struct sl_building {
    size_t storeys;          /* N, 1..SL_BUILDING_MAX_STOREYS */
    double f1_hz[3];         /* fundamental frequency per direction H1, H2, V */
    double damping;          /* modal damping ratio (0.05) */
} sl_building;

/* A building from "N:f1_h1:f1_h2:f1_v:damping" (storeys, the fundamental
 * frequency of each direction in Hz, the modal damping ratio), e.g.
 * "3:3.0:4.2:14:0.05" (the building of docs/synthesis.md 10). Returns
 * SL_OK, or SL_EINVAL naming the field (b unchanged): a field missing,
 * not a number, or outside what sl_building_floor accepts. */
sl_status sl_building_parse(const char *spec, sl_building *b, sl_error *err);

/* Modal frequencies (Hz) and participation x shape at floor j (1..N) of
 * direction d (0, 1, 2): freq[r], gp[r] = Gamma_r phi_r(j), r < N. */
void sl_building_modes(const sl_building *b, int d, size_t floor, double *freq, double *gp);

/* Floor motions of floor `floor` (1..N) for the ground set g (checked;
 * absent components give absent floor components): out owns its motions
 * (free with sl_set_free_motions, io/setdir.h). Returns SL_OK, SL_EINVAL,
 * SL_ENOMEM. */
sl_status sl_building_floor(const sl_building *b, size_t floor, const sl_set *g, sl_set *out,
                            sl_error *err);

#endif
