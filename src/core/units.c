/* units.c - unit names and conversion factors to SI. */
#include "core/units.h"

#include <string.h>
#include <strings.h>

sl_unit sl_unit_parse(const char *name)
{
    if (!name)
        return SL_UNIT_NONE;
    if (!strcasecmp(name, "g"))
        return SL_UNIT_G;
    if (!strcmp(name, "m/s2") || !strcmp(name, "m/s^2") || !strcmp(name, "m/s/s"))
        return SL_UNIT_MS2;
    if (!strcmp(name, "cm/s2") || !strcmp(name, "cm/s^2") || !strcmp(name, "cm/s/s") ||
        !strcasecmp(name, "gal"))
        return SL_UNIT_CMS2;
    if (!strcmp(name, "mm/s2") || !strcmp(name, "mm/s^2") || !strcmp(name, "mm/s/s"))
        return SL_UNIT_MMS2;
    return SL_UNIT_NONE;
}

const char *sl_unit_name(sl_unit u)
{
    switch (u) {
    case SL_UNIT_G: return "g";
    case SL_UNIT_MS2: return "m/s2";
    case SL_UNIT_CMS2: return "cm/s2";
    case SL_UNIT_MMS2: return "mm/s2";
    default: return "none";
    }
}

double sl_unit_to_ms2(sl_unit u)
{
    switch (u) {
    case SL_UNIT_G: return SL_G;
    case SL_UNIT_MS2: return 1.0;
    case SL_UNIT_CMS2: return 0.01;
    case SL_UNIT_MMS2: return 0.001;
    default: return 0.0;
    }
}
