/*
 * fsfault.h - file-system faults on demand for the output guard's tests: a
 * table of io/fsops.h whose every call counts, can run a hook first (a
 * user's save between two steps of a run) and can fail the Nth call of one
 * operation with a chosen errno (the call not made; a close is made, then
 * reported failed). Also a tree snapshot (every path, type, mode, link target
 * and file byte) to compare a folder before and after.
 */
#ifndef SL_TEST_FSFAULT_H
#define SL_TEST_FSFAULT_H

#define _GNU_SOURCE
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io/fsops.h"

enum {
    FS_OPEN, FS_CLOSE, FS_READ, FS_WRITE, FS_STAT, FS_MKDIR, FS_UNLINK, FS_RENAME,
    FS_LINK, FS_SYMLINK, FS_READLINK, FS_CHMOD, FS_FLOCK, FS_FTRUNCATE, FS_NOPS
};
static const char *const fs_op_name[FS_NOPS] = {
    "open", "close", "read", "write", "stat", "mkdir", "unlink", "rename",
    "link", "symlink", "readlink", "chmod", "flock", "ftruncate"};

static long fs_count[FS_NOPS];
static int fs_fail_op = -1;   /* the operation to fail, -1: none */
static long fs_fail_at;       /* its call number (1-based; 0: every call) */
static int fs_fail_errno;
static int fs_failed;         /* the fault was injected */
/* Called before each call (op, its number, the path or NULL). */
static void (*fs_hook)(int op, long n, const char *path);
/* Paths reported as mount roots by stat (a mount, without mounting). */
static const char *fs_mount_path;
/* A file system without renameat2's flags (NFS, CIFS): EINVAL for any. */
static int fs_no_rename_flags;

static int fs_tick(int op, const char *path)
{
    long n = ++fs_count[op];
    if (fs_hook)
        fs_hook(op, n, path);
    if (op == fs_fail_op && (n == fs_fail_at || !fs_fail_at)) {
        fs_failed = 1;
        errno = fs_fail_errno;
        return 1;
    }
    return 0;
}

#define FS_SYS (sl_fsops_system())
static int fw_open(int d, const char *p, int f, mode_t m)
{
    return fs_tick(FS_OPEN, p) ? -1 : FS_SYS->open(d, p, f, m);
}
static int fw_close(int fd)
{
    int r = FS_SYS->close(fd);
    return fs_tick(FS_CLOSE, NULL) ? -1 : r;
}
static ssize_t fw_read(int fd, void *b, size_t n)
{
    return fs_tick(FS_READ, NULL) ? -1 : FS_SYS->read(fd, b, n);
}
static ssize_t fw_write(int fd, const void *b, size_t n)
{
    return fs_tick(FS_WRITE, NULL) ? -1 : FS_SYS->write(fd, b, n);
}
static int fw_stat(int d, const char *p, sl_fstat *st)
{
    if (fs_tick(FS_STAT, p))
        return -1;
    int r = FS_SYS->stat(d, p, st);
    if (!r && fs_mount_path && p) {
        char full[8192];
        if (d == AT_FDCWD)
            snprintf(full, sizeof full, "%s", p);
        else {
            char fdp[64], dir[4096];
            snprintf(fdp, sizeof fdp, "/proc/self/fd/%d", d);
            ssize_t k = readlink(fdp, dir, sizeof dir - 1);
            dir[k > 0 ? k : 0] = '\0';
            snprintf(full, sizeof full, "%s/%s", dir, p);
        }
        if (!strcmp(full, fs_mount_path))
            st->mount_root = 1;
    }
    return r;
}
static int fw_mkdir(int d, const char *p, mode_t m)
{
    return fs_tick(FS_MKDIR, p) ? -1 : FS_SYS->mkdir(d, p, m);
}
static int fw_unlink(int d, const char *p, int f)
{
    return fs_tick(FS_UNLINK, p) ? -1 : FS_SYS->unlink(d, p, f);
}
static int fw_rename(int fd, const char *f, int td, const char *t, unsigned fl)
{
    if (fs_tick(FS_RENAME, f))
        return -1;
    if (fl && fs_no_rename_flags) {
        errno = EINVAL;
        return -1;
    }
    return FS_SYS->rename(fd, f, td, t, fl);
}
static int fw_link(int fd, const char *f, int td, const char *t)
{
    return fs_tick(FS_LINK, f) ? -1 : FS_SYS->link(fd, f, td, t);
}
static int fw_symlink(const char *tg, int d, const char *p)
{
    return fs_tick(FS_SYMLINK, p) ? -1 : FS_SYS->symlink(tg, d, p);
}
static ssize_t fw_readlink(int d, const char *p, char *b, size_t n)
{
    return fs_tick(FS_READLINK, p) ? -1 : FS_SYS->readlink(d, p, b, n);
}
static int fw_chmod(int d, const char *p, mode_t m)
{
    return fs_tick(FS_CHMOD, p) ? -1 : FS_SYS->chmod(d, p, m);
}
static int fw_flock(int fd, int op)
{
    return fs_tick(FS_FLOCK, NULL) ? -1 : FS_SYS->flock(fd, op);
}
static int fw_ftruncate(int fd, off_t n)
{
    return fs_tick(FS_FTRUNCATE, NULL) ? -1 : FS_SYS->ftruncate(fd, n);
}
static const sl_fsops fs_faulty = {fw_open,  fw_close,   fw_read,     fw_write,   fw_stat,
                                   fw_mkdir, fw_unlink,  fw_rename,   fw_link,    fw_symlink,
                                   fw_readlink, fw_chmod, fw_flock,   fw_ftruncate};

