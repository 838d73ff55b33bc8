/* version.c - the library's version and build identity at run time
 * (version.h). */
#include "core/version.h"

/* Made by the Makefile: SL_SOURCE_ID (64 hex digits) and SL_SOURCE_ID_SHORT
 * (its first 12), the fingerprint of the sources (version.h). */
#include "source_id.h"

const char *sl_version(void)
{
    return SEISLIDE_VERSION_STRING;
}

const char *sl_source_id(void)
{
    return SL_SOURCE_ID;
}

const char *sl_build_id(void)
{
    return "seislide " SEISLIDE_VERSION_STRING " (source " SL_SOURCE_ID_SHORT ")";
}
