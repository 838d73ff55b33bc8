/* walk.c - a folder tree walked iteratively; see walk.h. */
#define _GNU_SOURCE /* O_DIRECTORY, O_NOFOLLOW, O_CLOEXEC */
#include "core/compare.h"
#include "io/walk.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* A folder being walked: its path and the names it held when listed. */
typedef struct frame {
    char *rel;     /* "" for the root */
    char **names;  /* sorted by strcmp */
    size_t n, next;
    sl_fstat st;   /* the folder itself (its "post" entry) */
    int depth;     /* of its entries */
} frame;

struct sl_walk {
    int rootfd;
    dev_t root_dev;
    frame *stack;
    size_t depth, cap;
    sl_walk_entry e;
    char *rel;        /* e.rel: owned */
    int enter;        /* the last entry is a folder to enter */
    char *where;      /* the path of an error */
};

static void frame_free(frame *f)
{
    for (size_t i = 0; i < f->n; i++)
        free(f->names[i]);
    free(f->names);
    free(f->rel);
    memset(f, 0, sizeof *f);
}

/* The names of the folder open as fd (consumed), sorted, into f. */
static int list(frame *f, int fd)
{
    DIR *d = fdopendir(fd);
    if (!d) {
        int e = errno;
        sl_fs->close(fd);
        errno = e;
        return -1;
    }
    rewinddir(d);
    size_t cap = 0;
    int bad = 0;
    for (struct dirent *de; !bad && (errno = 0, de = readdir(d)) != NULL;) {
        if (!strcmp(de->d_name, ".") || !strcmp(de->d_name, ".."))
            continue;
        if (f->n == cap) {
            size_t c = cap ? 2 * cap : 16;
            char **p = realloc(f->names, c * sizeof *p);
            if (!p) {
                bad = ENOMEM;
                break;
            }
            f->names = p;
            cap = c;
        }
        if (!(f->names[f->n] = strdup(de->d_name)))
            bad = ENOMEM;
        else
            f->n++;
    }
    if (!bad && errno)
        bad = errno;
    closedir(d);
    if (bad) {
        errno = bad;
        return -1;
    }
    if (f->n)
        qsort(f->names, f->n, sizeof *f->names, sl_cmp_str);
    return 0;
}

static int push(sl_walk *w, char *rel, const sl_fstat *st, int fd, int depth)
{
    if (w->depth == w->cap) {
        size_t c = w->cap ? 2 * w->cap : 16;
        frame *s = realloc(w->stack, c * sizeof *s);
        if (!s) {
            free(rel);
            sl_fs->close(fd);
            errno = ENOMEM;
            return -1;
        }
        w->stack = s;
        w->cap = c;
    }
    frame *f = &w->stack[w->depth];
    *f = (frame){.rel = rel, .st = *st, .depth = depth};
    if (list(f, fd) != 0) {
        int e = errno;
        frame_free(f);
        errno = e;
        return -1;
    }
    w->depth++;
    return 0;
}

static void set_where(sl_walk *w, const char *rel)
{
    free(w->where);
    w->where = strdup(rel ? rel : "");
}

sl_walk *sl_walk_open(int rootfd)
{
    sl_walk *w = calloc(1, sizeof *w);
    char *rel = strdup("");
    sl_fstat st;
    int fd = -1, e = ENOMEM;
    if (!w || !rel)
        goto fail;
    w->rootfd = rootfd;
    if (sl_fs->stat(rootfd, NULL, &st) != 0 ||
        (fd = sl_fs->open(rootfd, ".", O_RDONLY | O_DIRECTORY | O_CLOEXEC, 0)) < 0) {
        e = errno;
        goto fail;
    }
    if (push(w, rel, &st, fd, 1) != 0) { /* push frees rel and fd on its failure */
        e = errno;
        sl_walk_close(w);
        errno = e;
        return NULL;
    }
    w->root_dev = st.dev;
    return w;
fail:
    free(rel);
    sl_walk_close(w);
    errno = e;
    return NULL;
}

/* "a" + "/" + "b", malloc'd ("b" when a is ""). */
static char *join(const char *a, const char *b)
{
    size_t na = strlen(a), nb = strlen(b);
    char *s = malloc(na + nb + 2);
    if (!s)
        return NULL;
    memcpy(s, a, na);
    if (na)
        s[na++] = '/';
    memcpy(s + na, b, nb + 1);
    return s;
}

/* Enter the folder w->e names (listed as w->e.st). */
static int enter(sl_walk *w)
{
    char *rel = w->rel;
    w->rel = NULL;
    int fd = sl_fs->open(w->rootfd, rel, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC, 0);
    sl_fstat now;
    if (fd >= 0 && (sl_fs->stat(fd, NULL, &now) != 0 || now.dev != w->e.st.dev ||
                    now.ino != w->e.st.ino)) {
        sl_fs->close(fd);
        fd = -1;
        errno = ESTALE; /* replaced since it was listed: not followed */
    }
    if (fd < 0) {
        int e = errno;
        set_where(w, rel);
        free(rel);
        errno = e;
        return -1;
    }
    int depth = w->e.depth + 1;
    sl_fstat st = w->e.st;
    if (push(w, rel, &st, fd, depth) != 0) {
        int e = errno;
        set_where(w, w->depth ? w->stack[w->depth - 1].rel : "");
        errno = e;
        return -1;
    }
    return 0;
}

int sl_walk_next(sl_walk *w, const sl_walk_entry **out)
{
    if (!w)
        return 0;
    if (w->enter) {
        w->enter = 0;
        if (enter(w) != 0)
            return -1;
    }
    free(w->rel);
    w->rel = NULL;
    while (w->depth) {
        frame *f = &w->stack[w->depth - 1];
        if (f->next == f->n) { /* done with this folder: its "post" entry */
            if (w->depth == 1)
                return 0;
            w->rel = f->rel;
            f->rel = NULL;
            sl_walk_entry e = {.rel = w->rel, .st = f->st, .post = 1, .depth = f->depth - 1};
            frame_free(f);
            w->depth--;
            const char *slash = strrchr(w->rel, '/');
            e.name = slash ? slash + 1 : w->rel;
            w->e = e;
            *out = &w->e;
            return 1;
        }
        const char *name = f->names[f->next++];
        char *rel = join(f->rel, name);
        if (!rel) {
            errno = ENOMEM;
            return -1;
        }
        sl_fstat st;
        if (sl_fs->stat(w->rootfd, rel, &st) != 0) {
            int e = errno;
            if (e == ENOENT) { /* gone since listed */
                free(rel);
                continue;
            }
            set_where(w, rel);
            free(rel);
            errno = e;
            return -1;
        }
        w->rel = rel;
        w->e = (sl_walk_entry){.rel = rel, .name = rel + strlen(rel) - strlen(name), .st = st,
                               .depth = f->depth};
        if (S_ISDIR(st.mode)) {
            w->e.mount = st.mount_root || st.dev != w->root_dev;
            w->enter = !w->e.mount;
        }
        *out = &w->e;
        return 1;
    }
    return 0;
}

void sl_walk_prune(sl_walk *w)
{
    if (w)
        w->enter = 0;
}

const char *sl_walk_where(const sl_walk *w)
{
    if (!w)
        return "";
    return w->where ? w->where : w->rel ? w->rel : "";
}

void sl_walk_close(sl_walk *w)
{
    if (!w)
        return;
    while (w->depth)
        frame_free(&w->stack[--w->depth]);
    free(w->stack);
    free(w->rel);
    free(w->where);
    free(w);
}
