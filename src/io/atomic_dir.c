/* atomic_dir.c - an output folder replaced whole, or entry by entry where it
 * cannot be renamed; see atomic.h. */
#define _GNU_SOURCE /* renameat2 flags, O_DIRECTORY, O_CLOEXEC */
#include "core/compare.h"
#include "io/atomic.h"
#include "io/atomic_name.h"
#include "io/fsops.h"
#include "io/outguard.h"
#include "io/owner.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#ifndef RENAME_NOREPLACE
#define RENAME_NOREPLACE (1 << 0)
#endif
#ifndef RENAME_EXCHANGE
#define RENAME_EXCHANGE (1 << 1)
#endif

#define PATH_CAP SL_OUTGUARD_PATH
/* Tries at a free name for the fresh folder. */
#define TMP_TRIES 100
/* What is said of a folder kept (sl_outdir_drop's reason). */
#define WHY_CAP 1024

static int is_placeholder(const char *name)
{
    return !strcmp(name, ".keep") || !strcmp(name, ".gitkeep");
}

/* "a" + "/" + "b" into buf (n); -1 when it does not fit. */
/* The parent folder of resolved path p into buf ("/" for "/x"). */
static void parent_of(const char *p, char *buf, size_t n)
{
    const char *slash = strrchr(p, '/');
    snprintf(buf, n, "%.*s", !slash ? 1 : slash == p ? 1 : (int)(slash - p), slash ? p : ".");
}

/* Append to err's message (when there is one). */
static void add_to(sl_error *err, const char *fmt, ...)
{
    if (!err)
        return;
    size_t used = strlen(err->msg);
    va_list ap;
    va_start(ap, fmt);
    if (used + 1 < sizeof err->msg)
        vsnprintf(err->msg + used, sizeof err->msg - used, fmt, ap);
    va_end(ap);
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
        char name[PATH_CAP], parent[PATH_CAP];
        size_t n = strlen(dir);
        while (n > 1 && dir[n - 1] == '/')
            n--; /* "out/" names the folder "out" */
        if (n >= sizeof name)
            return sl_error_set(err, SL_EINVAL, dir, 0, "output folder: %s",
                                strerror(ENAMETOOLONG));
        snprintf(name, sizeof name, "%.*s", (int)n, dir);
        parent_of(name, parent, sizeof parent);
        int ok = stat(parent, &st) == 0 && S_ISDIR(st.st_mode) && access(parent, W_OK | X_OK) == 0;
        if (!ok)
            return sl_error_set(err, SL_EIO, dir, 0,
                                "cannot create the output folder: its parent is not a writable "
                                "folder");
        return SL_OK;
    }
    if (!S_ISDIR(st.st_mode))
        return sl_error_set(err, SL_EINVAL, dir, 0,
                            "output path exists and is not a folder; give a new or empty folder");
    if (access(dir, W_OK | X_OK) != 0 || !(st.st_mode & 0222)) {
        char why[64];
        if (access(dir, W_OK | X_OK) != 0)
            snprintf(why, sizeof why, "%s", strerror(errno));
        else
            snprintf(why, sizeof why, "mode %04o", (unsigned)(st.st_mode & 07777));
        return sl_error_set(err, SL_EIO, dir, 0, "the output folder is write-protected (%s): "
                            "seislide does not replace a folder that may not be written; make "
                            "it writable (chmod u+w), or give another folder (nothing was "
                            "written)", why);
    }
    char mnt[PATH_CAP];
    if (sl_path_mount_inside(dir, mnt, sizeof mnt))
        return sl_error_set(err, SL_EINVAL, dir, 0, "a file system is mounted at %s, inside the "
                            "output folder: seislide replaces the folder's outputs as a whole "
                            "and would not keep a mount in its place; unmount it, or mount it "
                            "outside the output folder (nothing was written)", mnt);
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
    int mount = -1; /* whether dir is a mount point, found when needed */
    while (s == SL_OK && (e = readdir(d)) != NULL) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..") || is_placeholder(e->d_name) ||
            sl_outdir_own_name(e->d_name))
            continue;
        /* the file system's own folder at the root of a volume mounted there (ext4) */
        if (!strcmp(e->d_name, "lost+found") && (mount < 0 ? (mount = sl_path_is_mount(dir)) : mount))
            continue;
        s = sl_error_set(err, SL_EINVAL, dir, 0,
                         "the output folder holds '%s' and seislide did not make it (it has no "
                         SL_MANIFEST_NAME "): seislide writes only into a new or empty folder, "
                         "or one it wrote; give another folder", e->d_name);
    }
    closedir(d);
    return s;
}

