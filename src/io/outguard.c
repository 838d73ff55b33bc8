/* outguard.c - paths resolved and compared, parents made, mounts found, the
 * lock; see outguard.h. (The manifest: manifest.c; carrying and removing:
 * outcarry.c.) */
#define _GNU_SOURCE /* flock, O_CLOEXEC */
#include "io/outguard.h"
#include "io/fsops.h"
#include "io/owner.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#define PATH_CAP SL_OUTGUARD_PATH
/* Times the lock is retried when its file was replaced under us. */
#define LOCK_TRIES 100
/* Longest "PID@HOST" read back from another run's lock file. */
#define LOCK_HOLDER 200

/* ---- paths -------------------------------------------------------------- */

/* "a" + "/" + "b" into buf (n); -1 when it does not fit. */
int sl_path_join(char *buf, size_t n, const char *a, const char *b)
{
    int w = snprintf(buf, n, "%s%s%s", a, (*a && a[strlen(a) - 1] != '/' && *b) ? "/" : "", b);
    return w < 0 || (size_t)w >= n ? -1 : 0;
}

int sl_path_resolve(const char *path, char *buf, size_t n)
{
    char res[PATH_CAP], cand[PATH_CAP], comp[PATH_CAP];
    if (!path || !*path) {
        errno = ENOENT;
        return -1;
    }
    if (path[0] == '/')
        snprintf(res, sizeof res, "/");
    else if (!realpath(".", res))
        return -1;
    const char *p = path;
    while (*p) {
        size_t k = strcspn(p, "/");
        if (k >= sizeof comp) {
            errno = ENAMETOOLONG;
            return -1;
        }
        memcpy(comp, p, k);
        comp[k] = '\0';
        p += k;
        p += strspn(p, "/");
        if (!k || !strcmp(comp, "."))
            continue;
        if (!strcmp(comp, "..")) { /* res has no links: its parent is the real one */
            char *slash = strrchr(res, '/');
            if (slash == res)
                res[1] = '\0';
            else if (slash)
                *slash = '\0';
            continue;
        }
        struct stat st;
        if (sl_path_join(cand, sizeof cand, res, comp)) {
            errno = ENAMETOOLONG;
            return -1;
        }
        if (lstat(cand, &st) != 0 || !realpath(cand, res))
            snprintf(res, sizeof res, "%s", cand); /* absent (or a dangling link): as written */
    }
    if (strlen(res) >= n) {
        errno = ENAMETOOLONG;
        return -1;
    }
    memcpy(buf, res, strlen(res) + 1);
    return 0;
}

/* Nonzero when resolved path `in` lies inside resolved folder `dir`. */
static int inside(const char *in, const char *dir)
{
    size_t k = strlen(dir);
    if (!strcmp(dir, "/"))
        return strcmp(in, "/") != 0;
    return strncmp(in, dir, k) == 0 && in[k] == '/';
}

static sl_overlap compare(const char *o, const char *i)
{
    if (!strcmp(o, i))
        return SL_OVERLAP_SAME;
    if (inside(o, i))
        return SL_OVERLAP_INSIDE;
    return inside(i, o) ? SL_OVERLAP_CONTAINS : SL_OVERLAP_NONE;
}

sl_overlap sl_path_overlap(const char *out, const char *input)
{
    char o[PATH_CAP], i[PATH_CAP], parent[PATH_CAP], link[PATH_CAP];
    if (sl_path_resolve(out, o, sizeof o) || sl_path_resolve(input, i, sizeof i))
        return SL_OVERLAP_NONE;
    sl_overlap v = compare(o, i);
    struct stat st;
    if (v || lstat(input, &st) != 0 || !S_ISLNK(st.st_mode))
        return v;
    /* a link: also where the link itself lies (its folder resolved) */
    size_t n = strlen(input);
    while (n > 1 && input[n - 1] == '/')
        n--;
    size_t cut = n;
    while (cut > 0 && input[cut - 1] != '/')
        cut--;
    char base[PATH_CAP];
    snprintf(parent, sizeof parent, "%.*s", (int)(cut ? cut : 1), cut ? input : ".");
    snprintf(base, sizeof base, "%.*s", (int)(n - cut), input + cut);
    if (sl_path_resolve(parent, link, sizeof link) || sl_path_join(i, sizeof i, link, base) != 0)
        return SL_OVERLAP_NONE;
    return compare(o, i);
}

