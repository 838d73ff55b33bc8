/*
 * synth_internal.h - library-internal parts of the spectrum-compatible
 * motion synthesis (callers use synth.h): the plan and motion structures and
 * the steps shared by the stage files
 *     synth.c             parameters, targets, the plan (FFT length, bins,
 *                         envelope, taper, baseline shapes, FFTW plans)
 *     synth_start.c       start motions: random wave packets (eq. 1), the
 *                         target on the grid, the high-pass, the first gain
 *     synth_iterate.c     the correction iteration (eq. 2-3), coarse phase
 *     synth_admissible.c  admissible motion: taper, soft peak compression
 *                         (eq. C2), baseline
 *     synth_sharp.c       sharp floor targets: crest reservation (eq. S2),
 *                         mode sweep start (eq. S1)
 *     synth_check.c       the SRP 3.7.1 checks of a motion, other dampings
 *     synth_record.c      records: start from a record, resampling
 *     synth_sets.c        sets in parallel with retries, record matching
 *                         sets, AT2 output
 * Method and equations: synth.h and docs/synthesis.md 3.
 */
#ifndef SL_SYNTH_INTERNAL_H
#define SL_SYNTH_INTERNAL_H

#include <fftw3.h>
#include <math.h>
#include <gsl/gsl_rng.h>

#include "synth/synth.h"

/* Coarse phase: the iteration first computes and checks the spectrum at
 * every SYNTH_COARSE_STRIDE-th grid point (33 per decade by default) on
 * SYNTH_COARSE_SPP sub-steps per period (sampled-peak error <= 1 - cos(pi/6)
 * = 13 %, less on average), with a margin SYNTH_COARSE_MARGIN inside the
 * band; only the final iterations compute every point at full accuracy
 * (20 sub-steps per period). docs/synthesis.md 3.3. */
#define SYNTH_COARSE_STRIDE 3
#define SYNTH_COARSE_SPP 6.0
/* Multirate ratio of the coarse phase's spectrum (spectrum.h eq. M1): each
 * oscillator at f runs at the lowest rate fs/2^l >= SYNTH_COARSE_RATIO f.
 * Synthetic motions only; records keep the single-rate coarse spectrum. */
#define SYNTH_COARSE_RATIO 20.0
/* Over-relaxation of the correction: X_k *= r^SYNTH_RELAX (1.6: 10 iterations
 * per component against 16 at 1.0, RG 1.60, 12 sets). */
#define SYNTH_RELAX 1.6
/* Iterations without improvement after which an attempt is given up. */
#define SYNTH_STALL 8u
#define SYNTH_COARSE_MARGIN 0.02
/* Smallest motion handled, samples. */
#define SYNTH_MIN_N 16
/* Largest FFT length accepted (a guard against absurd options). */
#define SYNTH_MAX_NFFT ((size_t)1 << 28)
/* A target is rigid at its end when its SA at the last frequency is within
 * this factor of its ZPA (set_target; compress_peaks eq. C2). */
#define SYNTH_RIGID_RATIO 1.1
/* Sharp floor targets (synth_sharp.c, docs/synthesis.md 4 "Limit: very
 * sharp floors"), by the largest SA/ZPA over the checked range. Above
 * SYNTH_CREST_AMP, where the peak count stops being a check (synth.h), every
 * iterate of a synthetic motion gets the crest reservation (eq. S2; the
 * example floors 02-04 in floors/: 4.24-5.23); above SYNTH_SHARP_AMP its
 * start also gets the mode sweep (eq. S1; templates/floor.ini: 7.05). */
#define SYNTH_CREST_AMP SL_SYNTH_PEAKS_MAX_AMP
#define SYNTH_SHARP_AMP 6.0
/* m->sharp: which of the two. */
#define SYNTH_SHARP_CREST 1
#define SYNTH_SHARP_SWEEP 2