/* ---- the folders runs into a folder leave ----------------------------------- */

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

/* A folder (or a temporary manifest) a run into `dir` made. */
typedef struct run_folder {
    char full[PATH_CAP];
    char name[NAME_MAX + 1];
    int is_dir, beside; /* beside: in dir's parent (a sibling), else inside dir */
    sibling_owner owner;
    long pid;
    char host[80];
} run_folder;

/* Every ".BASE.tmp-*" beside the resolved folder dir and every
 * SL_OUTDIR_TMP_INSIDE "*" inside it, into *out (malloc'd): the count. */
static size_t list_runs(const char *dir, run_folder **out)
{
    char parent[PATH_CAP], base[NAME_MAX + 1], prefix[NAME_MAX + 16];
    parent_of(dir, parent, sizeof parent);
    const char *slash = strrchr(dir, '/');
    snprintf(base, sizeof base, "%s", slash ? slash + 1 : dir);
    snprintf(prefix, sizeof prefix, ".%s" SL_ATOMIC_TMP_TAG, base);
    const char *where[2] = {parent, dir}, *pre[2] = {prefix, SL_OUTDIR_TMP_INSIDE};
    run_folder *r = NULL;
    size_t n = 0, cap = 0;
    for (int k = 0; k < 2; k++) {
        DIR *d = opendir(where[k]);
        for (struct dirent *e; d && (e = readdir(d)) != NULL;) {
            size_t plen = strlen(pre[k]);
            if (strncmp(e->d_name, pre[k], plen) != 0)
                continue;
            if (n == cap) {
                size_t c = cap ? 2 * cap : 8;
                run_folder *p = realloc(r, c * sizeof *p);
                if (!p)
                    break;
                r = p;
                cap = c;
            }
            run_folder *f = &r[n];
            struct stat st;
            if (sl_path_join(f->full, sizeof f->full, where[k], e->d_name) || lstat(f->full, &st) != 0 ||
                !(S_ISDIR(st.st_mode) || (k == 1 && S_ISREG(st.st_mode))))
                continue;
            snprintf(f->name, sizeof f->name, "%s", e->d_name);
            f->is_dir = S_ISDIR(st.st_mode);
            f->beside = k == 0;
            f->owner = owner_of(e->d_name + plen, &f->pid, f->host, sizeof f->host);
            n++;
        }
        if (d)
            closedir(d);
    }
    *out = r;
    return n;
}

/* ---- the fresh folder ------------------------------------------------------------ */

struct sl_atomic_dir {
    char *path;         /* final, resolved */
    char *tmp;          /* fresh */
    int in_place;       /* the fresh folder inside `path`, its entries exchanged one by one */
    char version[128];  /* for the manifest */
    int prepared;       /* manifest written, the user's entries carried */
    sl_manifest *old;   /* the final folder's manifest (NULL: none) */
    sl_manifest *mine;  /* the fresh folder's */
    sl_carried *carried;
    char **taken;       /* names moved from the final folder into the fresh one */
    size_t ntaken;
    char stale[SL_ATOMIC_STALE_TEXT]; /* what was found of earlier runs (sl_atomic_dir_stale) */
};

/* Append to d->stale. */
static void stale_note(sl_atomic_dir *d, const char *fmt, ...)
{
    size_t used = strlen(d->stale);
    if (used + 1 >= sizeof d->stale)
        return;
    if (used)
        used += (size_t)snprintf(d->stale + used, sizeof d->stale - used, "; ");
    va_list ap;
    va_start(ap, fmt);
    if (used < sizeof d->stale)
        vsnprintf(d->stale + used, sizeof d->stale - used, fmt, ap);
    va_end(ap);
}

