/*
 * outguard.h - what keeps an output folder from harming anything seislide
 * did not write: the folder's manifest, the comparison of the output path
 * with every input, the missing parent folders, and the lock that keeps two
 * runs out of one folder. The fresh folder and its swap are atomic.h's.
 *
 * The manifest. A folder seislide writes holds SL_MANIFEST_NAME, text:
 *
 *     seislide-manifest 1
 *     # written by seislide 1.x; ...
 *     .seislide-cache/
 *     bldA/
 *     bldA/floor_01-ground.csv
 *     plant.csv
 *
 * the first line exactly SL_MANIFEST_HEAD, then comment lines ("#"), then
 * one path a line relative to the folder, in byte order: every file
 * (regular file or symbolic link) the run wrote, every folder it made (a
 * trailing "/"), and the cache folder SL_MANIFEST_CACHE as one line (its
 * entries are the cache's). A path never starts with '/', never has an
 * empty, "." or ".." component. What the manifest does not name (and is not
 * the manifest itself) is the user's: a run into the folder keeps it, byte
 * for byte and as the same file (a hard link: sl_manifest_carry).
 *
 * Paths compared. sl_path_resolve() makes a path absolute without symbolic
 * links, "." or "..": realpath(3) of its longest leading part that exists,
 * the rest appended component by component ("x/.." of a part that does not
 * exist yet is dropped, as mkdir -p would resolve it once made).
 */
#ifndef SL_IO_OUTGUARD_H
#define SL_IO_OUTGUARD_H

#include <stddef.h>

#include "core/status.h"

#define SL_MANIFEST_NAME ".seislide-manifest"
#define SL_MANIFEST_HEAD "seislide-manifest 1"
/* The result cache a run keeps in its output folder (plant/cache.h's
 * SL_CACHE_DIR_NAME): seislide's whatever the manifest says. */
#define SL_MANIFEST_CACHE ".seislide-cache"
/* A manifest over this size is refused unread. */
#define SL_MANIFEST_MAX_BYTES (64L << 20)
/* Longest path handled (as PATH_MAX). */
#define SL_OUTGUARD_PATH 4096

/* ---- paths -------------------------------------------------------------- */

/* Absolute, symbolic links, "." and ".." resolved (above) into buf of size
 * n. 0, or -1 with errno (ENAMETOOLONG, or what realpath says). */
int sl_path_resolve(const char *path, char *buf, size_t n);

typedef enum sl_overlap {
    SL_OVERLAP_NONE = 0,
    SL_OVERLAP_SAME,     /* the output is the input */
    SL_OVERLAP_INSIDE,   /* the output is inside the input (a folder) */
    SL_OVERLAP_CONTAINS  /* the output holds the input */
} sl_overlap;

/* How output path `out` (which may not exist) and an existing input path
 * meet, compared resolved; an input that is a symbolic link is compared both
 * as the link (its folder resolved) and as what it points to. An input that
 * does not exist is compared as written, resolved as far as it exists. */
sl_overlap sl_path_overlap(const char *out, const char *input);

/* Create the missing parent folders of dir (not dir itself), as mkdir -p
 * does, with mode 0777 less the umask. 0, or -1 with errno and, in bad
 * (size nbad), the folder that could not be made. */
int sl_mkdir_parents(const char *dir, char *bad, size_t nbad);

/* ---- the lock ----------------------------------------------------------- */

typedef struct sl_outlock sl_outlock;

/* Take the lock of output folder dir: the file ".BASE.lock" beside it (BASE
 * the folder's name, its parent resolved), locked with flock(2) (released
 * by the system when the process ends, however it ends), holding
 * "PID@HOST". NULL and err filled when another process holds it (SL_EINVAL:
 * "another run is writing this output folder: process PID@HOST (lock
 * FILE)") or when the file cannot be made (SL_EIO). On a file system
 * without locks (ENOLCK, EOPNOTSUPP) a lock is returned that holds nothing. */
sl_outlock *sl_outlock_take(const char *dir, sl_error *err);
/* The lock file's path ("" for a lock that holds nothing). */
const char *sl_outlock_path(const sl_outlock *l);
/* Remove the lock file and release the lock; frees l. Harmless on NULL. */
void sl_outlock_release(sl_outlock *l);

/* ---- the manifest ------------------------------------------------------- */

typedef struct sl_manifest sl_manifest;

/* Read dir's manifest into *m: SL_OK with *m NULL when dir has none; an
 * unreadable or malformed one is SL_EIO/SL_EPARSE naming it and its line. */
sl_status sl_manifest_read(const char *dir, sl_manifest **m, sl_error *err);
/* Nonzero when m names the relative path rel (a folder as "rel/"). */
int sl_manifest_has(const sl_manifest *m, const char *rel);
void sl_manifest_free(sl_manifest *m);

/* Write fresh/SL_MANIFEST_NAME naming everything in the folder fresh (the
 * outputs of one run, before anything is carried into it), with the program
 * `version` in its comment. */
sl_status sl_manifest_write(const char *fresh, const char *version, sl_error *err);

/* Into `to` (a run's fresh folder, its manifest written), every entry of the
 * folder `from` that old (from's manifest; NULL: none) does not name: a file
 * or symbolic link by a hard link (a copy where the file system refuses
 * one), a folder made with its mode and filled so. Never the manifest or the
 * cache. move != 0 renames instead, and only what `to` lacks (what was added
 * to `from` after the carry, swept after the swap). SL_EINVAL when a user's
 * entry has the path of one the run wrote (err names it), SL_EIO. */
sl_status sl_manifest_carry(const char *from, const char *to, const sl_manifest *old, int move,
                            sl_error *err);

#endif
