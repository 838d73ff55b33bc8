/*
 * atomic.h - write a file, or a whole output folder, so that it appears
 * complete or not at all.
 *
 * Files: sl_atomic_open() creates a hidden temporary file in the
 * destination's directory; sl_atomic_commit() flushes, closes and renames it
 * over the final name; sl_atomic_abort() removes it.
 *
 * Folders: sl_atomic_dir_open() creates a fresh hidden sibling folder
 * (".NAME.tmp-PID@HOST-XXXXXX", the owner in the name) to write every output
 * into, after removing those of earlier runs into NAME whose process is gone
 * (a run killed by SIGKILL or a power cut; sl_atomic_dir_stale says what); sl_atomic_dir_commit()
 * writes its manifest, carries into it by hard links what the final folder
 * holds that seislide did not write (outguard.h), swaps it in for the final
 * folder (renameat2 RENAME_EXCHANGE where the system has it, else two
 * renames) and removes the old folder, so stale files of an earlier run never
 * sit beside new ones and the user's files stay; sl_atomic_dir_abort()
 * removes the fresh folder and everything in it.
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

/* Check an output folder before any work (outguard.h): absent (its parent
 * must be a writable folder), a folder seislide wrote (it holds a readable
 * manifest), or a folder holding nothing but ".keep", ".gitkeep" and the
 * cache. Returns SL_OK, or SL_EIO/SL_EINVAL/SL_EPARSE naming the path and,
 * for a folder seislide did not make, one entry in it. */
sl_status sl_outdir_check(const char *dir, sl_error *err);

typedef struct sl_atomic_dir sl_atomic_dir;

/* Create the fresh folder for final folder `dir` (checked with
 * sl_outdir_check first); `version` goes into its manifest. NULL and err
 * filled on failure. */
sl_atomic_dir *sl_atomic_dir_open(const char *dir, const char *version, sl_error *err);
/* The fresh folder to write into. */
const char *sl_atomic_dir_path(const sl_atomic_dir *d);
/* What sl_atomic_dir_open found beside the final folder of earlier runs'
 * fresh folders (same name pattern): "" when none, else "; "-separated
 * "removed NAME (left by process PID, which is gone: ...)" for a folder of
 * this host whose process no longer exists (kill(pid, 0): ESRCH), and
 * "kept NAME (...)" for one of a live process, of another host, or with no
 * owner in its name (never removed). Borrowed from d. */
const char *sl_atomic_dir_stale(const sl_atomic_dir *d);
/* Before the swap: write the fresh folder's manifest (naming everything in
 * it), then carry into it every entry of the final folder that the final
 * folder's manifest does not name (the user's: hard links, outguard.h's
 * sl_manifest_carry). d stays the caller's: on failure (SL_EINVAL: a user's
 * entry where the run writes one, named) nothing has changed but the fresh
 * folder, and the caller may still take back what it moved in. */
sl_status sl_atomic_dir_prepare(sl_atomic_dir *d, sl_error *err);
/* Prepare (when not done), swap the fresh folder in for the final one, move
 * into it what was added to the old one since the carry, and remove the old
 * one; frees d. On failure the final folder is unchanged (the fresh one
 * removed). */
sl_status sl_atomic_dir_commit(sl_atomic_dir *d, sl_error *err);
/* Remove the fresh folder and its contents; frees d. Harmless on NULL. */
void sl_atomic_dir_abort(sl_atomic_dir *d);

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

/* Remove a folder tree (no symbolic links followed). 0 or -1 (errno). */
int sl_remove_tree(const char *path);

#endif
