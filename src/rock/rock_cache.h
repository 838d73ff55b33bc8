/*
 * rock_cache.h - the rocking results of a floor's items kept in the run's
 * cache folder (plant/cache.h), so that a rerun with the same list
 * recomputes nothing.
 *
 * Key text (pbuf.h encoding): "seislide rocking result", the program's
 * build identity (sl_build_id: version and source fingerprint), the floor's
 * identity under the run's seed (plant/identity.h: the floor's numbers and
 * seed; the motions depend on nothing else), the floor's set count, every
 * option of sl_rockf_opts that changes a result (its engine's too), and per
 * item its block
 * (b, h, r) and orientation. The key hash (64-bit FNV-1a, 16 hex digits)
 * names the file "<hash>.slrock".
 *
 * File: "SLROCK01", the key text's length and bytes, the payload's length
 * and bytes (per item every field of sl_rockf_result), CRC-32 (4 bytes LE)
 * of every byte before it. A reader takes it only when the magic, the
 * lengths, the CRC, the key text (byte for byte) and the item count agree;
 * anything else is a miss. Written through a temporary file renamed over the
 * final name (io/atomic.h): a reader sees the old file, none or the whole
 * new one. Two runs that compute the same entry write the same bytes.
 */
#ifndef SL_ROCK_CACHE_H
#define SL_ROCK_CACHE_H

#include <stddef.h>
#include <stdint.h>

#include "core/status.h"
#include "io/floor.h"
#include "rock/rock_floor.h"

#define SL_ROCKC_SUFFIX ".slrock"

typedef struct sl_rockc_key {
    unsigned char *text;
    size_t len;
    char hash[17];
} sl_rockc_key;

/* The key of items[n] on floor fl (run seed, n_sets per floor, options o).
 * SL_ENOMEM. Free with sl_rockc_key_free. */
sl_status sl_rockc_key_make(const sl_floor *fl, uint64_t run_seed, size_t n_sets,
                            const sl_rockf_opts *o, const sl_rockf_item *items, size_t n,
                            sl_rockc_key *k, sl_error *err);
void sl_rockc_key_free(sl_rockc_key *k);

/* Read out[n] from folder dir: 1 taken, 0 not there or not usable. */
int sl_rockc_read(const char *dir, const sl_rockc_key *k, sl_rockf_result *out, size_t n);

/* Write out[n] under key k into dir (atomically). SL_EIO, SL_ENOMEM. */
sl_status sl_rockc_write(const char *dir, const sl_rockc_key *k, const sl_rockf_result *out,
                         size_t n, sl_error *err);

#endif
