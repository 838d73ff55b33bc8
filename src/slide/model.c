/*
 * model.c - defaults of the sliding-block options (model.h).
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
