/* owner.c - this host's name and whether a process is gone; see owner.h. */
#include "io/owner.h"

#include <ctype.h>
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <time.h>
#include <unistd.h>

void sl_owner_host(char *buf, size_t n)
{
    char h[256] = "";
    if (n == 0)
        return;
    if (gethostname(h, sizeof h - 1) != 0 || !h[0])
        snprintf(h, sizeof h, "localhost");
    size_t k = 0;
    for (const char *p = h; *p && k + 1 < n; p++)
        buf[k++] = (isalnum((unsigned char)*p) || *p == '.' || *p == '_' || *p == '-') ? *p : '_';
    buf[k] = '\0';
}

int sl_owner_pid_gone(long pid)
{
    if (pid <= 0 || (long)(pid_t)pid != pid)
        return 1;
    return kill((pid_t)pid, 0) != 0 && errno == ESRCH;
}

void sl_owner_tmp_name(char *buf, size_t n, const char *prefix)
{
    static const char set[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789";
    static _Thread_local unsigned long long state;
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    state ^= (unsigned long long)ts.tv_nsec * 0x9E3779B97F4A7C15ULL ^ (unsigned long long)ts.tv_sec ^
             ((unsigned long long)getpid() << 32);
    if (!state)
        state = 88172645463325252ULL;
    char host[80], x[7];
    sl_owner_host(host, sizeof host);
    for (int i = 0; i < 6; i++) { /* xorshift64 */
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        x[i] = set[state % (sizeof set - 1)];
    }
    x[6] = '\0';
    snprintf(buf, n, "%s%ld@%s-%s", prefix ? prefix : "", (long)getpid(), host, x);
}
