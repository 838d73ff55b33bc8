/*
 * version.h - the version of seislide, declared once: the Makefile (the
 * shared library's file name), seislide.pc, `seislide --version` and the
 * "program" line of every workbook and CSV read it from here, the latter
 * two with the build's source fingerprint (below).
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

/* The build's identity (docs/reliability.md, "Which code made a number").
 * The version number names a release; two builds of one version may still
 * compute different numbers, so every number is tied to the code behind
 * it by a fingerprint of the sources: the SHA-256 over the SHA-256 sums of
 * the Makefile and of every file under src/, by name and content, made by
 * the Makefile (`make source-id` prints it). Any change of a source, of the
 * compile flags or of a constant changes it; it is part of every cache key
 * (plant/entry.h), so a cached result is never served to another build.
 *
 * sl_source_id(): the fingerprint, 64 hex digits (a static string).
 * sl_build_id(): "seislide MAJOR.MINOR.PATCH (source XXXXXXXXXXXX)", the
 * version and the fingerprint's first 12 digits, as the program line of
 * every CSV, workbook and verify record prints it (a static string). */
SL_API const char *sl_source_id(void);
SL_API const char *sl_build_id(void);

#endif
