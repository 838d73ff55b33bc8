/*
 * test_physical_floors.c - synthesized floor motions slide like the physical
 * floor motions behind their spectrum (issue 12; docs/synthesis.md 10-12, docs/notes.md 3).
 *
 * Physical floor motions: real three-component records of ../shared/records
 * (study/physfloor.h: rule, scaled to a larger horizontal PGA of 0.3 g)
 * through the 3-storey building of study/building.h (H modes 3.0/8.4/12.1 Hz
 * and 4.2/11.8/17.0 Hz, V 14 Hz, 5 %). Their mean 2 %, 5 % and 10 % spectra
 * and mean PGA are written as a floor file (sl_pf_write_floor) and read back;
 * sets are synthesized for it (synth.h defaults: matched at 5 %); the same
 * NLTHA engine (sl_slide_batch) slides a block on the physical and on the
 * synthesized sets. The issue asks for the ratio of the mean peak sliding,
 * synthesized / physical, in [0.75, 1.33] at mu g/ZPA = 0.1 ... 0.9 on every
 * floor. MEASURED on 83 records (tools/physfloors.c, docs/synthesis.md 10),
 * the synthesized sets slid with each floor's own intensity scatter
 * (method/scatter.h (R4): 0.354-0.369 here): 0.81-0.95 at mu g/ZPA
 * 0.1-0.5, 0.89-0.98 at 0.7, 0.97-1.35 at 0.9 (SE 0.07-0.22), inside the
 * band or within 1 SE of it; without the intensity scatter 0.45-0.51 at 0.7
 * and 0.10-0.15 at 0.9. Every floor's sigma 0.10 fails this test.
 * This test, on 16 of those records, asserts: agreement with the full
 * comparison within 3 SE of its own ratio (+ 0.02), the band within
 * 2 SE where the full comparison meets it, broadened (+-15 %) spectra sliding
 * more than plain ones, the floor file's ZPA, the 2 % and 10 % tables against
 * the synthesized motions' own 2 % and 10 % spectra (set mean), the ratio's
 * SE (P1 of physfloor.h) and the record rule. Ground: synthesized RG 1.60
 * sets against the same records matched to RG 1.60 (sl_study_match_rg160),
 * both without intensity scatter (as in the full comparison), same checks;
 * and the synthesized ground sets slid the run's way (with the scatter)
 * never below the band.
 * Power: with 16 records and 8 sets the SE is 0.13-0.17 on the floors at mu
 * g/ZPA 0.1-0.5 (0.08-0.11 on the ground),
 * so only a change that moves the sliding by about 0.4-0.5 there fails
 * the agreement check; smaller changes (4-cycle packets: 0.05-0.14 in the
 * full comparison) need tools/physfloors.
 * SEISLIDE_TEST_VERBOSE prints every ratio with its SE.
 */
#include <omp.h>
#include <stdint.h>

#include "analysis.h"
#include "harness.h"
#include "io/floor.h"
#include "io/motion.h"
#include "io/setdir.h"
#include "signal/spectrum.h"
#include "slide/slide.h"
#include "study/building.h"
#include "study/physfloor.h"
#include "study/study.h"
#include "method/scatter.h"
#include "synth/synth.h"

static int verbose(void) { return getenv("SEISLIDE_TEST_VERBOSE") != NULL; }

/* Records: 16 three-component records of ../shared/records, 16 events on
 * 3 continents (the full comparison, tools/physfloors.c, uses every record
 * that passes the rule of study/physfloor.h: 83). */
static const char *const recs[] = {
    "RSN1063_NORTHR_RRS",      "RSN1111_KOBE_NIS",
    "RSN1158_KOCAELI_DZC",     "RSN1602_DUZCE_BOL",
    "RSN1787_HECTOR_HEC",      "RSN879_LANDERS_LCN",
    "RSN753_LOMAP_CLS",        "RSN174_IMPVALL.H_H-E11",
    "RSN292_ITALY_A-STU",      "RSN313_CORINTH_COR",
    "RSN322_COALINGA.H_H-CAK", "RSN458_MORGAN_G04",
    "RSN587_NEWZEAL_A-MAT",    "CWA_2022Chihshang_HWA004",
    "GEONET_2016Kaikoura_HSES", "CSMIP_2022Ferndale_89486_Fortuna"};
#define NREC (sizeof recs / sizeof recs[0])
#define NSYN 8    /* synthesized sets per floor */
#define NMU 5     /* mu g/ZPA = 0.1, 0.3, ..., 0.9 */
#define NF 136    /* spectrum grid: 0.1-50 Hz, 50 per decade */
#define PGA_G 0.3
#define LO 0.75  /* the band */
#define HI 1.33