struct sl_synth {
    size_t n;            /* motion samples */
    double dt;           /* s */
    size_t nfft;         /* N, even */
    size_t nbin;         /* N/2 + 1 */
    double df;           /* 1/(N dt), Hz */
    sl_synth_params p;
    double *grid;        /* check grid, Hz */
    size_t ngrid;
    size_t *bin_j;       /* bin k: r(f_k) = r_j^(1 - w) r_{j+1}^w ... */
    double *bin_w;
    size_t *bin_ja;      /* ... or, when grid points [ja, jb) fall in the */
    size_t *bin_jb;      /* bin's cell f_k +- df/2, the mean of their ln r */
    double *env;         /* n: envelope */
    double *taper;       /* ntaper: half-cosine end taper, 0 at the end sample */
    size_t ntaper;
    double *bl[2];       /* n: baseline shapes (t/T)(1 - t/T) (t/T)^i */
    double bl_inv[2][2]; /* inverse of the end-value matrix of the shapes */
    fftw_plan r2c, c2r;  /* on fftw_malloc'd arrays of N reals, N/2 + 1 complexes */
    double *bin_fade;    /* nbin: sl_synth_edge_fade of every bin for the whole
                          * grid checked (the common case; no log2 per bin) */
};

struct sl_synth_motion {
    const sl_synth *s;
    int ready;             /* a set_* succeeded */
    double zpa;            /* m/s^2 */
    double damping;
    const sl_spectrum *tspec; /* the target spectrum (borrowed) */
    double fc_hz;          /* compression: content above this only (compress_peaks) */
    double knee;           /* compression knee: SL_SYNTH_KNEE, records SL_SYNTH_KNEE_RECORD */
    double level;          /* compression level / ZPA (peak_level()) */
    int record;            /* started from a record: dead-band correction */
    size_t j_lo, j_hi;     /* checked grid points [j_lo, j_hi) */
    int rigid_end;         /* the target's end SA within SYNTH_RIGID_RATIO of its ZPA */
    int sharp;             /* SYNTH_SHARP_CREST | SYNTH_SHARP_SWEEP or 0 (synth_sharp.c) */
    unsigned iter;         /* iterations since set_* */
    unsigned attempt;
    double *tgt;           /* grid: target (NAN outside) */
    double *psa;           /* grid: spectrum of the current iterate */
    double *lnr;           /* grid: ln of the correction ratio */
    double *hp;            /* nbin: high-pass magnitude H(f_k) (set_target) */
    fftw_complex *cwork;   /* nbin */
    double *rwork;         /* N */
    double *acc;           /* n: current iterate */
    double *best_acc;      /* n: best iterate */
    double *best_psa;      /* grid */
    double best_score;     /* violation of the best iterate (0 = passes) */
    int coarse;            /* coarse phase: spectrum at every stride-th point */
    size_t stride;         /* SYNTH_COARSE_STRIDE, on SYNTH_COARSE_SPP sub-steps */
    unsigned best_iter;
    /* Spectrum plans of the checked range (coefficients made once, remade
     * when the range or damping changes): full accuracy, and the coarse
     * phase's points (multirate, SYNTH_COARSE_RATIO). */
    sl_spectrum_plan *plan_full, *plan_coarse;
    size_t plan_lo, plan_hi;
    double plan_zeta;
    int plan_record;       /* records: coarse phase without multirate (its worst
                            * error, 10 % at 0.1 Hz on records, steers a
                            * dead-band match astray: docs/synthesis.md 3.2) */
    size_t *cidx;          /* ngrid: grid index of each coarse point */
    size_t ncoarse;
    double *cval;          /* ngrid: coarse spectrum values */
};

/* Spectral checks of psa against the target over the checked range. */
typedef struct sl_synth_spec_check {
    double min_ratio, f_min, max_ratio, f_max;
    size_t run, n_below;
} sl_synth_spec_check;

/* The fade of the correction outside the checked range [f_lo, f_hi]: 1
 * inside, falling linearly in log2 f to 0 at SL_SYNTH_EDGE_OCTAVES outside
 * (sl_synth_iterate: ln r(f_k) is multiplied by it). */
