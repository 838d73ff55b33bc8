/*
 * history.c - time histories of one analysis (model.h): create, grow, free,
 * append.
 */
#include "slide/model.h"

#include <stdlib.h>

void sl_history_free(sl_history *h)
{
    if (!h)
        return;
    free(h->t_s);
    free(h->ux_m);
    free(h->uy_m);
    free(h->vx_ms);
    free(h->vy_ms);
    free(h->fx_w);
    free(h->fy_w);
    free(h);
}

int sl_history_reserve(sl_history *h, size_t cap)
{
    double **arr[] = {&h->t_s, &h->ux_m, &h->uy_m, &h->vx_ms, &h->vy_ms, &h->fx_w, &h->fy_w};
    for (size_t k = 0; k < sizeof arr / sizeof arr[0]; k++) {
        double *p = realloc(*arr[k], (cap ? cap : 1) * sizeof(double));
        if (!p)
            return -1;
        *arr[k] = p;
    }
    return 0;
}

sl_history *sl_history_alloc(size_t cap, double dt_s)
{
    sl_history *h = calloc(1, sizeof *h);
    if (!h)
        return NULL;
    h->dt_s = dt_s;
    if (sl_history_reserve(h, cap)) {
        sl_history_free(h);
        return NULL;
    }
    return h;
}

void sl_history_push(sl_history *h, double t, double ux, double uy, double vx, double vy,
                     double fx, double fy)
{
    size_t i = h->n++;
    h->t_s[i] = t;
    h->ux_m[i] = ux;
    h->uy_m[i] = uy;
    h->vx_ms[i] = vx;
    h->vy_ms[i] = vy;
    h->fx_w[i] = fx;
    h->fy_w[i] = fy;
}
