/* manifest.c - the manifest of an output folder: read, listed, written; see
 * outguard.h. */
#define _GNU_SOURCE /* O_CLOEXEC, O_NOFOLLOW */
#include "core/compare.h"
#include "io/fsops.h"
#include "io/outguard.h"
#include "io/owner.h"
#include "io/walk.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define PATH_CAP SL_OUTGUARD_PATH
/* Tries at a free temporary name. */
#define TMP_TRIES 100

/* "a" + "/" + "b" into buf (n); -1 when it does not fit. */
struct sl_manifest {
    size_t n, cap;
    char **path; /* sorted by strcmp */
    char *text;  /* as read (sl_manifest_read), else NULL */
    size_t len;
};

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
    free(m->text);
    free(m);
}

int sl_manifest_has(const sl_manifest *m, const char *rel)
{
    return m && m->n && bsearch(&rel, m->path, m->n, sizeof *m->path, sl_cmp_str) != NULL;
}

/* strcmp(key "/", elem) without making key "/": the order of m->path */
static int cmp_as_dir(const void *key, const void *elem)
{
    const char *r = *(const char *const *)key, *p = *(char *const *)elem;
    size_t k = strlen(r);
    int c = strncmp(r, p, k);
    if (c)
        return c;
    if (p[k] != '/')
        return (unsigned char)'/' - (unsigned char)p[k];
    return p[k + 1] ? -1 : 0;
}

