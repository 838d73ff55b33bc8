/* atomic.c - temporary file + rename, see atomic.h. */
#include "io/atomic.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

struct sl_atomic {
    FILE *f;
    char *path;
    char *tmp;
};

sl_atomic *sl_atomic_open(const char *path, sl_error *err)
{
    sl_atomic *a = calloc(1, sizeof *a);
    size_t n = strlen(path);
    if (!a || !(a->path = strdup(path)) || !(a->tmp = malloc(n + 32))) {
        if (a) {
            free(a->path);
            free(a);
        }
        sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
        return NULL;
    }
    /* hidden sibling: DIR/.NAME.tmp-XXXXXX */
    const char *slash = strrchr(path, '/');
    size_t dirlen = slash ? (size_t)(slash - path) + 1 : 0;
    memcpy(a->tmp, path, dirlen);
    snprintf(a->tmp + dirlen, n + 32 - dirlen, ".%s.tmp-XXXXXX", path + dirlen);
    int fd = mkstemp(a->tmp);
    if (fd < 0 || !(a->f = fdopen(fd, "wb"))) {
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
