/*
 * identity.h - a floor's identity: the one canonical serialisation of
 * everything that changes a floor's results. Both the floor's seed (the
 * motions it gets; analysis.h, "Seed") and its cache key (entry.h) are made
 * from it, by the one walk in identity.c, so the two cannot disagree about
 * what a floor is.
 *
 * The serialisation (pbuf.h encoding: 8-byte little-endian integers, doubles
 * as their exact IEEE 754 bits, -0 written as +0), in this order:
 *
 *   "settings": every field of sl_analysis_opts that changes a result
 *       (identity.c, opts_fields: sets, the convergence targets and batch
 *       plan, the band, the run's seed, sub-steps and rtol of the 2-D
 *       engine, the intensity scatter, the clearance policy and factors of
 *       safety), then the friction grid (its count and every value);
 *   "floor": whether the file gives `seed =`, and that seed (0 when not);
 *       then per component H1, H2, V: its index, its ZPA (m/s^2), its count
 *       of dampings, and per damping: the ratio, the count of frequencies
 *       and every (frequency in Hz, value in m/s^2) pair.
 *
 * The counts make the text unambiguous (two floors with the same numbers in
 * another arrangement have different identities).
 *
 * Not part of it, because no result depends on it: the file's path, format
 * and lines, the floor's name, building, description, elevation and units
 * (values are compared in SI), `h2 = same_as_h1` (H2's numbers are part of
 * it), whether a ZPA was given or read from the table (its value is part of
 * it), the other floors of the run, the output folder, the cache folder,
 * progress (-q), --force, --accept-failed-checks, --motions and the title
 * block. The program version, the source fingerprint and the entry schema
 * are added by the key (entry.h), not here. identity.c lists these fields
 * by name, and a test fails on a field of the structs that is neither
 * walked nor listed.
 *
 * Seed. The seed's base is the file's `seed =` when given, else the 64-bit
 * FNV-1a hash of the floor part's numbers taken in the order above (each
 * component's index, ZPA, and every damping, frequency and value, as 8 bytes
 * little-endian; not the counts, nor the seed fields): the definition the
 * seeds of existing floors were made with, kept so that their motions and
 * results do not move. The floor's seed is splitmix64(base) XOR the run's
 * seed. The options never enter the seed: a changed friction grid or
 * convergence target reuses the same motions (set i is always the same).
 */
#ifndef SL_PLANT_IDENTITY_H
#define SL_PLANT_IDENTITY_H

#include <stdint.h>

#include "analysis.h"
#include "io/floor.h"
#include "plant/pbuf.h"

/* Append the identity of floor fl under options o to w (w->oom on failure;
 * the caller checks). */
void sl_identity_write(sl_pbuf *w, const sl_floor *fl, const sl_analysis_opts *o);

/* The seed of floor fl's motions under the run's seed (above, "Seed"). */
uint64_t sl_identity_seed(uint64_t run_seed, const sl_floor *fl);

#endif
