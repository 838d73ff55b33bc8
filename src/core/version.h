/*
 * version.h - the version of seislide, declared once: the Makefile (the
 * shared library's file name), seislide.pc, `seislide --version` and the
 * "program" line of every workbook and CSV read it from here.
 *
 * SEISLIDE_VERSION_* are the version of the headers a program was compiled
 * with; sl_version() is the version of the library it runs with.
 */
#ifndef SL_VERSION_H
#define SL_VERSION_H

#include "core/api.h"

#define SEISLIDE_VERSION_MAJOR 0
#define SEISLIDE_VERSION_MINOR 1
#define SEISLIDE_VERSION_PATCH 0

#define SL_VERSION_STR_(x) #x
#define SL_VERSION_STR(x) SL_VERSION_STR_(x)
/* "MAJOR.MINOR.PATCH", e.g. "0.1.0". */
#define SEISLIDE_VERSION_STRING                                                \
    SL_VERSION_STR(SEISLIDE_VERSION_MAJOR) "." SL_VERSION_STR(SEISLIDE_VERSION_MINOR) "." \
    SL_VERSION_STR(SEISLIDE_VERSION_PATCH)

/* The library's version, "MAJOR.MINOR.PATCH" (a static string). */
SL_API const char *sl_version(void);

#endif
