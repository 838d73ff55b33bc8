/*
 * study.h - the pieces of the source study's evaluation (`seislide study`,
 * docs/validation.md) that are more than one call of another module:
 *
 *  - modifying a recorded set to match Regulatory Guide 1.60 (synth.h,
 *    record matching: the record's Fourier phases kept);
 *  - the sliding spectra of a group of sets: NLTHA peak vector displacement
 *    per set (slide.h), the ASCE/SEI 43-05 best estimate per set on the set's
 *    own 10 %-damped spectra (asce.h), both averaged over the group, and the
 *    design spectra, cap and crossover (design.h).
 *
 * Group averages (the source study: "averaged over a set"):
 *     NLTHA best estimate  m(mu)  = (1/N) sum_s peak_s(mu)
 *     ASCE best estimate   d(mu)  = (1/N) sum_s delta_s(mu)   (NAN if any set
 *                                   has no answer, e.g. no crossing)
 *     x                    = mu g / PGA, PGA = (1/N) sum_s PGA_h,s
 * with PGA_h,s the larger horizontal peak of set s; the design rows follow
 * design.h (NLTHA 3.0 x m, ASCE 2.0 x d, cap 1.5 x mean 100-40 PGD).
 *
 * Units: SI (m, s, m/s^2). Memory: every *_free pairs with its producer.
 */
#ifndef SL_STUDY_H
#define SL_STUDY_H

#include <stddef.h>

#include "method/design.h"
#include "io/motion.h"
#include "slide/slide.h"
#include "core/status.h"
#include "synth/synth.h"

/* A record set of the study: its folder under the records folder, what it
 * stands for, and why it is there (a stand-in's reason, or the basis of its
 * group membership). */
typedef struct sl_study_entry {
    const char *dir, *name, *why;
} sl_study_entry;

typedef struct sl_study_group {
    const char *name;  /* e.g. "near-field soil" */
    const char *tag;   /* file-name tag, e.g. "nfsoil" */
    const sl_study_entry *e;
    size_t n;
} sl_study_group;

/* The study's seven-record ground set (docs/validation.md), with the stand-in
 * for each record the collection lacks in three components. */
#define SL_STUDY_NGROUND 7
extern const sl_study_group sl_study_ground;

/* Real three-component sets grouped like the study's four PEER sets:
 * near-field soil, far-field soil, near-field rock, pulse-like. */
#define SL_STUDY_NGROUPS 4
extern const sl_study_group sl_study_groups[SL_STUDY_NGROUPS];

/* Modify a recorded set (H1, H2 and V; e.g. from sl_set_read_dir(),
 * io/setdir.h) to match the RG 1.60 spectra (horizontal for H1 and
 * H2, vertical for V) at damping zeta and PGA pga_ms2, with the default
 * acceptance checks of synth.h: the records are resampled to the largest
 * step dt/k <= 0.01 s (linear interpolation, exact for their
 * piecewise-linear reading) and zero-extended to at least the minimum
 * duration (20 s). out is filled as by sl_synth_match_set(). Returns SL_OK,
 * SL_ENOCONV (out complete, some check failed: see out->pass), or an error
 * (out cleared). */
sl_status sl_study_match_rg160(const sl_set *rec, double zeta, double pga_ms2,
                               sl_synth_set *out, sl_error *err);

/* As sl_study_match_rg160 with the synthesis parameters p (e.g. without
 * the high-pass, hp_frac = 0, or another aim). */
sl_status sl_study_match_rg160_p(const sl_set *rec, double zeta, double pga_ms2,
                                 const sl_synth_params *p, sl_synth_set *out, sl_error *err);

/* Sliding spectra of a group of sets. */
typedef struct sl_study_spectra {
    size_t n_sets, n_mu;
    double *mu;            /* n_mu friction values (copy) */
    double *peak_m;        /* peak_m[s * n_mu + k]: NLTHA peak |u| of set s at mu[k] */
    double *asce_set_m;    /* asce_set_m[s * n_mu + k]: ASCE best estimate of set s */
    double *nltha_mean_m;  /* n_mu: mean of peak_m over the sets */
    double *asce_mean_m;   /* n_mu: mean of asce_set_m (NAN if any is NAN) */
    double *pgd_m;         /* n_sets: 100-40 peak displacement of each set */
    double pga_ms2;        /* mean larger-horizontal PGA of the sets */
    sl_design *design;     /* design spectra and crossover, x = mu g / pga_ms2 */
} sl_study_spectra;

/* Compute the sliding spectra of n_sets checked sets (each with H1, H2 and
 * V) at n_mu increasing friction values with the engine options `so` (NULL =
 * defaults). The ASCE method takes each set's 10 %-damped PSA of H1 and H2
 * on the default grid (0.1-50 Hz, 100 per decade), A_v = the set's vertical
 * peak, ZPA_h = its larger horizontal peak. Returns NULL and fills err on
 * failure. Free with sl_study_spectra_free(). */
sl_study_spectra *sl_study_spectra_compute(const sl_set *sets, size_t n_sets, const double *mu,
                                           size_t n_mu, const sl_slide_opts *so, sl_error *err);

void sl_study_spectra_free(sl_study_spectra *s);

#endif
