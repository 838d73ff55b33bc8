/*
 * study_parts.h - the four computed parts of the source study's evaluation
 * (docs/validation.md), as data: every
 * number `seislide study` prints or plots comes from these structs and the
 * constants below; the command only formats them.
 *
 *  1  model validation: Rinaldi 228, then 228 + 318, at SL_STUDY_P1_MU: the
 *     engine against the smoothed and elastic-plastic reference models
 *  2  El Centro #9 matched to RG 1.60 at SL_STUDY_P2_PGA_G, SL_STUDY_P2_MU:
 *     peaks under x, y, x+y, x+z, y+z, x+y+z
 *  3  the seven-record ground set matched to RG 1.60 at 1 g, scaled to
 *     each of SL_STUDY_LEVELS_G: design spectra, crossover, FS 3.0 check
 *  4  the four real record groups, unscaled, on the default friction grid
 *
 * Every part reads its records from the folder `records` (one sub-folder
 * per set, io/setdir.h). Units: SI. Memory: each *_run fills a struct the
 * caller frees with the matching *_free (also after a failed run).
 */
#ifndef SL_STUDY_PARTS_H
#define SL_STUDY_PARTS_H

#include <stddef.h>

#include "core/standards.h"
#include "slide/slide.h"
#include "study/study.h"

/* The source study's settings (docs/validation.md). */
#define SL_STUDY_ZETA SL_ASCE_DAMPING /* RG 1.60 matching damping of the study */
#define SL_STUDY_P1_MU 0.3            /* part 1 friction coefficient */
#define SL_STUDY_P1_DIR "RSN1063_NORTHR_RRS" /* Rinaldi */
#define SL_STUDY_P2_MU 0.1            /* part 2 friction coefficient */
#define SL_STUDY_P2_PGA_G 0.8         /* part 2 PGA, g */
#define SL_STUDY_P2_DIR "RSN6_IMPVALL.I_I-ELC" /* El Centro #9 */
#define SL_STUDY_SMOOTH_ETA 20.0      /* the study's validation smoothing exponent */
#define SL_STUDY_SMOOTH_UY_M 1e-7     /* the study's yield displacement, m */
#define SL_STUDY_NLEVELS 4            /* part 3 PGA levels */
extern const double sl_study_levels_g[SL_STUDY_NLEVELS]; /* 0.2, 0.4, 0.6, 0.8 g */
/* Part 3 grid of x = mu g/PGA: from SL_STUDY_P3_X0 step SL_STUDY_P3_DX, NX values. */
#define SL_STUDY_P3_X0 0.05
#define SL_STUDY_P3_DX 0.005
#define SL_STUDY_P3_NX 191 /* to 1.00 */
#define SL_STUDY_P3_K01 10 /* index of x = 0.10 */
/* The study's published values the claims table compares with. */
#define SL_STUDY_CLAIM_DUX_PCT (-81.0) /* u_x, x -> x+y */
#define SL_STUDY_CLAIM_DUY_PCT 15.0    /* u_y, y -> x+y */
#define SL_STUDY_CLAIM_FS 3.0          /* recommended factor on the ASCE best estimate */

/* 100 (to - from) / from, NAN unless from > 0: a change in percent. */
double sl_study_pct(double to, double from);

/* ---- Part 1 ---------------------------------------------------------- */
#define SL_STUDY_P1_NMODELS 3
extern const sl_model sl_study_p1_models[SL_STUDY_P1_NMODELS]; /* engine, smooth, plastic */
extern const char *const sl_study_p1_model_names[SL_STUDY_P1_NMODELS];
extern const char *const sl_study_p1_model_tags[SL_STUDY_P1_NMODELS];

typedef struct sl_study_p1_run {
    sl_slide_result r;
    sl_history *h;  /* owned */
    double run_ms;  /* wall time of the run, ms */
} sl_study_p1_run;

typedef struct sl_study_part1 {
    sl_study_p1_run run[2][SL_STUDY_P1_NMODELS]; /* [228 alone, 228 + 318][model] */
    double dev[2]; /* largest |peak_ref - peak_engine| / peak_engine */
} sl_study_part1;

sl_status sl_study_part1_run(const char *records, sl_study_part1 *p, sl_error *err);
void sl_study_part1_free(sl_study_part1 *p);

/* ---- Part 2 ---------------------------------------------------------- */
#define SL_STUDY_P2_NCASES 6
typedef struct sl_study_p2_case {
    const char *name, *tag; /* "x+y", "xy" */
    int y_first;            /* the run's first axis is y */
    sl_slide_result r;
    sl_history *h;          /* owned */
    double ux_m, uy_m;      /* peak u_x, u_y (NAN when that axis is not driven) */
} sl_study_p2_case;

