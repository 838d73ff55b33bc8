/*
 * cache.h - a folder of floor results that check themselves: one file per
 * floor, named by its key's hash (entry.h), shared safely by runs at the
 * same time, on one machine or several over a network file system.
 *
 * Entry file "<hash>.slr" (pbuf.h encoding):
 *     "SLENTRY1"  the key text  payload length  payload  CRC-32 (4 bytes LE)
 * The CRC-32 (zlib) covers every byte before it. A reader takes the entry
 * only when the file is at most SL_CACHE_MAX_BYTES, the magic, the lengths,
 * the CRC and the key text (byte for byte) all agree and the payload decodes
 * with consistent counts (entry.h); anything else is a damaged entry: the
 * caller recomputes the floor and says so.
 *
 * Writing: a temporary file ".<hash>.tmp-<host>-<pid>-XXXXXX" in the same
 * folder, written, fsync'd, renamed over the final name, the folder fsync'd:
 * a reader sees the old entry, no entry or the whole new one, never part of
 * one, whatever is interrupted. Temporary files and locks of dead processes
 * of this host are removed by sl_cache_open.
 *
 * Locks: "<hash>.lock" created with open(O_CREAT | O_EXCL) (atomic on local
 * file systems and on NFS version 3 and later), holding "host pid time". A
 * run that finds a floor locked computes other floors first and comes back.
 * A lock is stale, and is broken, when its host is this host and its pid is
 * not alive, or when it has not been refreshed (sl_cache_lock_touch, from the
 * progress of the floor, at least every SL_CACHE_LOCK_TOUCH_S) for
 * SL_CACHE_LOCK_STALE_S (a process on another machine that died). Breaking a
 * lock renames it away first, so only one of two breakers wins. In the
 * worst case (a clock skewed by more than the staleness) two runs compute
 * the same floor: both write the same bytes atomically, so the cache is
 * never corrupted, only work is repeated.
 */
#ifndef SL_PLANT_CACHE_H
#define SL_PLANT_CACHE_H

#include <stddef.h>

#include "analysis.h"
#include "core/status.h"
#include "plant/entry.h"

#define SL_CACHE_DIR_NAME ".seislide-cache"
#define SL_CACHE_SUFFIX ".slr"
#define SL_CACHE_MAX_BYTES (256L * 1024 * 1024)
#define SL_CACHE_LOCK_STALE_S 600.0
#define SL_CACHE_LOCK_TOUCH_S 30.0

/* Create the folder when absent (its parent must exist), check that it is
 * writable, and remove the temporary files and the locks of dead processes
 * of this host (a run killed while writing an entry, or after writing it and
 * before unlocking). SL_EIO naming it. */
sl_status sl_cache_open(const char *dir, sl_error *err);

/* Outcome of reading an entry. */
typedef enum sl_cache_read_result {
    SL_CACHE_MISS = 0, /* no entry */
    SL_CACHE_HIT,      /* *out is the floor's result */
    SL_CACHE_DAMAGED   /* an entry that failed a check; why says which */
} sl_cache_read_result;

/* Read the entry of key k from folder dir. */
sl_cache_read_result sl_cache_read(const char *dir, const sl_entry_key *k, size_t n_mu,
                                   sl_analysis **out, char *why, size_t nwhy);
/* Read the entry file `path` whose key must hash to `hash` (a result file of
 * a shard, whose key is known by hash only); *key_text gets a malloc'd copy
 * of its key text when key_text is not NULL. */
sl_cache_read_result sl_cache_read_path(const char *path, const char *hash, size_t n_mu,
                                        sl_analysis **out, char *why, size_t nwhy);

/* Write the entry of key k (atomically, see above). SL_EIO/SL_ENOMEM. */
sl_status sl_cache_write(const char *dir, const sl_entry_key *k, const sl_analysis *a,
                         sl_error *err);

typedef enum sl_cache_lock_result {
    SL_CACHE_LOCKED = 0, /* this process holds the lock */
    SL_CACHE_BUSY,       /* a live process holds it */
    SL_CACHE_LOCK_ERROR  /* the folder is not writable: err says why */
} sl_cache_lock_result;

sl_cache_lock_result sl_cache_lock(const char *dir, const char *hash, sl_error *err);
/* Refresh the lock's time (at most every SL_CACHE_LOCK_TOUCH_S). */
void sl_cache_lock_touch(const char *dir, const char *hash);
void sl_cache_unlock(const char *dir, const char *hash);

#endif
