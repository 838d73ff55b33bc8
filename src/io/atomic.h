/*
 * atomic.h - write a file, or a whole output folder, so that it appears
 * complete or not at all.
 *
 * Files: sl_atomic_open() creates a hidden temporary file in the
 * destination's directory; sl_atomic_commit() flushes, closes and renames it
 * over the final name; sl_atomic_abort() removes it.
 *
 * Folders: sl_atomic_dir_open() creates a fresh hidden folder to write
 * every output into (below: beside the final folder, or inside it where the
 * folder cannot be renamed), after removing those of earlier runs into it
 * whose process is gone (a run killed by SIGKILL or a power cut;
 * sl_atomic_dir_stale says what); sl_atomic_dir_commit() writes its
 * manifest, carries into it by hard links what the final folder holds that
 * seislide did not write (outguard.h), swaps it in and removes the old
 * outputs, so stale files of an earlier run never sit beside new ones and
 * the user's files stay; sl_atomic_dir_abort() removes the fresh folder.
 *
 * Permissions: files 0666 and folders 0777, less the process umask (what
 * open(2) and mkdir(2) would give), never mkstemp's private 0600.
 */
#ifndef SL_ATOMIC_H
#define SL_ATOMIC_H

#include <stdio.h>

#include "core/status.h"

/* Temporary names: ".BASE" SL_ATOMIC_TMP_TAG "PID@HOST-XXXXXX". */
#define SL_ATOMIC_TMP_TAG ".tmp-"
/* Size of the text of sl_atomic_dir_stale(). */
#define SL_ATOMIC_STALE_TEXT 2048

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

/* ---- folders (atomic_dir.c) ------------------------------------------------
 *
 * How a folder is replaced. Where the folder can be renamed (the usual
 * case: its parent is writable and it is not a mount point), the fresh
 * folder is a hidden sibling, ".NAME.tmp-PID@HOST-XXXXXX", swapped in for
 * the folder in one step (renameat2 RENAME_EXCHANGE; two renames where the
 * file system lacks it): the folder holds the whole old outputs or the whole
 * new ones at every instant. Where it cannot be (a mount point, such as a
 * container's `-v host:/out` or a network share mounted there; a folder in a
 * read-only parent), the run writes it in place: the fresh folder is hidden
 * inside it (SL_OUTDIR_TMP_INSIDE "PID@HOST-XXXXXX") and each of its entries
 * is exchanged with the folder's entry of that name, one after another, the
 * manifest naming both runs' outputs meanwhile: every file and building
 * folder appears whole, and a run killed during those few renames leaves a
 * mixture of old and new outputs (never a partial file, never a user's file
 * lost) that the next run replaces.
 *
 * Both ways, every failure of the commit puts everything back as it was (the
 * entries taken into the fresh folder, sl_atomic_dir_take, included) and
 * removes the fresh folder keeping every entry of the user's
 * (outguard.h: sl_outdir_drop). */

/* Check an output folder (resolved: sl_outdir_resolve) before any work
 * (outguard.h): absent (its parent must be a writable folder), a folder
 * seislide wrote (it holds a readable manifest), or a folder holding nothing
 * but ".keep", ".gitkeep" and seislide's own names (the cache; and
 * "lost+found" at the root of a mounted volume). It must be
 * writable (a folder without write permission, mode 0555 even for root, is
 * refused), and no other file system may be mounted inside it (a mount
 * cannot move with a swap, and removing the old folder would empty it).
 * Returns SL_OK, or SL_EIO/SL_EINVAL/SL_EPARSE naming the path and, for a
 * folder seislide did not make, one entry in it. */
sl_status sl_outdir_check(const char *dir, sl_error *err);

typedef struct sl_atomic_dir sl_atomic_dir;

typedef enum sl_atomic_how {
    SL_ATOMIC_AUTO = 0, /* swap where the folder can be renamed, else in place */
    SL_ATOMIC_SWAP,     /* a sibling swapped in */
    SL_ATOMIC_IN_PLACE  /* entry by entry inside the folder (tests force it) */
} sl_atomic_how;

/* Create the fresh folder for final folder `dir` (resolved; checked with
 * sl_outdir_check first), after removing what killed runs into it left
 * (sl_atomic_dir_stale says what); `version` goes into its manifest. NULL
 * and err filled on failure. */
