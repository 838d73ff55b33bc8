/*
 * atomic.h - write a file so that it appears complete or not at all.
 *
 * sl_atomic_open() creates a hidden temporary file in the destination's
 * directory; sl_atomic_commit() flushes, closes and renames it over the
 * final name; sl_atomic_abort() removes it. A failed or interrupted run
 * never leaves a partial file under the final name.
 */
#ifndef SL_ATOMIC_H
#define SL_ATOMIC_H

#include <stdio.h>

#include "core/status.h"

typedef struct sl_atomic sl_atomic;

/* Open a temporary file for `path`. NULL and err filled on failure. */
sl_atomic *sl_atomic_open(const char *path, sl_error *err);
/* The stream to write to. */
FILE *sl_atomic_file(sl_atomic *a);
/* The temporary file's name (e.g. for libraries that write by name). */
const char *sl_atomic_tmpname(const sl_atomic *a);
/* Flush, close and rename to the final name; frees a. On any write error
 * the temporary file is removed and err names the final path. */
sl_status sl_atomic_commit(sl_atomic *a, sl_error *err);
/* Close and remove the temporary file; frees a. Harmless on NULL. */
void sl_atomic_abort(sl_atomic *a);

#endif