int sl_manifest_has_dir(const sl_manifest *m, const char *rel)
{
    return m && m->n && bsearch(&rel, m->path, m->n, sizeof *m->path, cmp_as_dir) != NULL;
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

size_t sl_manifest_count(const sl_manifest *m) { return m ? m->n : 0; }

const char *sl_manifest_path(const sl_manifest *m, size_t i)
{
    return m && i < m->n ? m->path[i] : NULL;
}

/* Sorted, each path once. */
static void manifest_sort(sl_manifest *m)
{
    if (!m->n)
        return;
    qsort(m->path, m->n, sizeof *m->path, sl_cmp_str);
    size_t k = 1;
    for (size_t i = 1; i < m->n; i++) {
        if (!strcmp(m->path[i], m->path[k - 1]))
            free(m->path[i]);
        else
            m->path[k++] = m->path[i];
    }
    m->n = k;
}

sl_manifest *sl_manifest_union(const sl_manifest *a, const sl_manifest *b)
{
    sl_manifest *m = calloc(1, sizeof *m);
    const sl_manifest *both[2] = {a, b};
    for (int j = 0; m && j < 2; j++)
        for (size_t i = 0; both[j] && i < both[j]->n; i++)
            if (manifest_add(m, both[j]->path[i], strlen(both[j]->path[i]))) {
                sl_manifest_free(m);
                return NULL;
            }
    if (m)
        manifest_sort(m);
    return m;
}

/* The whole regular file dir/name (at most max bytes) into *text (malloc'd,
 * NUL-terminated), its length in *len: 0; 1 when absent; -1 (errno; EFBIG
 * when too large, EINVAL when not a regular file). */
static int slurp(const char *dir, const char *name, long max, char **text, size_t *len)
{
    char path[PATH_CAP];
    if (sl_path_join(path, sizeof path, dir, name)) {
        errno = ENAMETOOLONG;
        return -1;
    }
    int fd = sl_fs->open(AT_FDCWD, path, O_RDONLY | O_NOFOLLOW | O_CLOEXEC, 0);
    if (fd < 0)
        return errno == ENOENT ? 1 : (errno == ELOOP ? (errno = EINVAL, -1) : -1);
    sl_fstat st;
    int e = 0;
    if (sl_fs->stat(fd, NULL, &st) != 0)
        e = errno;
    else if (!S_ISREG(st.mode))
        e = EINVAL;
    else if (st.size > max)
        e = EFBIG;
    char *t = e ? NULL : malloc((size_t)st.size + 1);
    size_t got = 0;
    if (!e && !t)
        e = ENOMEM;
    while (!e && got < (size_t)st.size) {
        ssize_t k = sl_fs->read(fd, t + got, (size_t)st.size - got);
        if (k < 0 && errno == EINTR)
            continue;
        if (k <= 0) {
            e = k < 0 ? errno : EIO;
            break;
        }
        got += (size_t)k;
    }
    sl_fs->close(fd);
    if (e) {
        free(t);
        errno = e;
        return -1;
    }
    t[got] = '\0';
    *text = t;
    *len = got;
    return 0;
}

sl_status sl_manifest_read(const char *dir, sl_manifest **out, sl_error *err)
{
    char path[PATH_CAP];
    *out = NULL;
    if (sl_path_join(path, sizeof path, dir, SL_MANIFEST_NAME))
        return sl_error_set(err, SL_EIO, dir, 0, "path too long");
    char *text = NULL;
    size_t len = 0;
    int r = slurp(dir, SL_MANIFEST_NAME, SL_MANIFEST_MAX_BYTES, &text, &len);
    if (r == 1)
        return SL_OK;
    if (r < 0) {
        if (errno == EINVAL || errno == EFBIG)
            return sl_error_set(err, SL_EPARSE, path, 0, "not a manifest seislide wrote (%s)",
                                errno == EFBIG ? "too large" : "not a regular file");
        return sl_error_set(err, errno == ENOMEM ? SL_ENOMEM : SL_EIO, path, 0, "cannot read: %s",
                            strerror(errno));
    }
    sl_manifest *m = calloc(1, sizeof *m);
    sl_status s = m ? SL_OK : sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
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
    if (s) {
        free(text);
        sl_manifest_free(m);
        return s;
    }
    m->text = text;
    m->len = len;
    manifest_sort(m);
    *out = m;
    return SL_OK;
}

sl_status sl_manifest_list(const char *dir, sl_manifest **out, sl_error *err)
{
    *out = NULL;
    sl_manifest *m = calloc(1, sizeof *m);
    int fd = sl_fs->open(AT_FDCWD, dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC, 0);
    sl_walk *w = fd >= 0 ? sl_walk_open(fd) : NULL;
    int e = m ? 0 : ENOMEM, r = 0;
    if (!e && !w)
        e = errno ? errno : ENOMEM;
    const sl_walk_entry *en;
    while (!e && (r = sl_walk_next(w, &en)) == 1) {
        if (en->post)
            continue;
        if (en->depth == 1 && (!strcmp(en->name, SL_MANIFEST_NAME) ||
                               !strncmp(en->name, SL_OUTDIR_OWN_PREFIX,
                                        strlen(SL_OUTDIR_OWN_PREFIX)))) {
            sl_walk_prune(w);
            continue;
        }
        if (en->mount) {
            e = EXDEV; /* a file system mounted in a fresh folder: not seislide's to name */
            break;
        }
        size_t k = strlen(en->rel);
        if (S_ISDIR(en->st.mode)) {
            char *r2 = malloc(k + 2);
            if (!r2) {
                e = ENOMEM;
                break;
            }
            memcpy(r2, en->rel, k);
            memcpy(r2 + k, "/", 2);
            e = manifest_add(m, r2, k + 1) ? ENOMEM : 0;
            free(r2);
            if (en->depth == 1 && !strcmp(en->name, SL_MANIFEST_CACHE))
                sl_walk_prune(w); /* the cache: one line */
        } else {
            e = manifest_add(m, en->rel, k) ? ENOMEM : 0;
        }
    }
    if (!e && r < 0)
        e = errno;
    sl_status s = SL_OK;
    if (e) {
        char where[PATH_CAP];
        if (sl_path_join(where, sizeof where, dir, sl_walk_where(w)))
            snprintf(where, sizeof where, "%s", dir);
        s = sl_error_set(err, e == ENOMEM ? SL_ENOMEM : SL_EIO, where, 0, "cannot list: %s",
                         strerror(e));
        sl_manifest_free(m);
    } else {
        manifest_sort(m);
        *out = m;
    }
    sl_walk_close(w);
    if (fd >= 0)
        sl_fs->close(fd);
    return s;
}

/* text (len bytes) as dir's manifest, through a temporary file renamed over it. */
static sl_status save_text(const char *dir, const char *text, size_t len, sl_error *err)
{
    char path[PATH_CAP], tmp[PATH_CAP], name[256];
    if (sl_path_join(path, sizeof path, dir, SL_MANIFEST_NAME))
        return sl_error_set(err, SL_EIO, dir, 0, "path too long");
    int fd = -1, e = 0;
    for (int t = 0; t < TMP_TRIES; t++) {
        sl_owner_tmp_name(name, sizeof name, SL_OUTDIR_TMP_INSIDE);
        if (sl_path_join(tmp, sizeof tmp, dir, name)) {
            errno = ENAMETOOLONG;
            break;
        }
        fd = sl_fs->open(AT_FDCWD, tmp, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd >= 0 || errno != EEXIST)
            break;
    }
    if (fd < 0)
        e = errno;
    else {
        if (sl_fs_write_all(fd, text, len) != 0)
            e = errno;
        if (sl_fs->close(fd) != 0 && !e)
            e = errno;
        if (!e && sl_fs->rename(AT_FDCWD, tmp, AT_FDCWD, path, 0) != 0)
            e = errno;
        if (e)
            sl_fs->unlink(AT_FDCWD, tmp, 0);
    }
    return e ? sl_error_set(err, SL_EIO, path, 0, "cannot write: %s", strerror(e)) : SL_OK;
}

sl_status sl_manifest_save(const char *dir, const sl_manifest *m, const char *version,
                           sl_error *err)
{
    size_t cap = 512;
    for (size_t i = 0; m && i < m->n; i++)
        cap += strlen(m->path[i]) + 1;
    char *text = malloc(cap);
    if (!text)
        return sl_error_set(err, SL_ENOMEM, dir, 0, "out of memory");
    int used = snprintf(text, cap, "%s\n# written by %s: every file and folder below is an "
                        "output of seislide; a run into this folder replaces them and keeps "
                        "every other file\n", SL_MANIFEST_HEAD, version ? version : "seislide");
    size_t len = used > 0 && (size_t)used < 512 ? (size_t)used : 0;
    for (size_t i = 0; m && i < m->n; i++) {
        size_t k = strlen(m->path[i]);
        memcpy(text + len, m->path[i], k);
        text[len + k] = '\n';
        len += k + 1;
    }
    sl_status s = save_text(dir, text, len, err);
    free(text);
    return s;
}

sl_status sl_manifest_restore(const char *dir, const sl_manifest *m, const char *version,
                              sl_error *err)
{
    if (m && m->text)
        return save_text(dir, m->text, m->len, err);
    return sl_manifest_save(dir, m, version, err);
}