/* The folders earlier runs into d->path left: those of this host whose
 * process is gone are removed, the user's entries in them moved back into
 * the folder first (sl_outdir_drop); the others are named in d->stale. */
static void clean_stale(sl_atomic_dir *d)
{
    run_folder *r;
    size_t n = list_runs(d->path, &r);
    char why[WHY_CAP];
    for (size_t i = 0; i < n; i++) {
        run_folder *f = &r[i];
        if (!f->is_dir) { /* a manifest being written */
            if (f->owner == OWNER_GONE)
                sl_fs->unlink(AT_FDCWD, f->full, 0);
            continue;
        }
        switch (f->owner) {
        case OWNER_UNKNOWN:
            stale_note(d, "kept %s (no owner recorded: remove it by hand if no run is writing "
                       "there)", f->name);
            break;
        case OWNER_OTHER_HOST:
            stale_note(d, "kept %s (process %ld of host %s, which this run cannot check)",
                       f->name, f->pid, f->host);
            break;
        case OWNER_SELF:
            break;
        case OWNER_LIVE:
            stale_note(d, "kept %s (process %ld is running: another run writing there)", f->name,
                       f->pid);
            break;
        case OWNER_GONE:
            if (sl_outdir_drop(f->full, d->path, NULL, SL_DROP_CACHE, why, sizeof why) == 0)
                stale_note(d, "removed %s (left by process %ld, which is gone: an interrupted "
                           "run)", f->name, f->pid);
            else
                stale_note(d, "kept %s (left by process %ld, which is gone): it holds %s; look "
                           "into it, then remove it", f->name, f->pid, why);
            break;
        }
    }
    free(r);
}

int sl_atomic_dir_salvage(const char *dir, const char *name, char *said, size_t nsaid)
{
    char want[PATH_CAP], from[PATH_CAP];
    struct stat st;
    int moved = 0;
    if (said && nsaid)
        said[0] = '\0';
    if (sl_path_join(want, sizeof want, dir, name) || lstat(want, &st) == 0)
        return 0;
    run_folder *r;
    size_t n = list_runs(dir, &r);
    for (size_t i = 0; !moved && i < n; i++) {
        if (!r[i].is_dir || r[i].owner != OWNER_GONE || sl_path_join(from, sizeof from, r[i].full, name) ||
            lstat(from, &st) != 0)
            continue;
        if (sl_fs->mkdir(AT_FDCWD, dir, 0777) != 0 && errno != EEXIST)
            break;
        if (sl_fs->rename(AT_FDCWD, from, AT_FDCWD, want, 0) != 0)
            break;
        moved = 1;
        if (said && nsaid)
            snprintf(said, nsaid, "took %s back from %s (left by process %ld, which is gone: a "
                     "run killed just before its swap)", name, r[i].name, r[i].pid);
    }
    free(r);
    return moved;
}

int sl_atomic_dir_recover(const char *dir, char *said, size_t nsaid)
{
    char mark[PATH_CAP];
    struct stat st;
    int done = 0;
    if (said && nsaid)
        said[0] = '\0';
    if (lstat(dir, &st) == 0 || errno != ENOENT)
        return 0;
    run_folder *r;
    size_t n = list_runs(dir, &r);
    for (size_t i = 0; !done && i < n; i++) {
        if (!r[i].beside || !r[i].is_dir || r[i].owner != OWNER_GONE ||
            sl_path_join(mark, sizeof mark, r[i].full, SL_MANIFEST_NAME) || lstat(mark, &st) != 0 ||
            sl_fs->rename(AT_FDCWD, r[i].full, AT_FDCWD, dir, 0) != 0)
            continue;
        done = 1;
        if (said && nsaid)
            snprintf(said, nsaid, "put %s back in its place (left by process %ld, which is gone: "
                     "a run killed while it swapped the folder in)", r[i].name, r[i].pid);
    }
    free(r);
    return done;
}

