/* cache.c - a folder of self-checking floor results; see cache.h. */
#include "plant/cache.h"
#include "io/owner.h"

#include <dirent.h>
#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#define MAGIC "SLENTRY1"

static int lock_stale(const char *path);

/* After ".tmp-HOST-" or ".lock.stale-HOST-": this host's process id, then
 * (temporary entries, tmp = 1) "-" and mkstemp's 6 characters, or (locks put
 * aside) the end of the name. 1 when it is exactly that and the process is
 * gone. The strict form keeps another host whose name only starts with ours
 * ("node-b" for "node") from being read as a dead process of this one. */
static int owner_gone(const char *rest, int tmp)
{
    char *end;
    errno = 0;
    long pid = strtol(rest, &end, 10);
    if (end == rest || !isdigit((unsigned char)*rest) || errno || pid <= 0)
        return 0;
    if (tmp ? (end[0] != '-' || strlen(end + 1) != 6) : *end != '\0')
        return 0;
    return sl_owner_pid_gone(pid);
}

/* What dead processes of this host left in the cache folder: their
 * temporary entries and the locks they put aside go, and a lock whose run
 * was killed after its entry was written is broken as sl_cache_lock does.
 * Made when the cache is opened and when a lock of a dead run is broken
 * (that run may have died while writing its entry). */
static void sweep_dead(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d)
        return;
    char host[128], prefix[160], aside[160], path[4400];
    sl_owner_host(host, sizeof host);
    snprintf(prefix, sizeof prefix, ".tmp-%s-", host);
    snprintf(aside, sizeof aside, ".lock.stale-%s-", host);
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        size_t len = strlen(e->d_name);
        const char *t = e->d_name[0] == '.' ? strstr(e->d_name, prefix) : NULL;
        const char *a = strstr(e->d_name, aside);
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        if (t || a) { /* a temporary entry, or a lock put aside, of a dead process */
            if (owner_gone(t ? t + strlen(prefix) : a + strlen(aside), t != NULL))
                unlink(path);
        } else if (len > 5 && !strcmp(e->d_name + len - 5, ".lock") && lock_stale(path)) {
            /* the lock of a run killed after its entry was written: broken as sl_cache_lock does */
            char moved[4600];
            snprintf(moved, sizeof moved, "%s.stale-%s-%ld", path, host, (long)getpid());
            if (rename(path, moved) == 0)
                unlink(moved);
        }
    }
    closedir(d);
}

sl_status sl_cache_open(const char *dir, sl_error *err)
{
    if (mkdir(dir, 0777) != 0 && errno != EEXIST)
        return sl_error_set(err, SL_EIO, dir, 0, "cannot create the cache folder: %s",
                            strerror(errno));
    DIR *d = opendir(dir);
    if (!d)
        return sl_error_set(err, SL_EIO, dir, 0, "cannot read the cache folder: %s",
                            strerror(errno));
    closedir(d);
    if (access(dir, W_OK) != 0)
        return sl_error_set(err, SL_EIO, dir, 0, "the cache folder is not writable");
    sweep_dead(dir);
    return SL_OK;
}

/* The whole file, at most SL_CACHE_MAX_BYTES. 0 ok, -1 absent, -2 other. */
static int slurp(const char *path, unsigned char **buf, size_t *n, char *why, size_t nwhy)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        if (errno == ENOENT)
            return -1;
        snprintf(why, nwhy, "cannot read: %s", strerror(errno));
        return -2;
    }
    struct stat st;
    if (fstat(fileno(f), &st) != 0 || !S_ISREG(st.st_mode) || st.st_size > SL_CACHE_MAX_BYTES) {
        fclose(f);
        snprintf(why, nwhy, "not a regular file of at most %ld bytes", SL_CACHE_MAX_BYTES);
        return -2;
    }
    size_t cap = (size_t)st.st_size + 1; /* one more: a file that grew is noticed */
    unsigned char *b = malloc(cap);
    size_t got = b ? fread(b, 1, cap, f) : 0;
    int bad = !b || ferror(f) || got == cap;
    fclose(f);
    if (bad) {
        free(b);
        snprintf(why, nwhy, "cannot read it whole");
        return -2;
    }
    *buf = b;
    *n = got;
    return 0;
}

