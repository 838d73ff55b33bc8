/* outcarry.c - the user's entries carried into a run's fresh folder, and a
 * folder removed without losing any of them; see outguard.h. Both walk the
 * tree without recursion (walk.h) and reach every entry relative to an open
 * folder, no link followed, no other file system entered. */
#define _GNU_SOURCE /* O_DIRECTORY, O_NOFOLLOW, O_CLOEXEC, RENAME_NOREPLACE */
#include "io/fsops.h"
#include "io/outguard.h"
#include "io/walk.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#ifndef RENAME_NOREPLACE
#define RENAME_NOREPLACE (1 << 0)
#endif

#define PATH_CAP SL_OUTGUARD_PATH
/* Bytes copied at a time (a copy where the file system refuses a hard link). */
#define COPY_CHUNK 65536

/* ---- what a carry made -------------------------------------------------- */

typedef struct carried_rec {
    char *rel;
    dev_t dev;             /* of both: one file system */
    ino_t src_ino;         /* the user's entry as checked */
    struct timespec src_mtime;
    off_t src_size;
    ino_t made_ino;        /* the entry made in the fresh folder (src_ino for a hard link) */
} carried_rec;

struct sl_carried {
    size_t n, cap;
    carried_rec *r; /* sorted by rel once the carry is done */
};

void sl_carried_free(sl_carried *c)
{
    if (!c)
        return;
    for (size_t i = 0; i < c->n; i++)
        free(c->r[i].rel);
    free(c->r);
    free(c);
}

static int by_rel(const void *a, const void *b)
{
    return strcmp(((const carried_rec *)a)->rel, ((const carried_rec *)b)->rel);
}

static const carried_rec *carried_find(const sl_carried *c, const char *rel)
{
    if (!c || !c->n)
        return NULL;
    carried_rec key = {.rel = (char *)rel};
    return bsearch(&key, c->r, c->n, sizeof *c->r, by_rel);
}

static int carried_add(sl_carried *c, const char *rel, const sl_fstat *src, ino_t made)
{
    if (c->n == c->cap) {
        size_t cap = c->cap ? 2 * c->cap : 64;
        carried_rec *r = realloc(c->r, cap * sizeof *r);
        if (!r)
            return -1;
        c->r = r;
        c->cap = cap;
    }
    char *s = strdup(rel);
    if (!s)
        return -1;
    c->r[c->n++] = (carried_rec){s, src->dev, src->ino, src->mtime, src->size, made};
    return 0;
}

/* ---- small steps ---------------------------------------------------------- */

/* "a" + "/" + "b" into buf (n); -1 when it does not fit. */
static int same_time(struct timespec a, struct timespec b)
{
    return a.tv_sec == b.tv_sec && a.tv_nsec == b.tv_nsec;
}

/* The missing folders of rel's path below dirfd made (mode 0777 less the
 * umask): the deepest one that exists found first (one stat when the
 * parent is there, as in a walk), those below it made. 0; -1 with errno
 * (ENOTDIR: a part is not a folder). */
static int make_parents(int dirfd, const char *rel)
{
    size_t k = strlen(rel);
    char *p = malloc(k + 1);
    if (!p)
        return -1;
    memcpy(p, rel, k + 1);
    int r = 0;
    char *end = strrchr(p, '/'); /* p up to `end`: the parent */
    char *have = NULL;           /* the end of the deepest part that exists */
    for (char *s = end; s; ) {
        *s = '\0';
        sl_fstat st;
        if (sl_fs->stat(dirfd, p, &st) == 0) {
            if (!S_ISDIR(st.mode)) {
                errno = ENOTDIR;
                r = -1;
            }
            *s = '/';
            have = s;
            break;
        }
        if (errno != ENOENT) {
            r = -1;
            *s = '/';
            break;
        }
        char *up = strrchr(p, '/');
        *s = '/';
        s = up;
    }
    /* made from below `have` (or the top) down to the parent */
    for (char *s = have ? strchr(have + 1, '/') : strchr(p, '/'); !r && s && s <= end;
         s = strchr(s + 1, '/')) {
        *s = '\0';
        if (sl_fs->mkdir(dirfd, p, 0777) != 0 && errno != EEXIST)
            r = -1;
        *s = '/';
    }
    int e = errno;
    free(p);
    errno = e;
    return r;
}

