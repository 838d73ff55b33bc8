/*
 * atomic_name.h - the hidden temporary names of atomic.c and atomic_dir.c
 * (internal): ".BASE" SL_ATOMIC_TMP_TAG "PID@HOST-XXXXXX" beside a path, the
 * owner in the name so that a later run can tell what a killed process left
 * from a live run's.
 */
#ifndef SL_IO_ATOMIC_NAME_H
#define SL_IO_ATOMIC_NAME_H

#include <sys/types.h>

/* "DIR/.BASE.tmp-PID@HOST-XXXXXX" for path "DIR/BASE" (malloc'd; NULL when
 * out of memory); a trailing '/' of a folder path is ignored. */
char *sl_atomic_hidden_name(const char *path);
/* Another random XXXXXX at the end of a name made so (after EEXIST). */
void sl_atomic_hidden_renew(char *name);
/* The process umask (read by setting and restoring it). */
mode_t sl_atomic_umask(void);

#endif
