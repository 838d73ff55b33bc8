/*
 * study.c - recorded sets, RG 1.60 matching and group sliding spectra for
 * the study reproduction (study.h, docs/validation.md).
 */
#include "study/study.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "method/asce.h"
#include "method/asce_input.h"
#include "signal/rg160.h"
#include "signal/spectrum.h"

/* ------------------------------------------------------------------ */
/* The record sets of the study                                        */
/* ------------------------------------------------------------------ */

/* A record set of the study and why it is there. */
/* Part 3: the study's seven-record ground set (docs/validation.md), with the
 * stand-in for each record the collection lacks in three components. */
static const sl_study_entry ground_set[] = {
    {"RSN20_NCALIF.FH_H-FRN", "Ferndale 1954 (Ferndale City Hall)", "the study's record"},
    {"RSN77_SFERN_PUL", "Pacoima Dam 1971 (upper left abutment)", "the study's record"},
    {"RSN31_PARKF_C08", "Cholame-Shandon #5 1966 -> Cholame-Shandon #8, 1966",
     "stand-in: same event and array; the collection has #5 in one component only"},
    {"RSN777_LOMAP_HCH", "Hollister 1961 -> Hollister City Hall, Loma Prieta 1989",
     "stand-in: the 1961 records were made at this station; 1961 is not in the collection"},
    {"RSN57_SFERN_ORR", "Taft 1952 -> Castaic Old Ridge Route, San Fernando 1971",
     "stand-in: Taft is in the collection in one component only; Castaic is a "
     "moderate-distance record of a California reverse-fault event of the same era"},
    {"RSN776_LOMAP_HSP", "Ferndale 1941 (1) -> Hollister South & Pine, Loma Prieta 1989",
     "stand-in: 1941 is not in the collection; a northern-California soil record at "
     "moderate distance, like Ferndale's"},
    {"RSN162_IMPVALL.H_H-CXO", "Ferndale 1941 (2) -> Calexico Fire Station, Imperial Valley 1979",
     "stand-in: as above; a soil record of a moderate (M6.5) event"},
};
_Static_assert(sizeof ground_set / sizeof ground_set[0] == SL_STUDY_NGROUND,
               "SL_STUDY_NGROUND must count ground_set");
const sl_study_group sl_study_ground = {"ground set", "ground", ground_set,
                                       sizeof ground_set / sizeof ground_set[0]};

/* Part 4: real three-component sets grouped like the study's four PEER sets.
 * The collection has no distance, site or pulse metadata; the classification is
 * ours, from published sets (named per record). */
static const sl_study_entry group_nf_soil[] = {
    {"RSN6_IMPVALL.I_I-ELC", "El Centro #9, Imperial Valley 1940", "NGA-West2: Rrup ~6 km, soil"},
    {"RSN187_IMPVALL.H_H-PTS", "Parachute Test Site, Imperial Valley 1979", "Rrup ~13 km, soil"},
    {"RSN458_MORGAN_G04", "Gilroy Array #4, Morgan Hill 1984", "Rrup ~12 km, soil"},
    {"RSN768_LOMAP_G04", "Gilroy Array #4, Loma Prieta 1989", "Rrup ~14 km, soil"},
    {"RSN764_LOMAP_GOF", "Gilroy Historic Bldg., Loma Prieta 1989", "Rrup ~11 km, soil"},
};
static const sl_study_entry group_ff_soil[] = {
    {"RSN953_NORTHR_MUL", "Beverly Hills Mulholland, Northridge 1994", "FEMA P695 far-field set"},
    {"RSN960_NORTHR_LOS", "Canyon Country W Lost Canyon, Northridge 1994", "FEMA P695 far-field set"},
    {"RSN1602_DUZCE_BOL", "Bolu, Duzce 1999", "FEMA P695 far-field set"},
    {"RSN174_IMPVALL.H_H-E11", "El Centro Array #11, Imperial Valley 1979", "FEMA P695 far-field set"},
    {"RSN1116_KOBE_SHI", "Shin-Osaka, Kobe 1995", "FEMA P695 far-field set"},
    {"RSN1158_KOCAELI_DZC", "Duzce, Kocaeli 1999", "FEMA P695 far-field set"},
    {"RSN848_LANDERS_CLW", "Coolwater, Landers 1992", "FEMA P695 far-field set"},
    {"RSN752_LOMAP_CAP", "Capitola, Loma Prieta 1989", "FEMA P695 far-field set"},
};
static const sl_study_entry group_nf_rock[] = {
    {"RSN753_LOMAP_CLS", "Corralitos, Loma Prieta 1989", "FEMA P695 near-field (no pulse); Rrup ~4 km, Vs30 ~460 m/s"},
    {"RSN454_MORGAN_GIL", "Gilroy Gavilan College, Morgan Hill 1984", "rock station (Vs30 ~730 m/s), Rrup ~15 km"},
    {"RSN1111_KOBE_NIS", "Nishi-Akashi, Kobe 1995", "Rrup ~7 km, Vs30 ~610 m/s"},
    {"RSN1787_HECTOR_HEC", "Hector, Hector Mine 1999", "Rrup ~12 km, Vs30 ~730 m/s"},
    {"RSN1_HELENA.A_A-HMC", "Carroll College, Helena 1935", "rock station a few km from the source"},
};
static const sl_study_entry group_pulse[] = {
    {"RSN1063_NORTHR_RRS", "Rinaldi Receiving Station, Northridge 1994", "Baker (2007) pulse list"},
    {"RSN77_SFERN_PUL", "Pacoima Dam, San Fernando 1971", "Baker (2007) pulse list"},
    {"RSN879_LANDERS_LCN", "Lucerne, Landers 1992", "Baker (2007) pulse list"},
    {"RSN161_IMPVALL.H_H-BRA", "Brawley Airport, Imperial Valley 1979", "Baker (2007) pulse list"},
    {"RSN292_ITALY_A-STU", "Sturno, Irpinia 1980", "Baker (2007) pulse list; FEMA P695 near-field pulse set"},
};
#define GROUP(name, tag, arr) {name, tag, arr, sizeof arr / sizeof arr[0]}
const sl_study_group sl_study_groups[SL_STUDY_NGROUPS] = {
    GROUP("near-field soil", "nfsoil", group_nf_soil),
    GROUP("far-field soil", "ffsoil", group_ff_soil),
    GROUP("near-field rock", "nfrock", group_nf_rock),
    GROUP("pulse-like", "pulse", group_pulse),
};