/* The full comparison (tools/physfloors.c: 83 records, 48 synthesized sets
 * per case, seed 12; docs/synthesis.md 10): ratio synthesized / physical at
 * mu g/ZPA = 0.1 ... 0.9 per floor, and ground (synthesized RG 1.60 /
 * records matched to RG 1.60). This test's subset must agree with it within
 * 3 standard errors of its own ratio (P1 of study/physfloor.h) plus 0.02. */
static const double ref_floor[3][NMU] = {{0.81, 0.84, 0.87, 0.98, 1.35},
                                         {0.87, 0.86, 0.86, 0.89, 0.98},
                                         {0.88, 0.95, 0.91, 0.94, 0.97}};
static const double ref_ground[NMU] = {0.86, 0.89, 0.81, 0.76, 0.63};

static int read_recs(const char *shared, sl_set *g)
{
    sl_pf_rule rule;
    sl_pf_rule_default(&rule);
    int n = 0;
    for (size_t r = 0; r < NREC; r++) {
        char dir[1024];
        sl_error e;
        snprintf(dir, sizeof dir, "%s/records/%s", shared, recs[r]);
        if (sl_pf_read_record(dir, &rule, PGA_G * SL_G, &g[n], &e) == SL_OK) {
            CHECK_CLOSE(sl_set_pga_h(&g[n]), PGA_G * SL_G, 0, 1e-12);
            n++;
        } else {
            char buf[2200];
            fprintf(stderr, "  skipped: %s\n", sl_error_format(&e, buf, sizeof buf));
        }
    }
    return n;
}

/* Peak sliding pk[i * NMU + k] of sets i at mu[k]. */
static void slide_all(const sl_set *sets, size_t n, const double *mu, double *pk)
{
    sl_slide_opts so;
    sl_slide_opts_default(&so);
    sl_slide_result *res = calloc(n * NMU, sizeof *res);
    if (verbose()) {
        double th = 0, pg = 0, pgc = 0;
        size_t nth = 0; /* the threshold is infinite where the vertical lifts the block */
        for (size_t i = 0; i < n; i++) {
            double t = sl_slide_mu_threshold(&sets[i], &so);
            if (isfinite(t))
                th += t, nth++;
            pg += sl_set_pga_h(&sets[i]) / SL_G / (double)n;
            pgc += 0.5 * (sl_motion_pga(sets[i].h1) + sl_motion_pga(sets[i].h2)) / SL_G / (double)n;
        }
        fprintf(stderr,
                "    %zu sets: mean mu threshold %.3f (%zu finite), mean PGA_h %.3f g, mean comp "
                "PGA %.3f g\n",
                n, nth ? th / (double)nth : NAN, nth, pg, pgc);
    }
    sl_error e;
    CHECK(sl_slide_batch(sets, n, mu, NMU, &so, res, &e) == SL_OK, "%s", e.msg);
    for (size_t i = 0; i < n * NMU; i++)
        pk[i] = res[i].peak_m;
    free(res);
}

/* As slide_all, the way `seislide run` slides a floor's synthesized sets:
 * with the floor's intensity scatter sigma (method/scatter.h (R4), the
 * run's default), each set's expected peak over the intensity factor
 * (method/scatter.h (R3)). */
static void slide_run_way(const sl_set *sets, size_t n, const double *mu, double sigma,
                          double *pk)
{
    sl_error e;
    sl_slide_opts so;
    sl_slide_opts_default(&so);
    sl_scatter *sc = sl_scatter_alloc(sigma, mu, NMU, &e);
    CHECK(sc && sl_scatter_slide_batch(sc, sets, n, &so, pk, NULL, &e) == SL_OK, "%s", e.msg);
    sl_scatter_free(sc);
}

/* Ratio and SE at every mu; checks agreement with ref[] (3 SE + 0.02) and,
 * where in_band[k], consistency with the band within 2 SE. */