int sl_mkdir_parents(const char *dir, char *bad, size_t nbad)
{
    char p[PATH_CAP];
    if (bad && nbad)
        bad[0] = '\0';
    if (!dir || strlen(dir) >= sizeof p) {
        errno = ENAMETOOLONG;
        return -1;
    }
    snprintf(p, sizeof p, "%s", dir);
    size_t n = strlen(p);
    while (n > 1 && p[n - 1] == '/')
        p[--n] = '\0';
    for (size_t i = 1; i < n; i++) {
        if (p[i] != '/' || p[i - 1] == '/')
            continue;
        p[i] = '\0';
        struct stat st;
        int e = 0;
        if (stat(p, &st) != 0) {
            if (mkdir(p, 0777) != 0 && errno != EEXIST)
                e = errno;
            else if (stat(p, &st) != 0)
                e = errno;
        }
        if (!e && !S_ISDIR(st.st_mode))
            e = ENOTDIR;
        if (e) {
            if (bad && nbad)
                snprintf(bad, nbad, "%s", p);
            errno = e;
            return -1;
        }
        p[i] = '/';
    }
    return 0;
}


sl_status sl_outdir_resolve(const char *dir, char *buf, size_t n, sl_error *err)
{
    struct stat st;
    if (!dir || !*dir)
        return sl_error_set(err, SL_EINVAL, dir, 0, "no output folder given");
    if (lstat(dir, &st) == 0 && S_ISLNK(st.st_mode) && stat(dir, &st) != 0 && errno == ENOENT) {
        char target[PATH_CAP];
        ssize_t k = readlink(dir, target, sizeof target - 1);
        target[k > 0 ? k : 0] = '\0';
        return sl_error_set(err, SL_EINVAL, dir, 0, "the output folder is a symbolic link to "
                            "'%s', which does not exist: make that folder, or give a folder "
                            "that is not a dangling link (nothing was written)", target);
    }
    if (sl_path_resolve(dir, buf, n) != 0)
        return sl_error_set(err, SL_EIO, dir, 0, "output folder: %s", strerror(errno));
    return SL_OK;
}

/* ---- file systems mounted in or on a folder ------------------------------ */

/* A mount point of /proc/self/mountinfo (its 5th field) unescaped in place:
 * "\040" is a space, "\011" a tab, "\012" a newline, "\134" a backslash. */
static void unescape(char *s)
{
    char *w = s;
    for (char *r = s; *r; r++) {
        if (r[0] == '\\' && r[1] >= '0' && r[1] <= '3' && r[2] >= '0' && r[2] <= '7' &&
            r[3] >= '0' && r[3] <= '7') {
            *w++ = (char)((r[1] - '0') * 64 + (r[2] - '0') * 8 + (r[3] - '0'));
            r += 3;
        } else {
            *w++ = *r;
        }
    }
    *w = '\0';
}

/* The first mount point of /proc/self/mountinfo that is `real` itself
 * (exact) or lies inside it (!exact), into first: 1 found, else 0. */
static int mountinfo_find(const char *real, int exact, char *first, size_t n)
{
    FILE *f = fopen("/proc/self/mountinfo", "re");
    if (!f)
        return 0;
    char *line = NULL;
    size_t cap = 0;
    int found = 0;
    while (!found && getline(&line, &cap, f) > 0) {
        char *save = NULL, *field = strtok_r(line, " ", &save);
        for (int i = 1; field && i < 5; i++)
            field = strtok_r(NULL, " ", &save);
        if (!field)
            continue;
        unescape(field);
        if (exact ? !strcmp(field, real) : inside(field, real)) {
            found = 1;
            if (first && n)
                snprintf(first, n, "%s", field);
        }
    }
    free(line);
    fclose(f);
    return found;
}

int sl_path_mount_inside(const char *real, char *first, size_t n)
{
    return mountinfo_find(real, 0, first, n);
}

int sl_path_is_mount(const char *real)
{
    sl_fstat a, b;
    char parent[PATH_CAP];
    if (sl_fs->stat(AT_FDCWD, real, &a) != 0 || !S_ISDIR(a.mode))
        return 0;
    if (a.mount_root || mountinfo_find(real, 1, NULL, 0))
        return 1;
    if (sl_path_join(parent, sizeof parent, real, "..") != 0 || sl_fs->stat(AT_FDCWD, parent, &b) != 0)
        return 0;
    return a.dev != b.dev;
}

int sl_outdir_own_name(const char *name)
{
    return !strcmp(name, SL_MANIFEST_NAME) || !strcmp(name, SL_MANIFEST_CACHE) ||
           !strncmp(name, SL_OUTDIR_OWN_PREFIX, strlen(SL_OUTDIR_OWN_PREFIX));
}

/* ---- the lock ----------------------------------------------------------- */