/* A copy of the regular file fromfd/rel as tofd/rel (created), its mode. */
static int copy_file(int fromfd, int tofd, const char *rel, mode_t mode)
{
    int in = sl_fs->open(fromfd, rel, O_RDONLY | O_NOFOLLOW | O_CLOEXEC, 0), out = -1;
    int e = in < 0 ? errno : 0;
    if (!e && (out = sl_fs->open(tofd, rel, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600)) < 0)
        e = errno;
    char *buf = e ? NULL : malloc(COPY_CHUNK);
    if (!e && !buf)
        e = ENOMEM;
    while (!e) {
        ssize_t k = sl_fs->read(in, buf, COPY_CHUNK);
        if (k < 0 && errno == EINTR)
            continue;
        if (k < 0)
            e = errno;
        if (k <= 0)
            break;
        if (sl_fs_write_all(out, buf, (size_t)k) != 0)
            e = errno;
    }
    free(buf);
    if (!e && sl_fs->chmod(out, NULL, mode & 07777) != 0)
        e = errno;
    if (in >= 0)
        sl_fs->close(in);
    if (out >= 0 && sl_fs->close(out) != 0 && !e)
        e = errno;
    if (e && out >= 0)
        sl_fs->unlink(tofd, rel, 0);
    errno = e;
    return e ? -1 : 0;
}

/* A symbolic link tofd/rel to what fromfd/rel points to. */
static int copy_link(int fromfd, int tofd, const char *rel)
{
    char *target = malloc(PATH_CAP);
    if (!target)
        return -1;
    ssize_t k = sl_fs->readlink(fromfd, rel, target, PATH_CAP - 1);
    int r = -1;
    if (k >= 0) {
        target[k] = '\0';
        r = sl_fs->symlink(target, tofd, rel);
    }
    int e = errno;
    free(target);
    errno = e;
    return r;
}

/* The same entry at tofd/rel as at fromfd/rel (st): a hard link, else (a
 * file system that refuses one) a new symbolic link or a copy. */
static int keep_entry(int fromfd, int tofd, const char *rel, const sl_fstat *st)
{
    if (sl_fs->link(fromfd, rel, tofd, rel) == 0)
        return 0;
    if (errno != EXDEV && errno != EPERM && errno != EMLINK && errno != EOPNOTSUPP)
        return -1;
    if (S_ISLNK(st->mode))
        return copy_link(fromfd, tofd, rel);
    if (S_ISREG(st->mode))
        return copy_file(fromfd, tofd, rel, st->mode);
    errno = EOPNOTSUPP; /* a pipe, socket or device: only a hard link keeps it */
    return -1;
}

/* ---- carrying ------------------------------------------------------------- */

typedef struct carry {
    const char *from;
    int fromfd, tofd;
    const sl_manifest *old;
    int top_stays;
    sl_carried *made;
    char **dirs; /* the user's folders made in `to`, innermost last (their mode set at "post") */
    size_t ndirs, capdirs;
    sl_error *err;
} carry;

static sl_status conflict(carry *c, const char *rel)
{
    char p[PATH_CAP];
    if (sl_path_join(p, sizeof p, c->from, rel))
        snprintf(p, sizeof p, "%s", c->from);
    return sl_error_set(c->err, SL_EINVAL, p, 0, "seislide did not write this (the folder's "
                        SL_MANIFEST_NAME " does not name it) and this run writes an entry of "
                        "that name: move it out of the folder and run again; the folder is "
                        "unchanged");
}

static sl_status failed(carry *c, const char *rel, const char *what, int e)
{
    char p[PATH_CAP];
    if (sl_path_join(p, sizeof p, c->from, rel)) /* longer than a path may be: its start */
        snprintf(p, sizeof p, "%s/%.300s...", c->from, rel);
    return sl_error_set(c->err, e == ENOMEM ? SL_ENOMEM : SL_EIO, p, 0, "%s: %s; the output "
                        "folder is unchanged%s", what, strerror(e),
                        e == ENAMETOOLONG || e == EMFILE || e == ENFILE
                            ? " (a folder nested deeper than the system takes: move it out of "
                              "the output folder)"
                            : "");
}

