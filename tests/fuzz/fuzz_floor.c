/*
 * fuzz_floor.c - the floor response spectrum readers (INI with inih, CSV
 * tables): sl_floor_load() on any bytes, as NAME.ini or NAME.csv (first
 * byte). A floor it accepts must satisfy floor.h's validation contract:
 * every spectrum with >= SL_FLOOR_MIN_POINTS strictly increasing
 * frequencies inside SL_FLOOR_F_MIN_HZ-SL_FLOOR_F_MAX_HZ, values positive,
 * finite and at most SL_FLOOR_MAX_SA_G g, damping ratios in (0, 1)
 * ascending, a finite positive ZPA, a non-empty name.
 */
#include "fuzz_common.h"

#include "io/floor.h"

static void check_floor(const sl_floor *fl)
{
    fuzz_require(fl->name && fl->name[0]);
    for (int c = 0; c < SL_FLOOR_NCOMP; c++) {
        const sl_floor_component *fc = &fl->comp[c];
        fuzz_require(fc->nspec >= 1 && fc->nspec <= SL_FLOOR_MAX_DAMPINGS);
        fuzz_require(isfinite(fc->zpa_ms2) && fc->zpa_ms2 > 0.0);
        for (size_t k = 0; k < fc->nspec; k++) {
            const sl_spectrum *s = &fc->spec[k];
            fuzz_require(s->damping > 0.0 && s->damping < 1.0);
            fuzz_require(k == 0 || s->damping > fc->spec[k - 1].damping);
            fuzz_require(s->n >= SL_FLOOR_MIN_POINTS);
            for (size_t i = 0; i < s->n; i++) {
                fuzz_require(s->f_hz[i] >= SL_FLOOR_F_MIN_HZ && s->f_hz[i] <= SL_FLOOR_F_MAX_HZ);
                fuzz_require(i == 0 || s->f_hz[i] > s->f_hz[i - 1]);
                fuzz_require(isfinite(s->sa_ms2[i]) && s->sa_ms2[i] > 0.0);
                fuzz_require(s->sa_ms2[i] <= SL_FLOOR_MAX_SA_G * SL_G * (1 + 1e-12));
            }
        }
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const char *const names[] = {"floor.ini", "floor.csv"};
    const char *path = fuzz_write(names[fuzz_select(&data, &size, 2)], data, size);
    if (!path)
        return 0;
    sl_error err;
    sl_error_clear(&err);
    sl_floor *fl = sl_floor_load(path, &err);
    if (fl) {
        check_floor(fl);
        sl_floor_check_plausible(fl, &err);
        /* a floor read keeps within the plausibility rules (floor.h) */
        sl_floor_plausibility p;
        sl_floor_plausibility_of(fl, &p);
        fuzz_require(p.spike <= SL_FLOOR_SPIKE_MAX && p.dip <= SL_FLOOR_DIP_MAX &&
                     p.dip_first <= SL_FLOOR_DIP_FIRST_MAX);
        fuzz_require(p.order >= SL_FLOOR_ORDER_MIN && p.spread <= SL_FLOOR_SPREAD_MAX);
        fuzz_require(p.order_mean >= SL_FLOOR_ORDER_MEAN_MIN * (1 - 1e-12));
        char w[600];
        fuzz_require(sl_floor_zpa_warning(fl, w, sizeof w) == (w[0] != '\0'));
        for (int c = 0; c < SL_FLOOR_NCOMP; c++)
            (void)sl_floor_sa10(fl, (sl_floor_comp)c);
    } else {
        fuzz_require(err.code != SL_OK && err.msg[0]);
    }
    sl_floor_free(fl);
    return 0;
}
