/* identity.c - a floor's identity, the one walk that makes both its key text
 * and its seed; see identity.h. */
#include "plant/identity.h"

#include <string.h>

/* Every field of sl_analysis_opts, sl_floor, sl_floor_component and
 * sl_spectrum is either walked below (o->, fl->, fc->, sp->) or named in
 * this list of fields no result depends on (identity.h, "Not part of it");
 * tests/test_identity.c reads the structs from their headers and fails on
 * a field that is neither, so a new setting cannot be left out of the key
 * by forgetting it:
 *   not sl_analysis_opts.progress, sl_analysis_opts.progress_ctx
 *   not sl_floor.path, sl_floor.name, sl_floor.description, sl_floor.building,
 *       sl_floor.format, sl_floor.elevation_m, sl_floor.units, sl_floor.units_line,
 *       sl_floor.units_text, sl_floor.h2_same_as_h1
 *   not sl_floor_component.zpa_given, sl_floor_component.line
 */

/* The walk's two outputs: the text (when w is not NULL) and the FNV-1a
 * hash of the floor's numbers (the seed's base). */
typedef struct walk {
    sl_pbuf *w;
    uint64_t h;
} walk;

/* A number of the floor: written, and hashed (8 bytes LE, as sl_pbuf_f64). */
static void num(walk *k, double v)
{
    unsigned char le[8];
    uint64_t b;
    if (v == 0)
        v = 0.0; /* -0 and +0 alike */
    memcpy(&b, &v, sizeof b);
    for (int i = 0; i < 8; i++)
        le[i] = (unsigned char)(b >> (8 * i));
    if (k->w)
        sl_pbuf_bytes(k->w, le, sizeof le);
    k->h = sl_fnv64(k->h, le, sizeof le);
}

/* A count or a flag: written, not hashed (identity.h, "Seed"). */
static void count(walk *k, uint64_t n)
{
    if (k->w)
        sl_pbuf_u64(k->w, n);
}

/* The floor part; returns the hash of its numbers. */
static uint64_t floor_walk(sl_pbuf *w, const sl_floor *fl)
{
    walk k = {w, SL_FNV64_OFFSET};
    count(&k, (uint64_t)fl->has_seed);
    count(&k, fl->has_seed ? fl->seed : 0);
    for (int c = 0; c < SL_FLOOR_NCOMP; c++) {
        const sl_floor_component *fc = &fl->comp[c];
        num(&k, (double)c);
        num(&k, fc->zpa_ms2);
        count(&k, fc->nspec);
        for (size_t s = 0; s < fc->nspec; s++) {
            const sl_spectrum *sp = &fc->spec[s];
            num(&k, sp->damping);
            count(&k, sp->n);
            for (size_t i = 0; i < sp->n; i++) {
                num(&k, sp->f_hz[i]);
                num(&k, sp->sa_ms2[i]);
            }
        }
    }
    return k.h;
}

static void f64(sl_pbuf *w, double v)
{
    sl_pbuf_f64(w, v == 0 ? 0.0 : v);
}

/* Every setting of sl_analysis_opts that changes a result, one a line. Not
 * here: progress and its context (no effect). */
static void opts_fields(sl_pbuf *w, const sl_analysis_opts *o)
{
    sl_pbuf_u64(w, o->n_sets);
    f64(w, o->rel_se);
    f64(w, o->abs_se_m);
    sl_pbuf_u64(w, o->max_sets);
    sl_pbuf_u64(w, o->first_batch);
    sl_pbuf_u64(w, o->min_batch);
    f64(w, o->plan_margin);
    f64(w, o->plan_growth);
    sl_pbuf_u64(w, o->boot_resamples);
    f64(w, o->band_level);
    sl_pbuf_u64(w, (uint64_t)o->band_method);
    sl_pbuf_u64(w, o->seed);
    sl_pbuf_u64(w, o->substeps);
    f64(w, o->rtol);
    f64(w, o->scatter);
    sl_pbuf_u64(w, (uint64_t)o->policy);
    f64(w, o->fs_nltha);
    f64(w, o->fs_asce);
    sl_pbuf_u64(w, o->n_mu);
    for (size_t i = 0; i < o->n_mu; i++)
        f64(w, o->mu[i]);
}

void sl_identity_write(sl_pbuf *w, const sl_floor *fl, const sl_analysis_opts *o)
{
    sl_pbuf_str(w, "settings");
    opts_fields(w, o);
    sl_pbuf_str(w, "floor");
    floor_walk(w, fl);
}

/* SplitMix64 finaliser (Steele, Lea and Flood 2014). */
static uint64_t mix64(uint64_t x)
{
    x += 0x9e3779b97f4a7c15ULL;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
}

uint64_t sl_identity_seed(uint64_t run_seed, const sl_floor *fl)
{
    uint64_t content = floor_walk(NULL, fl);
    return mix64(fl->has_seed ? fl->seed : content) ^ run_seed;
}
