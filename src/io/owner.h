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

/* This host's name as one word for file names and lock files: the whole
 * name gethostname gives (at most HOST_NAME_MAX, 64 on Linux, and n - 1
 * characters), letters, digits, '.', '_' and '-' kept, anything else '_';
 * "localhost" when it has none. Never shortened further, so that two hosts
 * of one shared cache whose names share a long prefix stay apart. */
void sl_owner_host(char *buf, size_t n);

/* 1 when process pid of this host is gone (kill(pid, 0) fails with ESRCH)
 * or pid is no process id (<= 0, or out of range: no process holds it);
 * 0 when it lives or belongs to another user. */
int sl_owner_pid_gone(long pid);

/* A temporary name "PREFIX" "PID@HOST-XXXXXX" (XXXXXX six random letters
 * and digits, another each call) into buf (size n): the owner in the name,
 * so that a later run can tell what a killed process left from a live run's
 * (atomic.c's fresh folders, outguard's temporary manifests). */
void sl_owner_tmp_name(char *buf, size_t n, const char *prefix);

#endif