static void check_ratio(const char *what, const double *syn, size_t ns, const double *phys,
                        size_t np, const double *ref, const int *in_band, double *ratio)
{
    if (verbose())
        fprintf(stderr, "  %s: ratio", what);
    for (int k = 0; k < NMU; k++) {
        double se, r = sl_pf_ratio(syn + k, ns, NMU, phys + k, np, NMU, &se);
        ratio[k] = r;
        if (verbose())
            fprintf(stderr, " %.2f±%.2f", r, se);
        if (ref)
            CHECK(fabs(r - ref[k]) <= 3 * se + 0.02,
                  "%s: ratio %.3f ± %.3f at mu g/ZPA %.1f, full comparison %.2f", what, r, se,
                  0.1 + 0.2 * k, ref[k]);
        if (in_band && in_band[k])
            CHECK(r + 2 * se >= LO && r - 2 * se <= HI,
                  "%s: ratio %.3f ± %.3f at mu g/ZPA %.1f outside [%.2f, %.2f] by > 2 SE", what,
                  r, se, 0.1 + 0.2 * k, LO, HI);
    }
    if (verbose())
        fprintf(stderr, "\n");
}

/* The other dampings of the physical floor files: 2 % and 10 % (the
 * synthesis matches the 5 % table). */
#define NOTHER 2
static const double other_damping[NOTHER] = {0.02, 0.10};

/* Synthesize NSYN sets for a floor file, slide them at mu[] (syn[]), and
 * compare each other damping's table with the sets' own spectra at that
 * damping (set mean of S/T over the table's grid: lowest r_lo[d], highest
 * r_hi[d]); *pga_zpa: the mean PGA/ZPA of the synthesized H components;
 * *rigid: their mean 5 % SA at the floor file's highest frequency / PGA. */
static void floor_synth(const char *path, const double *mu, double *syn, double r_lo[NOTHER],
                        double r_hi[NOTHER], double *pga_zpa, double *rigid)
{
    sl_error e;
    sl_floor *fl = sl_floor_load(path, &e);
    CHECK(fl, "%s", e.msg);
    if (!fl)
        return;
    sl_synth_target tgt[3];
    CHECK(sl_synth_targets_floor(fl, 0, tgt, &e) == SL_OK, "%s", e.msg);
    CHECK(tgt[0].spec->damping == 0.05, "matched at %g, not the 5 %% table", tgt[0].spec->damping);
    sl_synth *s = sl_synth_alloc(4001, 0.005, NULL, &e);
    sl_synth_set out[NSYN];
    sl_status st = sl_synth_make_sets(s, tgt, 12, 0, NSYN, out, NULL, NULL, &e);
    int nfail = 0;
    for (int k = 0; k < NSYN && (st == SL_OK || st == SL_ENOCONV); k++)
        nfail += !out[k].pass;
    CHECK((st == SL_OK || st == SL_ENOCONV) && nfail <= 1, "%s: synthesis status %d, %d failed",
          path, st, nfail);
    sl_set sets[NSYN];
    for (int k = 0; k < NSYN; k++)
        sets[k] = out[k].set;
    slide_run_way(sets, NSYN, mu, sl_scatter_sigma_of_floor(fl), syn);
    *pga_zpa = 0;
    for (int k = 0; k < NSYN; k++)
        *pga_zpa += (sl_motion_pga(sets[k].h1) / fl->comp[SL_FLOOR_H1].zpa_ms2 +
                     sl_motion_pga(sets[k].h2) / fl->comp[SL_FLOOR_H2].zpa_ms2) /
                    (2.0 * NSYN);
    *rigid = 0;
    {
        const sl_spectrum *t5 = sl_floor_spectrum(fl, SL_FLOOR_H1, 0.05);
        const double ftop = t5 ? t5->f_hz[t5->n - 1] : 50.0;
        for (int k = 0; k < NSYN; k++)
            for (int c = 0; c < 2; c++) {
                const sl_motion *mo = c ? sets[k].h2 : sets[k].h1;
                double sa = NAN;
                CHECK(sl_spectrum_compute(mo->acc_ms2, mo->n, mo->dt_s, &ftop, 1, 0.05, &sa, NULL,
                                          NULL, &e) == SL_OK, "%s", e.msg);
                *rigid += sa / sl_motion_pga(mo) / (2.0 * NSYN);
            }
    }
    /* each other damping's table against the motions' own spectra (set mean) */
    for (int d = 0; d < NOTHER; d++) {
        r_lo[d] = INFINITY;
        r_hi[d] = 0;
        for (int c = 0; c < 2; c++) {
            const sl_spectrum *tb = sl_floor_spectrum(fl, (sl_floor_comp)c, other_damping[d]);
            CHECK(tb != NULL, "%s: no %g table", path, other_damping[d]);
            if (!tb)
                continue;
            double mean[NF] = {0};
            for (int k = 0; k < NSYN; k++) {
                const sl_motion *m = c == 0 ? sets[k].h1 : sets[k].h2;
                double psa[NF];
                sl_spectrum_compute(m->acc_ms2, m->n, m->dt_s, tb->f_hz, tb->n, other_damping[d],
                                    psa, NULL, NULL, NULL);
                for (size_t j = 0; j < tb->n; j++)
                    mean[j] += psa[j] / tb->sa_ms2[j] / NSYN;
            }
            for (size_t j = 0; j < tb->n; j++) {
                r_lo[d] = mean[j] < r_lo[d] ? mean[j] : r_lo[d];
                r_hi[d] = mean[j] > r_hi[d] ? mean[j] : r_hi[d];
            }
        }
    }
    for (int k = 0; k < NSYN; k++)
        sl_synth_set_clear(&out[k]);
    sl_synth_free(s);
    sl_floor_free(fl);
}

