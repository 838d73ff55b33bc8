/*
 * bench.h - speed against error of the engine, the reference models, the
 * response spectra, the synthesis and the main job (`seislide bench`,
 * docs/performance.md), as measurements; the command formats them.
 *
 * Motions: the three-component records RSN1063_NORTHR_RRS, RSN6_IMPVALL.I_I-ELC
 * and RSN77_SFERN_PUL under shared/records (io/setdir.h), or, when none is
 * there, three deterministic broadband stand-ins (sums of sines under an
 * envelope). Errors of the peak vector sliding displacement are against
 * the engine's 2-D integrator at SL_BENCH_REF_SUBSTEPS sub-steps, whose
 * own convergence is measured against SL_BENCH_REF_CHECK_SUBSTEPS.
 * Relative errors count where the reference peak is at least
 * SL_BENCH_PEAK_FLOOR_M. Timing: best of `repeat` runs, one thread for the
 * engine and spectra (OpenMP parallelism is over motions and is not what
 * is measured); the main job runs on all threads.
 *
 * Units: SI; times in seconds unless the name says otherwise. Memory:
 * sl_bench_run() fills an sl_bench the caller frees with sl_bench_free().
 */
#ifndef SL_BENCH_H
#define SL_BENCH_H

#include <stddef.h>

#include "core/standards.h"
#include "io/motion.h"
#include "slide/slide.h"

#define SL_BENCH_PEAK_FLOOR_M 1e-3    /* below a millimetre a table rounds to zero */
#define SL_BENCH_REF_SUBSTEPS 1024u
#define SL_BENCH_REF_CHECK_SUBSTEPS 2048u
#define SL_BENCH_MAX_SETS 3
#define SL_BENCH_NSUB 7               /* engine sub-steps 1, 2, ..., 64 */
#define SL_BENCH_N_MODEL_MU 4
extern const double sl_bench_model_mu[SL_BENCH_N_MODEL_MU]; /* 0.05, 0.1, 0.2, 0.4 */
#define SL_BENCH_MAX_SETTINGS 64
#define SL_BENCH_NTARGETS 3
extern const double sl_bench_targets[SL_BENCH_NTARGETS];    /* 1e-2, 1e-3, 1e-4 */
#define SL_BENCH_NSPP 5
extern const double sl_bench_spp[SL_BENCH_NSPP];            /* steps per period 5..80 */
#define SL_BENCH_SPP_REF 640.0
#define SL_BENCH_SPEC_DAMPING 0.05
#define SL_BENCH_SYNTH_PGA_G 0.3
#define SL_BENCH_SYNTH_SEEDS 10
#define SL_BENCH_NFLOORS 4
extern const char *const sl_bench_floors[SL_BENCH_NFLOORS]; /* floors/0*.ini */
#define SL_BENCH_LIMIT_SUBSTEPS 16u

typedef struct sl_bench_opts {
    const char *shared;    /* folder holding records/ */
    unsigned long repeat;  /* best of this many runs (>= 1) */
    int quick;             /* skip the slowest reference-model settings */
    void (*progress)(void *ctx, const char *msg);
    void *ctx;
} sl_bench_opts;

/* 1. The engine over the default friction grid, per motion. */
typedef struct sl_bench_engine {
    double t1d_s;                    /* 1-D exact on H1, per run of the grid */
    double t_s[SL_BENCH_NSUB];       /* 2-D at 1..64 sub-steps */
    double rel[SL_BENCH_NSUB], abs_m[SL_BENCH_NSUB];
    double conv_rel, conv_abs_m;     /* reference against the check */
} sl_bench_engine;

/* 2. One model setting over all motions on sl_bench_model_mu. */
typedef struct sl_bench_setting {
    char model[16], label[48];       /* "engine" | "smooth" | "plastic" */
    sl_slide_opts o;
    double us_per, rel, abs_m;       /* mean us per (motion, mu); worst errors */
    int failed;                      /* a run failed (the solver gave up) */
} sl_bench_setting;

/* 7. The arithmetic limit against the engine, per motion. */
typedef struct sl_bench_limit {
    double per_s;        /* engine time per (sub-step, mu) */
    double share;        /* fraction of (sub-step, mu) pairs sliding */
    double per_slide_s;  /* engine time per sliding update, at most */
} sl_bench_limit;

/* Section 6: the fixed count the converged run is compared with (the former
 * default of `seislide run`). */
#define SL_BENCH_FIXED_SETS 7

typedef struct sl_bench {
    int n_sets;
    sl_set set[SL_BENCH_MAX_SETS];   /* owned */
    char name[SL_BENCH_MAX_SETS][64];
    double mean_n;                   /* mean samples per motion */
    sl_bench_engine engine[SL_BENCH_MAX_SETS];
    int n_settings;
    sl_bench_setting setting[SL_BENCH_MAX_SETTINGS];
    int pareto[SL_BENCH_NTARGETS][3]; /* fastest setting per model reaching the target, -1 */
    size_t spec_nf;                  /* frequencies of section 4 */
    double spec_ms[SL_BENCH_MAX_SETS][SL_BENCH_NSPP], spec_err[SL_BENCH_MAX_SETS][SL_BENCH_NSPP];
    int synth_ok;                    /* section 5 ran */
    char synth_error[256];
    int synth_passed;
    double synth_mean_s, synth_max_s, synth_lo, synth_hi, synth_corr;
    int threads;                     /* threads of the main job */
    int floor_found[SL_BENCH_NFLOORS];
    char floor_name[SL_BENCH_NFLOORS][128];
    /* per floor and setting (0: a fixed 7 sets, the former default; 1: converged, the
     * default): synthesis, NLTHA, statistics, ASCE + design, s; sets; stop reason */
    double floor_t[SL_BENCH_NFLOORS][2][4];
    size_t floor_sets[SL_BENCH_NFLOORS][2];
    int floor_stop[SL_BENCH_NFLOORS][2];
    size_t floor_skipped[SL_BENCH_NFLOORS];
    double limit_s;                  /* the arithmetic limit per update */
    sl_bench_limit limit[SL_BENCH_MAX_SETS];
} sl_bench;

/* Run every measurement. Returns NULL and fills err when a run that must
 * succeed (the engine, a spectrum) fails or memory runs out. */
sl_bench *sl_bench_run(const sl_bench_opts *o, sl_error *err);
void sl_bench_free(sl_bench *b);

#endif