/* Counting from zero, no fault, no hook; the faulty table installed. */
static void fs_reset(void)
{
    memset(fs_count, 0, sizeof fs_count);
    fs_fail_op = -1;
    fs_failed = 0;
    fs_hook = NULL;
    fs_mount_path = NULL;
    fs_no_rename_flags = 0;
    sl_fsops_install(&fs_faulty);
}

/* Fail the n-th call of op with errno e from now on (counts restarted). */
static void fs_fail(int op, long n, int e)
{
    memset(fs_count, 0, sizeof fs_count);
    fs_fail_op = op;
    fs_fail_at = n;
    fs_fail_errno = e;
    fs_failed = 0;
}

/* ---- files and trees ------------------------------------------------------ */

static int fs_put(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return -1;
    fputs(text, f);
    return fclose(f);
}

/* The whole text of a small file ("" when unreadable). */
static const char *fs_get(const char *path)
{
    static char buf[4096];
    buf[0] = '\0';
    FILE *f = fopen(path, "r");
    if (f) {
        size_t k = fread(buf, 1, sizeof buf - 1, f);
        buf[k] = '\0';
        fclose(f);
    }
    return buf;
}

#ifndef FSFAULT_NO_SNAPSHOT
/* A snapshot: one line per entry "path type mode target-or-bytes", sorted.
 * Read through folder descriptors (recursion with small frames: any depth). */