static sl_cache_read_result parse(const unsigned char *b, size_t n, const sl_entry_key *k,
                                  const char *hash, size_t n_mu, sl_analysis **out, char *why,
                                  size_t nwhy)
{
    if (n < 8 + 4 || memcmp(b, MAGIC, 8) != 0) {
        snprintf(why, nwhy, "not an entry (no %s header)", MAGIC);
        return SL_CACHE_DAMAGED;
    }
    unsigned long have, want = sl_pbuf_crc32_check(b, n, &have);
    if (want != have) {
        snprintf(why, nwhy, "checksum mismatch (CRC-32 %08lx, stored %08lx)", want, have);
        return SL_CACHE_DAMAGED;
    }
    sl_preader r = {.b = b, .n = n - 4, .pos = 8};
    size_t klen = (size_t)sl_preader_count(&r, n, "key too long");
    const unsigned char *kt = sl_preader_bytes(&r, klen);
    if (kt) {
        char h[17];
        sl_entry_key_hash((const char *)kt, klen, h);
        if (k ? (klen != k->len || memcmp(kt, k->text, klen) != 0) : strcmp(h, hash) != 0) {
            snprintf(why, nwhy, "the entry holds another key");
            return SL_CACHE_DAMAGED;
        }
    }
    size_t plen = (size_t)sl_preader_count(&r, n, "payload too long");
    if (!r.bad && plen != r.n - r.pos) {
        snprintf(why, nwhy, "payload length %zu, %zu bytes present", plen, r.n - r.pos);
        return SL_CACHE_DAMAGED;
    }
    sl_analysis *a = r.bad ? NULL : sl_entry_decode(&r, n_mu);
    if (!a) {
        snprintf(why, nwhy, "cannot decode: %s", r.why ? r.why : "?");
        return SL_CACHE_DAMAGED;
    }
    *out = a;
    return SL_CACHE_HIT;
}

sl_cache_read_result sl_cache_read_path(const char *path, const char *hash, size_t n_mu,
                                        sl_analysis **out, char *why, size_t nwhy)
{
    unsigned char *b = NULL;
    size_t n = 0;
    *out = NULL;
    int s = slurp(path, &b, &n, why, nwhy);
    if (s)
        return s == -1 ? SL_CACHE_MISS : SL_CACHE_DAMAGED;
    sl_cache_read_result r = parse(b, n, NULL, hash, n_mu, out, why, nwhy);
    free(b);
    return r;
}

sl_cache_read_result sl_cache_read(const char *dir, const sl_entry_key *k, size_t n_mu,
                                   sl_analysis **out, char *why, size_t nwhy)
{
    char path[4400];
    snprintf(path, sizeof path, "%s/%s" SL_CACHE_SUFFIX, dir, k->hash);
    unsigned char *b = NULL;
    size_t n = 0;
    *out = NULL;
    int s = slurp(path, &b, &n, why, nwhy);
    if (s)
        return s == -1 ? SL_CACHE_MISS : SL_CACHE_DAMAGED;
    sl_cache_read_result r = parse(b, n, k, k->hash, n_mu, out, why, nwhy);
    free(b);
    return r;
}

static int write_all(int fd, const unsigned char *b, size_t n)
{
    while (n) {
        ssize_t w = write(fd, b, n);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0)
            return -1;
        b += w;
        n -= (size_t)w;
    }
    return 0;
}

