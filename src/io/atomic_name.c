/* atomic_name.c - hidden temporary names; see atomic_name.h. */
#include "io/atomic_name.h"
#include "io/atomic.h"
#include "io/owner.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* Room for "PID@HOST-XXXXXX" after the prefix. */
#define OWNER_ROOM 160

mode_t sl_atomic_umask(void)
{
    mode_t m = umask(022);
    umask(m);
    return m;
}

char *sl_atomic_hidden_name(const char *path)
{
    size_t n = strlen(path);
    while (n > 1 && path[n - 1] == '/')
        n--;
    size_t dirlen = 0;
    for (size_t i = 0; i < n; i++)
        if (path[i] == '/')
            dirlen = i + 1;
    size_t cap = n + strlen(SL_ATOMIC_TMP_TAG) + OWNER_ROOM;
    char *prefix = malloc(cap), *t = malloc(cap);
    if (!prefix || !t) {
        free(prefix);
        free(t);
        return NULL;
    }
    snprintf(prefix, cap, "%.*s.%.*s" SL_ATOMIC_TMP_TAG, (int)dirlen, path, (int)(n - dirlen),
             path + dirlen);
    sl_owner_tmp_name(t, cap, prefix);
    free(prefix);
    return t;
}

void sl_atomic_hidden_renew(char *name)
{
    size_t n = strlen(name);
    char fresh[OWNER_ROOM];
    if (n < 6)
        return;
    sl_owner_tmp_name(fresh, sizeof fresh, "");
    memcpy(name + n - 6, fresh + strlen(fresh) - 6, 6);
}
