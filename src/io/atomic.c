/* atomic.c - a file written through a temporary name and a rename; see
 * atomic.h. (Folders: atomic_dir.c.) */
#define _GNU_SOURCE /* O_CLOEXEC */
#include "io/atomic.h"
#include "io/atomic_name.h"
#include "io/fsops.h"
#include "io/owner.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Tries at a free temporary name. */
#define TMP_TRIES 100

struct sl_atomic {
    FILE *f;
    char *path;
    char *tmp;
};

sl_atomic *sl_atomic_open(const char *path, sl_error *err)
{
    sl_atomic *a = calloc(1, sizeof *a);
    if (!a || !(a->path = strdup(path)) || !(a->tmp = sl_atomic_hidden_name(path))) {
        if (a) {
            free(a->path);
            free(a);
        }
        sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
        return NULL;
    }
    int fd = -1;
    for (int t = 0; t < TMP_TRIES; t++) {
        fd = sl_fs->open(AT_FDCWD, a->tmp, O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
        if (fd >= 0 || errno != EEXIST)
            break;
        sl_atomic_hidden_renew(a->tmp);
    }
    if (fd < 0 || sl_fs->chmod(fd, NULL, 0666 & ~sl_atomic_umask()) != 0 ||
        !(a->f = fdopen(fd, "wb"))) {
        sl_error_set(err, SL_EIO, path, 0, "cannot create: %s", strerror(errno));
        if (fd >= 0) {
            close(fd);
            sl_fs->unlink(AT_FDCWD, a->tmp, 0);
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
    if (!bad && sl_fs->rename(AT_FDCWD, a->tmp, AT_FDCWD, a->path, 0) != 0) {
        e = errno;
        bad = 1;
    }
    if (bad) {
        sl_fs->unlink(AT_FDCWD, a->tmp, 0);
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
    sl_fs->unlink(AT_FDCWD, a->tmp, 0);
    atomic_free(a);
}

