/*
 * model.c - defaults and names of the sliding-block options (model.h).
 */
#include "slide/model.h"

#include <string.h>

void sl_slide_opts_default(sl_slide_opts *o)
{
    memset(o, 0, sizeof *o);
    o->model = SL_MODEL_EXACT;
    o->g_ms2 = SL_G;
    o->rtol = SL_SLIDE_DEFAULT_RTOL;
    o->atol_m = SL_SLIDE_DEFAULT_ATOL_M;
    o->substeps = SL_SLIDE_DEFAULT_SUBSTEPS;
    o->up_ratio = 1.0;
    o->invert = 0;
    o->smooth_eta = 5.0;
    o->smooth_uy_m = 1e-4;
    o->smooth_rtol = 1e-6;
    o->smooth_atol = 1e-9;
    o->smooth_solver = 0;
    o->plastic_uy_m = 1e-4;
    o->plastic_substeps = 8;
    o->keep_going = 1;
}

sl_status sl_slide_opts_set_tol(sl_slide_opts *o, double rtol, double atol_m, sl_error *err)
{
    int smooth = o->model == SL_MODEL_SMOOTH;
    if (rtol > 0 && !smooth && !(rtol >= SL_SLIDE_RTOL_MIN && rtol <= SL_SLIDE_RTOL_MAX))
        return sl_error_set(err, SL_EINVAL, NULL, 0, "slide: rtol %g must be in [1e-9, 0.1]", rtol);
    if (rtol > 0)
        *(smooth ? &o->smooth_rtol : &o->rtol) = rtol;
    if (atol_m > 0)
        *(smooth ? &o->smooth_atol : &o->atol_m) = atol_m;
    return SL_OK;
}

/* Index of name in the n names, or -1. */
static int name_index(const char *name, const char *const *names, int n)
{
    for (int q = 0; q < n; q++)
        if (!strcmp(name, names[q]))
            return q;
    return -1;
}

int sl_model_parse(const char *name)
{
    static const char *const names[] = {"exact", "smooth", "plastic"};
    static const sl_model models[] = {SL_MODEL_EXACT, SL_MODEL_SMOOTH, SL_MODEL_PLASTIC};
    int q = name_index(name, names, 3);
    return q < 0 ? -1 : (int)models[q];
}

int sl_smooth_solver_parse(const char *name)
{
    static const char *const names[] = {"msbdf", "rk4imp", "bsimp", "rkf45"};
    return name_index(name, names, 4);
}
