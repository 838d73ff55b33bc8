/*
 * fuzz_motion.c - the ground-motion readers: PEER .AT2 (both header
 * layouts), one/two-column text and CSV motions (sl_motion_read, format
 * detected from the content or forced), the agency formats GeoNet .V2A /
 * CSMIP .V2 (sl_channels_read), USGS .smc (sl_smc_read) and CWA .acc
 * (sl_cwa_acc_read). The first byte picks the reader. A motion a reader
 * accepts must have n >= 1 samples, a finite dt > 0 and finite
 * accelerations no larger than SL_MOTION_MAX_ABS_G g (motion.h).
 */
#include "fuzz_common.h"

#include "io/formats.h"
#include "io/motion.h"

static void check_motion(const sl_motion *m)
{
    fuzz_require(m->n >= 1 && m->acc_ms2);
    fuzz_require(isfinite(m->dt_s) && m->dt_s > 0.0);
    fuzz_require(fuzz_all_finite(m->acc_ms2, m->n));
    for (size_t i = 0; i < m->n; i++)
        fuzz_require(fabs(m->acc_ms2[i]) <= SL_MOTION_MAX_ABS_G * SL_G * (1 + 1e-12));
    (void)sl_motion_pga(m);
}

static void read_one(const char *name, sl_format fmt, sl_unit units, double dt,
                     const uint8_t *data, size_t size)
{
    const char *path = fuzz_write(name, data, size);
    if (!path)
        return;
    sl_read_opts o = {fmt, units, dt};
    sl_error err;
    sl_error_clear(&err);
    sl_motion *m = sl_motion_read(path, &o, &err);
    if (m)
        check_motion(m);
    else
        fuzz_require(err.code != SL_OK && err.msg[0]);
    sl_motion_free(m);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    sl_error err;
    sl_error_clear(&err);
    switch (fuzz_select(&data, &size, 8)) {
    case 0: read_one("rec.AT2", SL_FORMAT_AUTO, SL_UNIT_NONE, 0, data, size); break;
    case 1: read_one("rec.txt", SL_FORMAT_AUTO, SL_UNIT_G, 0.01, data, size); break;
    case 2: read_one("rec.csv", SL_FORMAT_CSV, SL_UNIT_NONE, 0, data, size); break;
    case 3: read_one("rec.dat", SL_FORMAT_TWOCOL, SL_UNIT_CMS2, 0, data, size); break;
    case 4: read_one("rec.txt", SL_FORMAT_ONECOL, SL_UNIT_MS2, 0.005, data, size); break;
    case 5: {
        const char *path = fuzz_write("rec.V2A", data, size);
        sl_channels ch = {0};
        if (path && sl_channels_read(path, &ch, &err) == SL_OK) {
            fuzz_require(ch.n >= 1 && ch.n <= SL_CHANNELS_MAX);
            for (size_t k = 0; k < ch.n; k++) {
                check_motion(ch.m[k]);
                fuzz_require(memchr(ch.comp[k], '\0', SL_COMP_NAME_MAX) != NULL);
            }
        }
        sl_channels_free(&ch);
        break;
    }
    case 6: {
        const char *path = fuzz_write("rec.smc", data, size);
        char comp[SL_COMP_NAME_MAX];
        sl_motion *m = path ? sl_smc_read(path, comp, sizeof comp, &err) : NULL;
        if (m) {
            check_motion(m);
            fuzz_require(memchr(comp, '\0', sizeof comp) != NULL);
        }
        sl_motion_free(m);
        break;
    }
    default: {
        const char *path = fuzz_write("rec_E.acc", data, size);
        sl_motion *m = path ? sl_cwa_acc_read(path, &err) : NULL;
        if (m)
            check_motion(m);
        sl_motion_free(m);
        break;
    }
    }
    return 0;
}