static char **snap_lines;
static size_t snap_n, snap_cap;
static void snap_add(char *line)
{
    if (snap_n == snap_cap) {
        snap_cap = snap_cap ? 2 * snap_cap : 256;
        snap_lines = realloc(snap_lines, snap_cap * sizeof *snap_lines);
    }
    snap_lines[snap_n++] = line;
}
static void snap_dir(int dirfd, const char *rel)
{
    int fd = openat(dirfd, ".", O_RDONLY | O_DIRECTORY);
    DIR *d = fd >= 0 ? fdopendir(fd) : NULL;
    if (!d)
        return;
    for (struct dirent *e; (e = readdir(d)) != NULL;) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
            continue;
        struct stat st;
        if (fstatat(dirfd, e->d_name, &st, AT_SYMLINK_NOFOLLOW) != 0)
            continue;
        size_t k = strlen(rel) + strlen(e->d_name) + 2;
        char *r = malloc(k);
        snprintf(r, k, "%s/%s", rel, e->d_name);
        char what[4200] = "";
        if (S_ISLNK(st.st_mode)) {
            ssize_t n = readlinkat(dirfd, e->d_name, what, sizeof what - 1);
            what[n > 0 ? n : 0] = '\0';
        } else if (S_ISREG(st.st_mode)) {
            int f = openat(dirfd, e->d_name, O_RDONLY);
            ssize_t n = f >= 0 ? read(f, what, sizeof what - 1) : 0;
            what[n > 0 ? n : 0] = '\0';
            if (f >= 0)
                close(f);
            for (char *c = what; *c; c++)
                if (*c == '\n')
                    *c = '|';
        }
        size_t len = k + strlen(what) + 32;
        char *line = malloc(len);
        snprintf(line, len, "%s %c %o %s", r,
                 S_ISLNK(st.st_mode) ? 'l' : S_ISREG(st.st_mode) ? 'f' : 'd',
                 (unsigned)(st.st_mode & 07777), what);
        snap_add(line);
        if (S_ISDIR(st.st_mode)) {
            int sub = openat(dirfd, e->d_name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW);
            if (sub >= 0) {
                snap_dir(sub, r);
                close(sub);
            }
        }
        free(r);
    }
    closedir(d);
}
static int by_line(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}
/* The snapshot of tree `root` (malloc'd; "" when absent). */
static char *fs_snapshot(const char *root)
{
    snap_n = 0;
    int fd = open(root, O_RDONLY | O_DIRECTORY);
    if (fd >= 0) {
        snap_dir(fd, "");
        close(fd);
    }
    if (snap_n)
        qsort(snap_lines, snap_n, sizeof *snap_lines, by_line);
    size_t len = 1;
    for (size_t i = 0; i < snap_n; i++)
        len += strlen(snap_lines[i]) + 1;
    char *out = malloc(len);
    size_t used = 0;
    for (size_t i = 0; i < snap_n; i++) {
        size_t k = strlen(snap_lines[i]);
        memcpy(out + used, snap_lines[i], k);
        used += k;
        out[used++] = '\n';
        free(snap_lines[i]);
    }
    out[used] = '\0';
    snap_n = 0;
    return out;
}

#endif

/* dirfd/name removed, whatever it holds (any depth; modes made writable). */
static void fs_rm_at(int dirfd, const char *name)
{
    struct stat st;
    if (fstatat(dirfd, name, &st, AT_SYMLINK_NOFOLLOW) != 0)
        return;
    if (S_ISDIR(st.st_mode)) {
        fchmodat(dirfd, name, 0700, 0);
        int fd = openat(dirfd, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW);
        DIR *d = fd >= 0 ? fdopendir(fd) : NULL;
        for (struct dirent *e; d && (e = readdir(d)) != NULL;)
            if (strcmp(e->d_name, ".") && strcmp(e->d_name, ".."))
                fs_rm_at(fd, e->d_name);
        if (d)
            closedir(d);
        unlinkat(dirfd, name, AT_REMOVEDIR);
    } else {
        unlinkat(dirfd, name, 0);
    }
}

/* Everything in folder dir removed, by the system's calls (no fault). */
static void fs_empty_dir(const char *dir)
{
    const sl_fsops *was = sl_fsops_install(NULL);
    int fd = open(dir, O_RDONLY | O_DIRECTORY);
    DIR *d = fd >= 0 ? fdopendir(fd) : NULL;
    for (struct dirent *e; d && (e = readdir(d)) != NULL;)
        if (strcmp(e->d_name, ".") && strcmp(e->d_name, ".."))
            fs_rm_at(fd, e->d_name);
    if (d)
        closedir(d);
    sl_fsops_install(was);
}

/* Entries of folder dir whose name starts with prefix. */
static int fs_count_prefix(const char *dir, const char *prefix)
{
    int n = 0;
    DIR *d = opendir(dir);
    for (struct dirent *e; d && (e = readdir(d)) != NULL;)
        n += !strncmp(e->d_name, prefix, strlen(prefix));
    if (d)
        closedir(d);
    return n;
}

#endif