static inline double sl_synth_edge_fade(double f, double f_lo, double f_hi)
{
    double oct = f < f_lo ? log2(f_lo / f) : f > f_hi ? log2(f / f_hi) : 0.0;
    return oct >= SL_SYNTH_EDGE_OCTAVES ? 0.0 : 1.0 - oct / SL_SYNTH_EDGE_OCTAVES;
}

/* ---- Steps shared by the stage files (library-internal) ---- */

/* The target's interpolated spectrum on the grid, the checked range, the
 * rigid end and the high-pass magnitude (synth_start.c). */
sl_status sl_synth_set_target(sl_synth_motion *m, const sl_synth_target *t, sl_error *err);
/* A target's spectrum and ZPA are usable (synth.c). */
sl_status sl_synth_check_target(const sl_synth_target *t, sl_error *err);
/* acc[j] += amp exp(-x^2/(2 sg^2)) cos(2 pi f x + phi), x = j dt - tk,
 * j0 <= j <= j1: one wavelet of eq. 1 by recurrences (synth_start.c). */
void sl_synth_add_wavelet(double *acc, size_t j0, size_t j1, double dt, double tk, double amp,
                          double sg, double f, double phi);
/* Start from m->acc at any level: high-pass, one gain to aim x T, then
 * iteration 0 (synth_start.c). */
sl_status sl_synth_start(sl_synth_motion *m, sl_error *err);
/* End values (v(T), d(T)) from rest, exact piecewise-linear integration
 * (synth_admissible.c). */
void sl_synth_end_values(const double *a, size_t n, double dt, double *v_end, double *d_end);
/* Soft peak compression / expansion of m->acc (eq. C2; synth_admissible.c). */
size_t sl_synth_compress_peaks(sl_synth_motion *m, double level, double knee);
/* Taper, compression, baseline, spectrum, keep the best (synth_admissible.c). */
sl_status sl_synth_finish(sl_synth_motion *m, sl_error *err);
/* Spectrum of m->acc into m->psa, full or coarse (synth_iterate.c). */
sl_status sl_synth_spectrum_of_acc(sl_synth_motion *m, sl_error *err);
/* Spectral checks of psa over the checked range (synth_iterate.c). */
void sl_synth_spectral_check(const sl_synth_motion *m, const double *psa,
                             sl_synth_spec_check *c);
/* Violation of the spectral limits, 0 when all hold (synth_iterate.c). */
double sl_synth_violation(const sl_synth_params *p, const sl_synth_spec_check *c,
                          size_t npoints);
/* sl_synth_check_motion with the App. B PSD computed only when with_psd
 * (else ok_psd = 1 and the PSD fields NAN; synth_check.c). */
void sl_synth_check_motion_psd(const sl_synth_motion *m, sl_synth_check *out, int with_psd);
/* The App. B PSD fields of out for acc against the target spectrum ts
 * (synth_check.c). */
void sl_synth_check_psd(const double *acc, size_t n, double dt, const sl_spectrum *ts,
                        double psd_frac, sl_synth_check *out);
/* SYNTH_SHARP_CREST when the target's largest SA/ZPA on the checked range
 * exceeds SYNTH_CREST_AMP, | SYNTH_SHARP_SWEEP when it exceeds
 * SYNTH_SHARP_AMP, else 0 (synth_sharp.c). */
int sl_synth_sharp_target(const sl_synth_motion *m);
/* a_low of m->acc into m->rwork[0, n): its DFT bins below m->fc_hz, the
 * long-period part the peak compression (eq. C2) and the crest reservation
 * (eq. S2) leave untouched (synth_admissible.c). */
void sl_synth_low_part(sl_synth_motion *m);
/* Sharp targets: the mode sweep added to the start (eq. S1; SA/ZPA above
 * SYNTH_SHARP_AMP) and the crest reservation of an iterate (eq. S2; above
 * SYNTH_CREST_AMP), synth_sharp.c. */
void sl_synth_add_mode_sweep(sl_synth_motion *m, gsl_rng *rng);
size_t sl_synth_reserve_crest(sl_synth_motion *m);
/* Leave the coarse phase: the best iterate at full accuracy (synth_iterate.c). */
sl_status sl_synth_end_coarse(sl_synth_motion *m, sl_error *err);

#endif
