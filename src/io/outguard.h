/*
 * outguard.h - what keeps an output folder from harming anything seislide
 * did not write: the resolved path used for every step, the comparison of
 * the output path with every input, the missing parent folders, file systems
 * mounted in or on the folder, the lock that keeps two runs out of one
 * folder, the folder's manifest, the user's entries carried into a run's
 * fresh folder, and the removal of a folder that keeps every entry of the
 * user's. The fresh folder and its swap are atomic.h's.
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
 * empty, "." or ".." component. What the manifest does not name is the
 * user's (but for the names of sl_outdir_own_name at the folder's top): a
 * run into the folder keeps it, byte for byte and as the same file (a hard
 * link: sl_manifest_carry).
 *
 * Paths compared. sl_path_resolve() makes a path absolute without symbolic
 * links, "." or "..": realpath(3) of its longest leading part that exists,
 * the rest appended component by component ("x/.." of a part that does not
 * exist yet is dropped, as mkdir -p would resolve it once made).
 *
 * Every call that reads or changes a folder goes through fsops.h (so that
 * tests can make it fail); trees are walked without recursion (walk.h).
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
/* Names beginning so at an output folder's top are seislide's own: the lock
 * of a folder written in place, the fresh folders of such a folder and the
 * temporary files of a manifest being written. */
#define SL_OUTDIR_OWN_PREFIX ".seislide."
/* The lock inside a folder whose parent cannot be written (sl_outlock_take). */
#define SL_OUTDIR_LOCK_INSIDE ".seislide.lock"
/* Temporaries inside an output folder: ".seislide.tmp-PID@HOST-XXXXXX". */
#define SL_OUTDIR_TMP_INSIDE ".seislide.tmp-"
/* A manifest over this size is refused unread. */
#define SL_MANIFEST_MAX_BYTES (64L << 20)
/* Longest path handled (as PATH_MAX). */
#define SL_OUTGUARD_PATH 4096

/* ---- paths -------------------------------------------------------------- */

/* a "/" b into buf of size n (no "/" added after an empty a or one ending in
 * "/", nor before an empty b). 0, or -1 when it does not fit. */
int sl_path_join(char *buf, size_t n, const char *a, const char *b);

/* Absolute, symbolic links, "." and ".." resolved (above) into buf of size
 * n. 0, or -1 with errno (ENAMETOOLONG, or what realpath says). */
int sl_path_resolve(const char *path, char *buf, size_t n);

/* The output folder `dir` resolved (sl_path_resolve) into buf (size n): the
 * one path every step of a run uses (lock, checks, fresh folder, swap,
 * cache). A symbolic link is followed to its folder; one whose target does
 * not exist is refused (SL_EINVAL naming the link and its target), as is a
 * path that cannot be resolved (SL_EIO). */
sl_status sl_outdir_resolve(const char *dir, char *buf, size_t n, sl_error *err);

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

/* 1 when another file system is mounted on the resolved folder `real`
 * itself (statx's mount root, a mount point of /proc/self/mountinfo, or
 * another device than its parent's), else 0 (also when it does not exist). */
int sl_path_is_mount(const char *real);

/* The first mount point strictly inside the resolved folder `real`, from
 * /proc/self/mountinfo, into first (size n): 1 found, 0 none (or no /proc:
 * the walks of outcarry.c still never enter another file system). */
int sl_path_mount_inside(const char *real, char *first, size_t n);

/* Nonzero for a top-level name of an output folder that is seislide's
 * whatever its manifest says: the manifest, the cache and SL_OUTDIR_OWN_PREFIX. */
int sl_outdir_own_name(const char *name);

/* ---- the lock ----------------------------------------------------------- */

typedef struct sl_outlock sl_outlock;