static void test_floors(void)
{
    const char *shared = harness_shared_dir();
    if (!shared)
        SKIP("../shared not found (set SEISLIDE_SHARED): physical floors not checked");
    sl_set g[NREC];
    size_t nrec = (size_t)read_recs(shared, g);
    CHECK(nrec >= 12, "only %zu records usable", nrec);
    double f[NF];
    for (int j = 0; j < NF; j++)
        f[j] = 0.1 * pow(500.0, (double)j / (NF - 1));
    const sl_building b = {3, {3.0, 4.2, 14.0}, 0.05};
    char dir[] = "/tmp/seislide-pf-XXXXXX";
    CHECK(mkdtemp(dir) != NULL, "mkdtemp");
    /* the band holds within 2 SE of the full comparison at every
     * mu g/ZPA with the run's intensity scatter (docs/synthesis.md 11) */
    static const int in_band[NMU] = {1, 1, 1, 1, 1};
    for (size_t fl = 1; fl <= 3; fl++) {
        sl_set fm[NREC];
        sl_error e;
        for (size_t r = 0; r < nrec; r++)
            CHECK(sl_building_floor(&b, fl, &g[r], &fm[r], &e) == SL_OK, "%s", e.msg);
        double zpa = 0;
        for (size_t r = 0; r < nrec; r++)
            zpa += sl_set_pga_h(&fm[r]) / (double)nrec;
        double mu[NMU], phys[NREC * NMU], ratio[2][NMU];
        for (int k = 0; k < NMU; k++)
            mu[k] = (0.1 + 0.2 * k) * zpa / SL_G;
        slide_all(fm, nrec, mu, phys);
        for (int broaden = 0; broaden < 2; broaden++) {
            char path[256], what[64];
            snprintf(path, sizeof path, "%s/floor%zu%s.ini", dir, fl, broaden ? "b" : "");
            snprintf(what, sizeof what, "floor %zu%s (ZPA %.2f g)", fl,
                     broaden ? " broadened" : "", zpa / SL_G);
            CHECK(sl_pf_write_floor(path, "physical floor", fm, nrec, f, NF, broaden, &e) ==
                      SL_OK,
                  "%s", e.msg);
            sl_floor *flf = sl_floor_load(path, &e);
            CHECK(flf, "%s", e.msg);
            for (int c = 0; c < 3 && flf; c++) { /* ZPA = mean component PGA */
                double z = 0;
                for (size_t r = 0; r < nrec; r++)
                    z += sl_motion_pga(c == 0 ? fm[r].h1 : c == 1 ? fm[r].h2 : fm[r].v) /
                         (double)nrec;
                CHECK_CLOSE(flf->comp[c].zpa_ms2, z, 0, 1e-5);
            }
            sl_floor_free(flf);
            double syn[NSYN * NMU], rlo[NOTHER] = {NAN, NAN}, rhi[NOTHER] = {NAN, NAN}, pz = NAN,
                   rig = NAN;
            floor_synth(path, mu, syn, rlo, rhi, &pz, &rig);
            /* The floor motions are rigid at 50 Hz (SA(50 Hz)/PGA 1.005), so
             * the synthesized ones' PGA is the ZPA: no upward correction in
             * the rigid range and the peak expansion of synth.c (eq. 2r, C2)
             * give 1.03 (aim); without them 0.86-0.93 (docs/synthesis.md 10). */
            CHECK(pz >= 0.98 && pz <= 1.06, "%s: synthesized H PGA/ZPA %.3f", what, pz);
            /* and rigid at the top, as the floor motions are (1.005): the
             * expansion reaches the PGA by the peak, not by resonant content
             * near the last frequency (1.007-1.012; with the expansion's
             * knee from the level instead of the peak, eq. C2: 1.034-1.053) */
            CHECK(rig >= 0.99 && rig <= 1.025, "%s: synthesized H SA(top, 5 %%)/PGA %.3f", what,
                  rig);
            if (verbose())
                fprintf(stderr, "  %s: synthesized H PGA/ZPA %.3f, SA(top, 5 %%)/PGA %.3f\n", what,
                        pz, rig);
            check_ratio(what, syn, NSYN, phys, nrec, broaden ? NULL : ref_floor[fl - 1],
                        broaden ? NULL : in_band, ratio[broaden]);
            CHECK(rlo[1] >= 0.8 && rhi[1] <= 1.25,
                  "floor %zu: own 10 %% spectra / 10 %% table %.3f-%.3f", fl, rlo[1], rhi[1]);
            /* 2 %: the lightly damped oscillator sees how many cycles the
             * motions hold at the floor mode (docs/synthesis.md 12). Band:
             * the synthesis limits [0.9, 1.3] widened by 0.05, since the
             * motions are matched at 5 % only and their 2 % spectrum is a
             * consequence, not a target (measured 0.875-1.303; 4-cycle
             * packets 0.907-1.333): it fails when the motions' 2 % response
             * departs from the physical floor motions' by more than that.
             * Not for broadened files: the max over +-15 % lifts the sharp
             * 2 % peak's flanks more than the 5 % ones, so a broadened 2 %
             * table is not the 2 % spectrum of motions matched to the
             * broadened 5 % one (0.824 measured). */
            CHECK(broaden || (rlo[0] >= 0.85 && rhi[0] <= 1.35),
                  "floor %zu: own 2 %% spectra / 2 %% table %.3f-%.3f", fl, rlo[0], rhi[0]);
            if (verbose())
                fprintf(stderr,
                        "  %s: synthesized motions' own spectra / physical table (set mean): "
                        "2 %% %.3f-%.3f, 10 %% %.3f-%.3f\n",
                        what, rlo[0], rhi[0], rlo[1], rhi[1]);
            remove(path);
        }
        /* design conservatism: the broadened spectra make the sets slide more
         * (same seed, so the two ratios share their synthesized noise) */
        for (int k = 0; k < 3; k++)
            CHECK(ratio[1][k] > ratio[0][k], "floor %zu: broadened %.3f <= plain %.3f at %.1f",
                  fl, ratio[1][k], ratio[0][k], 0.1 + 0.2 * k);
        for (size_t r = 0; r < nrec; r++)
            sl_set_free_motions(&fm[r]);
    }
    rmdir(dir);
    for (size_t r = 0; r < nrec; r++)
        sl_set_free_motions(&g[r]);
}

