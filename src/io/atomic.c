/* atomic.c - temporary file + rename, fresh folder + swap; see atomic.h. */
#define _GNU_SOURCE /* renameat2 (Linux, glibc >= 2.28) */
#include "io/atomic.h"
#include "io/outguard.h"
#include "io/owner.h"

#include <dirent.h>
#include <stdio.h>
#include <errno.h>
#include <fcntl.h>
#include <ftw.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Open file descriptors nftw may use while removing a tree. */
#define REMOVE_TREE_FDS 16

struct sl_atomic {
    FILE *f;
    char *path;
    char *tmp;
};

/* The process umask (read by setting and restoring it). */
static mode_t current_umask(void)
{
    mode_t m = umask(022);
    umask(m);
    return m;
}

/* "DIR/.BASE.tmp-PID@HOST-XXXXXX" for path "DIR/BASE" (malloc'd): the owner
 * is in the name, so that a later run can tell a folder left by a killed
 * process from a live run's. A trailing '/' of a folder path is ignored. */
static char *hidden_sibling(const char *path)
{
    size_t n = strlen(path);
    while (n > 1 && path[n - 1] == '/')
        n--;
    char host[80];
    sl_owner_host(host, sizeof host);
    size_t cap = n + strlen(host) + 64;
    char *t = malloc(cap);
    if (!t)
        return NULL;
    size_t dirlen = 0;
    for (size_t i = 0; i < n; i++)
        if (path[i] == '/')
            dirlen = i + 1;
    memcpy(t, path, dirlen);
    snprintf(t + dirlen, cap - dirlen, ".%.*s" SL_ATOMIC_TMP_TAG "%ld@%s-XXXXXX",
             (int)(n - dirlen), path + dirlen, (long)getpid(), host);
    return t;
}

sl_atomic *sl_atomic_open(const char *path, sl_error *err)
{
    sl_atomic *a = calloc(1, sizeof *a);
    if (!a || !(a->path = strdup(path)) || !(a->tmp = hidden_sibling(path))) {
        if (a) {
            free(a->path);
            free(a);
        }
        sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
        return NULL;
    }
    int fd = mkstemp(a->tmp);
    if (fd < 0 || fchmod(fd, 0666 & ~current_umask()) != 0 || !(a->f = fdopen(fd, "wb"))) {
        sl_error_set(err, SL_EIO, path, 0, "cannot create: %s", strerror(errno));
        if (fd >= 0) {
            close(fd);
            unlink(a->tmp);
        }
        free(a->tmp);
        free(a->path);
        free(a);
        return NULL;
    }
    return a;
}

FILE *sl_atomic_file(sl_atomic *a) { return a ? a->f : NULL; }

const char *sl_atomic_tmpname(const sl_atomic *a) { return a ? a->tmp : NULL; }

static void atomic_free(sl_atomic *a)
{
    free(a->tmp);
    free(a->path);
    free(a);
}

sl_status sl_atomic_commit(sl_atomic *a, sl_error *err)
{
    if (!a)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "no file to commit");
    int bad = ferror(a->f);
    bad |= (fflush(a->f) != 0);
    int e = errno;
    bad |= (fclose(a->f) != 0);
    a->f = NULL;
    if (!bad && rename(a->tmp, a->path) != 0) {
        e = errno;
        bad = 1;
    }
    if (bad) {
        unlink(a->tmp);
        sl_error_set(err, SL_EIO, a->path, 0, "cannot write: %s", strerror(e ? e : EIO));
        atomic_free(a);
        return SL_EIO;
    }
    atomic_free(a);
    return SL_OK;
}

void sl_atomic_abort(sl_atomic *a)
{
    if (!a)
        return;
    if (a->f)
        fclose(a->f);
    unlink(a->tmp);
    atomic_free(a);
}

/* ---- folders ------------------------------------------------------------ */

static int remove_entry(const char *p, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st;
    (void)ftw;
    return (flag == FTW_DP ? rmdir(p) : unlink(p)) == 0 || errno == ENOENT ? 0 : -1;
}

int sl_remove_tree(const char *path)
{
    return nftw(path, remove_entry, REMOVE_TREE_FDS, FTW_DEPTH | FTW_PHYS);
}

static int is_placeholder(const char *name)
{
    return !strcmp(name, ".keep") || !strcmp(name, ".gitkeep");
}