const char *sl_atomic_dir_stale(const sl_atomic_dir *d) { return d ? d->stale : ""; }

const char *sl_atomic_dir_path(const sl_atomic_dir *d) { return d ? d->tmp : NULL; }

int sl_atomic_dir_in_place(const sl_atomic_dir *d) { return d && d->in_place; }

static void atomic_dir_free(sl_atomic_dir *d)
{
    for (size_t i = 0; i < d->ntaken; i++)
        free(d->taken[i]);
    free(d->taken);
    sl_carried_free(d->carried);
    sl_manifest_free(d->old);
    sl_manifest_free(d->mine);
    free(d->tmp);
    free(d->path);
    free(d);
}

/* Whether folder `dir` (existing) cannot be renamed: a mount point, or in a
 * parent that may not be written. */
static int cannot_rename(const char *dir)
{
    char parent[PATH_CAP];
    parent_of(dir, parent, sizeof parent);
    return sl_path_is_mount(dir) || access(parent, W_OK | X_OK) != 0;
}

sl_atomic_dir *sl_atomic_dir_open_how(const char *dir, const char *version, sl_atomic_how how,
                                      sl_error *err)
{
    if (sl_outdir_check(dir, err))
        return NULL;
    sl_atomic_dir *a = calloc(1, sizeof *a);
    if (!a || !(a->path = strdup(dir))) {
        free(a);
        sl_error_set(err, SL_ENOMEM, dir, 0, "out of memory");
        return NULL;
    }
    snprintf(a->version, sizeof a->version, "%s", version ? version : "seislide");
    struct stat st;
    int exists = lstat(dir, &st) == 0;
    a->in_place = how == SL_ATOMIC_IN_PLACE || (how == SL_ATOMIC_AUTO && exists && cannot_rename(dir));
    if (a->in_place && !exists && sl_fs->mkdir(AT_FDCWD, dir, 0777) != 0) {
        sl_error_set(err, SL_EIO, dir, 0, "cannot create: %s", strerror(errno));
        atomic_dir_free(a);
        return NULL;
    }
    clean_stale(a);
    char name[NAME_MAX + 1], inside[PATH_CAP];
    int made = 0, e = 0;
    for (int t = 0; !made && t < TMP_TRIES; t++) {
        free(a->tmp);
        a->tmp = NULL;
        if (a->in_place) {
            sl_owner_tmp_name(name, sizeof name, SL_OUTDIR_TMP_INSIDE);
            a->tmp = sl_path_join(inside, sizeof inside, dir, name) ? NULL : strdup(inside);
        } else {
            a->tmp = sl_atomic_hidden_name(dir);
        }
        if (!a->tmp) {
            e = ENOMEM;
            break;
        }
        made = sl_fs->mkdir(AT_FDCWD, a->tmp, 0777) == 0;
        e = made ? 0 : errno;
        if (e != EEXIST)
            break;
    }
    if (!made) {
        sl_error_set(err, SL_EIO, dir, 0, "cannot create a folder %s it: %s",
                     a->in_place ? "inside" : "beside", strerror(e ? e : EIO));
        atomic_dir_free(a);
        return NULL;
    }
    return a;
}

sl_atomic_dir *sl_atomic_dir_open(const char *dir, const char *version, sl_error *err)
{
    return sl_atomic_dir_open_how(dir, version, SL_ATOMIC_AUTO, err);
}

sl_status sl_atomic_dir_take(sl_atomic_dir *d, const char *name, sl_error *err)
{
    char from[PATH_CAP], to[PATH_CAP];
    struct stat st;
    if (!d)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "no folder to commit");
    if (sl_path_join(from, sizeof from, d->path, name) || sl_path_join(to, sizeof to, d->tmp, name))
        return sl_error_set(err, SL_EIO, d->path, 0, "path too long");
    if (lstat(from, &st) != 0)
        return SL_OK; /* nothing to take */
    char **t = realloc(d->taken, (d->ntaken + 1) * sizeof *t);
    if (!t || !(t[d->ntaken] = strdup(name))) {
        if (t)
            d->taken = t;
        return sl_error_set(err, SL_ENOMEM, from, 0, "out of memory");
    }
    d->taken = t;
    if (sl_fs->rename(AT_FDCWD, from, AT_FDCWD, to, 0) != 0) {
        free(t[d->ntaken]);
        return sl_error_set(err, SL_EIO, from, 0, "cannot carry it over with the outputs: %s; "
                            "the output folder is unchanged", strerror(errno));
    }
    d->ntaken++;
    return SL_OK;
}