/* Take the lock of output folder dir: the file ".BASE.lock" beside it (BASE
 * the folder's name, its parent resolved; SL_OUTDIR_LOCK_INSIDE inside the
 * folder when its parent cannot be written: a mount point in a read-only
 * tree), locked with flock(2) (released by the system when the process
 * ends, however it ends), holding "PID@HOST". The file is locked only when
 * it is still the one at that path after the lock is taken (a run that
 * removed it as it released the lock): else it is opened again. NULL and
 * err filled when another process holds it (SL_EINVAL: "another run is
 * writing this output folder: process PID@HOST (lock FILE)") or when the
 * file cannot be made (SL_EIO). On a file system without locks (ENOLCK,
 * EOPNOTSUPP) a lock is returned that holds nothing. */
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
/* sl_manifest_has(m, rel "/"): does it list rel as a folder? */
int sl_manifest_has_dir(const sl_manifest *m, const char *rel);
/* The number of paths m names, and the i-th in byte order. */
size_t sl_manifest_count(const sl_manifest *m);
const char *sl_manifest_path(const sl_manifest *m, size_t i);
/* Every path of a and of b (either may be NULL), as a new manifest; NULL
 * when out of memory. */
sl_manifest *sl_manifest_union(const sl_manifest *a, const sl_manifest *b);
void sl_manifest_free(sl_manifest *m);

/* Everything in folder dir as its manifest would name it (every file and
 * folder, the cache as one line; not the manifest nor, at the top, the names
 * of SL_OUTDIR_OWN_PREFIX). SL_EIO naming the path. */
sl_status sl_manifest_list(const char *dir, sl_manifest **m, sl_error *err);
/* Write m as dir's manifest, whole or not at all (a temporary file renamed
 * over it), with the program `version` in its comment. */
sl_status sl_manifest_save(const char *dir, const sl_manifest *m, const char *version,
                           sl_error *err);
/* m written back as dir's manifest byte for byte as sl_manifest_read read it
 * (else as sl_manifest_save writes it): an in-place commit put back. */
sl_status sl_manifest_restore(const char *dir, const sl_manifest *m, const char *version,
                              sl_error *err);

/* ---- the user's entries, carried and kept -------------------------------- */

/* What a carry made: for every file or link carried, the user's entry as it
 * was checked (device, inode, modification time, size) and the one made in
 * the fresh folder (its inode: the same for a hard link). */
typedef struct sl_carried sl_carried;
void sl_carried_free(sl_carried *c);

/* Into `to` (a run's fresh folder, its manifest written), every entry of the
 * folder `from` that old (from's manifest; NULL: none) does not name: a file
 * or symbolic link by a hard link (a copy where the file system refuses
 * one), a folder made with its mode and filled so. Never the manifest, the
 * cache or SL_OUTDIR_OWN_PREFIX names at the top. With top_stays (a folder
 * written in place) the user's entries at from's top are not carried (they
 * stay where they are) unless `to` has an entry of that name: only those
 * inside folders seislide wrote, or where the run writes. *made
 * (when not NULL) gets what was carried (sl_carried_free). Any error stops
 * the carry: SL_EINVAL when a user's entry has the path of one the run wrote
 * or is a mount point (err names it), SL_EIO naming the path and the
 * system's reason. `to` may then hold part of the carry (sl_outdir_drop
 * removes it). `from` is never changed. */
sl_status sl_manifest_carry(const char *from, const char *to, const sl_manifest *old,
                            int top_stays, sl_carried **made, sl_error *err);

enum {
    SL_DROP_OURS = 1, /* everything in the folder is seislide's (a fresh folder before its manifest) */
    SL_DROP_CACHE = 2 /* its cache (SL_MANIFEST_CACHE at its top) may go */
};
/* Remove folder x (a run's fresh folder not swapped in, the old folder
 * swapped out, or one a killed run left) and keep every byte of the user's:
 * an entry x's manifest names is seislide's and goes (a folder once empty);
 * with SL_DROP_OURS, or when x has no manifest, everything is. Any other
 * entry is the user's, and goes only when `dest` (the output folder) holds
 * the same at its path: the same file (device and inode), the version a
 * carry recorded in c (unchanged since: inode, modification time and size;
 * or the copy the carry made), or, for a folder x has no record of, equal
 * bytes (a regular file) or target (a link). One `dest` lacks is moved
 * there (a folder whole); one newer than the entry a carry made there
 * replaces it. The cache goes only with SL_DROP_CACHE (else it is moved
 * back to dest like a user's folder). No link is followed and no other file
 * system entered. Whatever cannot be so placed stays in x with its
 * manifest, and x stays: returns the number of entries kept (0: x is
 * gone), the first and why in `why` (size nwhy). */
size_t sl_outdir_drop(const char *x, const char *dest, const sl_carried *c, int flags, char *why,
                      size_t nwhy);

#endif
