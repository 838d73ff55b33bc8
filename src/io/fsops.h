/*
 * fsops.h - the file-system calls through which the output guard (outguard.c,
 * manifest.c, outcarry.c, walk.c, atomic_dir.c) reads and changes folders, in
 * one table, so that a test can make any of them fail (tests/test_atomic.c,
 * tests/test_outguard.c: EXDEV, EBUSY, ENOSPC, EACCES, ENAMETOOLONG at the
 * Nth call) or do something between two of them (a user's save while a run
 * commits). The program never changes the table; it is no part of the
 * library's interface (not in seislide.h).
 *
 * Every call is relative to a folder open as `dirfd` (AT_FDCWD: the current
 * folder), never follows a symbolic link in its last part, and returns as
 * the system call does (-1 and errno on failure).
 */
#ifndef SL_IO_FSOPS_H
#define SL_IO_FSOPS_H

#include <stddef.h>
#include <sys/types.h>
#include <time.h>

/* What the guard needs of an entry (lstat(2), or statx(2) where the
 * system has it: then also whether a file system is mounted there). */
typedef struct sl_fstat {
    mode_t mode;
    dev_t dev;
    ino_t ino;
    off_t size;
    nlink_t nlink;
    struct timespec mtime;
    int mount_root; /* 1: the root of a mount (statx STATX_ATTR_MOUNT_ROOT) */
} sl_fstat;

typedef struct sl_fsops {
    /* openat(2); mode used with O_CREAT */
    int (*open)(int dirfd, const char *path, int flags, mode_t mode);
    int (*close)(int fd);
    ssize_t (*read)(int fd, void *buf, size_t n);
    ssize_t (*write)(int fd, const void *buf, size_t n);
    /* the entry itself (no link followed); path NULL: the open file dirfd */
    int (*stat)(int dirfd, const char *path, sl_fstat *st);
    int (*mkdir)(int dirfd, const char *path, mode_t mode);
    /* unlinkat(2): flags 0 or AT_REMOVEDIR */
    int (*unlink)(int dirfd, const char *path, int flags);
    /* renameat(2) for flags 0, else renameat2(2) (RENAME_EXCHANGE, RENAME_NOREPLACE) */
    int (*rename)(int fromfd, const char *from, int tofd, const char *to, unsigned flags);
    /* linkat(2), the link itself when `from` is one */
    int (*link)(int fromfd, const char *from, int tofd, const char *to);
    int (*symlink)(const char *target, int dirfd, const char *path);
    ssize_t (*readlink)(int dirfd, const char *path, char *buf, size_t n);
    /* path NULL: fchmod(2) of dirfd, else fchmodat(2) */
    int (*chmod)(int dirfd, const char *path, mode_t mode);
    int (*flock)(int fd, int op);
    int (*ftruncate)(int fd, off_t len);
} sl_fsops;

/* All n bytes of buf written to fd through sl_fs (again after EINTR or a
 * short write). 0, or -1 with errno (EIO where write wrote nothing). */
int sl_fs_write_all(int fd, const void *buf, size_t n);
/* rename(from, to) through sl_fs without replacing an entry at `to` (where
 * the file system has no RENAME_NOREPLACE: checked, then renamed). 0, or -1
 * with errno (EEXIST: `to` exists). */
int sl_fs_rename_new(int fromfd, const char *from, int tofd, const char *to);

/* The table in use (the system's unless a test installed its own). */
extern const sl_fsops *sl_fs;
/* The system's table. */
const sl_fsops *sl_fsops_system(void);
/* Use `ops` from now on (NULL: the system's); returns the table used before.
 * For tests only. */
const sl_fsops *sl_fsops_install(const sl_fsops *ops);

#endif
