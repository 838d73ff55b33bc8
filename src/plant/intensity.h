/*
 * intensity.h - the floors of one building checked against each other
 * (docs/formats-floor.md, "Floors of one building").
 *
 * A floor file alone cannot show values in m/s2 labelled g when they land
 * inside the plausible 0.01-5 g (io/floor.h, sl_floor_check_plausible); its
 * building can: the ZPAs of one building's floors lie within a few times
 * each other. Measured on physical floors (tools/zpafloors.c: 83 records
 * scaled to 0.3 g through six shear buildings of 1 to 10 storeys, 1.2 to
 * 8 Hz), the bounds below hold every one of them with a margin of 1.25:
 *
 *   median: a floor's horizontal ZPA over the median of the ZPAs of its
 *           building's other floors lies within SL_INTENSITY_MEDIAN_MIN-MAX
 *           (measured 0.171-3.78);
 *   height: of two floors whose elevations are both given, the higher one's
 *           ZPA over the lower one's lies within SL_INTENSITY_UP_MIN-MAX
 *           (measured 0.499-7.06); at one elevation, within 1/UP_MAX-UP_MAX.
 *
 * A unit slip changes a floor's ZPA by 9.81 (g and m/s2), 100 or 1000: out
 * of these bounds wherever the floor's true place in its building is not
 * itself near a bound. A floor out of line is named (the one whose ZPA is
 * furthest from the median of the others; when no single floor stands out,
 * the two floors of the pair): its file, its ZPA, the other floors' ZPAs
 * and elevations, and the unit its values are likely in (the other unit
 * that brings its ZPA nearest the median of the others). A floor accepted
 * in writing (the run's --accept-floor) is left out of the comparison; what
 * the rules would have said of it becomes its warning.
 *
 * Only floors of one building are compared: the buildings of a plant stand
 * on one site, but their floors' ZPAs differ more (measured: a floor over
 * the median of a whole plant of the six buildings, 0.345-4.94, and a plant
 * may be read at several ground levels, as the bench plant is).
 */
#ifndef SL_PLANT_INTENSITY_H
#define SL_PLANT_INTENSITY_H

#include <stddef.h>

#include "core/status.h"
#include "core/units.h"

#define SL_INTENSITY_MEDIAN_MIN 0.137
#define SL_INTENSITY_MEDIAN_MAX 4.7
#define SL_INTENSITY_UP_MIN 0.4
#define SL_INTENSITY_UP_MAX 8.8
/* The longest warning of an accepted floor (with its NUL). */
#define SL_INTENSITY_WARN_MAX 1200

typedef struct sl_intensity_floor {
    const char *id, *name, *path; /* for messages */
    sl_unit units;                /* the file's units */
    const char *units_text;       /* as written ("g", "gal") */
    double zpa_h_ms2;             /* the larger horizontal ZPA */
    double elevation_m;           /* NAN when not given */
    int accepted;                 /* accepted in writing: not compared */
} sl_intensity_floor;

/* Check the n floors of one building (`building`: its id in messages, ""
 * for a one-building run). SL_OK, or SL_EINVAL naming the floor out of line
 * (err: its file and the message above). For each accepted floor the rules
 * would refuse, warn[i] receives what they say of it (else ""); warn may be
 * NULL. */
sl_status sl_intensity_check(const sl_intensity_floor *f, size_t n, const char *building,
                             char (*warn)[SL_INTENSITY_WARN_MAX], sl_error *err);

#endif