/* The intensity tail on a soft, lightly damped building (issue 41;
 * docs/synthesis.md 11): floor 4 of the 5-storey
 * building of H modes 1.6 and 1.9 Hz at 2 % (the narrowest floor there,
 * physical PGA log standard deviation 0.44 on 83 records). Synthesized sets
 * slid with the floor's sigma (R4) against the physical floor motions of the
 * test's records. MEASURED in the full comparison (tools/tailfloors.c, 83
 * records, 48 sets, sigma 0.457): 0.93-1.01 at mu g/ZPA 0.1-0.5, 1.02-1.23
 * at 0.6-1.0 (SE 0.11-0.25); with the former constant 0.30, 0.67-0.80 at
 * 0.8-1.0. Asserted: the band within 2 SE at every mu g/ZPA (16
 * records, 8 sets: SE 0.12-0.61, so a weak check), and the floor's sigma
 * 0.40-0.50 (the rule's frequency term: the former constant was 0.30). */
static void test_tail(void)
{
    const char *shared = harness_shared_dir();
    if (!shared)
        SKIP("../shared not found (set SEISLIDE_SHARED): the tail not checked");
    sl_set g[NREC], fm[NREC];
    size_t nrec = (size_t)read_recs(shared, g);
    CHECK(nrec >= 12, "only %zu records usable", nrec);
    const sl_building b = {5, {1.6, 1.9, 12.0}, 0.02};
    sl_error e;
    double zpa = 0, f[NF], mu[NMU], phys[NREC * NMU], syn[NSYN * NMU], ratio[NMU];
    for (size_t r = 0; r < nrec; r++) {
        CHECK(sl_building_floor(&b, 4, &g[r], &fm[r], &e) == SL_OK, "%s", e.msg);
        zpa += sl_set_pga_h(&fm[r]) / (double)nrec;
    }
    for (int j = 0; j < NF; j++)
        f[j] = 0.1 * pow(500.0, (double)j / (NF - 1));
    for (int k = 0; k < NMU; k++)
        mu[k] = (0.1 + 0.2 * k) * zpa / SL_G;
    slide_all(fm, nrec, mu, phys);
    char dir[] = "/tmp/seislide-tail-XXXXXX", path[64];
    CHECK(mkdtemp(dir) != NULL, "mkdtemp");
    snprintf(path, sizeof path, "%s/floor4.ini", dir);
    CHECK(sl_pf_write_floor(path, "soft floor", fm, nrec, f, NF, 0, &e) == SL_OK, "%s", e.msg);
    sl_floor *fl = sl_floor_load(path, &e);
    CHECK(fl, "%s", e.msg);
    if (fl) {
        double sigma = sl_scatter_sigma_of_floor(fl);
        CHECK(sigma > 0.40 && sigma < 0.50, "soft floor: sigma %.3f (83 records: 0.457)", sigma);
        if (verbose())
            fprintf(stderr, "  soft 2 %% building, floor 4: sigma %.3f\n", sigma);
        double rlo[NOTHER], rhi[NOTHER], pz, rig;
        floor_synth(path, mu, syn, rlo, rhi, &pz, &rig);
        static const int in_band[NMU] = {1, 1, 1, 1, 1};
        check_ratio("soft 2 % building, floor 4", syn, NSYN, phys, nrec, NULL, in_band, ratio);
        sl_floor_free(fl);
    }
    remove(path);
    rmdir(dir);
    for (size_t r = 0; r < nrec; r++) {
        sl_set_free_motions(&fm[r]);
        sl_set_free_motions(&g[r]);
    }
}