typedef struct sl_study_part2 {
    sl_synth_set matched; /* the matched El Centro set (x, y, z) */
    sl_study_p2_case c[SL_STUDY_P2_NCASES]; /* x, y, x+y, x+z, y+z, x+y+z */
    double dux, duy;      /* % change of u_x (x -> x+y) and u_y (y -> x+y) */
    double dvx, dvy;      /* % change of u_x (x -> x+z) and u_y (y -> y+z) */
    double dvx3, dvy3;    /* % change of u_x and u_y, x+y -> x+y+z */
} sl_study_part2;

sl_status sl_study_part2_run(const char *records, sl_study_part2 *p, sl_error *err);
void sl_study_part2_free(sl_study_part2 *p);

/* ---- Part 3 ---------------------------------------------------------- */
typedef struct sl_study_part3 {
    sl_synth_set matched[SL_STUDY_NGROUND]; /* at 1 g */
    double ratio_lo[SL_STUDY_NGROUND], ratio_hi[SL_STUDY_NGROUND]; /* spectrum/target */
    double pgd_m[SL_STUDY_NGROUND][2];      /* PGD of H1 and H2 at 1 g */
    double pgd_mean_m;                      /* mean PGD of H1 at 1 g */
    sl_study_spectra *level[SL_STUDY_NLEVELS];
    double cross[SL_STUDY_NLEVELS];      /* crossover x (NAN: none) */
    double fs3_x[SL_STUDY_NLEVELS];      /* largest x where 3.0 ASCE best < NLTHA design */
    double uncons_hi[SL_STUDY_NLEVELS];  /* ranges above the crossover */
} sl_study_part3;

/* progress(ctx, message) after each record and level (may be NULL). */
sl_status sl_study_part3_run(const char *records, sl_study_part3 *p,
                             void (*progress)(void *, const char *), void *ctx, sl_error *err);
void sl_study_part3_free(sl_study_part3 *p);

/* The largest x of a grid point where min(FS x ASCE best, cap) < NLTHA
 * design; NAN when none. */
double sl_study_fs_limit(const sl_study_spectra *sp, double fs);

/* ---- Part 4 ---------------------------------------------------------- */
typedef struct sl_study_part4 {
    sl_study_spectra *group[SL_STUDY_NGROUPS];
    size_t below[SL_STUDY_NGROUPS], defined[SL_STUDY_NGROUPS]; /* ASCE best < NLTHA mean */
    double xb_lo[SL_STUDY_NGROUPS], xb_hi[SL_STUDY_NGROUPS];   /* x range of those */
    double frac_best[SL_STUDY_NGROUPS]; /* below / defined (NAN when none defined) */
    double cross[SL_STUDY_NGROUPS];     /* crossover x (NAN: none) */
} sl_study_part4;

sl_status sl_study_part4_run(const char *records, sl_study_part4 *p,
                             void (*progress)(void *, const char *), void *ctx, sl_error *err);
void sl_study_part4_free(sl_study_part4 *p);

/* ---- Part 5: where the crossover comes from --------------------------- */
/* One change at a time from part 3's setting at SL_STUDY_P5_PGA_G, the
 * crossover of the seven without one record at a time, and the crossover of
 * SL_STUDY_P5_NDRAWS random seven-record draws (seed SL_STUDY_P5_SEED) from
 * the records of part 4's groups, each matched to RG 1.60 as in part 3. */
#define SL_STUDY_P5_PGA_G 0.4
#define SL_STUDY_P5_NDRAWS 12
#define SL_STUDY_P5_SEED 5u
#define SL_STUDY_P5_FLAT_X 0.2 /* the ASCE level is read over x < this */
enum {
    SL_STUDY_P5_BASE = 0, SL_STUDY_P5_NO_HP, SL_STUDY_P5_AIM1, SL_STUDY_P5_NO_V,
    SL_STUDY_P5_SCALE, SL_STUDY_P5_PLASTIC, SL_STUDY_P5_NO_CAP, SL_STUDY_P5_CAP_H1,
    SL_STUDY_P5_NCHANGES
};
extern const char *const sl_study_p5_change_names[SL_STUDY_P5_NCHANGES];

typedef struct sl_study_part5 {
    double cross[SL_STUDY_P5_NCHANGES];   /* crossover x per change (NAN: none) */
    double asce_lo_m, asce_hi_m;          /* ASCE best mean over x < SL_STUDY_P5_FLAT_X */
    double ratio_at_cross;                /* NLTHA mean / ASCE best mean there (base) */
    double loo[SL_STUDY_NGROUND];         /* without record i */
    double loo_lo, loo_hi;
    size_t n_pool;                        /* records matched for the draws */
    double draw[SL_STUDY_P5_NDRAWS];      /* crossover of each draw (NAN: none) */
    size_t draws_none;
    size_t draws_cons;                    /* of those without: ASCE conservative at the lowest x */
    double draw_lo, draw_hi;              /* over the draws with one */
} sl_study_part5;

/* p3: part 3 run (its matched sets). */
sl_status sl_study_part5_run(const char *records, const sl_study_part3 *p3, sl_study_part5 *p,
                             void (*progress)(void *, const char *), void *ctx, sl_error *err);

#endif
