/* version.c - the library's version at run time (version.h). */
#include "core/version.h"

const char *sl_version(void)
{
    return SEISLIDE_VERSION_STRING;
}
