/*
 * owner.h - who owns a temporary file, folder or lock: this host's name and
 * whether a process of this host is gone. Used by the atomic writer
 * (atomic.c: ".BASE.tmp-PID@HOST-XXXXXX") and the result cache
 * (plant/cache.c: entries, locks), so that both name and recognise their
 * owners the same way.
 */
#ifndef SL_IO_OWNER_H
#define SL_IO_OWNER_H

#include <stddef.h>

/* This host's name as one word for file names and lock files: letters,
 * digits, '.', '_' and '-' kept, anything else '_'; "localhost" when it has
 * none; at most 32 characters (and n - 1), so that a name holding it stays
 * well below NAME_MAX. */
void sl_owner_host(char *buf, size_t n);

/* 1 when process pid of this host is gone (kill(pid, 0) fails with ESRCH);
 * 0 when it lives, belongs to another user, or pid is not a process id. */
int sl_owner_pid_gone(long pid);

#endif
