/* outguard.c - manifest, paths compared, parents made, the lock; see outguard.h. */
#define _GNU_SOURCE /* flock */
#include "io/outguard.h"
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
static int join(char *buf, size_t n, const char *a, const char *b)
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
        if (join(cand, sizeof cand, res, comp)) {
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
    if (sl_path_resolve(parent, link, sizeof link) || join(i, sizeof i, link, base) != 0)
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

/* ---- the lock ----------------------------------------------------------- */

struct sl_outlock {
    int fd;       /* -1: holds nothing (no locks on this file system) */
    char path[PATH_CAP];
};

/* ".BASE.lock" beside the resolved folder dir, into path. */
static int lock_path(const char *dir, char *path, size_t n)
{
    char r[PATH_CAP];
    if (sl_path_resolve(dir, r, sizeof r))
        return -1;
    char *slash = strrchr(r, '/');
    const char *base = slash[1] ? slash + 1 : "seislide";
    int w = snprintf(path, n, "%.*s/.%s.lock", (int)(slash - r), r, base);
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
        int fd = open(l->path, O_RDWR | O_CREAT | O_CLOEXEC, 0666);
        if (fd < 0) {
            sl_error_set(err, SL_EIO, l->path, 0, "cannot create the output folder's lock: %s",
                         strerror(errno));
            break;
        }
        if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
            int e = errno;
            if (e == EWOULDBLOCK) {
                char who[LOCK_HOLDER + 1];
                ssize_t k = pread(fd, who, LOCK_HOLDER, 0);
                who[k > 0 ? k : 0] = '\0';
                who[strcspn(who, "\r\n")] = '\0';
                close(fd);
                sl_error_set(err, SL_EINVAL, dir, 0, "another run is writing this output folder: "
                             "process %s (lock %s); wait for it to end, or give another folder",
                             who[0] ? who : "(not yet named)", l->path);
                break;
            }
            close(fd);
            if (e == ENOLCK || e == EOPNOTSUPP || e == ENOTSUP || e == ENOSYS || e == EINVAL) {
                l->path[0] = '\0'; /* no locks here: a lock that holds nothing */
                return l;
            }
            sl_error_set(err, SL_EIO, l->path, 0, "cannot lock: %s", strerror(e));
            break;
        }
        /* the file may have been removed (and made anew) by the run that held it */
        struct stat a, b;
        if (fstat(fd, &a) != 0 || stat(l->path, &b) != 0 || a.st_ino != b.st_ino ||
            a.st_dev != b.st_dev) {
            close(fd);
            continue;
        }
        char host[80], text[LOCK_HOLDER];
        sl_owner_host(host, sizeof host);
        int w = snprintf(text, sizeof text, "%ld@%s\n", (long)getpid(), host);
        if (ftruncate(fd, 0) != 0 || pwrite(fd, text, (size_t)w, 0) != (ssize_t)w) {
            sl_error_set(err, SL_EIO, l->path, 0, "cannot write the lock: %s", strerror(errno));
            unlink(l->path);
            close(fd);
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
        unlink(l->path);
        close(l->fd);
    }
    free(l);
}

/* ---- the manifest ------------------------------------------------------- */

struct sl_manifest {
    size_t n, cap;
    char **path; /* sorted by strcmp */
};