struct sl_outlock {
    int fd;       /* -1: holds nothing (no locks on this file system) */
    char path[PATH_CAP];
};

/* ".BASE.lock" beside the resolved folder dir, into path; inside it
 * (SL_OUTDIR_LOCK_INSIDE) when the parent cannot be written and dir exists. */
static int lock_path(const char *dir, char *path, size_t n)
{
    char r[PATH_CAP];
    if (sl_path_resolve(dir, r, sizeof r))
        return -1;
    char *slash = strrchr(r, '/');
    const char *base = slash[1] ? slash + 1 : "seislide";
    char parent[PATH_CAP];
    snprintf(parent, sizeof parent, "%.*s", slash == r ? 1 : (int)(slash - r), r);
    struct stat st;
    int w;
    if (access(parent, W_OK | X_OK) != 0 && stat(r, &st) == 0 && S_ISDIR(st.st_mode))
        w = snprintf(path, n, "%s/" SL_OUTDIR_LOCK_INSIDE, r);
    else
        w = snprintf(path, n, "%.*s/.%s.lock", (int)(slash - r), r, base);
    return w < 0 || (size_t)w >= n ? -1 : 0;
}

sl_outlock *sl_outlock_take(const char *dir, sl_error *err)
{
    sl_outlock *l = calloc(1, sizeof *l);
    if (!l) {
        sl_error_set(err, SL_ENOMEM, dir, 0, "out of memory");
        return NULL;
    }
    l->fd = -1;
    if (lock_path(dir, l->path, sizeof l->path)) {
        sl_error_set(err, SL_EIO, dir, 0, "output folder: %s", strerror(errno));
        free(l);
        return NULL;
    }
    for (int tries = 0; tries < LOCK_TRIES; tries++) {
        int fd = sl_fs->open(AT_FDCWD, l->path, O_RDWR | O_CREAT | O_CLOEXEC, 0666);
        if (fd < 0) {
            sl_error_set(err, SL_EIO, l->path, 0, "cannot create the output folder's lock: %s",
                         strerror(errno));
            break;
        }
        if (sl_fs->flock(fd, LOCK_EX | LOCK_NB) != 0) {
            int e = errno;
            if (e == EWOULDBLOCK) {
                char who[LOCK_HOLDER + 1];
                ssize_t k = pread(fd, who, LOCK_HOLDER, 0);
                who[k > 0 ? k : 0] = '\0';
                who[strcspn(who, "\r\n")] = '\0';
                sl_fs->close(fd);
                sl_error_set(err, SL_EINVAL, dir, 0, "another run is writing this output folder: "
                             "process %s (lock %s); wait for it to end, or give another folder",
                             who[0] ? who : "(not yet named)", l->path);
                break;
            }
            sl_fs->close(fd);
            if (e == ENOLCK || e == EOPNOTSUPP || e == ENOTSUP || e == ENOSYS || e == EINVAL) {
                l->path[0] = '\0'; /* no locks here: a lock that holds nothing */
                return l;
            }
            sl_error_set(err, SL_EIO, l->path, 0, "cannot lock: %s", strerror(e));
            break;
        }
        /* the file may have been removed (and made anew) by the run that held it */
        sl_fstat a, b;
        if (sl_fs->stat(fd, NULL, &a) != 0 || sl_fs->stat(AT_FDCWD, l->path, &b) != 0 ||
            a.ino != b.ino || a.dev != b.dev) {
            sl_fs->close(fd);
            continue;
        }
        char host[80], text[LOCK_HOLDER];
        sl_owner_host(host, sizeof host);
        int w = snprintf(text, sizeof text, "%ld@%s\n", (long)getpid(), host);
        if (sl_fs->ftruncate(fd, 0) != 0 || sl_fs->write(fd, text, (size_t)w) != (ssize_t)w) {
            sl_error_set(err, SL_EIO, l->path, 0, "cannot write the lock: %s", strerror(errno));
            sl_fs->unlink(AT_FDCWD, l->path, 0);
            sl_fs->close(fd);
            break;
        }
        l->fd = fd;
        return l;
    }
    if (err && !err->code)
        sl_error_set(err, SL_EIO, l->path, 0, "cannot lock: the lock file keeps changing");
    free(l);
    return NULL;
}

const char *sl_outlock_path(const sl_outlock *l) { return l ? l->path : ""; }

void sl_outlock_release(sl_outlock *l)
{
    if (!l)
        return;
    if (l->fd >= 0) { /* removed while held: a run that opened it meanwhile retries */
        sl_fs->unlink(AT_FDCWD, l->path, 0);
        sl_fs->close(l->fd);
    }
    free(l);
}

