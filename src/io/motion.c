/*
 * motion.c - sl_motion_read(): load a ground-motion file once (io/text.h),
 * tell its format (PEER .AT2 by extension or by an NPTS line 4, else
 * columns) and hand it to the AT2 reader (at2.c) or the column reader
 * (columns.c); plus the checks those readers share and the vertical
 * component's name. See docs/formats.md, section "Ground motions".
 */
#include "io/motion_read.h"

#include "core/units.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

static const char units_hint[] = "units not given (use --units g|m/s2|cm/s2)";

sl_status sl_motion_check_acc(double si, double raw, sl_unit u, const char *path, long line,
                           sl_error *err)
{
    if (fabs(si) <= SL_MOTION_MAX_ABS_G * SL_G)
        return SL_OK;
    return sl_error_set(err, SL_EINVAL, path, line, "acceleration %g %s is %s %g g in magnitude "
                        "(not a floor or ground motion; check the value and the units)",
                        raw, sl_unit_name(u), isfinite(si) ? "above" : "infinite in SI, above",
                        SL_MOTION_MAX_ABS_G);
}

/* Decide the unit (motion_read.h). */
sl_status sl_motion_resolve_units(sl_unit file_u, sl_unit opt_u, const char *path,
                               long line, sl_unit *out, sl_error *err)
{
    if (file_u != SL_UNIT_NONE && opt_u != SL_UNIT_NONE && file_u != opt_u)
        return sl_error_set(err, SL_EINVAL, path, line,
                            "units %s in the file disagree with the units given (%s)",
                            sl_unit_name(file_u), sl_unit_name(opt_u));
    *out = file_u != SL_UNIT_NONE ? file_u : opt_u;
    if (*out == SL_UNIT_NONE)
        return sl_error_set(err, SL_EINVAL, path, line, "%s", units_hint);
    return SL_OK;
}

/* An explicit dt (opts) must agree with the file's. */
sl_status sl_motion_check_opt_dt(double opt_dt, double file_dt, const char *path,
                              long line, sl_error *err)
{
    if (opt_dt > 0 && fabs(opt_dt - file_dt) > SL_MOTION_DT_REL_TOL * file_dt)
        return sl_error_set(err, SL_EINVAL, path, line,
                            "dt %.9g s given disagrees with the file's dt %.9g s",
                            opt_dt, file_dt);
    return SL_OK;
}

static int ext_is_at2(const char *path)
{
    size_t n = strlen(path);
    return n >= 4 && path[n - 4] == '.' && sl_text_find_ci(path + n - 3, 3, "AT2") == 0;
}

sl_motion *sl_motion_read(const char *path, const sl_read_opts *opts, sl_error *err)
{
    sl_read_opts o = {0};
    if (opts)
        o = *opts;
    sl_error_clear(err);
    if (!path) {
        sl_error_set(err, SL_EINVAL, NULL, 0, "no file name given");
        return NULL;
    }
    if ((int)o.format < SL_FORMAT_AUTO || o.format > SL_FORMAT_CSV) {
        sl_error_set(err, SL_EINVAL, path, 0, "unknown format code %d", (int)o.format);
        return NULL;
    }
    if ((int)o.units < SL_UNIT_NONE || o.units > SL_UNIT_MMS2) {
        sl_error_set(err, SL_EINVAL, path, 0, "unknown units code %d", (int)o.units);
        return NULL;
    }
    if (o.dt_s != 0 && !(o.dt_s > 0 && isfinite(o.dt_s))) {
        sl_error_set(err, SL_EINVAL, path, 0, "dt %g must be > 0", o.dt_s);
        return NULL;
    }

    sl_text t;
    const sl_text_opts to = {SL_MOTION_MAX_BYTES, "a motion file", NULL, 0};
    if (sl_text_load(path, &to, &t, err) != SL_OK)
        return NULL;
    if (t.len == 0) {
        sl_text_free(&t);
        sl_error_set(err, SL_EPARSE, path, 0, "empty file");
        return NULL;
    }

    sl_format fmt = o.format;
    if (fmt == SL_FORMAT_AUTO) {
        if (ext_is_at2(path)) {
            fmt = SL_FORMAT_AT2;
        } else {
            /* AT2 when line 4 is an NPTS/DT line */
            sl_text probe = t;
            const char *s = NULL;
            size_t n = 0;
            int k = 0;
            while (k < 4 && sl_text_next(&probe, &s, &n))
                k++;
            if (k == 4 && sl_text_find_ci(s, n, "NPTS") >= 0)
                fmt = SL_FORMAT_AT2;
        }
    }
    sl_motion *m = fmt == SL_FORMAT_AT2 ? sl_motion_read_at2(path, &t, &o, err)
                                        : sl_motion_read_columns(path, &t, fmt, &o, err);
    sl_text_free(&t);
    return m;
}

int sl_motion_name_is_vertical(const char *path)
{
    const char *b = strrchr(path, '/');
    b = b ? b + 1 : path;
    size_t n = strlen(b);
    const char *dot = strrchr(b, '.');
    if (dot)
        n = (size_t)(dot - b);
    static const char *const tails[] = {"UP", "DWN", "DOWN", "VER", "VRT", "-V", "-Z", "_Z", "_V"};
    for (size_t k = 0; k < sizeof tails / sizeof tails[0]; k++) {
        size_t m = strlen(tails[k]);
        if (n >= m && !strncasecmp(b + n - m, tails[k], m))
            return 1;
    }
    return 0;
}
