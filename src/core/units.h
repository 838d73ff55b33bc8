/*
 * units.h - SI inside, named units at every boundary.
 *
 * Every acceleration read or written by seislide names its unit. Inside the
 * library all quantities are SI: m, s, m/s^2. Conversion happens once, at the
 * boundary, through the factors here.
 */
#ifndef SL_UNITS_H
#define SL_UNITS_H

#include "core/api.h"

/* Standard gravity, m/s^2 (ISO 80000-3). */
#define SL_G 9.80665

/* pi (math.h's M_PI is not in C11). */
#define SL_PI 3.14159265358979323846

/* One inch in metres (RG 1.60 uses 36 in of displacement per 1 g). */
#define SL_INCH_M 0.0254

typedef enum sl_unit {
    SL_UNIT_NONE = 0, /* not given: an error where a unit is required */
    SL_UNIT_G,        /* standard gravity */
    SL_UNIT_MS2,      /* m/s^2 */
    SL_UNIT_CMS2,     /* cm/s^2 = gal */
    SL_UNIT_MMS2      /* mm/s^2 */
} sl_unit;

/* Parse a unit name: "g", "m/s2", "m/s^2", "cm/s2", "cm/s^2", "gal",
 * "mm/s2", "mm/s^2" (case-insensitive for "g" and "gal").
 * Returns SL_UNIT_NONE for anything else. */
SL_API sl_unit sl_unit_parse(const char *name);

/* The canonical name of a unit ("g", "m/s2", "cm/s2", "mm/s2"). */
SL_API const char *sl_unit_name(sl_unit u);

/* Multiply a value in unit u by this to get m/s^2 (0 for SL_UNIT_NONE). */
SL_API double sl_unit_to_ms2(sl_unit u);

#endif