/* The taken entries back into the final folder: 0, or how many could not be. */
static size_t put_back(sl_atomic_dir *d)
{
    char from[PATH_CAP], to[PATH_CAP];
    size_t lost = 0;
    struct stat st;
    while (d->ntaken) {
        char *name = d->taken[--d->ntaken];
        if (!sl_path_join(from, sizeof from, d->tmp, name) && !sl_path_join(to, sizeof to, d->path, name) &&
            lstat(from, &st) == 0 && sl_fs_rename_new(AT_FDCWD, from, AT_FDCWD, to) != 0)
            lost++;
        free(name);
    }
    return lost;
}

sl_status sl_atomic_dir_prepare(sl_atomic_dir *d, sl_error *err)
{
    if (!d)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "no folder to commit");
    if (d->prepared)
        return SL_OK;
    struct stat st;
    sl_manifest_free(d->mine);
    d->mine = NULL;
    sl_status s = sl_manifest_list(d->tmp, &d->mine, err);
    if (!s)
        s = sl_manifest_save(d->tmp, d->mine, d->version, err);
    if (!s && lstat(d->path, &st) == 0) {
        sl_manifest_free(d->old);
        d->old = NULL;
        sl_carried_free(d->carried);
        d->carried = NULL;
        s = sl_manifest_read(d->path, &d->old, err);
        /* a folder swapped out must say what in it is seislide's (sl_outdir_drop) */
        if (!s && !d->old)
            s = sl_manifest_save(d->path, NULL, d->version, err);
        if (!s)
            s = sl_manifest_carry(d->path, d->tmp, d->old, d->in_place, &d->carried, err);
    }
    d->prepared = !s;
    return s;
}

/* After a failure before the swap: the taken entries back, the fresh folder
 * removed (the user's entries in it kept), d freed; returns s. */
static sl_status fail_back(sl_atomic_dir *d, sl_status s, sl_error *err)
{
    char why[WHY_CAP];
    size_t lost = put_back(d);
    size_t kept = sl_outdir_drop(d->tmp, d->path, d->carried, 0, why, sizeof why);
    if (lost || kept)
        add_to(err, "; the fresh folder %s was kept: it holds %s", d->tmp,
               kept ? why : "what the run had taken from the output folder");
    atomic_dir_free(d);
    return s;
}

/* After the swap: the old outputs (in folder `old`) removed, the user's
 * entries there kept (sl_outdir_drop); frees d. */
static sl_status finish_old(sl_atomic_dir *d, const char *old, sl_error *err)
{
    char why[WHY_CAP];
    sl_status s = SL_OK;
    if (sl_outdir_drop(old, d->path, d->carried, SL_DROP_CACHE, why, sizeof why))
        s = sl_error_set(err, SL_EIO, d->path, 0, "the new outputs are in place, but the "
                         "previous ones could not be removed whole and were kept in %s: it "
                         "holds %s; look into it, then remove it", old, why);
    atomic_dir_free(d);
    return s;
}