/* The building model against its closed forms: N = 3 frequency ratios
 * sin(3 pi/14)/sin(pi/14) = 2.802 and sin(5 pi/14)/sin(pi/14) = 4.049;
 * sum_r Gamma_r phi_r(j) = 1 on every floor (B5); a very stiff building
 * moves with the ground; the top floor of a 1-storey building is one
 * oscillator, whose peak absolute acceleration is the spectrum's SA_abs. */
static void test_building_model(void)
{
    sl_building b = {3, {3.0, 4.2, 14.0}, 0.05};
    double f[SL_BUILDING_MAX_STOREYS], gp[SL_BUILDING_MAX_STOREYS];
    for (size_t j = 1; j <= 3; j++) {
        sl_building_modes(&b, 0, j, f, gp);
        CHECK_CLOSE(f[0], 3.0, 0, 1e-12);
        CHECK_CLOSE(f[1] / f[0], sin(3 * M_PI / 14) / sin(M_PI / 14), 0, 1e-12);
        CHECK_CLOSE(f[2] / f[0], sin(5 * M_PI / 14) / sin(M_PI / 14), 0, 1e-12);
        CHECK_CLOSE(gp[0] + gp[1] + gp[2], 1.0, 1e-12, 0);
    }
    /* a ground motion: 20 s of a decaying chirp at 200/s */
    size_t n = 4001;
    double *a = malloc(n * sizeof *a);
    for (size_t i = 0; i < n; i++) {
        double t = 0.005 * (double)i;
        a[i] = sin(2 * M_PI * (0.5 + 0.4 * t) * t) * exp(-0.1 * t);
    }
    sl_motion *g = sl_motion_from_array(a, n, 0.005, "chirp");
    sl_set gs = {g, g, g}, out;
    sl_error e;
    /* quasi-static error (f/f1)^2 <= (8.5/80)^2 = 1.1 % of the PGA */
    sl_building stiff = {3, {80.0, 80.0, 80.0}, 0.05};
    CHECK(sl_building_floor(&stiff, 3, &gs, &out, &e) == SL_OK, "%s", e.msg);
    double dmax = 0;
    for (size_t i = 0; i < n; i++)
        dmax = fabs(out.h1->acc_ms2[i] - a[i]) > dmax ? fabs(out.h1->acc_ms2[i] - a[i]) : dmax;
    CHECK(dmax < 0.02, "stiff building: floor - ground up to %g (PGA 1)", dmax);
    sl_set_free_motions(&out);
    sl_building one = {1, {2.0, 2.0, 2.0}, 0.05};
    CHECK(sl_building_floor(&one, 1, &gs, &out, &e) == SL_OK, "%s", e.msg);
    double fq = 2.0, sa_abs = NAN;
    sl_spectrum_opts o;
    sl_spectrum_opts_default(&o);
    o.free_vibration = 0;
    CHECK(sl_spectrum_compute_opts(a, n, 0.005, &fq, 1, 0.05, &o, NULL, NULL, &sa_abs, &e) ==
              SL_OK,
          "%s", e.msg);
    CHECK_CLOSE(sl_motion_pga(out.h1), sa_abs, 0, 0.02);
    sl_set_free_motions(&out);
    sl_motion_free(g);
    free(a);
}

