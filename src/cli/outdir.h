/*
 * outdir.h - an output folder written whole or not at all, also when the
 * process is interrupted: the command line's side of atomic.h's fresh folder.
 *
 * cli_outdir_open() makes the missing parents, takes the folder's lock,
 * checks the folder (sl_outdir_check), creates the fresh
 * sibling folder (removing those of killed earlier runs, and saying so on
 * stderr) and installs SIGINT, SIGTERM and SIGHUP handlers. While the
 * command computes, the fresh folder is still empty: a signal removes it and the process dies of the signal.
 * After cli_outdir_writing() a signal is only noted; cli_outdir_commit()
 * then drops the fresh folder instead of swapping it in, and
 * cli_outdir_finish() re-raises the signal. Either way one line is printed,
 * "seislide: interrupted; the outputs in DIR were left as they were", and the
 * process dies of the signal (exit status 128 + its number in a shell).
 */
#ifndef SL_CLI_OUTDIR_H
#define SL_CLI_OUTDIR_H

#include "io/atomic.h"

/* Before any work: CLI_EXIT_OK when output dir (a folder or a file; `what`
 * names it in the message: "output folder", "--history") is apart from each
 * of the n input paths (NULL ones skipped), else a usage error (exit 2)
 * naming the input dir is, is inside or holds (outguard.h: sl_path_overlap). */
int cli_outdir_apart(const char *cmd, const char *what, const char *dir,
                     const char *const *inputs, size_t n);
/* cli_outdir_apart for a floor file the operands reached (perhaps through a
 * symbolic link) and, with folder_too (a plant's floor), its building folder. */
int cli_outdir_apart_floor(const char *cmd, const char *dir, const char *path, int folder_too);
/* Resolve dir (outguard.h: sl_outdir_resolve; a link followed, "." and ".."
 * resolved: the one path every step uses, cli_outdir_path), make its
 * missing parents (mkdir -p), take its lock (another run
 * writing there: SL_EINVAL naming it; held until cli_outdir_finish), put
 * back a folder a killed swap left aside, take `salvage` (NULL: nothing;
 * the cache a run moves into its fresh folder just before the swap) back
 * from a fresh folder of a run killed in between (sl_atomic_dir_salvage),
 * check dir (sl_outdir_check) and create the fresh folder; what was found
 * of earlier runs is said on stderr. `version` goes into the manifest. */
sl_atomic_dir *cli_outdir_open(const char *dir, const char *version, const char *salvage,
                               sl_error *err);
/* From now on a signal is noted, not acted on. */
void cli_outdir_writing(void);
/* Write the manifest and carry the user's entries in (sl_atomic_dir_prepare;
 * on failure *d stays), swap the fresh folder in and set *d to NULL (SL_OK,
 * or the swap's error); after a noted signal do nothing and return SL_EIO. */
sl_status cli_outdir_commit(sl_atomic_dir **d, sl_error *err);
/* A path inside the fresh folder, or inside the resolved output folder,
 * renamed to the same path in the output folder as the user named it (what
 * the user will look for), in place; others unchanged. */
void cli_outdir_final_name(char *path, size_t n);
/* The output folder resolved by cli_outdir_open ("" before). */
const char *cli_outdir_path(void);
/* Nonzero when a signal was noted. */
int cli_outdir_interrupted(void);
/* Print err (cli_print_error) unless a signal was noted: then the error is
 * the signal's, which cli_outdir_finish() reports. */
void cli_outdir_error(const sl_error *err);
/* Drop a fresh folder not committed (NULL: nothing), release the lock and,
 * after a noted signal, die of it. */
void cli_outdir_finish(sl_atomic_dir *d);

#endif