sl_status sl_outdir_check(const char *dir, sl_error *err)
{
    struct stat st;
    if (!dir || !*dir)
        return sl_error_set(err, SL_EINVAL, dir, 0, "no output folder given");
    if (stat(dir, &st) != 0) {
        if (errno != ENOENT)
            return sl_error_set(err, SL_EIO, dir, 0, "output folder: %s", strerror(errno));
        /* absent: its parent must be a writable folder */
        char *parent = strdup(dir);
        if (!parent)
            return sl_error_set(err, SL_ENOMEM, dir, 0, "out of memory");
        for (size_t n = strlen(parent); n > 1 && parent[n - 1] == '/'; n--)
            parent[n - 1] = '\0'; /* "out/" names the folder "out" */
        char *slash = strrchr(parent, '/');
        if (slash == parent)
            slash[1] = '\0';
        else if (slash)
            *slash = '\0';
        else
            strcpy(parent, ".");
        int ok = stat(parent, &st) == 0 && S_ISDIR(st.st_mode) && access(parent, W_OK | X_OK) == 0;
        free(parent);
        if (!ok)
            return sl_error_set(err, SL_EIO, dir, 0,
                                "cannot create the output folder: its parent is not a writable "
                                "folder");
        return SL_OK;
    }
    if (!S_ISDIR(st.st_mode))
        return sl_error_set(err, SL_EINVAL, dir, 0,
                            "output path exists and is not a folder; give a new or empty folder");
    sl_manifest *m;
    sl_status s = sl_manifest_read(dir, &m, err);
    if (s || m) { /* marked: seislide's; its other entries are kept by the run */
        sl_manifest_free(m);
        return s;
    }
    DIR *d = opendir(dir);
    if (!d)
        return sl_error_set(err, SL_EIO, dir, 0, "output folder: %s", strerror(errno));
    struct dirent *e;
    while (s == SL_OK && (e = readdir(d)) != NULL) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..") || is_placeholder(e->d_name) ||
            !strcmp(e->d_name, SL_MANIFEST_CACHE))
            continue;
        s = sl_error_set(err, SL_EINVAL, dir, 0,
                         "the output folder holds '%s' and seislide did not make it (it has no "
                         SL_MANIFEST_NAME "): seislide writes only into a new or empty folder, "
                         "or one it wrote; give another folder", e->d_name);
    }
    closedir(d);
    return s;
}

struct sl_atomic_dir {
    char *path; /* final */
    char *tmp;  /* fresh */
    char version[128];  /* for the manifest */
    int prepared;       /* manifest written, the user's entries carried */
    sl_manifest *old;   /* the final folder's manifest (NULL: none) */
    char stale[SL_ATOMIC_STALE_TEXT]; /* what was found of earlier runs (sl_atomic_dir_stale) */
};

/* Append to d->stale. */
static void stale_note(sl_atomic_dir *d, const char *fmt, const char *name, long pid,
                       const char *host)
{
    size_t used = strlen(d->stale);
    if (used + 1 >= sizeof d->stale)
        return;
    if (used)
        used += (size_t)snprintf(d->stale + used, sizeof d->stale - used, "; ");
    if (used < sizeof d->stale)
        snprintf(d->stale + used, sizeof d->stale - used, fmt, name, pid, host);
}

/* Where the fresh folders of runs into `path` live: *parent (the folder
 * that holds `path`, "." for a bare name), *prefix (".BASE.tmp-") and
 * whether `path` named a parent at all (*has_dir); returns *parent opened
 * (opendir; NULL when it cannot be read). */
static DIR *open_siblings(const char *path, char *parent, size_t nparent, char *prefix,
                          size_t nprefix, int *has_dir)
{
    size_t n = strlen(path);
    while (n > 1 && path[n - 1] == '/')
        n--;
    size_t dirlen = 0;
    for (size_t i = 0; i < n; i++)
        if (path[i] == '/')
            dirlen = i + 1;
    snprintf(parent, nparent, "%.*s", (int)(dirlen ? dirlen : 1), dirlen ? path : ".");
    snprintf(prefix, nprefix, ".%.*s" SL_ATOMIC_TMP_TAG, (int)(n - dirlen), path + dirlen);
    *has_dir = dirlen != 0;
    return opendir(parent);
}

/* Who left a fresh folder "PREFIX" + rest ("PID@HOST-XXXXXX"). */
typedef enum sibling_owner {
    OWNER_UNKNOWN, /* no owner in the name */
    OWNER_OTHER_HOST,
    OWNER_SELF,
    OWNER_LIVE,    /* a running process of this host */
    OWNER_GONE     /* a process of this host that no longer exists */
} sibling_owner;

static sibling_owner owner_of(const char *rest, long *pid, char *owner, size_t nowner)
{
    const char *at = strchr(rest, '@'), *dash = strrchr(rest, '-');
    char *end, host[80];
    *pid = strtol(rest, &end, 10);
    owner[0] = '\0';
    if (!(rest[0] >= '0' && rest[0] <= '9') || end != at || !dash || dash < at ||
        strlen(dash + 1) != 6 || *pid <= 0)
        return OWNER_UNKNOWN;
    snprintf(owner, nowner, "%.*s", (int)(dash - at - 1), at + 1);
    sl_owner_host(host, sizeof host);
    if (strcmp(owner, host) != 0)
        return OWNER_OTHER_HOST;
    if (*pid == (long)getpid())
        return OWNER_SELF;
    return sl_owner_pid_gone(*pid) ? OWNER_GONE : OWNER_LIVE;
}

