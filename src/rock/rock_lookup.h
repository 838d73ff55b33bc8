/*
 * rock_lookup.h - the rocking lookup of a floor: the probability of tipping
 * over a grid of slenderness and size, so that a designer can place a
 * slender item that is not yet on a list (docs/rocking.md, "The rocking
 * lookup").
 *
 * Grid: b/h = sl_rockl_bh(i) (half the base over the height of the centre of
 * mass) by h = sl_rockl_h_m(j) (the height of the centre of mass, m); each block
 * uniform and rectangular (base 2 b = 2 (b/h) h), Housner's restitution,
 * the worst orientation, as a components item with mu >= b/h
 * (rock_floor.h: the same statistics, the same stopping rule).
 */
#ifndef SL_ROCK_LOOKUP_H
#define SL_ROCK_LOOKUP_H

#include "core/api.h"
#include "rock/rock_floor.h"

#define SL_ROCKL_NBH 8
#define SL_ROCKL_NH 5
#define SL_ROCKL_N (SL_ROCKL_NBH * SL_ROCKL_NH)
/* The grid's b/h (i < SL_ROCKL_NBH: 0.10, 0.15, 0.20, 0.25, 0.30, 0.40, 0.50,
 * 0.60) and h (j < SL_ROCKL_NH: 0.25, 0.5, 1.0, 1.5, 2.0 m). */
SL_API double sl_rockl_bh(int i);
SL_API double sl_rockl_h_m(int j);

/* The grid's blocks, b/h major: items[i * SL_ROCKL_NH + j] has b/h
 * sl_rockl_bh(i) and h sl_rockl_h_m(j). */
SL_API void sl_rockl_items(sl_rockf_item items[SL_ROCKL_N]);

#endif
