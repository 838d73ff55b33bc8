/* fsops.c - the system's file-system calls in one table; see fsops.h. */
#define _GNU_SOURCE /* statx, renameat2, flock */
#include "io/fsops.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

static int sys_open(int dirfd, const char *path, int flags, mode_t mode)
{
    return openat(dirfd, path, flags, mode);
}

static int sys_stat(int dirfd, const char *path, sl_fstat *st)
{
    const char *p = path ? path : "";
    int flags = AT_SYMLINK_NOFOLLOW | AT_NO_AUTOMOUNT | (path ? 0 : AT_EMPTY_PATH);
#ifdef STATX_ATTR_MOUNT_ROOT
    struct statx x;
    if (statx(dirfd, p, flags, STATX_BASIC_STATS, &x) == 0) {
        *st = (sl_fstat){.mode = x.stx_mode, .dev = makedev(x.stx_dev_major, x.stx_dev_minor),
                         .ino = (ino_t)x.stx_ino, .size = (off_t)x.stx_size,
                         .nlink = (nlink_t)x.stx_nlink,
                         .mtime = {(time_t)x.stx_mtime.tv_sec, (long)x.stx_mtime.tv_nsec},
                         .mount_root = (x.stx_attributes_mask & STATX_ATTR_MOUNT_ROOT) &&
                                       (x.stx_attributes & STATX_ATTR_MOUNT_ROOT)};
        return 0;
    }
    if (errno != ENOSYS && errno != EPERM)
        return -1; /* EPERM: a filter that forbids statx */
#endif
    struct stat s;
    if (fstatat(dirfd, p, &s, flags & ~AT_NO_AUTOMOUNT) != 0)
        return -1;
    *st = (sl_fstat){.mode = s.st_mode, .dev = s.st_dev, .ino = s.st_ino, .size = s.st_size,
                     .nlink = s.st_nlink, .mtime = s.st_mtim};
    return 0;
}

static int sys_mkdir(int dirfd, const char *path, mode_t mode) { return mkdirat(dirfd, path, mode); }

static int sys_unlink(int dirfd, const char *path, int flags)
{
    return unlinkat(dirfd, path, flags);
}

static int sys_rename(int fromfd, const char *from, int tofd, const char *to, unsigned flags)
{
    if (!flags && fromfd == AT_FDCWD && tofd == AT_FDCWD)
        return rename(from, to); /* rename(2), as tests/cli/test_faults.sh counts them */
    if (!flags)
        return renameat(fromfd, from, tofd, to);
    return renameat2(fromfd, from, tofd, to, flags);
}

static int sys_link(int fromfd, const char *from, int tofd, const char *to)
{
    return linkat(fromfd, from, tofd, to, 0);
}

static int sys_chmod(int dirfd, const char *path, mode_t mode)
{
    return path ? fchmodat(dirfd, path, mode, 0) : fchmod(dirfd, mode);
}

static const sl_fsops sys_ops = {
    .open = sys_open,       .close = close,         .read = read,
    .write = write,         .stat = sys_stat,       .mkdir = sys_mkdir,
    .unlink = sys_unlink,   .rename = sys_rename,   .link = sys_link,
    .symlink = symlinkat,   .readlink = readlinkat, .chmod = sys_chmod,
    .flock = flock,         .ftruncate = ftruncate,
};

const sl_fsops *sl_fs = &sys_ops;

const sl_fsops *sl_fsops_system(void) { return &sys_ops; }

int sl_fs_write_all(int fd, const void *buf, size_t n)
{
    const char *b = buf;
    while (n) {
        ssize_t w = sl_fs->write(fd, b, n);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0) {
            if (w == 0)
                errno = EIO;
            return -1;
        }
        b += w;
        n -= (size_t)w;
    }
    return 0;
}

int sl_fs_rename_new(int fromfd, const char *from, int tofd, const char *to)
{
    if (sl_fs->rename(fromfd, from, tofd, to, RENAME_NOREPLACE) == 0)
        return 0;
    if (errno != EINVAL && errno != ENOSYS)
        return -1;
    sl_fstat st;
    if (sl_fs->stat(tofd, to, &st) == 0) {
        errno = EEXIST;
        return -1;
    }
    return sl_fs->rename(fromfd, from, tofd, to, 0);
}

const sl_fsops *sl_fsops_install(const sl_fsops *ops)
{
    const sl_fsops *before = sl_fs;
    sl_fs = ops ? ops : &sys_ops;
    return before;
}
