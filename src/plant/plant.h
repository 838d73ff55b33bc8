/*
 * plant.h - a plant: the buildings of a facility and their floors, as one
 * list of floors in a fixed order (buildings by folder name, floors by file
 * name), each with its key (entry.h), its expected cost and, when sharded,
 * its shard.
 *
 * Layout. `seislide run PLANT`: when PLANT is one folder that holds no floor
 * files itself and holds sub-folders, it is a plant, each non-hidden
 * sub-folder a building whose floor files are read as `seislide run` reads a
 * folder; the building's id is its folder name as written (as a floor id;
 * its output folder's name made safe by sl_report_file_name). Any
 * other operands (floor files, a folder of floor files, several of them) are
 * one building, as before. A floor id must be unique within its building; the
 * same id in two buildings is fine.
 *
 * Cost model (for balancing shards). The expected cost of a floor is the
 * number of NLTHA integrations it needs: S x (1 + M), with S the motion sets
 * (--sets, else SL_PLANT_COST_SETS, a typical converged count) and M the
 * friction values of the grid at which some motion can slide, mu g <
 * ZPA_h exp(2 sigma) (ZPA_h the larger horizontal ZPA, sigma the floor's
 * intensity scatter, analysis.h opts.scatter): below that every set integrates, above it none does. Floors are
 * dealt to shards by the greedy longest-processing-time rule: in order of
 * decreasing cost (ties: plant order), each to the shard with the least
 * cost so far (ties: the lower shard number). The share therefore depends
 * only on the plant's floors and the settings, never on the machine.
 */
#ifndef SL_PLANT_H
#define SL_PLANT_H

#include <stddef.h>

#include "analysis.h"
#include "plant/entry.h"
#include "report/deliver.h"

#define SL_PLANT_MAX_BUILDINGS 256
#define SL_PLANT_MAX_FLOORS 4096
#define SL_PLANT_COST_SETS 60
#define SL_PLANT_MAX_SHARDS 1000

typedef struct sl_plant_floor {
    size_t building;          /* index into sl_plant.building */
    char *id;                 /* floor id, unique in its building */
    char *name, *path, *description, *units; /* the meta (deliver.h), owned */
    double elevation_m;
    unsigned long crc32;
    long size_bytes;
    const sl_floor *floor;    /* the floor read (NULL in a merge) */
    sl_entry_key key;         /* the key (in a merge: the hash only) */
    double cost;              /* expected cost (above) */
    unsigned shard;           /* 1..N when sharded */
    sl_analysis *an;          /* its result, once computed or read */
    int reused;               /* 1: read from the cache */
    char *warnings;           /* the run's warnings about it, "; "-separated (owned; NULL:
                                 none): its units, its ZPA's plausibility, accepted out of
                                 line with its building (sl_plant_check_intensity) */
    int accepted;             /* accepted in writing (sl_plant_accept) */
} sl_plant_floor;

typedef struct sl_plant {
    int is_plant;             /* 1: a folder of buildings; 0: one building, outputs as before */
    size_t n_buildings;
    char (*building)[SL_DELIVER_ID_MAX];
    size_t n;
    sl_plant_floor *floors;
    sl_deliver_inputs **inputs; /* per building: the floors read (run only) */
} sl_plant;

/* Read the plant named by the operands (see Layout); warnings as in
 * sl_deliver_inputs_load. p must be zeroed; free it with sl_plant_free. */
sl_status sl_plant_load(sl_plant *p, const char *const *args, size_t nargs, int force,
                        char *warnings, size_t nw, sl_error *err);
/* Keys and costs of every floor under options o for program `version`. */
sl_status sl_plant_keys(sl_plant *p, const sl_analysis_opts *o, const char *version,
                        sl_error *err);
/* Accept in writing the floor named by ref (--accept-floor): a floor id, or
 * BUILDING/ID in a plant (an id alone when one building has it), compared
 * without case. SL_EINVAL naming the floors when ref names none or several. */
sl_status sl_plant_accept(sl_plant *p, const char *ref, sl_error *err);
/* Check the floors of each building against each other (plant/intensity.h):
 * SL_EINVAL naming the floor out of line; an accepted floor the rules
 * would refuse gets what they say of it in its warnings. */
sl_status sl_plant_check_intensity(sl_plant *p, sl_error *err);

/* Deal the floors to n_shards shards (floor.shard = 1..n_shards; see above). */
void sl_plant_assign(sl_plant *p, unsigned n_shards);
void sl_plant_free(sl_plant *p);

/* Write the outputs of a whole plant (every floor's an set) into dir:
 * one building: deliver.h's files in dir itself; a plant: dir/<building>/
 * with them and dir/plant.csv, dir/plant.xlsx (report/plant_book.h). */
sl_status sl_plant_deliver(const sl_plant *p, const char *dir, const sl_deliver_opts *o,
                           sl_error *err);

#endif
