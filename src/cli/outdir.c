/* outdir.c - an output folder that survives interruption; see outdir.h. */
#include "outdir.h"

#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "io/outguard.h"

/* the folder as the user named it, as resolved (the one path every step uses), the fresh folder */
static char final_dir[4096], real_dir[4096], fresh[4096], lock_file[4096];
static sl_outlock *lock; /* held from cli_outdir_open to cli_outdir_finish */
static char said[4600]; /* the line printed when a signal ends the command */
static volatile sig_atomic_t writing, interrupted;

/* Async-signal-safe: write, unlink, rmdir, signal, raise. */
static void on_signal(int s)
{
    interrupted = s;
    if (writing)
        return;
    rmdir(fresh);
    if (lock_file[0])
        unlink(lock_file); /* the lock itself goes with the process */
    ssize_t w = write(STDERR_FILENO, said, strlen(said));
    (void)w;
    signal(s, SIG_DFL);
    raise(s);
}

/* Print each "; "-separated item of what sl_atomic_dir_open found. */
static void say_stale(const char *dir, const char *text)
{
    while (text && *text) {
        const char *end = strstr(text, "; ");
        int len = end ? (int)(end - text) : (int)strlen(text);
        cli_msg("output folder %s: %.*s", dir, len, text);
        text = end ? end + 2 : NULL;
    }
}

int cli_outdir_apart(const char *cmd, const char *what, const char *dir,
                     const char *const *inputs, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        sl_overlap v = inputs[i] ? sl_path_overlap(dir, inputs[i]) : SL_OVERLAP_NONE;
        if (v)
            return cli_usage(cmd, "%s '%s' %s '%s': give an output apart from every input "
                             "(nothing was read or written)", what, dir,
                             v == SL_OVERLAP_SAME     ? "is the input"
                             : v == SL_OVERLAP_INSIDE ? "is inside the input"
                                                      : "holds the input",
                             inputs[i]);
    }
    return CLI_EXIT_OK;
}

int cli_outdir_apart_floor(const char *cmd, const char *dir, const char *path, int folder_too)
{
    char folder[4096];
    const char *slash = strrchr(path, '/');
    snprintf(folder, sizeof folder, "%.*s", slash ? (int)(slash - path) : 1, slash ? path : ".");
    const char *in[2] = {path, folder_too && slash && slash != path ? folder : NULL};
    return cli_outdir_apart(cmd, "output folder", dir, in, 2);
}

/* The path resolved (real_dir), parents made, the lock taken, a folder of a
 * killed swap put back. */
static sl_status claim(const char *dir, sl_error *err)
{
    char bad[4096], note[8400];
    sl_status s = sl_outdir_resolve(dir, real_dir, sizeof real_dir, err);
    if (s)
        return s;
    snprintf(final_dir, sizeof final_dir, "%s", dir);
    if (sl_mkdir_parents(real_dir, bad, sizeof bad) != 0)
        return sl_error_set(err, SL_EIO, bad[0] ? bad : dir, 0, "cannot create the output "
                            "folder's parent: %s", strerror(errno));
    /* checked before the lock too: a write-protected folder (or one on a read-only
     * mount) is named as such, not by the lock that could not be made in it */
    if ((s = sl_outdir_check(real_dir, err)))
        return s;
    if (!(lock = sl_outlock_take(real_dir, err)))
        return err ? err->code : SL_EIO;
    snprintf(lock_file, sizeof lock_file, "%s", sl_outlock_path(lock));
    if (sl_atomic_dir_recover(real_dir, note, sizeof note))
        cli_msg("output folder %s: %s", dir, note);
    return SL_OK;
}

sl_atomic_dir *cli_outdir_open(const char *dir, const char *version, const char *salvage,
                               sl_error *err)
{
    if (claim(dir, err))
        return NULL;
    char text[8400];
    if (salvage && sl_outdir_check(real_dir, NULL) == SL_OK &&
        sl_atomic_dir_salvage(real_dir, salvage, text, sizeof text))
        cli_msg("output folder %s: %s", dir, text);
    /* INT, TERM and HUP held back from before the fresh folder exists until
     * the handler that removes it is in place (a shell starts a background
     * command with SIGINT ignored: one arriving in between was lost, and the
     * run went on to replace the outputs) */
    sigset_t hold, before;
    sigemptyset(&hold);
    sigaddset(&hold, SIGINT);
    sigaddset(&hold, SIGTERM);
    sigaddset(&hold, SIGHUP);
    sigprocmask(SIG_BLOCK, &hold, &before);
    sl_atomic_dir *d = sl_atomic_dir_open(real_dir, version, err);
    if (!d) {
        sigprocmask(SIG_SETMASK, &before, NULL);
        return NULL;
    }
    say_stale(dir, sl_atomic_dir_stale(d));
    snprintf(fresh, sizeof fresh, "%s", sl_atomic_dir_path(d));
    snprintf(said, sizeof said, "seislide: interrupted; the outputs in %s were left as they "
             "were\n", dir);
    signal(SIGINT, on_signal);
    signal(SIGTERM, on_signal);
    signal(SIGHUP, on_signal);
    sigprocmask(SIG_SETMASK, &before, NULL); /* one that came meanwhile is handled now */
    return d;
}

/* Nonzero when path is `dir` or lies inside it. */
static size_t under(const char *path, const char *dir)
{
    size_t k = strlen(dir);
    return k && !strncmp(path, dir, k) && (path[k] == '/' || !path[k]) ? k : 0;
}

void cli_outdir_final_name(char *path, size_t n)
{
    size_t k = under(path, fresh);
    if (!k && !(k = under(path, real_dir)))
        return;
    char tail[4096];
    snprintf(tail, sizeof tail, "%s", path + k);
    snprintf(path, n, "%.*s%s", (int)strcspn(final_dir, "\n"), final_dir, tail);
}

const char *cli_outdir_path(void) { return real_dir; }

void cli_outdir_writing(void) { writing = 1; }

int cli_outdir_interrupted(void) { return interrupted != 0; }

void cli_outdir_error(const sl_error *err)
{
    if (!interrupted)
        cli_print_error(err);
}

sl_status cli_outdir_commit(sl_atomic_dir **d, sl_error *err)
{
    if (interrupted) /* *d stays for cli_outdir_finish() to drop */
        return sl_error_set(err, SL_EIO, NULL, 0, "interrupted: the output folder is unchanged");
    sl_status s = sl_atomic_dir_prepare(*d, err); /* on failure *d stays, as above */
    if (s)
        return s;
    s = sl_atomic_dir_commit(*d, err); /* consumes *d */
    *d = NULL;
    if (s == SL_OK) /* a signal from now on finds the new outputs in place */
        snprintf(said, sizeof said, "seislide: interrupted after the output folder was written "
                 "whole\n");
    char cwd[4096];
    if (s == SL_OK && getcwd(cwd, sizeof cwd) == NULL && errno == ENOENT)
        cli_msg("note: the current folder was inside the output folder %s, which was replaced: "
                "cd to it again to see the new outputs", final_dir);
    return s;
}

void cli_outdir_finish(sl_atomic_dir *d)
{
    char why[4600];
    if (sl_atomic_dir_abort(d, why, sizeof why))
        cli_msg("output folder %s: %s", final_dir, why);
    lock_file[0] = '\0';
    sl_outlock_release(lock);
    lock = NULL;
    if (interrupted) {
        fputs(said, stderr);
        fflush(stderr);
        signal((int)interrupted, SIG_DFL);
        raise((int)interrupted);
    }
}