/* Ground: synthesized RG 1.60 sets against the records matched to RG 1.60
 * (the study's method), mean sliding at mu g/PGA = 0.1 ... 0.9. */
static void test_ground(void)
{
    const char *shared = harness_shared_dir();
    if (!shared)
        SKIP("../shared not found (set SEISLIDE_SHARED): ground not checked");
    sl_set g[NREC], matched[NREC];
    size_t nrec = (size_t)read_recs(shared, g), nm = 0;
    sl_synth_set ms[NREC];
    for (size_t r = 0; r < nrec; r++) {
        sl_error e;
        sl_status st = sl_study_match_rg160(&g[r], 0.05, PGA_G * SL_G, &ms[nm], &e);
        sl_set_free_motions(&g[r]);
        if (st == SL_OK || st == SL_ENOCONV)
            matched[nm] = ms[nm].set, nm++;
    }
    CHECK(nm >= 12, "only %zu records matched", nm);
    double mu[NMU], real[NREC * NMU], syn[NSYN * NMU], ratio[NMU];
    for (int k = 0; k < NMU; k++)
        mu[k] = (0.1 + 0.2 * k) * PGA_G;
    slide_all(matched, nm, mu, real);
    sl_spectrum *sp[3];
    sl_synth_target tgt[3];
    sl_error e;
    sl_synth *s = sl_synth_alloc(4001, 0.005, NULL, &e);
    CHECK(s && sl_synth_targets_rg160(PGA_G * SL_G, 0.05, NULL, sp, tgt, &e) == SL_OK, "%s",
          e.msg);
    sl_synth_set out[NSYN];
    CHECK(sl_synth_make_sets(s, tgt, 5, 0, NSYN, out, NULL, NULL, &e) == SL_OK, "%s", e.msg);
    sl_set sets[NSYN];
    for (int k = 0; k < NSYN; k++)
        sets[k] = out[k].set;
    /* no intensity scatter on either side, as in the full comparison: both
     * are sets matched to one spectrum (tools/physfloors.c, synthesis.md 11) */
    slide_all(sets, NSYN, mu, syn);
    /* the band within 2 SE at mu g/PGA 0.1-0.3 (docs/synthesis.md 10) */
    static const int in_band[NMU] = {1, 1, 0, 0, 0};
    check_ratio("ground RG 1.60 0.3 g, synthesized / matched", syn, NSYN, real, nm, ref_ground,
                in_band, ratio);
    /* What `seislide run` reports for a ground floor carries the intensity
     * scatter: never below the band (within 2 SE) at any mu, i.e. the
     * designer's NLTHA mean is not unconservative against the study's
     * reference (full comparison with RG 1.60's own sigma 0.354, seed 12:
     * 0.87, 0.98, 1.05, 1.33, 2.26; with the former 0.30, 0.87-0.90 at 0.1
     * ... 1.80-1.93 at 0.9, seeds 12-14; docs/synthesis.md 11-12). Weak with
     * 8 sets (scatter 0.05 still passes: 0.61 ± 0.15 at 0.9); the floors'
     * band catches 0.10. */
    double synr[NSYN * NMU];
    const sl_spectrum *h[2] = {tgt[0].spec, tgt[1].spec};
    const double zpa[2] = {tgt[0].zpa_ms2, tgt[1].zpa_ms2};
    slide_run_way(sets, NSYN, mu, sl_scatter_sigma_of_fc(sl_scatter_fc_hz(h, zpa)), synr);
    if (verbose())
        fprintf(stderr, "  ground, slid the run's way (intensity scatter) / matched:");
    for (int k = 0; k < NMU; k++) {
        double se, r = sl_pf_ratio(synr + k, NSYN, NMU, real + k, nm, NMU, &se);
        if (verbose())
            fprintf(stderr, " %.2f±%.2f", r, se);
        CHECK(r + 2 * se >= LO, "ground the run's way: ratio %.3f ± %.3f at mu g/PGA %.1f below %.2f",
              r, se, 0.1 + 0.2 * k, LO);
    }
    if (verbose())
        fprintf(stderr, "\n");
    for (int k = 0; k < NSYN; k++)
        sl_synth_set_clear(&out[k]);
    for (size_t r = 0; r < nm; r++)
        sl_synth_set_clear(&ms[r]);
    for (int c = 0; c < 3; c++)
        sl_spectrum_free(sp[c]);
    sl_synth_free(s);
}