sl_atomic_dir *sl_atomic_dir_open(const char *dir, const char *version, sl_error *err);
/* sl_atomic_dir_open choosing how the folder is replaced. */
sl_atomic_dir *sl_atomic_dir_open_how(const char *dir, const char *version, sl_atomic_how how,
                                      sl_error *err);
/* The fresh folder to write into. */
const char *sl_atomic_dir_path(const sl_atomic_dir *d);
/* Nonzero when the folder is written in place (above). */
int sl_atomic_dir_in_place(const sl_atomic_dir *d);
/* What sl_atomic_dir_open found of earlier runs' fresh folders (beside the
 * folder, or inside it for one written in place): "" when none, else
 * "; "-separated "removed NAME (left by process PID, which is gone: ...)"
 * for a folder of this host whose process no longer exists (kill(pid, 0):
 * ESRCH; the user's entries in it, if any, moved back into the folder
 * first), "kept NAME (...)" for one of a live process, of another host, with
 * no owner in its name, or holding a user's entry that could not be put
 * back (never removed). Borrowed from d. */
const char *sl_atomic_dir_stale(const sl_atomic_dir *d);
/* Move the entry `name` of the final folder (when it has one: the cache)
 * into the fresh folder, so that it travels with the outputs; it is put
 * back by any failure of the commit and by sl_atomic_dir_abort. SL_EIO
 * naming it (nothing changed). */
sl_status sl_atomic_dir_take(sl_atomic_dir *d, const char *name, sl_error *err);
/* Before the swap: write the fresh folder's manifest (naming everything in
 * it), give the final folder one if it has none, then carry into the fresh
 * folder every entry of the final folder that the final folder's manifest
 * does not name (the user's: hard links, outguard.h's sl_manifest_carry).
 * d stays the caller's: on failure (SL_EINVAL: a user's entry where the run
 * writes one, or a mount point, named; SL_EIO) the final folder is
 * unchanged, and the caller still commits or aborts. */
sl_status sl_atomic_dir_prepare(sl_atomic_dir *d, sl_error *err);
/* Prepare (when not done), swap the fresh folder in for the final one (or
 * its entries, in place), then remove the old outputs: the user's entries
 * added or changed since the carry are moved into the new folder, nothing
 * else of the user's is removed unless the new folder holds it (outguard.h:
 * sl_outdir_drop). Frees d. On failure before the swap the final folder is
 * as it was, the taken entries back in it, and the fresh folder removed
 * (err says so); when the old folder cannot be removed whole after the swap,
 * SL_EIO says where it was kept and why (the new outputs are in place). */
sl_status sl_atomic_dir_commit(sl_atomic_dir *d, sl_error *err);
/* Put the taken entries back and remove the fresh folder, keeping any
 * user's entry in it (sl_outdir_drop); frees d. Harmless on NULL. Returns
 * 0, or the number of entries kept in the fresh folder (then `why`, size
 * nwhy, names the folder, the first entry and why). */
size_t sl_atomic_dir_abort(sl_atomic_dir *d, char *why, size_t nwhy);

/* Before sl_atomic_dir_open (which removes them): move the entry `name` of
 * a fresh folder left by a process of this host that is gone back into
 * `dir` (created when absent), when `dir` has no `name` itself. For what a
 * caller moves into the fresh folder just before the swap (a cache): a run
 * killed between that move and the swap left it there. Returns 1 when
 * moved (said: "took NAME back from FOLDER (left by process PID, ...)"),
 * else 0 (said: ""). */
int sl_atomic_dir_salvage(const char *dir, const char *name, char *said, size_t nsaid);

/* When `dir` is absent: put back in its place a fresh folder of this host's
 * run that is gone and that holds a manifest (a whole set of outputs: a run
 * killed between the two renames of a swap without RENAME_EXCHANGE left no
 * `dir`). Returns 1 when done (said: "put NAME back in its place (...)"),
 * else 0. */
int sl_atomic_dir_recover(const char *dir, char *said, size_t nsaid);

/* Remove a folder tree: no symbolic link followed, no other file system
 * entered (a mount point inside is left, and the tree is then not removed
 * whole). 0 or -1 (errno). */
int sl_remove_tree(const char *path);

#endif
