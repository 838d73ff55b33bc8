/* rock_lookup.c - the grid of the rocking lookup (rock_lookup.h). */
#include "rock/rock_lookup.h"

#include <math.h>

static const double bh[SL_ROCKL_NBH] = {0.10, 0.15, 0.20, 0.25, 0.30, 0.40, 0.50, 0.60};
static const double h_m[SL_ROCKL_NH] = {0.25, 0.50, 1.00, 1.50, 2.00};

double sl_rockl_bh(int i)
{
    return i >= 0 && i < SL_ROCKL_NBH ? bh[i] : NAN;
}

double sl_rockl_h_m(int j)
{
    return j >= 0 && j < SL_ROCKL_NH ? h_m[j] : NAN;
}

void sl_rockl_items(sl_rockf_item items[SL_ROCKL_N])
{
    for (int i = 0; i < SL_ROCKL_NBH; i++)
        for (int j = 0; j < SL_ROCKL_NH; j++) {
            sl_rockf_item *it = &items[i * SL_ROCKL_NH + j];
            it->block.b_m = bh[i] * h_m[j];
            it->block.h_m = h_m[j];
            it->block.restitution = -1.0; /* Housner's */
            it->orientation_deg = NAN;    /* the worst */
        }
}