sl_status sl_cache_write(const char *dir, const sl_entry_key *k, const sl_analysis *a,
                         sl_error *err)
{
    sl_pbuf w = {0}, p = {0};
    sl_entry_encode(&p, a);
    sl_pbuf_bytes(&w, MAGIC, 8);
    sl_pbuf_u64(&w, k->len);
    sl_pbuf_bytes(&w, k->text, k->len);
    sl_pbuf_u64(&w, p.n);
    sl_pbuf_bytes(&w, p.b, p.n);
    sl_pbuf_crc32(&w);
    char host[128], tmp[4400], path[4400];
    sl_owner_host(host, sizeof host);
    snprintf(path, sizeof path, "%s/%s" SL_CACHE_SUFFIX, dir, k->hash);
    snprintf(tmp, sizeof tmp, "%s/.%s.tmp-%s-%ld-XXXXXX", dir, k->hash, host, (long)getpid());
    sl_status st = SL_OK;
    if (w.oom || p.oom) {
        st = sl_error_set(err, SL_ENOMEM, path, 0, "out of memory");
        goto done;
    }
    int fd = mkstemp(tmp);
    if (fd < 0) {
        st = sl_error_set(err, SL_EIO, path, 0, "cannot write a cache entry: %s", strerror(errno));
        goto done;
    }
    mode_t um = umask(0);
    umask(um);
    int bad = fchmod(fd, 0666 & ~um) != 0 || write_all(fd, w.b, w.n) != 0 || fsync(fd) != 0;
    int e = errno;
    bad |= close(fd) != 0;
    if (bad || rename(tmp, path) != 0) {
        e = bad ? e : errno;
        unlink(tmp);
        st = sl_error_set(err, SL_EIO, path, 0, "cannot write a cache entry: %s", strerror(e));
        goto done;
    }
    int dfd = open(dir, O_RDONLY | O_DIRECTORY);
    if (dfd >= 0) { /* the rename itself durable */
        fsync(dfd);
        close(dfd);
    }
done:
    sl_pbuf_free(&w);
    sl_pbuf_free(&p);
    return st;
}

static void lock_path(char *buf, size_t n, const char *dir, const char *hash)
{
    snprintf(buf, n, "%s/%s.lock", dir, hash);
}

/* Nonzero when the lock file at path is stale (cache.h). */
static int lock_stale(const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0)
        return 0; /* gone: the next try creates it */
    if (difftime(time(NULL), st.st_mtime) > SL_CACHE_LOCK_STALE_S)
        return 1;
    char buf[256] = "", host[128], me[128];
    FILE *f = fopen(path, "r");
    if (!f)
        return 0;
    size_t k = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    buf[k] = '\0';
    long pid = 0;
    sl_owner_host(me, sizeof me);
    if (sscanf(buf, "%127s %ld", host, &pid) != 2)
        /* being written this instant, or garbage: stale only when old */
        return difftime(time(NULL), st.st_mtime) > 10;
    return !strcmp(host, me) && sl_owner_pid_gone(pid);
}

sl_cache_lock_result sl_cache_lock(const char *dir, const char *hash, sl_error *err)
{
    char path[4400], aside[4600], host[128], line[256];
    lock_path(path, sizeof path, dir, hash);
    sl_owner_host(host, sizeof host);
    for (int attempt = 0; attempt < 2; attempt++) {
        int fd = open(path, O_WRONLY | O_CREAT | O_EXCL, 0666);
        if (fd >= 0) {
            int n = snprintf(line, sizeof line, "%s %ld %lld\n", host, (long)getpid(),
                             (long long)time(NULL));
            int bad = write_all(fd, (const unsigned char *)line, (size_t)n) != 0;
            bad |= close(fd) != 0;
            if (bad) {
                unlink(path);
                sl_error_set(err, SL_EIO, path, 0, "cannot write a lock: %s", strerror(errno));
                return SL_CACHE_LOCK_ERROR;
            }
            return SL_CACHE_LOCKED;
        }
        if (errno != EEXIST) {
            sl_error_set(err, SL_EIO, path, 0, "cannot create a lock: %s", strerror(errno));
            return SL_CACHE_LOCK_ERROR;
        }
        if (!lock_stale(path))
            return SL_CACHE_BUSY;
        /* break it: rename it aside (one breaker wins), then remove it */
        snprintf(aside, sizeof aside, "%s.stale-%s-%ld", path, host, (long)getpid());
        if (rename(path, aside) == 0) {
            unlink(aside);
            sweep_dead(dir); /* its run may have died writing the entry */
        }
    }
    return SL_CACHE_BUSY;
}

void sl_cache_lock_touch(const char *dir, const char *hash)
{
    static _Thread_local time_t last; /* per thread: reentrant */
    time_t now = time(NULL);
    if (difftime(now, last) < SL_CACHE_LOCK_TOUCH_S)
        return;
    last = now;
    char path[4400];
    lock_path(path, sizeof path, dir, hash);
    utimensat(AT_FDCWD, path, NULL, 0);
}

void sl_cache_unlock(const char *dir, const char *hash)
{
    char path[4400];
    lock_path(path, sizeof path, dir, hash);
    unlink(path);
}