/* A step within this relative slack of another is the same step. */
#define STEP_SLACK 1e-9

sl_status sl_study_match_rg160(const sl_set *rec, double zeta, double pga_ms2,
                               sl_synth_set *out, sl_error *err)
{
    sl_synth_params p;
    sl_synth_params_default(&p);
    return sl_study_match_rg160_p(rec, zeta, pga_ms2, &p, out, err);
}

sl_status sl_study_match_rg160_p(const sl_set *rec, double zeta, double pga_ms2,
                                 const sl_synth_params *params, sl_synth_set *out, sl_error *err)
{
    memset(out, 0, sizeof *out);
    if (!rec || !rec->h1 || !rec->h2 || !rec->v)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "matching needs three components");
    sl_synth_params p = *params;
    const sl_motion *comp[SL_SYNTH_NCOMP] = {rec->h1, rec->h2, rec->v};
    double dt = sl_synth_match_dt(comp[0]->dt_s); /* SRP 3.7.1: Nyquist >= 50 Hz */
    sl_motion *rs[SL_SYNTH_NCOMP] = {NULL, NULL, NULL};
    sl_spectrum *spec[SL_SYNTH_NCOMP] = {NULL, NULL, NULL};
    sl_synth_target tgt[SL_SYNTH_NCOMP];
    sl_synth *plan = NULL;
    sl_status st = SL_OK;
    size_t n = 0;
    for (int c = 0; c < SL_SYNTH_NCOMP && st == SL_OK; c++) {
        if (!(rs[c] = sl_synth_resample_motion(comp[c], dt)))
            st = sl_error_set(err, SL_ENOMEM, comp[c]->path, 0, "cannot resample to dt %g s",
                              dt);
        else if (rs[c]->n > n)
            n = rs[c]->n;
    }
    size_t n_min = (size_t)ceil(p.min_duration_s / dt * (1 - STEP_SLACK)) + 1;
    if (n < n_min)
        n = n_min;
    if (st == SL_OK)
        st = sl_synth_targets_rg160(pga_ms2, zeta, &p, spec, tgt, err);
    if (st == SL_OK && !(plan = sl_synth_alloc(n, dt, &p, err)))
        st = err ? err->code : SL_ENOMEM;
    if (st == SL_OK) {
        const sl_motion *const r3[SL_SYNTH_NCOMP] = {rs[0], rs[1], rs[2]};
        st = sl_synth_match_set(plan, tgt, r3, out, err);
    }
    sl_synth_free(plan);
    for (int c = 0; c < SL_SYNTH_NCOMP; c++) {
        sl_motion_free(rs[c]);
        sl_spectrum_free(spec[c]);
    }
    return st;
}

void sl_study_spectra_free(sl_study_spectra *s)
{
    if (!s)
        return;
    free(s->mu);
    free(s->peak_m);
    free(s->asce_set_m);
    free(s->nltha_mean_m);
    free(s->asce_mean_m);
    free(s->pgd_m);
    sl_design_free(s->design);
    free(s);
}

/* ASCE best estimates of one set at every mu, into best[0..n_mu-1]: the
 * set's own 10 %-damped spectra (asce_input.h), no cap (the group's cap is
 * applied in design.c). */