/* (P1) against a hand calculation and against the scatter of the ratio
 * over many independent samples (the delta method is first order: with 40
 * values per sample its SE is within a few % of the true one). */
static void test_ratio_se(void)
{
    const double a[3] = {1, 2, 3}, b[2] = {2, 4};
    double se, r = sl_pf_ratio(a, 3, 1, b, 2, 1, &se);
    /* R = 2/3, SE = R sqrt(1/(3 2^2) + 2/(2 3^2)) */
    CHECK_CLOSE(r, 2.0 / 3.0, 1e-15, 0);
    CHECK_CLOSE(se, 2.0 / 3.0 * sqrt(1.0 / 12 + 1.0 / 9), 1e-15, 0);
    /* exponential samples (skewed, as peak sliding is), means 1 and 2 */
    enum { NA = 40, NB = 40, REP = 4000 };
    uint64_t x = 12345;
    double sr = 0, sr2 = 0, sse = 0;
    for (int q = 0; q < REP; q++) {
        double va[NA], vb[NB];
        for (int i = 0; i < NA + NB; i++) {
            x = x * 6364136223846793005ULL + 1442695040888963407ULL; /* LCG (Knuth MMIX) */
            double u = ((double)(x >> 11) + 0.5) / 9007199254740992.0;
            if (i < NA)
                va[i] = -log(u);
            else
                vb[i - NA] = -2 * log(u);
        }
        double s1, r1 = sl_pf_ratio(va, NA, 1, vb, NB, 1, &s1);
        sr += r1 / REP;
        sr2 += r1 * r1 / REP;
        sse += s1 / REP;
    }
    double sd = sqrt(sr2 - sr * sr);
    /* true SE: 0.5 sqrt(1/40 + 1/40) = 0.112 (delta method); empirical within 8 % */
    CHECK_CLOSE(sse, sd, 0, 0.08);
    CHECK_CLOSE(sd, 0.5 * sqrt(2.0 / 40), 0, 0.08);
}

/* The record rule: a record below the rule is refused with the value named;
 * a used record is scaled to the requested larger horizontal PGA. */
static void test_record_rule(void)
{
    const char *shared = harness_shared_dir();
    if (!shared)
        SKIP("../shared not found (set SEISLIDE_SHARED): record rule not checked");
    char dir[1024];
    snprintf(dir, sizeof dir, "%s/records/%s", shared, recs[1]);
    sl_pf_rule rule;
    sl_pf_rule_default(&rule);
    sl_set s;
    sl_error e;
    if (sl_pf_read_record(dir, &rule, 0.3 * SL_G, &s, &e) != SL_OK) {
        CHECK(0, "%s", e.msg);
        return;
    }
    CHECK_CLOSE(sl_set_pga_h(&s), 0.3 * SL_G, 0, 1e-12);
    CHECK(s.h1->dt_s <= 0.01 + 1e-12 && s.v && s.h2, "dt %g", s.h1->dt_s);
    sl_set_free_motions(&s);
    rule.min_pga_g = 5.0;
    CHECK(sl_pf_read_record(dir, &rule, 0.3 * SL_G, &s, &e) == SL_EINVAL &&
              strstr(e.msg, "PGA") && strstr(e.msg, " 5 g"),
          "rule PGA: %s", e.msg);
    sl_pf_rule_default(&rule);
    rule.min_duration_s = 1e4;
    CHECK(sl_pf_read_record(dir, &rule, 0.3 * SL_G, &s, &e) == SL_EINVAL &&
              strstr(e.msg, "duration"),
          "rule duration: %s", e.msg);
    sl_pf_rule_default(&rule);
    rule.max_dt_s = 1e-4;
    CHECK(sl_pf_read_record(dir, &rule, 0.3 * SL_G, &s, &e) == SL_EINVAL && strstr(e.msg, "dt"),
          "rule dt: %s", e.msg);
    snprintf(dir, sizeof dir, "%s/records/RSN15_KERN_TAF", shared); /* no vertical */
    CHECK(sl_pf_read_record(dir, &rule, 0.3 * SL_G, &s, &e) != SL_OK, "Taft: no vertical");
}

int main(void)
{
    RUN(test_ratio_se);
    RUN(test_record_rule);
    RUN(test_building_model);
    RUN(test_ground);
    RUN(test_floors);
    RUN(test_tail);
    return HARNESS_END("physical_floors");
}