static int push_dir(carry *c, const char *rel)
{
    if (c->ndirs == c->capdirs) {
        size_t cap = c->capdirs ? 2 * c->capdirs : 16;
        char **d = realloc(c->dirs, cap * sizeof *d);
        if (!d)
            return -1;
        c->dirs = d;
        c->capdirs = cap;
    }
    if (!(c->dirs[c->ndirs] = strdup(rel)))
        return -1;
    c->ndirs++;
    return 0;
}

/* One entry of the walk over `from`. */
static sl_status carry_entry(carry *c, sl_walk *w, const sl_walk_entry *e)
{
    const char *rel = e->rel;
    if (e->post) { /* a folder of the user's made in `to`: its mode, now that it is filled */
        if (c->ndirs && !strcmp(c->dirs[c->ndirs - 1], rel)) {
            free(c->dirs[--c->ndirs]);
            if (sl_fs->chmod(c->tofd, rel, e->st.mode & 07777) != 0)
                return failed(c, rel, "cannot set the mode of its copy", errno);
        }
        return SL_OK;
    }
    if (e->depth == 1 && sl_outdir_own_name(e->name)) {
        sl_walk_prune(w);
        return SL_OK;
    }
    sl_fstat t;
    int there = sl_fs->stat(c->tofd, rel, &t) == 0;
    if (!there && errno != ENOENT)
        return failed(c, rel, "cannot check the fresh folder", errno);
    if (S_ISDIR(e->st.mode)) {
        int listed = sl_manifest_has_dir(c->old, rel);
        if (e->mount) { /* a mount cannot move with the folder */
            char p[PATH_CAP];
            if (sl_path_join(p, sizeof p, c->from, rel))
                snprintf(p, sizeof p, "%s", c->from);
            return sl_error_set(c->err, SL_EINVAL, p, 0, "a file system is mounted here, inside "
                                "the output folder: seislide replaces the folder as a whole and "
                                "cannot move a mount with it; unmount it or mount it outside "
                                "the output folder and run again; the folder is unchanged");
        }
        if (e->depth == 1 && c->top_stays && !listed && !there) {
            sl_walk_prune(w); /* written in place: the user's entry stays where it is */
            return SL_OK;
        }
        if (there && !S_ISDIR(t.mode))
            return listed ? SL_OK : conflict(c, rel);
        if (!there && !listed) {
            if (make_parents(c->tofd, rel) != 0)
                return errno == ENOTDIR ? conflict(c, rel) : failed(c, rel, "cannot carry", errno);
            if (sl_fs->mkdir(c->tofd, rel, 0700) != 0)
                return failed(c, rel, "cannot make its folder in the fresh folder", errno);
            if (push_dir(c, rel) != 0)
                return failed(c, rel, "cannot carry", ENOMEM);
        }
        return SL_OK;
    }
    if (sl_manifest_has(c->old, rel))
        return SL_OK; /* seislide's: replaced, or gone with the old outputs */
    if (there) /* in place too: the run's entry of that name would take its place */
        return conflict(c, rel);
    if (e->depth == 1 && c->top_stays)
        return SL_OK;
    if (make_parents(c->tofd, rel) != 0)
        return errno == ENOTDIR ? conflict(c, rel) : failed(c, rel, "cannot carry", errno);
    if (keep_entry(c->fromfd, c->tofd, rel, &e->st) != 0)
        return failed(c, rel, "cannot keep it in the new outputs", errno);
    if (c->made) {
        if (sl_fs->stat(c->tofd, rel, &t) != 0)
            return failed(c, rel, "cannot check what was carried", errno);
        if (carried_add(c->made, rel, &e->st, t.ino) != 0)
            return failed(c, rel, "cannot carry", ENOMEM);
    }
    return SL_OK;
}