/* The fresh folders of earlier runs into d->path, in its parent folder:
 * ".BASE.tmp-PID@HOST-XXXXXX" of this host whose process is gone
 * (kill(pid, 0) fails with ESRCH) are removed; the others are named in
 * d->stale (a live run's, another host's, or an older one with no owner). */
static void clean_stale(sl_atomic_dir *d)
{
    char parent[4096], prefix[1024];
    int has_dir;
    DIR *dir = open_siblings(d->path, parent, sizeof parent, prefix, sizeof prefix, &has_dir);
    if (!dir)
        return;
    size_t plen = strlen(prefix);
    for (struct dirent *e; (e = readdir(dir)) != NULL;) {
        if (strncmp(e->d_name, prefix, plen) != 0)
            continue;
        char full[8192], owner[80];
        struct stat st;
        snprintf(full, sizeof full, "%s%s%s", parent, has_dir ? "" : "/", e->d_name);
        if (lstat(full, &st) != 0 || !S_ISDIR(st.st_mode))
            continue;
        long pid;
        switch (owner_of(e->d_name + plen, &pid, owner, sizeof owner)) {
        case OWNER_UNKNOWN:
            stale_note(d, "kept %s (no owner recorded: remove it by hand if no run is writing "
                       "there)", e->d_name, 0, "");
            break;
        case OWNER_OTHER_HOST:
            stale_note(d, "kept %s (process %ld of host %s, which this run cannot check)",
                       e->d_name, pid, owner);
            break;
        case OWNER_SELF:
            break;
        case OWNER_LIVE:
            stale_note(d, "kept %s (process %ld is running: another run writing there)",
                       e->d_name, pid, "");
            break;
        case OWNER_GONE:
            if (sl_remove_tree(full) == 0)
                stale_note(d, "removed %s (left by process %ld, which is gone: an interrupted "
                           "run)", e->d_name, pid, "");
            else
                stale_note(d, "could not remove %s (left by process %ld, which is gone)",
                           e->d_name, pid, "");
            break;
        }
    }
    closedir(dir);
}

/* The next entry of d named prefix<owner> whose owner is gone (*pid: its
 * process), or NULL after the last. */
static struct dirent *next_gone(DIR *d, const char *prefix, long *pid)
{
    size_t plen = strlen(prefix);
    char owner[80];
    for (struct dirent *e; (e = readdir(d)) != NULL;)
        if (strncmp(e->d_name, prefix, plen) == 0 &&
            owner_of(e->d_name + plen, pid, owner, sizeof owner) == OWNER_GONE)
            return e;
    return NULL;
}

int sl_atomic_dir_salvage(const char *dir, const char *name, char *said, size_t nsaid)
{
    char parent[4096], prefix[1024], want[8192];
    struct stat st;
    int has_dir, moved = 0;
    if (said && nsaid)
        said[0] = '\0';
    snprintf(want, sizeof want, "%s/%s", dir, name);
    if (lstat(want, &st) == 0)
        return 0;
    DIR *d = open_siblings(dir, parent, sizeof parent, prefix, sizeof prefix, &has_dir);
    if (!d)
        return 0;
    long pid;
    for (struct dirent *e; !moved && (e = next_gone(d, prefix, &pid)) != NULL;) {
        char from[8192];
        snprintf(from, sizeof from, "%s%s%s/%s", parent, has_dir ? "" : "/", e->d_name, name);
        if (lstat(from, &st) != 0)
            continue;
        if (mkdir(dir, 0777) != 0 && errno != EEXIST)
            break;
        if (rename(from, want) != 0)
            break;
        moved = 1;
        if (said && nsaid)
            snprintf(said, nsaid, "took %s back from %s (left by process %ld, which is gone: a "
                     "run killed just before its swap)", name, e->d_name, pid);
    }
    closedir(d);
    return moved;
}

const char *sl_atomic_dir_stale(const sl_atomic_dir *d) { return d ? d->stale : ""; }

sl_atomic_dir *sl_atomic_dir_open(const char *dir, const char *version, sl_error *err)
{
    if (sl_outdir_check(dir, err))
        return NULL;
    sl_atomic_dir *a = calloc(1, sizeof *a);
    if (!a || !(a->path = strdup(dir)) || !(a->tmp = hidden_sibling(dir))) {
        if (a)
            free(a->path);
        free(a);
        sl_error_set(err, SL_ENOMEM, dir, 0, "out of memory");
        return NULL;
    }
    snprintf(a->version, sizeof a->version, "%s", version ? version : "seislide");
    clean_stale(a);
    if (!mkdtemp(a->tmp) || chmod(a->tmp, 0777 & ~current_umask()) != 0) {
        sl_error_set(err, SL_EIO, dir, 0, "cannot create a folder beside it: %s", strerror(errno));
        rmdir(a->tmp);
        free(a->tmp);
        free(a->path);
        free(a);
        return NULL;
    }
    return a;
}

