/* standards.c - the default friction grid (standards.h). */
#include "core/standards.h"

void sl_mu_grid_default(double mu[SL_MU_GRID_N])
{
    for (size_t k = 0; k < SL_MU_GRID_N; k++)
        mu[k] = SL_MU_GRID_FROM + (double)k * SL_MU_GRID_STEP;
}
