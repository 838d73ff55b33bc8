/* asce_input.c - the ASCE method's input from a floor, a set or RG 1.60
 * (asce_input.h). */
#include "method/asce_input.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "signal/rg160.h"
#include "signal/spectrum.h"

static void source_init(sl_asce_source *src)
{
    memset(src, 0, sizeof *src);
    sl_asce_input_default(&src->in);
}

void sl_asce_source_free(sl_asce_source *src)
{
    if (!src)
        return;
    sl_spectrum_free(src->own[0]);
    sl_spectrum_free(src->own[1]);
    memset(src, 0, sizeof *src);
}

double sl_asce_floor_zpa_h(const sl_floor *fl)
{
    return fmax(fl->comp[SL_FLOOR_H1].zpa_ms2, fl->comp[SL_FLOOR_H2].zpa_ms2);
}

sl_status sl_asce_input_from_floor(const sl_floor *fl, const sl_spectrum *const *fallback,
                                   sl_asce_source *src, sl_error *err)
{
    source_init(src);
    const sl_spectrum *sp[2] = {sl_floor_sa10(fl, SL_FLOOR_H1), sl_floor_sa10(fl, SL_FLOOR_H2)};
    if ((!sp[0] || !sp[1]) && fallback) {
        sp[0] = fallback[0];
        sp[1] = fallback[1];
    }
    for (int k = 0; k < 2; k++)
        if (!sp[k]) {
            const sl_floor_comp c = k ? SL_FLOOR_H2 : SL_FLOOR_H1;
            return sl_error_set(err, SL_EUNSUPPORTED, fl->path, fl->comp[c].line,
                                "[%s] has no 10 %%-damped spectrum (sa_0.10), which the ASCE "
                                "method needs; this command has no fallback: add sa_0.10 or use "
                                "motions synthesized for the floor (--h1 --h2 --v)",
                                sl_floor_comp_name(c));
        }
    src->in.h1 = sp[0];
    src->in.h2 = sp[1];
    src->in.av_ms2 = fl->comp[SL_FLOOR_V].zpa_ms2;
    src->in.zpa_h_ms2 = sl_asce_floor_zpa_h(fl);
    src->in.pgd_m = NAN;
    return SL_OK;
}

sl_status sl_asce_input_from_set(const sl_set *set, sl_asce_source *src, sl_error *err)
{
    source_init(src);
    if (!set || !set->h1 || !set->h2)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "ASCE input: the set needs H1 and H2");
    size_t n = 0;
    double *f = sl_spectrum_grid(SL_SPECTRUM_FMIN_HZ, SL_SPECTRUM_FMAX_HZ,
                                 SL_SPECTRUM_PER_DECADE, &n);
    double *psa = f ? malloc(2 * n * sizeof *psa) : NULL;
    for (int q = 0; q < 2 && psa; q++)
        if ((src->own[q] = sl_spectrum_alloc(n, SL_ASCE_DAMPING)))
            memcpy(src->own[q]->f_hz, f, n * sizeof *f);
    sl_status st = SL_OK;
    if (!psa || !src->own[0] || !src->own[1]) {
        st = sl_error_set(err, SL_ENOMEM, NULL, 0, "out of memory");
    } else {
        const sl_motion *hm[2] = {set->h1, set->h2};
        st = sl_spectrum_batch(hm, 2, f, n, SL_ASCE_DAMPING, NULL, psa, NULL, NULL, err);
    }
    if (st == SL_OK) {
        for (int q = 0; q < 2; q++)
            memcpy(src->own[q]->sa_ms2, psa + (size_t)q * n, n * sizeof *psa);
        src->in.h1 = src->own[0];
        src->in.h2 = src->own[1];
        src->in.av_ms2 = set->v ? sl_motion_pga(set->v) : 0.0;
        src->in.zpa_h_ms2 = sl_set_pga_h(set);
        src->in.pgd_m = sl_set_pgd_100_40(set);
    } else {
        sl_asce_source_free(src);
    }
    free(psa);
    free(f);
    return st;
}

sl_status sl_asce_input_from_rg160(double pga_g, sl_asce_source *src, sl_error *err)
{
    source_init(src);
    if (!(pga_g > 0) || !isfinite(pga_g))
        return sl_error_set(err, SL_EINVAL, NULL, 0, "RG 1.60: PGA %g g must be > 0", pga_g);
    size_t n = 0;
    double *f = sl_rg160_grid(SL_RG160_HORIZONTAL, SL_SPECTRUM_FMIN_HZ, SL_SPECTRUM_FMAX_HZ,
                              SL_SPECTRUM_PER_DECADE, &n);
    sl_spectrum *sp = f ? sl_spectrum_alloc(n, SL_ASCE_DAMPING) : NULL;
    if (!sp) {
        free(f);
        return sl_error_set(err, SL_ENOMEM, NULL, 0, "out of memory");
    }
    memcpy(sp->f_hz, f, n * sizeof *f);
    free(f);
    src->own[0] = sp;
    sl_status st = sl_rg160_psa(SL_RG160_HORIZONTAL, SL_ASCE_DAMPING, pga_g * SL_G, sp->f_hz, n,
                                sp->sa_ms2, err);
    if (st != SL_OK) {
        sl_asce_source_free(src);
        return st;
    }
    src->in.h1 = src->in.h2 = sp;
    src->in.av_ms2 = pga_g * SL_G; /* vertical ZPA = horizontal PGA */
    src->in.zpa_h_ms2 = pga_g * SL_G;
    double pgd1 = SL_RG160_DISP_PER_G_M * pga_g; /* 36 in per g, each horizontal */
    src->in.pgd_m = pgd1 + SL_COMB_100_40 * pgd1;
    return SL_OK;
}