sl_status sl_manifest_carry(const char *from, const char *to, const sl_manifest *old,
                            int top_stays, sl_carried **made, sl_error *err)
{
    carry c = {.from = from, .old = old, .top_stays = top_stays, .err = err, .fromfd = -1,
               .tofd = -1};
    if (made)
        *made = NULL;
    if (made && !(c.made = calloc(1, sizeof *c.made)))
        return sl_error_set(err, SL_ENOMEM, from, 0, "out of memory");
    sl_status s = SL_OK;
    sl_walk *w = NULL;
    if ((c.fromfd = sl_fs->open(AT_FDCWD, from, O_RDONLY | O_DIRECTORY | O_CLOEXEC, 0)) < 0)
        s = failed(&c, "", "cannot read the output folder", errno);
    else if ((c.tofd = sl_fs->open(AT_FDCWD, to, O_RDONLY | O_DIRECTORY | O_CLOEXEC, 0)) < 0)
        s = sl_error_set(err, SL_EIO, to, 0, "cannot open: %s", strerror(errno));
    else if (!(w = sl_walk_open(c.fromfd)))
        s = failed(&c, "", "cannot read the output folder", errno);
    const sl_walk_entry *e;
    int r = 0;
    while (!s && (r = sl_walk_next(w, &e)) == 1)
        s = carry_entry(&c, w, e);
    if (!s && r < 0)
        s = failed(&c, sl_walk_where(w), "cannot read", errno);
    sl_walk_close(w);
    while (c.ndirs)
        free(c.dirs[--c.ndirs]);
    free(c.dirs);
    if (c.fromfd >= 0)
        sl_fs->close(c.fromfd);
    if (c.tofd >= 0)
        sl_fs->close(c.tofd);
    if (s) {
        sl_carried_free(c.made);
        return s;
    }
    if (c.made && c.made->n)
        qsort(c.made->r, c.made->n, sizeof *c.made->r, by_rel);
    if (made)
        *made = c.made;
    return SL_OK;
}

/* ---- dropping a folder ------------------------------------------------------ */

typedef struct drop {
    const char *x;
    int xfd, dfd; /* dfd -1: no destination */
    const sl_manifest *m;
    const sl_carried *c;
    int flags;
    size_t kept;
    char *why;
    size_t nwhy;
} drop;

static void keep(drop *d, const char *rel, const char *reason)
{
    if (!d->kept++ && d->why && d->nwhy)
        snprintf(d->why, d->nwhy, "%s: %s", rel, reason);
}

/* Equal bytes (regular files of one size) or equal targets (links). */
static int same_content(drop *d, const char *rel, const sl_fstat *a, const sl_fstat *b)
{
    if ((a->mode & S_IFMT) != (b->mode & S_IFMT))
        return 0;
    if (S_ISLNK(a->mode)) {
        char *t = malloc(2 * (size_t)PATH_CAP);
        if (!t)
            return 0;
        ssize_t ka = sl_fs->readlink(d->xfd, rel, t, PATH_CAP);
        ssize_t kb = sl_fs->readlink(d->dfd, rel, t + PATH_CAP, PATH_CAP);
        int same = ka >= 0 && ka == kb && !memcmp(t, t + PATH_CAP, (size_t)ka);
        free(t);
        return same;
    }
    if (!S_ISREG(a->mode) || a->size != b->size)
        return 0;
    int fa = sl_fs->open(d->xfd, rel, O_RDONLY | O_NOFOLLOW | O_CLOEXEC, 0);
    int fb = fa < 0 ? -1 : sl_fs->open(d->dfd, rel, O_RDONLY | O_NOFOLLOW | O_CLOEXEC, 0);
    char *buf = fb < 0 ? NULL : malloc(2 * (size_t)COPY_CHUNK);
    int same = buf != NULL;
    for (off_t left = a->size; same && left > 0;) {
        size_t want = left < COPY_CHUNK ? (size_t)left : COPY_CHUNK;
        ssize_t ka = sl_fs->read(fa, buf, want), kb = sl_fs->read(fb, buf + COPY_CHUNK, want);
        same = ka > 0 && ka == kb && !memcmp(buf, buf + COPY_CHUNK, (size_t)ka);
        left -= ka > 0 ? ka : left;
    }
    free(buf);
    if (fa >= 0)
        sl_fs->close(fa);
    if (fb >= 0)
        sl_fs->close(fb);
    return same;
}