static sl_status commit_swap(sl_atomic_dir *d, sl_error *err)
{
    struct stat st;
    if (lstat(d->path, &st) != 0) {
        if (sl_fs_rename_new(AT_FDCWD, d->tmp, AT_FDCWD, d->path) != 0)
            return fail_back(d, sl_error_set(err, SL_EIO, d->path, 0, "cannot create: %s",
                                             strerror(errno)), err);
        atomic_dir_free(d);
        return SL_OK;
    }
    /* one atomic step: the old folder now has the fresh folder's name */
    if (sl_fs->rename(AT_FDCWD, d->tmp, AT_FDCWD, d->path, RENAME_EXCHANGE) == 0)
        return finish_old(d, d->tmp, err);
    if (errno != EINVAL && errno != ENOSYS)
        return fail_back(d, sl_error_set(err, SL_EIO, d->path, 0, "cannot replace: %s; the "
                                         "output folder is unchanged", strerror(errno)), err);
    /* no exchange on this file system: two renames, the old folder aside (a run
     * killed in between leaves no DIR: the next one puts a folder back,
     * sl_atomic_dir_recover) */
    char *old = sl_atomic_hidden_name(d->path);
    int e = 0, back = 0;
    if (!old)
        e = ENOMEM;
    else if (sl_fs_rename_new(AT_FDCWD, d->path, AT_FDCWD, old) != 0)
        e = errno;
    else if (sl_fs->rename(AT_FDCWD, d->tmp, AT_FDCWD, d->path, 0) != 0) {
        e = errno;
        back = sl_fs->rename(AT_FDCWD, old, AT_FDCWD, d->path, 0);
    }
    if (e) {
        sl_status s = sl_error_set(err, SL_EIO, d->path, 0, "cannot replace: %s; the output "
                                   "folder is unchanged", strerror(e));
        if (back) /* no DIR now: the next run puts it back (sl_atomic_dir_recover) */
            add_to(err, " but was left aside as %s: the next run into it puts it back", old);
        free(old);
        return fail_back(d, s, err);
    }
    sl_status s = finish_old(d, old, err);
    free(old);
    return s;
}

/* ---- in place ------------------------------------------------------------------- */

/* What a step of an in-place commit did (undone in reverse on a failure). */
typedef enum step_kind { STEP_EXCHANGED, STEP_MOVED_IN, STEP_MOVED_OUT } step_kind;
typedef struct step {
    char *name;
    step_kind kind;
} step;

/* Exchange tmpfd/name and dirfd/name: 0, or -1 (errno) with both as they
 * were, or -2 when they could not be put back (a failure in the middle of
 * the fallback). Where the file system has no RENAME_EXCHANGE: three
 * renames through an aside name of its own in the fresh folder, each undone
 * on a failure of the next. */
static int exchange(int tmpfd, int dirfd, const char *name)
{
    if (sl_fs->rename(tmpfd, name, dirfd, name, RENAME_EXCHANGE) == 0)
        return 0;
    if (errno != EINVAL && errno != ENOSYS)
        return -1;
    char aside[NAME_MAX + 1];
    snprintf(aside, sizeof aside, SL_OUTDIR_TMP_INSIDE "aside-%s", name);
    if (sl_fs_rename_new(dirfd, name, tmpfd, aside) != 0) /* the old entry aside */
        return -1;
    int e;
    if (sl_fs->rename(tmpfd, name, dirfd, name, 0) != 0) { /* the new one in */
        e = errno;
        int back = sl_fs->rename(tmpfd, aside, dirfd, name, 0);
        errno = e;
        return back ? -2 : -1;
    }
    if (sl_fs->rename(tmpfd, aside, tmpfd, name, 0) != 0) { /* the old one where the new was */
        e = errno;
        int back = sl_fs->rename(dirfd, name, tmpfd, name, 0) != 0 ||
                   sl_fs->rename(tmpfd, aside, dirfd, name, 0) != 0;
        errno = e;
        return back ? -2 : -1;
    }
    return 0;
}

static int undo(int tmpfd, int dirfd, const step *s)
{
    switch (s->kind) {
    case STEP_EXCHANGED:
        return exchange(tmpfd, dirfd, s->name);
    case STEP_MOVED_IN:
        return sl_fs_rename_new(dirfd, s->name, tmpfd, s->name);
    case STEP_MOVED_OUT:
        return sl_fs_rename_new(tmpfd, s->name, dirfd, s->name);
    }
    return -1;
}

/* The names at the top of the fresh folder to move in (all but its
 * manifest and seislide's temporaries), in byte order: *n of them into *out
 * (malloc'd).
 * 0, or -1 (errno). */