static int by_bytes(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

static int manifest_add(sl_manifest *m, const char *s, size_t k)
{
    if (m->n == m->cap) {
        size_t cap = m->cap ? 2 * m->cap : 64;
        char **p = realloc(m->path, cap * sizeof *p);
        if (!p)
            return -1;
        m->path = p;
        m->cap = cap;
    }
    if (!(m->path[m->n] = strndup(s, k)))
        return -1;
    m->n++;
    return 0;
}

void sl_manifest_free(sl_manifest *m)
{
    if (!m)
        return;
    for (size_t i = 0; i < m->n; i++)
        free(m->path[i]);
    free(m->path);
    free(m);
}

int sl_manifest_has(const sl_manifest *m, const char *rel)
{
    return m && m->n && bsearch(&rel, m->path, m->n, sizeof *m->path, by_bytes) != NULL;
}

/* A path the manifest may hold (outguard.h): relative, no empty, "." or
 * ".." component but for one trailing '/'. */
static int good_rel(const char *s, size_t k)
{
    if (!k || s[0] == '/')
        return 0;
    if (s[k - 1] == '/')
        k--;
    for (size_t i = 0; i <= k;) {
        size_t j = i;
        while (j < k && s[j] != '/')
            j++;
        if (j == i || (j - i == 1 && s[i] == '.') || (j - i == 2 && s[i] == '.' && s[i + 1] == '.'))
            return 0;
        for (size_t q = i; q < j; q++)
            if ((unsigned char)s[q] < 0x20)
                return 0;
        i = j + 1;
    }
    return 1;
}

sl_status sl_manifest_read(const char *dir, sl_manifest **out, sl_error *err)
{
    char path[PATH_CAP];
    struct stat st;
    *out = NULL;
    if (join(path, sizeof path, dir, SL_MANIFEST_NAME))
        return sl_error_set(err, SL_EIO, dir, 0, "path too long");
    if (lstat(path, &st) != 0)
        return errno == ENOENT ? SL_OK : sl_error_set(err, SL_EIO, path, 0, "%s", strerror(errno));
    if (!S_ISREG(st.st_mode) || st.st_size > SL_MANIFEST_MAX_BYTES)
        return sl_error_set(err, SL_EPARSE, path, 0, "not a manifest seislide wrote (%s)",
                            S_ISREG(st.st_mode) ? "too large" : "not a regular file");
    FILE *f = fopen(path, "rb");
    sl_manifest *m = calloc(1, sizeof *m);
    char *text = malloc((size_t)st.st_size + 1);
    size_t len = f && text ? fread(text, 1, (size_t)st.st_size, f) : 0;
    sl_status s = SL_OK;
    if (!f || !m || !text)
        s = sl_error_set(err, f ? SL_ENOMEM : SL_EIO, path, 0, "%s",
                         f ? "out of memory" : strerror(errno));
    else if (ferror(f) || len != (size_t)st.st_size)
        s = sl_error_set(err, SL_EIO, path, 0, "cannot read");
    if (f)
        fclose(f);
    long line = 0;
    for (size_t i = 0; !s && i < len; line++) {
        size_t k = 0;
        while (i + k < len && text[i + k] != '\n')
            k++;
        const char *l = text + i;
        i += k + 1;
        if (line == 0) {
            if (k != strlen(SL_MANIFEST_HEAD) || memcmp(l, SL_MANIFEST_HEAD, k) != 0)
                s = sl_error_set(err, SL_EPARSE, path, 1, "not a manifest seislide wrote (the "
                                 "first line is not '" SL_MANIFEST_HEAD "')");
        } else if (k && l[0] != '#') {
            if (!good_rel(l, k))
                s = sl_error_set(err, SL_EPARSE, path, line + 1, "'%.*s' is not a path inside "
                                 "the folder", (int)(k > 200 ? 200 : k), l);
            else if (manifest_add(m, l, k))
                s = sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
        }
    }
    if (!s && line == 0)
        s = sl_error_set(err, SL_EPARSE, path, 1, "empty: not a manifest seislide wrote");
    free(text);
    if (s) {
        sl_manifest_free(m);
        return s;
    }
    qsort(m->path, m->n, sizeof *m->path, by_bytes);
    *out = m;
    return SL_OK;
}

/* Every entry under from/rel into m (folders with a trailing '/'). */
static int list_tree(sl_manifest *m, const char *from, const char *rel)
{
    char dir[PATH_CAP], r[PATH_CAP], full[PATH_CAP];
    if (join(dir, sizeof dir, from, rel))
        return -1;
    DIR *d = opendir(dir);
    if (!d)
        return -1;
    int bad = 0;
    for (struct dirent *e; !bad && (e = readdir(d)) != NULL;) {
        const char *name = e->d_name;
        struct stat st;
        if (!strcmp(name, ".") || !strcmp(name, ".."))
            continue;
        if (!*rel && !strcmp(name, SL_MANIFEST_NAME))
            continue;
        if (join(r, sizeof r, rel, name) || join(full, sizeof full, dir, name) ||
            lstat(full, &st) != 0) {
            bad = 1;
            break;
        }
        if (S_ISDIR(st.st_mode)) {
            size_t k = strlen(r);
            if (k + 2 > sizeof r)
                bad = 1;
            else {
                r[k] = '/';
                r[k + 1] = '\0';
                bad = manifest_add(m, r, k + 1);
                r[k] = '\0';
            }
            if (!bad && (*rel || strcmp(name, SL_MANIFEST_CACHE) != 0))
                bad = list_tree(m, from, r); /* the cache: one line */
        } else {
            bad = manifest_add(m, r, strlen(r));
        }
    }
    closedir(d);
    return bad ? -1 : 0;
}

sl_status sl_manifest_write(const char *fresh, const char *version, sl_error *err)
{
    char path[PATH_CAP];
    sl_manifest m = {0, 0, NULL};
    if (join(path, sizeof path, fresh, SL_MANIFEST_NAME))
        return sl_error_set(err, SL_EIO, fresh, 0, "path too long");
    int e = list_tree(&m, fresh, "") ? (errno ? errno : ENOMEM) : 0;
    FILE *f = e ? NULL : fopen(path, "wb");
    if (f) {
        qsort(m.path, m.n, sizeof *m.path, by_bytes);
        fprintf(f, "%s\n# written by %s: every file and folder below is an output of seislide; "
                "a run into this folder replaces them and keeps every other file\n",
                SL_MANIFEST_HEAD, version ? version : "seislide");
        for (size_t i = 0; i < m.n; i++)
            fprintf(f, "%s\n", m.path[i]);
        e = ferror(f) ? (errno ? errno : EIO) : 0;
        if (fclose(f) != 0 && !e)
            e = errno ? errno : EIO;
    } else if (!e) {
        e = errno;
    }
    for (size_t i = 0; i < m.n; i++)
        free(m.path[i]);
    free(m.path);
    return e ? sl_error_set(err, SL_EIO, path, 0, "cannot write: %s", strerror(e)) : SL_OK;
}

/* ---- carrying the user's entries ---------------------------------------- */

typedef struct carry {
    const char *from, *to;
    const sl_manifest *old;
    int move;
    sl_error *err;
} carry;

static sl_status conflict(carry *c, const char *rel)
{
    char p[PATH_CAP];
    join(p, sizeof p, c->from, rel);
    return sl_error_set(c->err, SL_EINVAL, p, 0, "seislide did not write this (the folder's "
                        SL_MANIFEST_NAME " does not name it) and this run writes an entry of "
                        "that name: move it out of the folder and run again; the folder is "
                        "unchanged");
}

/* The folders of to/rel's path that are missing, made (a file of that name:
 * a conflict). */
static sl_status make_parents(carry *c, const char *rel)
{
    char p[PATH_CAP], r[PATH_CAP];
    snprintf(r, sizeof r, "%s", rel);
    for (char *s = strchr(r, '/'); s; s = strchr(s + 1, '/')) {
        *s = '\0';
        struct stat st;
        if (join(p, sizeof p, c->to, r))
            return sl_error_set(c->err, SL_EIO, c->to, 0, "path too long");
        if (lstat(p, &st) != 0) {
            if (mkdir(p, 0777) != 0)
                return sl_error_set(c->err, SL_EIO, p, 0, "cannot create: %s", strerror(errno));
        } else if (!S_ISDIR(st.st_mode)) {
            return conflict(c, rel);
        }
        *s = '/';
    }
    return SL_OK;
}

/* A copy of regular file `from` (st) as `to`. */
static int copy_file(const char *from, const char *to, const struct stat *st)
{
    int in = open(from, O_RDONLY | O_CLOEXEC), out = -1, bad = in < 0;
    if (!bad)
        bad = (out = open(to, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600)) < 0;
    char buf[65536];
    for (ssize_t k; !bad && (k = read(in, buf, sizeof buf)) != 0;)
        bad = k < 0 || write(out, buf, (size_t)k) != k;
    bad |= out >= 0 && fchmod(out, st->st_mode & 07777) != 0;
    int e = errno;
    if (in >= 0)
        close(in);
    if (out >= 0 && close(out) != 0)
        bad = 1;
    if (bad && out >= 0)
        unlink(to);
    errno = e;
    return bad ? -1 : 0;
}

/* The same file at `to` as at `from`: a hard link, else (a file system that
 * refuses one) a new symbolic link or a copy. */
static int keep_entry(const char *from, const char *to, const struct stat *st)
{
    if (linkat(AT_FDCWD, from, AT_FDCWD, to, 0) == 0)
        return 0;
    if (errno != EXDEV && errno != EPERM && errno != EMLINK && errno != EOPNOTSUPP)
        return -1;
    if (S_ISLNK(st->st_mode)) {
        char target[PATH_CAP];
        ssize_t k = readlink(from, target, sizeof target - 1);
        if (k < 0)
            return -1;
        target[k] = '\0';
        return symlink(target, to);
    }
    return S_ISREG(st->st_mode) ? copy_file(from, to, st) : -1;
}

static sl_status carry_tree(carry *c, const char *rel)
{
    char dir[PATH_CAP], r[PATH_CAP], fp[PATH_CAP], tp[PATH_CAP], rs[PATH_CAP];
    if (join(dir, sizeof dir, c->from, rel))
        return sl_error_set(c->err, SL_EIO, c->from, 0, "path too long");
    DIR *d = opendir(dir);
    if (!d)
        return sl_error_set(c->err, SL_EIO, dir, 0, "cannot read: %s", strerror(errno));
    sl_status s = SL_OK;
    for (struct dirent *e; !s && (e = readdir(d)) != NULL;) {
        const char *name = e->d_name;
        struct stat st, tt;
        if (!strcmp(name, ".") || !strcmp(name, ".."))
            continue;
        if (!*rel && (!strcmp(name, SL_MANIFEST_NAME) || !strcmp(name, SL_MANIFEST_CACHE)))
            continue;
        if (join(r, sizeof r, rel, name) || join(fp, sizeof fp, c->from, r) ||
            join(tp, sizeof tp, c->to, r) || snprintf(rs, sizeof rs, "%s/", r) >= (int)sizeof rs) {
            s = sl_error_set(c->err, SL_EIO, dir, 0, "path too long");
            break;
        }
        if (lstat(fp, &st) != 0)
            continue; /* gone meanwhile */
        int there = lstat(tp, &tt) == 0;
        if (S_ISDIR(st.st_mode)) {
            int listed = sl_manifest_has(c->old, rs);
            if (there && !S_ISDIR(tt.st_mode) && !listed) {
                if (!c->move)
                    s = conflict(c, r);
                continue;
            }
            if (!listed && !there) {
                if (c->move) { /* the whole folder, added after the carry */
                    if ((s = make_parents(c, r)) == SL_OK && rename(fp, tp) != 0)
                        s = sl_error_set(c->err, SL_EIO, fp, 0, "cannot keep: %s",
                                         strerror(errno));
                    continue;
                }
                if ((s = make_parents(c, r)) != SL_OK)
                    continue;
                if (mkdir(tp, 0700) != 0) {
                    s = sl_error_set(c->err, SL_EIO, tp, 0, "cannot create: %s", strerror(errno));
                    continue;
                }
                s = carry_tree(c, r);
                if (!s && chmod(tp, st.st_mode & 07777) != 0)
                    s = sl_error_set(c->err, SL_EIO, tp, 0, "cannot set its mode: %s",
                                     strerror(errno));
                continue;
            }
            s = carry_tree(c, r);
            continue;
        }
        if (sl_manifest_has(c->old, r))
            continue; /* seislide's: replaced, or gone with the old outputs */
        if (there) {
            if (!c->move)
                s = conflict(c, r);
            continue;
        }
        if ((s = make_parents(c, r)) != SL_OK)
            continue;
        if (c->move ? rename(fp, tp) != 0 : keep_entry(fp, tp, &st) != 0)
            s = sl_error_set(c->err, SL_EIO, fp, 0, "cannot keep it in the new outputs: %s",
                             strerror(errno));
    }
    closedir(d);
    return s;
}

sl_status sl_manifest_carry(const char *from, const char *to, const sl_manifest *old, int move,
                            sl_error *err)
{
    carry c = {from, to, old, move, err};
    return carry_tree(&c, "");
}