/* x/rel moved to dest/rel (dest lacks it): 0, or -1 (errno). */
static int place(drop *d, const char *rel)
{
    if (make_parents(d->dfd, rel) != 0)
        return -1;
    return sl_fs_rename_new(d->xfd, rel, d->dfd, rel);
}

static void drop_entry(drop *d, sl_walk *w, const sl_walk_entry *e)
{
    const char *rel = e->rel;
    char reason[PATH_CAP + 200];
    if (e->post) {
        if (sl_fs->unlink(d->xfd, rel, AT_REMOVEDIR) != 0 && errno != ENOTEMPTY &&
            errno != EEXIST && errno != ENOENT) {
            snprintf(reason, sizeof reason, "cannot remove: %s", strerror(errno));
            keep(d, rel, reason);
        }
        return; /* not empty: what stays in it was counted */
    }
    if (e->depth == 1 && !strcmp(e->name, SL_MANIFEST_NAME))
        return; /* the last to go */
    if (e->mount) {
        keep(d, rel, "a file system is mounted there");
        return;
    }
    int dir = S_ISDIR(e->st.mode);
    if (dir && e->depth == 1 && !strcmp(e->name, SL_MANIFEST_CACHE) && (d->flags & SL_DROP_CACHE)) {
        sl_walk_prune(w);
        char p[PATH_CAP], sub[PATH_CAP];
        if (sl_path_join(p, sizeof p, d->x, rel) ||
            sl_outdir_drop(p, NULL, NULL, SL_DROP_OURS | SL_DROP_CACHE, sub, sizeof sub)) {
            snprintf(reason, sizeof reason, "the cache could not be removed whole");
            keep(d, rel, reason);
        }
        return;
    }
    int ours = (d->flags & SL_DROP_OURS) != 0;
    if (!ours)
        ours = dir ? sl_manifest_has_dir(d->m, rel) : sl_manifest_has(d->m, rel);
    if (dir && e->depth == 1 && !strcmp(e->name, SL_MANIFEST_CACHE))
        ours = 0; /* the cache stays (no SL_DROP_CACHE): taken back to dest as a user's folder */
    if (ours) {
        if (dir) {
            if (!(e->st.mode & S_IWUSR))
                sl_fs->chmod(d->xfd, rel, (e->st.mode & 07777) | S_IRWXU);
            return; /* entered: the user's entries in it are kept as below */
        }
        if (sl_fs->unlink(d->xfd, rel, 0) != 0 && errno != ENOENT) {
            snprintf(reason, sizeof reason, "cannot remove: %s", strerror(errno));
            keep(d, rel, reason);
        }
        return;
    }
    /* the user's */
    sl_fstat t;
    int there = d->dfd >= 0 && sl_fs->stat(d->dfd, rel, &t) == 0;
    if (!there && d->dfd >= 0 && errno != ENOENT) {
        snprintf(reason, sizeof reason, "cannot check the output folder: %s", strerror(errno));
        keep(d, rel, reason);
        if (dir)
            sl_walk_prune(w);
        return;
    }
    if (d->dfd < 0) {
        keep(d, rel, "a file of the user's and no output folder to keep it in");
        if (dir)
            sl_walk_prune(w);
        return;
    }
    if (dir) {
        if (there && S_ISDIR(t.mode)) { /* the same folder there: its entries one by one */
            if (!(e->st.mode & S_IWUSR))
                sl_fs->chmod(d->xfd, rel, (e->st.mode & 07777) | S_IRWXU);
            return;
        }
        sl_walk_prune(w);
        if (!there && place(d, rel) == 0)
            return;
        if (there)
            snprintf(reason, sizeof reason, "the output folder holds a file of that name");
        else
            snprintf(reason, sizeof reason, "cannot move it into the output folder: %s",
                     strerror(errno));
        keep(d, rel, reason);
        return;
    }
    const carried_rec *r = carried_find(d->c, rel);
    int same = there && t.dev == e->st.dev && t.ino == e->st.ino;
    int carried = r && r->dev == e->st.dev &&
                  ((r->src_ino == e->st.ino && same_time(r->src_mtime, e->st.mtime) &&
                    r->src_size == e->st.size) || r->made_ino == e->st.ino);
    if (same || (carried && there) || (!r && there && same_content(d, rel, &e->st, &t))) {
        if (sl_fs->unlink(d->xfd, rel, 0) != 0 && errno != ENOENT) {
            snprintf(reason, sizeof reason, "cannot remove: %s", strerror(errno));
            keep(d, rel, reason);
        }
        return;
    }
    if (!there) { /* added after the carry, or removed from the output folder since */
        if (place(d, rel) != 0) {
            snprintf(reason, sizeof reason, "cannot move it into the output folder: %s",
                     strerror(errno));
            keep(d, rel, reason);
        }
        return;
    }
    if (r && t.dev == r->dev && t.ino == r->made_ino) { /* a newer version than the one carried */
        if (sl_fs->rename(d->xfd, rel, d->dfd, rel, 0) != 0) {
            snprintf(reason, sizeof reason, "cannot put this newer version in the output "
                     "folder: %s", strerror(errno));
            keep(d, rel, reason);
        }
        return;
    }
    keep(d, rel, "differs from the file of that name in the output folder");
}

