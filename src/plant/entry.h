/*
 * entry.h - one floor's result as bytes: the key that names it and the
 * encoding of everything the writers (report/deliver.h, the plant index)
 * read from an sl_analysis, so that a result read back gives byte-identical
 * outputs.
 *
 * Key. The key text is: the program version (the caller's text: the build's
 * identity, core/version.h), the fingerprint of the library's sources
 * (sl_source_id(): any change of the code, a constant or the compile flags
 * gives other keys, so a cache never serves the results of another build),
 * the entry schema (a hash of the field tables of entry.c, so adding a
 * field invalidates old entries),
 * and the floor's identity (identity.h: every setting that changes a
 * result, the friction grid and the floor's numbers in SI, every double as
 * its exact bits; the same walk makes the floor's seed). Nothing else: not
 * the file's name, folder, building, floor name, description, elevation or
 * units. The key hash (64-bit FNV-1a of the key text, 16 hex digits) names
 * the entry; the entry stores the whole key text, and a reader compares it
 * byte for byte, so a hash collision is never a wrong result.
 *
 * Not stored: the synthesized motions themselves (`--motions` recomputes),
 * only their quality checks the workbook shows.
 */
#ifndef SL_PLANT_ENTRY_H
#define SL_PLANT_ENTRY_H

#include <stddef.h>

#include "analysis.h"
#include "core/status.h"
#include "io/floor.h"
#include "plant/pbuf.h"

/* Most sets, friction values and ranges an entry may hold (reader limits). */
#define SL_ENTRY_MAX_SETS 100000
#define SL_ENTRY_MAX_MU 100000

typedef struct sl_entry_key {
    char *text;     /* the key text (malloc'd) */
    size_t len;
    char hash[17];  /* 16 hex digits of its FNV-1a hash */
} sl_entry_key;

/* Build the key of floor fl under options o for program `version`.
 * SL_ENOMEM on failure. Free with sl_entry_key_free. */
sl_status sl_entry_key_make(const sl_floor *fl, const sl_analysis_opts *o, const char *version,
                            sl_entry_key *k, sl_error *err);
void sl_entry_key_free(sl_entry_key *k);
/* The hash of a key text (16 hex digits into out[17]). */
void sl_entry_key_hash(const char *text, size_t len, char out[17]);

/* Append the encoding of analysis a to w. */
void sl_entry_encode(sl_pbuf *w, const sl_analysis *a);
/* Decode an analysis from r (its counts checked against the limits above and
 * against each other; n_mu: the friction values it must have). NULL with
 * r->bad and r->why set on any failure (or out of memory). The result's
 * sets hold the checks only (no motions). */
sl_analysis *sl_entry_decode(sl_preader *r, size_t n_mu);

#endif