static sl_status asce_of_set(const sl_set *set, const double *mu, size_t n_mu, double *best,
                             sl_error *err)
{
    sl_asce_source src;
    sl_asce *a = NULL;
    sl_status st = sl_asce_input_from_set(set, &src, err);
    if (st == SL_OK) {
        src.in.pgd_m = NAN;
        if (!(a = sl_asce_alloc(&src.in, err)))
            st = err ? err->code : SL_ENOMEM;
    }
    for (size_t k = 0; k < n_mu && st == SL_OK; k++) {
        sl_asce_result r;
        st = sl_asce_eval(a, mu[k], &r, err);
        best[k] = r.delta_best_m;
    }
    sl_asce_free(a);
    sl_asce_source_free(&src);
    return st;
}

sl_study_spectra *sl_study_spectra_compute(const sl_set *sets, size_t n_sets, const double *mu,
                                           size_t n_mu, const sl_slide_opts *so, sl_error *err)
{
    if (!sets || n_sets == 0 || !mu || n_mu == 0) {
        sl_error_set(err, SL_EINVAL, NULL, 0, "study spectra: no sets or no friction values");
        return NULL;
    }
    for (size_t s = 0; s < n_sets; s++)
        if (!sets[s].h1 || !sets[s].h2 || !sets[s].v) {
            sl_error_set(err, SL_EINVAL, sets[s].h1 ? sets[s].h1->path : NULL, 0,
                         "study spectra: set %zu lacks a component (H1, H2 and V needed)", s);
            return NULL;
        }
    sl_study_spectra *r = calloc(1, sizeof *r);
    sl_slide_result *res = calloc(n_sets * n_mu, sizeof *res);
    int *noslide = calloc(n_mu, sizeof *noslide);
    if (r) {
        r->n_sets = n_sets;
        r->n_mu = n_mu;
        r->mu = malloc(n_mu * sizeof *r->mu);
        r->peak_m = calloc(n_sets * n_mu, sizeof *r->peak_m);
        r->asce_set_m = calloc(n_sets * n_mu, sizeof *r->asce_set_m);
        r->nltha_mean_m = calloc(n_mu, sizeof *r->nltha_mean_m);
        r->asce_mean_m = calloc(n_mu, sizeof *r->asce_mean_m);
        r->pgd_m = calloc(n_sets, sizeof *r->pgd_m);
    }
    if (!r || !res || !noslide || !r->mu || !r->peak_m || !r->asce_set_m ||
        !r->nltha_mean_m || !r->asce_mean_m || !r->pgd_m) {
        sl_error_set(err, SL_ENOMEM, NULL, 0, "out of memory");
        goto fail;
    }
    memcpy(r->mu, mu, n_mu * sizeof *mu);

    /* NLTHA of every set at every mu (OpenMP over sets) */
    sl_slide_opts def;
    sl_slide_opts_default(&def);
    if (sl_slide_batch(sets, n_sets, mu, n_mu, so ? so : &def, res, err))
        goto fail;
    for (size_t k = 0; k < n_mu; k++)
        noslide[k] = 1;
    for (size_t s = 0; s < n_sets; s++) {
        r->pgd_m[s] = sl_set_pgd_100_40(&sets[s]);
        r->pga_ms2 += sl_set_pga_h(&sets[s]) / (double)n_sets;
        for (size_t k = 0; k < n_mu; k++) {
            const sl_slide_result *x = &res[s * n_mu + k];
            r->peak_m[s * n_mu + k] = x->peak_m;
            r->nltha_mean_m[k] += x->peak_m / (double)n_sets;
            noslide[k] &= (x->flags & SL_SLIDE_SKIPPED) != 0;
        }
    }

    /* ASCE per set, then the group mean */
    for (size_t s = 0; s < n_sets; s++)
        if (asce_of_set(&sets[s], mu, n_mu, r->asce_set_m + s * n_mu, err))
            goto fail;
    for (size_t k = 0; k < n_mu; k++)
        for (size_t s = 0; s < n_sets; s++)
            r->asce_mean_m[k] += r->asce_set_m[s * n_mu + k] / (double)n_sets;

    sl_design_input di;
    sl_design_input_default(&di);
    di.n_mu = n_mu;
    di.n_sets = n_sets;
    di.mu = mu;
    di.peak_m = r->peak_m;
    di.no_slide = noslide;
    di.asce_best_m = r->asce_mean_m;
    di.pgd_m = r->pgd_m;
    di.zpa_h_ms2 = r->pga_ms2;
    if (!(r->design = sl_design_compute(&di, err)))
        goto fail;
    free(res);
    free(noslide);
    return r;
fail:
    free(res);
    free(noslide);
    sl_study_spectra_free(r);
    return NULL;
}