static int fresh_names(int tmpfd, char ***out, size_t *n)
{
    *n = 0;
    *out = NULL;
    int fd = sl_fs->open(tmpfd, ".", O_RDONLY | O_DIRECTORY | O_CLOEXEC, 0);
    DIR *dd = fd >= 0 ? fdopendir(fd) : NULL;
    if (!dd) {
        int e = errno;
        if (fd >= 0)
            sl_fs->close(fd);
        errno = e;
        return -1;
    }
    char **v = NULL;
    size_t cap = 0;
    int bad = 0;
    for (struct dirent *e; !bad && (e = readdir(dd)) != NULL;) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..") ||
            !strcmp(e->d_name, SL_MANIFEST_NAME) ||
            !strncmp(e->d_name, SL_OUTDIR_OWN_PREFIX, strlen(SL_OUTDIR_OWN_PREFIX)))
            continue;
        if (*n == cap) {
            size_t c = cap ? 2 * cap : 16;
            char **p = realloc(v, c * sizeof *p);
            if (!p) {
                bad = 1;
                break;
            }
            v = p;
            cap = c;
        }
        if (!(v[*n] = strdup(e->d_name)))
            bad = 1;
        else
            (*n)++;
    }
    closedir(dd);
    if (bad) {
        while (*n)
            free(v[--*n]);
        free(v);
        errno = ENOMEM;
        return -1;
    }
    if (*n)
        qsort(v, *n, sizeof *v, sl_cmp_str);
    *out = v;
    return 0;
}

static int has_name(char **v, size_t n, const char *name)
{
    for (size_t i = 0; i < n; i++)
        if (!strcmp(v[i], name))
            return 1;
    return 0;
}

/* The entries of the fresh folder exchanged with the final folder's of the
 * same names, then the old outputs it no longer writes moved out; the
 * manifest of the final folder names both runs' meanwhile. */
