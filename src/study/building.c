/* building.c - uniform shear-chain building, modal superposition (see
 * building.h, equations B1-B5). */
#include "study/building.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/units.h"
#include "io/setdir.h"
#include "signal/spectrum.h"

void sl_building_modes(const sl_building *b, int d, size_t floor, double *freq, double *gp)
{
    const size_t N = b->storeys;
    const double den = 2.0 * (double)N + 1.0;
    /* sqrt(k/m) from f1 by (B1) with r = 1 */
    const double w0 = 2 * SL_PI * b->f1_hz[d] / (2 * sin(SL_PI / (2 * den)));
    for (size_t r = 1; r <= N; r++) {
        double a = (2.0 * (double)r - 1.0) * SL_PI / den;
        double s1 = 0, s2 = 0;
        for (size_t j = 1; j <= N; j++) {
            double ph = sin(a * (double)j);   /* (B2) */
            s1 += ph;
            s2 += ph * ph;
        }
        freq[r - 1] = 2 * w0 * sin(a / 2) / (2 * SL_PI); /* (B1) */
        gp[r - 1] = s1 / s2 * sin(a * (double)floor);     /* (B3) x (B2) */
    }
}

sl_status sl_building_parse(const char *spec, sl_building *b, sl_error *err)
{
    static const char *const what[5] = {"storeys", "f1 of H1", "f1 of H2", "f1 of V",
                                        "damping"};
    double v[5];
    const char *p = spec ? spec : "";
    for (int i = 0; i < 5; i++) {
        char *end;
        v[i] = strtod(p, &end);
        if (end == p || !isfinite(v[i]) || (*end != (i < 4 ? ':' : '\0')))
            return sl_error_set(err, SL_EINVAL, NULL, 0,
                                "building \"%s\": the %s (field %d of N:f1_h1:f1_h2:f1_v:damping) "
                                "is missing or not a number",
                                spec ? spec : "", what[i], i + 1);
        p = end + 1;
    }
    if (!(v[0] >= 1 && v[0] <= SL_BUILDING_MAX_STOREYS && v[0] == floor(v[0])))
        return sl_error_set(err, SL_EINVAL, NULL, 0, "building \"%s\": storeys %g not a whole "
                            "number in 1..%d", spec, v[0], SL_BUILDING_MAX_STOREYS);
    for (int i = 1; i < 4; i++)
        if (!(v[i] > 0))
            return sl_error_set(err, SL_EINVAL, NULL, 0, "building \"%s\": %s %g Hz must be > 0",
                                spec, what[i], v[i]);
    if (!(v[4] > 0 && v[4] < 1))
        return sl_error_set(err, SL_EINVAL, NULL, 0, "building \"%s\": damping %g outside (0, 1)",
                            spec, v[4]);
    b->storeys = (size_t)v[0];
    for (int d = 0; d < 3; d++)
        b->f1_hz[d] = v[d + 1];
    b->damping = v[4];
    return SL_OK;
}

/* Floor acceleration of one component by (B4)-(B5). */
static sl_status floor_component(const sl_building *b, int d, size_t floor, const sl_motion *g,
                                 sl_motion **out, sl_error *err)
{
    const size_t n = g->n, N = b->storeys;
    double freq[SL_BUILDING_MAX_STOREYS], gp[SL_BUILDING_MAX_STOREYS];
    sl_building_modes(b, d, floor, freq, gp);
    double *acc = calloc(n, sizeof *acc), *u = malloc(n * sizeof *u), *v = malloc(n * sizeof *v);
    if (!acc || !u || !v) {
        free(acc);
        free(u);
        free(v);
        return sl_error_set(err, SL_ENOMEM, NULL, 0, "building: out of memory");
    }
    sl_status st = SL_OK;
    for (size_t r = 0; r < N && !st; r++) {
        st = sl_spectrum_history(g->acc_ms2, n, g->dt_s, freq[r], b->damping, NULL, u, v, err);
        const double w = 2 * SL_PI * freq[r];
        for (size_t i = 0; i < n && !st; i++)
            acc[i] -= gp[r] * (2 * b->damping * w * v[i] + w * w * u[i]); /* (B5) */
    }
    free(u);
    free(v);
    if (!st) {
        *out = sl_motion_from_array(acc, n, g->dt_s, g->label);
        if (!*out)
            st = sl_error_set(err, SL_ENOMEM, NULL, 0, "building: out of memory");
    }
    free(acc);
    return st;
}

sl_status sl_building_floor(const sl_building *b, size_t floor, const sl_set *g, sl_set *out,
                            sl_error *err)
{
    memset(out, 0, sizeof *out);
    if (!b || b->storeys < 1 || b->storeys > SL_BUILDING_MAX_STOREYS || floor < 1 ||
        floor > b->storeys || !(b->damping > 0 && b->damping < 1) || !g || !g->h1)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "building: bad model or floor");
    for (int d = 0; d < 3; d++)
        if (!(b->f1_hz[d] > 0) || !isfinite(b->f1_hz[d]))
            return sl_error_set(err, SL_EINVAL, NULL, 0, "building: f1 must be > 0");
    const sl_motion *in[3] = {g->h1, g->h2, g->v};
    sl_motion **o[3] = {&out->h1, &out->h2, &out->v};
    for (int d = 0; d < 3; d++) {
        if (!in[d])
            continue;
        sl_status st = floor_component(b, d, floor, in[d], o[d], err);
        if (st) {
            sl_set_free_motions(out);
            return st;
        }
    }
    return SL_OK;
}
