/* owner.c - this host's name and whether a process is gone; see owner.h. */
#include "io/owner.h"

#include <ctype.h>
#include <errno.h>
#include <signal.h>
#include <stdio.h>
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