static sl_status commit_in_place(sl_atomic_dir *d, sl_error *err)
{
    sl_manifest *both = sl_manifest_union(d->old, d->mine);
    int tmpfd = sl_fs->open(AT_FDCWD, d->tmp, O_RDONLY | O_DIRECTORY | O_CLOEXEC, 0);
    int dirfd = tmpfd < 0 ? -1 : sl_fs->open(AT_FDCWD, d->path, O_RDONLY | O_DIRECTORY | O_CLOEXEC, 0);
    size_t nnames = 0, nsteps = 0;
    char **names = NULL;
    step *steps = NULL;
    sl_status s = SL_OK;
    if (!both)
        s = sl_error_set(err, SL_ENOMEM, d->path, 0, "out of memory");
    else if (tmpfd < 0 || dirfd < 0)
        s = sl_error_set(err, SL_EIO, d->path, 0, "cannot open: %s", strerror(errno));
    else if (!(s = sl_manifest_save(d->tmp, both, d->version, err)) &&
             !(s = sl_manifest_save(d->path, both, d->version, err)) &&
             fresh_names(tmpfd, &names, &nnames) != 0)
        s = sl_error_set(err, SL_EIO, d->tmp, 0, "cannot read: %s", strerror(errno));
    size_t nold = sl_manifest_count(d->old);
    if (!s && !(steps = calloc(nnames + nold + 1, sizeof *steps)))
        s = sl_error_set(err, SL_ENOMEM, d->path, 0, "out of memory");
    size_t broken = 0; /* entries left half exchanged */
    for (size_t i = 0; !s && i < nnames; i++) {
        sl_fstat st;
        int there = sl_fs->stat(dirfd, names[i], &st) == 0;
        step_kind k = there ? STEP_EXCHANGED : STEP_MOVED_IN;
        int r = there ? exchange(tmpfd, dirfd, names[i]) : sl_fs_rename_new(tmpfd, names[i], dirfd, names[i]);
        if (r) {
            broken += r == -2;
            s = sl_error_set(err, SL_EIO, d->path, 0, "cannot replace '%s': %s; the output folder "
                             "is unchanged", names[i], strerror(errno));
        } else {
            steps[nsteps++] = (step){names[i], k};
        }
    }
    /* the old outputs at the top that this run does not write */
    for (size_t i = 0; !s && i < nold; i++) {
        const char *p = sl_manifest_path(d->old, i);
        size_t k = strcspn(p, "/");
        char top[NAME_MAX + 1];
        if (k > NAME_MAX || (p[k] == '/' && p[k + 1]))
            continue; /* deeper: goes with its top folder */
        snprintf(top, sizeof top, "%.*s", (int)k, p);
        sl_fstat st;
        if (has_name(names, nnames, top) || !strcmp(top, SL_MANIFEST_NAME) ||
            !strncmp(top, SL_OUTDIR_OWN_PREFIX, strlen(SL_OUTDIR_OWN_PREFIX)) ||
            sl_fs->stat(dirfd, top, &st) != 0)
            continue;
        char *own = strdup(top);
        if (!own || sl_fs_rename_new(dirfd, top, tmpfd, top) != 0) {
            s = sl_error_set(err, SL_EIO, d->path, 0, "cannot move the old output '%s' aside: %s; "
                             "the output folder is unchanged", top, strerror(own ? errno : ENOMEM));
            free(own);
        } else {
            steps[nsteps++] = (step){own, STEP_MOVED_OUT};
        }
    }
    if (!s)
        s = sl_manifest_save(d->path, d->mine, d->version, err);
    if (s && both) { /* everything back as it was */
        size_t undone = broken;
        while (nsteps)
            undone += undo(tmpfd, dirfd, &steps[--nsteps]) != 0;
        if (sl_manifest_restore(d->path, d->old, d->version, NULL) != SL_OK || undone)
            add_to(err, " (but %zu entries could not be put back: the folder holds old and new "
                   "outputs, and its manifest names both; run again)", undone ? undone : 1);
        sl_manifest_save(d->tmp, d->mine, d->version, NULL);
    }
    for (size_t i = 0; i < nsteps; i++)
        if (steps[i].kind == STEP_MOVED_OUT)
            free(steps[i].name);
    free(steps);
    for (size_t i = 0; i < nnames; i++)
        free(names[i]);
    free(names);
    sl_manifest_free(both);
    if (tmpfd >= 0)
        sl_fs->close(tmpfd);
    if (dirfd >= 0)
        sl_fs->close(dirfd);
    if (s)
        return fail_back(d, s, err);
    char *old = strdup(d->tmp);
    if (!old) { /* the fresh folder now holds the old outputs: said, kept */
        s = sl_error_set(err, SL_ENOMEM, d->path, 0, "out of memory");
        atomic_dir_free(d);
        return s;
    }
    s = finish_old(d, old, err);
    free(old);
    return s;
}

sl_status sl_atomic_dir_commit(sl_atomic_dir *d, sl_error *err)
{
    if (!d)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "no folder to commit");
    sl_status s = sl_atomic_dir_prepare(d, err);
    if (s)
        return fail_back(d, s, err);
    return d->in_place ? commit_in_place(d, err) : commit_swap(d, err);
}

size_t sl_atomic_dir_abort(sl_atomic_dir *d, char *why, size_t nwhy)
{
    if (why && nwhy)
        why[0] = '\0';
    if (!d)
        return 0;
    char w[WHY_CAP];
    size_t lost = put_back(d);
    size_t kept = sl_outdir_drop(d->tmp, d->path, d->carried, 0, w, sizeof w);
    if ((lost || kept) && why && nwhy)
        snprintf(why, nwhy, "the fresh folder %s was kept: it holds %s", d->tmp,
                 kept ? w : "what the run had taken from the output folder");
    atomic_dir_free(d);
    return kept + lost;
}

int sl_remove_tree(const char *path)
{
    if (sl_outdir_drop(path, NULL, NULL, SL_DROP_OURS | SL_DROP_CACHE, NULL, 0) == 0)
        return 0;
    errno = EBUSY;
    return -1;
}
