/*
 * walk.h - every entry of a folder tree, one at a time, without recursion:
 * the folders still to finish are a list on the heap, so a tree of any depth
 * is walked in a few kilobytes of stack, and what the system refuses (a path
 * longer than it takes, ENAMETOOLONG; too many open files) is an error naming
 * the path, never a crash.
 *
 * Entries are named by their path relative to the root folder (open as a
 * file descriptor the walk does not own) and reached through it with the
 * *at() calls of fsops.h, no symbolic link followed. A folder's entries come
 * in byte order of their names, a folder before them ("pre") and once more
 * after them ("post"). A folder on which another file system is mounted (a
 * mount root, or another device than the root's) is reported once with
 * `mount` set and never entered. A folder is entered only when it is still
 * the one that was listed (same device and inode): one replaced meanwhile is
 * an error (ESTALE), never followed elsewhere.
 */
#ifndef SL_IO_WALK_H
#define SL_IO_WALK_H

#include "io/fsops.h"

typedef struct sl_walk sl_walk;

typedef struct sl_walk_entry {
    const char *rel;  /* "a/b/c": relative to the root */
    const char *name; /* "c": its last part */
    sl_fstat st;      /* the entry itself (a link is not followed) */
    int post;         /* 1: a folder, after everything in it */
    int mount;        /* 1: a folder with another file system mounted on it (not entered) */
    int depth;        /* 1 for an entry of the root */
} sl_walk_entry;

/* A walk of the folder open as rootfd. NULL when out of memory or the
 * folder cannot be read (errno). */
sl_walk *sl_walk_open(int rootfd);
/* The next entry into *e (valid until the next call): 1; 0 after the last;
 * -1 on an error (errno; sl_walk_where names the path). An entry removed
 * after its folder was listed is skipped. */
int sl_walk_next(sl_walk *w, const sl_walk_entry **e);
/* Do not enter the folder just returned (its "pre" entry): no entries of it,
 * no "post" entry. */
void sl_walk_prune(sl_walk *w);
/* The path (relative to the root) of the last error, or of the last entry. */
const char *sl_walk_where(const sl_walk *w);
/* Harmless on NULL. */
void sl_walk_close(sl_walk *w);

#endif
