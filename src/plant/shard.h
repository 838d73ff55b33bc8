/*
 * shard.h - the result folder of one shard of a plant run, and reading it
 * back for `seislide merge`.
 *
 * `seislide run PLANT --shard K/N -o DIR` writes DIR/seislide-shard.bin (the
 * manifest) and DIR/results/<hash>.slr, the entries (cache.h) of the floors
 * dealt to shard K (plant.h, "Cost model"). The manifest (pbuf.h encoding):
 *     "SLSHARD2"  K  N  body length  body  CRC-32 (4 bytes LE)
 * where the body is the same for every shard of one plant and one set of
 * settings: the program version, the settings the outputs record (seed,
 * sub-steps, accuracy, the title block as given), the friction grid, whether
 * it is a plant, the building ids and every floor of the plant in plant
 * order (building, id, name, file, description, units, elevation, CRC-32 and
 * size of the file, key hash, shard, the run's warnings about it and whether
 * it was accepted with --accept-floor). Merge checks each manifest (magic,
 * lengths, CRC, every count bounded), that all bodies are equal byte for
 * byte, that the shards are exactly 1..N, and reads every floor's entry
 * from the shard that holds it (its key must hash to the recorded hash).
 */
#ifndef SL_PLANT_SHARD_H
#define SL_PLANT_SHARD_H

#include <stdint.h>

#include "plant/plant.h"
#include "report/report.h"

#define SL_SHARD_MANIFEST "seislide-shard.bin"
#define SL_SHARD_RESULTS "results"

/* What the outputs record, beside the floors. */
typedef struct sl_shard_settings {
    const char *version;
    uint64_t seed;
    unsigned substeps;
    double accuracy;
    sl_report_project project; /* as given (date NULL when not given) */
    size_t n_mu;
    const double *mu;
} sl_shard_settings;

/* Write dir/seislide-shard.bin for shard k of n of plant p (atomically). */
sl_status sl_shard_write_manifest(const char *dir, unsigned k, unsigned n, const sl_plant *p,
                                  const sl_shard_settings *s, sl_error *err);

/* A manifest read back: its plant (floors with their meta, key hash and
 * shard; no floor read, no key text) and settings, all owned. */
typedef struct sl_shard {
    unsigned k, n;
    unsigned char *body;
    size_t body_len;
    sl_plant plant;
    sl_shard_settings set;
    char *strings[8];    /* the owned strings of set */
    double *mu;          /* set.mu */
} sl_shard;

/* Read dir's manifest into sh (zeroed). SL_EINVAL naming the file and what
 * is wrong; free sh with sl_shard_free whatever the result. */
sl_status sl_shard_read(const char *dir, sl_shard *sh, sl_error *err);
void sl_shard_free(sl_shard *sh);

#endif