size_t sl_outdir_drop(const char *x, const char *dest, const sl_carried *c, int flags, char *why,
                      size_t nwhy)
{
    drop d = {.x = x, .xfd = -1, .dfd = -1, .c = c, .flags = flags, .why = why, .nwhy = nwhy};
    sl_manifest *m = NULL;
    char reason[PATH_CAP + 200];
    if (why && nwhy)
        why[0] = '\0';
    if ((d.xfd = sl_fs->open(AT_FDCWD, x, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC, 0)) < 0) {
        if (errno == ENOENT)
            return 0;
        snprintf(reason, sizeof reason, "cannot open: %s", strerror(errno));
        keep(&d, ".", reason);
        return d.kept;
    }
    if (!(flags & SL_DROP_OURS)) {
        sl_error err;
        sl_error_clear(&err);
        if (sl_manifest_read(x, &m, &err) != SL_OK) {
            keep(&d, SL_MANIFEST_NAME, err.msg);
            sl_fs->close(d.xfd);
            return d.kept;
        }
        if (!m)
            d.flags |= SL_DROP_OURS; /* a fresh folder killed before its manifest: all seislide's */
    }
    d.m = m;
    if (dest &&
        (d.dfd = sl_fs->open(AT_FDCWD, dest, O_RDONLY | O_DIRECTORY | O_CLOEXEC, 0)) < 0 &&
        errno != ENOENT) {
        snprintf(reason, sizeof reason, "cannot open the output folder: %s", strerror(errno));
        keep(&d, ".", reason);
    }
    sl_walk *w = d.kept ? NULL : sl_walk_open(d.xfd);
    if (!d.kept && !w) {
        snprintf(reason, sizeof reason, "cannot read: %s", strerror(errno));
        keep(&d, ".", reason);
    }
    const sl_walk_entry *e;
    int r = 0;
    while (w && (r = sl_walk_next(w, &e)) == 1)
        drop_entry(&d, w, e);
    if (w && r < 0) {
        snprintf(reason, sizeof reason, "cannot read: %s", strerror(errno));
        keep(&d, sl_walk_where(w), reason);
    }
    sl_walk_close(w);
    if (!d.kept && ((sl_fs->unlink(d.xfd, SL_MANIFEST_NAME, 0) != 0 && errno != ENOENT) ||
                    sl_fs->unlink(AT_FDCWD, x, AT_REMOVEDIR) != 0)) {
        snprintf(reason, sizeof reason, "cannot remove: %s", strerror(errno));
        keep(&d, ".", reason);
    }
    sl_fs->close(d.xfd);
    if (d.dfd >= 0)
        sl_fs->close(d.dfd);
    sl_manifest_free(m);
    return d.kept;
}