int sl_atomic_dir_recover(const char *dir, char *said, size_t nsaid)
{
    char parent[4096], prefix[1024], from[8192], mark[8400];
    struct stat st;
    int has_dir, done = 0;
    if (said && nsaid)
        said[0] = '\0';
    if (lstat(dir, &st) == 0 || errno != ENOENT)
        return 0;
    DIR *d = open_siblings(dir, parent, sizeof parent, prefix, sizeof prefix, &has_dir);
    if (!d)
        return 0;
    long pid;
    for (struct dirent *e; !done && (e = next_gone(d, prefix, &pid)) != NULL;) {
        snprintf(from, sizeof from, "%s%s%s", parent, has_dir ? "" : "/", e->d_name);
        snprintf(mark, sizeof mark, "%s/" SL_MANIFEST_NAME, from);
        if (lstat(mark, &st) != 0 || rename(from, dir) != 0)
            continue;
        done = 1;
        if (said && nsaid)
            snprintf(said, nsaid, "put %s back in its place (left by process %ld, which is gone: "
                     "a run killed while it swapped the folder in)", e->d_name, pid);
    }
    closedir(d);
    return done;
}

const char *sl_atomic_dir_path(const sl_atomic_dir *d) { return d ? d->tmp : NULL; }


static void atomic_dir_free(sl_atomic_dir *d)
{
    sl_manifest_free(d->old);
    free(d->tmp);
    free(d->path);
    free(d);
}

sl_status sl_atomic_dir_prepare(sl_atomic_dir *d, sl_error *err)
{
    if (!d)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "no folder to commit");
    if (d->prepared)
        return SL_OK;
    struct stat st;
    sl_status s = sl_manifest_write(d->tmp, d->version, err);
    if (!s && lstat(d->path, &st) == 0) {
        sl_manifest_free(d->old);
        d->old = NULL;
        s = sl_manifest_read(d->path, &d->old, err);
        if (!s)
            s = sl_manifest_carry(d->path, d->tmp, d->old, 0, err);
    }
    d->prepared = !s;
    return s;
}

/* After the swap: what was added to the old folder since the carry, moved
 * into the new one; then the old folder removed. */
static void drop_old(sl_atomic_dir *d, const char *old)
{
    sl_manifest_carry(old, d->path, d->old, 1, NULL);
    sl_remove_tree(old);
}

sl_status sl_atomic_dir_commit(sl_atomic_dir *d, sl_error *err)
{
    if (!d)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "no folder to commit");
    struct stat st;
    sl_status s = sl_atomic_dir_prepare(d, err);
    if (s) {
        sl_remove_tree(d->tmp);
        atomic_dir_free(d);
        return s;
    }
    if (lstat(d->path, &st) != 0) {
        if (rename(d->tmp, d->path) != 0)
            s = sl_error_set(err, SL_EIO, d->path, 0, "cannot create: %s", strerror(errno));
    } else {
        int done = 0;
#ifdef RENAME_EXCHANGE
        /* one atomic step: the old folder now has the fresh folder's name */
        done = renameat2(AT_FDCWD, d->tmp, AT_FDCWD, d->path, RENAME_EXCHANGE) == 0;
#endif
        if (!done) {
            /* two renames: the old folder aside, the fresh one in (a run killed in
             * between leaves no DIR: the next one puts a folder back,
             * sl_atomic_dir_recover) */
            char *old = hidden_sibling(d->path);
            if (!old || !mkdtemp(old) || rmdir(old) != 0 || rename(d->path, old) != 0) {
                s = sl_error_set(err, SL_EIO, d->path, 0, "cannot replace: %s", strerror(errno));
            } else if (rename(d->tmp, d->path) != 0) {
                s = sl_error_set(err, SL_EIO, d->path, 0, "cannot replace: %s", strerror(errno));
                rename(old, d->path);
            } else {
                drop_old(d, old);
            }
            free(old);
            if (s)
                sl_remove_tree(d->tmp);
            atomic_dir_free(d);
            return s;
        }
        drop_old(d, d->tmp); /* after the exchange d->tmp holds the old outputs */
        atomic_dir_free(d);
        return SL_OK;
    }
    if (s)
        sl_remove_tree(d->tmp);
    atomic_dir_free(d);
    return s;
}

void sl_atomic_dir_abort(sl_atomic_dir *d)
{
    if (!d)
        return;
    sl_remove_tree(d->tmp);
    atomic_dir_free(d);
}
