/*
 * tailfloors.c - the intensity tail near the sliding threshold: synthesized
 * floor sets against the physical floor motions behind their spectra, on
 * buildings of any period and damping (docs/synthesis.md 11, notes.md 3.9;
 * method/scatter.h (R4)).
 *
 * Physical floor motions: the records of study/physfloor.h (every usable
 * three-component record, scaled to a larger horizontal PGA of 0.3 g)
 * through a uniform shear building (study/building.h). Their mean 2, 5 and
 * 10 % spectra and mean PGA are written as a floor file, read back, and
 * sets are synthesized for it (synth.h defaults, as `seislide run`); the
 * same engine slides a block on both at mu g/ZPA = 0.1, 0.2, ..., 1.0 (ZPA
 * = the physical motions' mean larger horizontal PGA). The synthesized sets
 * are slid the run's way, with the intensity scatter of method/scatter.h
 * (R1)-(R3), at several sigma from ONE NLTHA per set on the friction
 * lattice 10^(q/SL_SCATTER_PER_DECADE) (every sigma's grid is part of it).
 *
 *   make tailfloors               (= nice build/tools/tailfloors: the buildings below)
 *   options: -r RECORDS_DIR (default $SEISLIDE_SHARED/records or
 *            ../shared/records), -n MAX_RECORDS (0 = all), -s NSYN (24),
 *            -S SEED (12), -b N:f1_h1:f1_h2:f1_v:damping (a building,
 *            repeatable; default: the buildings of the default list),
 *            -d (descriptors only: the physical floor motions and the
 *            floor spectra, no synthesis, no sliding; fast),
 *            -R SIGMA (one more column: a fixed scatter),
 *            -x (what else carries the tail, one change at a time: the two
 *            horizontals' intensities correlated as the physical motions'
 *            instead of one common factor; a shorter strong motion; the
 *            physical motions' near-peak cycles against their sliding),
 *            -m FILE (also the summary as one markdown table, a row per
 *            building, to FILE: `make tailfloors` writes
 *            docs/validation/tail_floors.md, which `seislide study`
 *            carries into docs/validation.md, section 8)
 * Prints markdown tables and one "DATA" line per floor; exit 0, or 1 with
 * a message.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <gsl/gsl_cdf.h>

#include "analysis.h"
#include "core/compare.h"
#include "core/units.h"
#include "io/floor.h"
#include "io/setdir.h"
#include "method/scatter.h"
#include "signal/realism.h"
#include "signal/spectrum.h"
#include "slide/slide.h"
#include "study/building.h"
#include "study/physfloor.h"
#include "synth/synth.h"

#define NMU 10      /* mu g/ZPA = 0.1, 0.2, ..., 1.0 */
#define NF 136      /* floor spectra: 0.1-50 Hz, 50 a decade */
#define PGA_G 0.3   /* the records' larger horizontal PGA */
#define SIG_LAT 0.7 /* the lattice covers every sigma up to this */
#define MAX_B 16
#define SE_OK 0.35  /* points whose physical mean has a relative SE up to this count */
#define NVAR 5      /* sigma 0, the former default, the physical PGA's, the rule, -R */
#define FORMER 0.30 /* the former default sigma, one for every floor */

static const char *const default_b[] = {
    "3:3.0:4.2:14:0.05",   /* the building of docs/synthesis.md 10 */
    "3:5.0:6.5:18:0.03",   /* stiff, 3 % */
    "5:1.6:1.9:12:0.02",   /* soft, 2 % */
};

typedef struct tf_opts {
    const char *records;
    size_t max_records, nsyn, nb;
    uint64_t seed;
    int descr_only;
    int experiments;    /* -x: one change at a time (experiments()) */
    int ground_scatter; /* -g: how the records' spectra scatter at one PGA */
    double fixed; /* -R, NAN: none */
    FILE *dump;   /* -D: every mean and SD for offline fits */
    FILE *md;     /* -m: the summary table */
    sl_building b[MAX_B];
    const char *bspec[MAX_B];
} tf_opts;

/* per building: the points of the summary */
typedef struct tf_sum {
    double lr_hi[NVAR], lr_lo[NVAR];  /* sums of ln R at mu g/ZPA >= 0.5 and < 0.5 */
    size_t n_hi, n_lo;
    double min_hi[NVAR];              /* smallest R at >= 0.5 where the physical SE <= SE_OK */
    double sig_lo, sig_hi, fc_lo, fc_hi; /* the floors' rule sigma and f_c, Hz (R4)-(R5) */
} tf_sum;

static void die(const sl_error *e)
{
    char buf[2200];
    fprintf(stderr, "tailfloors: %s\n", sl_error_format(e, buf, sizeof buf));
    exit(1);
}

static void *xcalloc(size_t n, size_t s)
{
    void *p = calloc(n ? n : 1, s);
    if (!p) {
        fprintf(stderr, "tailfloors: out of memory\n");
        exit(1);
    }
    return p;
}

/* peaks[i * nq + q] of sets at grid[nq] */
static double *slide(const sl_set *sets, size_t n, const double *grid, size_t nq)
{
    sl_slide_opts so;
    sl_slide_opts_default(&so);
    sl_slide_result *res = xcalloc(n * nq, sizeof *res);
    double *pk = xcalloc(n * nq, sizeof *pk);
    sl_error e;
    if (sl_slide_batch(sets, n, grid, nq, &so, res, &e))
        die(&e);
    for (size_t i = 0; i < n * nq; i++)
        pk[i] = res[i].peak_m;
    free(res);
    return pk;
}

static long lattice(double mu)
{
    return lround(log10(mu) * SL_SCATTER_PER_DECADE);
}

/* y[i * NMU + k]: (R3) at sigma for set i from its peaks uL on the lattice
 * grid L[nL] (sigma's grid is a part of it) */
static void scatter_y(double sigma, const double *mu, size_t n, const double *L, size_t nL,
                      const double *uL, double *y)
{
    sl_error e;
    sl_scatter *sc = sl_scatter_alloc(sigma, mu, NMU, &e);
    if (!sc)
        die(&e);
    size_t nq;
    const double *g = sl_scatter_grid(sc, &nq);
    double *u = xcalloc(nq, sizeof *u);
    for (size_t i = 0; i < n; i++) {
        for (size_t q = 0; q < nq; q++) {
            long j = lattice(g[q]) - lattice(L[0]);
            if (j < 0 || (size_t)j >= nL) {
                fprintf(stderr, "tailfloors: sigma %g needs mu %g outside the lattice\n", sigma,
                        g[q]);
                exit(1);
            }
            u[q] = uL[i * nL + (size_t)j];
        }
        if (sl_scatter_mean(sc, u, y + i * NMU, &e))
            die(&e);
    }
    free(u);
    sl_scatter_free(sc);
}

static void mean_sd_log(const double *x, size_t n, double *sd)
{
    double m = 0, q = 0;
    for (size_t i = 0; i < n; i++)
        m += log(x[i]) / (double)n;
    for (size_t i = 0; i < n; i++)
        q += (log(x[i]) - m) * (log(x[i]) - m);
    *sd = sqrt(q / (double)(n - 1));
}

static double corr_log(const double *a, const double *b, size_t n)
{
    double ma = 0, mb = 0, sab = 0, saa = 0, sbb = 0;
    for (size_t i = 0; i < n; i++)
        ma += log(a[i]) / (double)n, mb += log(b[i]) / (double)n;
    for (size_t i = 0; i < n; i++) {
        double x = log(a[i]) - ma, y = log(b[i]) - mb;
        sab += x * y, saa += x * x, sbb += y * y;
    }
    return sab / sqrt(saa * sbb);
}

/* The motions' intensity descriptors: sigma_ln of the larger H PGA, of H1
 * and H2, their correlation; peaks above 0.9 PGA per H component (mean,
 * max); D5-75 mean. */
typedef struct tf_desc {
    double s_pga, s_h1, s_h2, rho, peaks, d575;
    size_t peaks_max;
} tf_desc;

static void describe(const sl_set *s, size_t n, tf_desc *d)
{
    double *p = xcalloc(3 * n, sizeof *p);
    memset(d, 0, sizeof *d);
    for (size_t i = 0; i < n; i++) {
        p[i] = sl_set_pga_h(&s[i]);
        p[n + i] = sl_motion_pga(s[i].h1);
        p[2 * n + i] = sl_motion_pga(s[i].h2);
        for (int c = 0; c < 2; c++) {
            const sl_motion *m = c ? s[i].h2 : s[i].h1;
            size_t k = sl_realism_peaks_above(m->acc_ms2, m->n, 0.9);
            d->peaks += (double)k / (2.0 * (double)n);
            d->peaks_max = k > d->peaks_max ? k : d->peaks_max;
            d->d575 += sl_motion_d5_75(m) / (2.0 * (double)n);
        }
    }
    mean_sd_log(p, n, &d->s_pga);
    mean_sd_log(p + n, n, &d->s_h1);
    mean_sd_log(p + 2 * n, n, &d->s_h2);
    d->rho = corr_log(p + n, p + 2 * n, n);
    free(p);
}

/* What the floor spectrum of component c shows (its matched damping):
 * the peak / ZPA, where, and the 2 % / 5 % ratio at the peak (NAN without
 * a 2 % table). */
/* More of what the spectrum of component c shows (its matched damping):
 * the width around the peak where SA >= peak / sqrt(2), octaves; the
 * centroid frequency of the part above the ZPA, exp(sum (SA - ZPA)+ ln f /
 * sum (SA - ZPA)+) on the file's points (Hz); the expected V/A x 2 pi
 * f_peak (realism.h; 1 for a motion narrow-banded at f_peak) */
static void spectrum_more(const sl_floor *fl, int c, double *bw_oct, double *fc_hz, double *va_n)
{
    const sl_floor_component *k = &fl->comp[c];
    double z = sl_synth_floor_damping(fl, (sl_floor_comp)c);
    const sl_spectrum *s = NULL;
    for (size_t j = 0; j < k->nspec; j++)
        if (fabs(k->spec[j].damping - z) < 1e-9)
            s = &k->spec[j];
    size_t jp = 0;
    for (size_t j = 0; j < s->n; j++)
        jp = s->sa_ms2[j] > s->sa_ms2[jp] ? j : jp;
    size_t a = jp, b = jp;
    while (a > 0 && s->sa_ms2[a - 1] >= s->sa_ms2[jp] / sqrt(2.0))
        a--;
    while (b + 1 < s->n && s->sa_ms2[b + 1] >= s->sa_ms2[jp] / sqrt(2.0))
        b++;
    *bw_oct = log2(s->f_hz[b] / s->f_hz[a]);
    double w = 0, wl = 0;
    for (size_t j = 0; j < s->n; j++) {
        double e = fmax(s->sa_ms2[j] - k->zpa_ms2, 0);
        w += e;
        wl += e * log(s->f_hz[j]);
    }
    *fc_hz = exp(wl / w);
    double va, da, adv;
    sl_error e;
    if (sl_realism_expected(s, &va, &da, &adv, &e))
        die(&e);
    *va_n = va * 2 * SL_PI * s->f_hz[jp];
}

static void spectrum_desc(const sl_floor *fl, int c, double *pz, double *fpk, double *r25)
{
    const sl_floor_component *k = &fl->comp[c];
    double z = sl_synth_floor_damping(fl, (sl_floor_comp)c);
    const sl_spectrum *s5 = NULL, *s2 = NULL;
    for (size_t j = 0; j < k->nspec; j++) {
        if (fabs(k->spec[j].damping - z) < 1e-9)
            s5 = &k->spec[j];
        if (fabs(k->spec[j].damping - 0.02) < 1e-9)
            s2 = &k->spec[j];
    }
    size_t jp = 0;
    for (size_t j = 0; j < s5->n; j++)
        jp = s5->sa_ms2[j] > s5->sa_ms2[jp] ? j : jp;
    *pz = s5->sa_ms2[jp] / k->zpa_ms2;
    *fpk = s5->f_hz[jp];
    *r25 = s2 ? s2->sa_ms2[jp] / s5->sa_ms2[jp] : NAN;
}

/* the sigma in [0, SIG_LAT] (steps of 0.01) that brings the synthesized
 * mean closest to the physical one at mu g/ZPA >= 0.5 (least squares in
 * ln R weighted by 1 / SE(ln R)^2) */
static double sigma_star(const double *mu, size_t nsyn, const double *L, size_t nL,
                         const double *uL, const double *phys, size_t nrec)
{
    double best = NAN, bestq = INFINITY;
    double *y = xcalloc(nsyn * NMU, sizeof *y);
    for (int t = 1; t <= (int)lround(SIG_LAT * 100); t++) {
        double sg = 0.01 * t, q = 0;
        scatter_y(sg, mu, nsyn, L, nL, uL, y);
        for (int k = 4; k < NMU; k++) {
            double se, r = sl_pf_ratio(y + k, nsyn, NMU, phys + k, nrec, NMU, &se);
            if (r > 0 && se > 0)
                q += pow(log(r) / (se / r), 2);
            else
                q += 1e6;
        }
        if (q < bestq)
            bestq = q, best = sg;
    }
    free(y);
    return best;
}

static sl_set *synth(const tf_opts *o, const sl_floor *flr, double hold_frac, sl_synth_set **outp)
{
    sl_error e;
    sl_synth_params sp;
    sl_synth_params_default(&sp);
    if (hold_frac > 0)
        sp.hold_frac = hold_frac;
    sl_synth_target tgt[3];
    if (sl_synth_targets_floor(flr, 0, tgt, &e))
        die(&e);
    size_t n_t = (size_t)(SL_SYNTH_DURATION_S / SL_SYNTH_DT_S + 0.5) + 1;
    sl_synth *s = sl_synth_alloc(n_t, SL_SYNTH_DT_S, &sp, &e);
    sl_synth_set *out = xcalloc(o->nsyn, sizeof *out);
    if (!s)
        die(&e);
    sl_status st = sl_synth_make_sets(s, tgt, o->seed, 0, o->nsyn, out, NULL, NULL, &e);
    if (st && st != SL_ENOCONV)
        die(&e);
    sl_synth_free(s);
    sl_set *sets = xcalloc(o->nsyn, sizeof *sets);
    for (size_t k = 0; k < o->nsyn; k++)
        sets[k] = out[k].set;
    *outp = out;
    return sets;
}

/* -D: "tag building floor [sigma] mean[NMU] sd[NMU] n" */
static void dump_row(FILE *f, const char *tag, const char *b, size_t fl, double sigma,
                     const double *x, size_t n)
{
    if (!f)
        return;
    double m[NMU], sd[NMU];
    for (int k = 0; k < NMU; k++)
        sl_pf_mean_sd(x + k, n, NMU, &m[k], &sd[k]);
    fprintf(f, "%s %s %zu %.2f", tag, b, fl, sigma);
    for (int k = 0; k < NMU; k++)
        fprintf(f, " %.6g", m[k]);
    for (int k = 0; k < NMU; k++)
        fprintf(f, " %.6g", sd[k]);
    fprintf(f, " %zu\n", n);
}

/* mean over sets of (R3) at sigma, sets slid directly (sl_scatter_slide_batch) */
static double *run_way(const sl_set *sets, size_t n, const double *mu, double sigma)
{
    sl_error e;
    sl_slide_opts so;
    sl_slide_opts_default(&so);
    sl_scatter *sc = sl_scatter_alloc(sigma, mu, NMU, &e);
    double *y = xcalloc(n * NMU, sizeof *y);
    if (!sc || sl_scatter_slide_batch(sc, sets, n, &so, y, NULL, &e))
        die(&e);
    sl_scatter_free(sc);
    return y;
}

static void ratio_row(const char *label, const double *a, size_t na, const double *b, size_t nb)
{
    printf("| %s |", label);
    for (int k = 0; k < NMU; k++) {
        double se, r = sl_pf_ratio(a + k, na, NMU, b + k, nb, NMU, &se);
        printf(" %.2f ± %.2f |", r, se);
    }
    printf("\n");
}

/* -x: one change at a time against the run's model (one factor on both
 * horizontals, sigma of (R4), the default synthesis). */
static void experiments(const tf_opts *o, const sl_floor *flr, const sl_set *fm, const sl_set *fn,
                        size_t nrec, const sl_set *syn, const double *mu, double sigma,
                        double rho, const double *phys, const double *physn)
{
    enum { K = 8 }; /* factor draws per set (Latin hypercube in z1, z2) */
    const size_t n = o->nsyn;
    sl_set *t = xcalloc(n * K, sizeof *t);
    double *mc[2];
    /* 1. the two horizontals' factors correlated as the physical motions'
     * ln PGA (rho) instead of one common factor (rho = 1); the same z1 */
    for (int v = 0; v < 2; v++) {
        const double r = v ? rho : 1.0;
        for (size_t i = 0; i < n; i++)
            for (size_t k = 0; k < K; k++) {
                double z1 = gsl_cdf_ugaussian_Pinv(((double)k + 0.5) / K);
                double w = gsl_cdf_ugaussian_Pinv(((double)((k * 3 + i) % K) + 0.5) / K);
                double z2 = r * z1 + sqrt(fmax(1 - r * r, 0)) * w;
                double f1 = exp(sigma * z1 - 0.5 * sigma * sigma);
                double f2 = exp(sigma * z2 - 0.5 * sigma * sigma);
                sl_set *c = &t[i * K + k];
                c->h1 = sl_motion_copy(syn[i].h1);
                c->h2 = sl_motion_copy(syn[i].h2);
                c->v = sl_motion_copy(syn[i].v);
                if (!c->h1 || !c->h2 || !c->v) {
                    fprintf(stderr, "tailfloors: out of memory\n");
                    exit(1);
                }
                sl_motion_scale(c->h1, f1);
                sl_motion_scale(c->h2, f2);
            }
        mc[v] = slide(t, n * K, mu, NMU);
        for (size_t i = 0; i < n * K; i++)
            sl_set_free_motions(&t[i]);
    }
    printf("\n| -x: one change at a time | μg/ZPA 0.1 | 0.2 | 0.3 | 0.4 | 0.5 | 0.6 | 0.7 | 0.8 | 0.9 "
           "| 1.0 |\n|---|---|---|---|---|---|---|---|---|---|---|\n");
    char lab[160];
    snprintf(lab, sizeof lab, "H1, H2 factors correlated %.2f (physical) / one common factor "
             "(sigma %.2f, %d draws a set)", rho, sigma, K);
    ratio_row(lab, mc[1], n * K, mc[0], n * K);
    /* 2. a shorter strong motion: the envelope's hold 0.40 instead of 0.55 */
    sl_synth_set *out2;
    sl_set *syn2 = synth(o, flr, 0.40, &out2);
    tf_desc d2, d1;
    describe(syn2, n, &d2);
    describe(syn, n, &d1);
    double *y2 = run_way(syn2, n, mu, sigma), *y1 = run_way(syn, n, mu, sigma);
    tf_desc dp;
    describe(fm, nrec, &dp);
    snprintf(lab, sizeof lab, "hold 0.40 (D5-75 %.1f s) / hold 0.55 (%.1f s; physical %.1f s)",
             d2.d575, d1.d575, dp.d575);
    ratio_row(lab, y2, n, y1, n);
    ratio_row("synthesized, hold 0.40, rule / physical", y2, n, phys, nrec);
    for (size_t k = 0; k < n; k++)
        sl_synth_set_clear(&out2[k]);
    free(out2);
    free(syn2);
    /* 3. near-peak cycles: the physical motions at one PGA, grouped by the
     * peaks above 0.9 PGA of their stronger horizontal */
    double grp[3][NMU] = {{0}};
    size_t ng[3] = {0};
    for (size_t r = 0; r < nrec; r++) {
        const sl_motion *m = sl_motion_pga(fn[r].h1) >= sl_motion_pga(fn[r].h2) ? fn[r].h1 : fn[r].h2;
        size_t c = sl_realism_peaks_above(m->acc_ms2, m->n, 0.9);
        int gi = c <= 1 ? 0 : c == 2 ? 1 : 2;
        ng[gi]++;
        for (int k = 0; k < NMU; k++)
            grp[gi][k] += physn[r * NMU + k];
    }
    printf("| physical at one PGA, mean sliding (mm) with 1 / 2 / >= 3 peaks above 0.9 PGA (%zu / "
           "%zu / %zu motions) |", ng[0], ng[1], ng[2]);
    for (int k = 0; k < NMU; k++)
        printf(" %.1f / %.1f / %.1f |", 1e3 * grp[0][k] / (double)(ng[0] ? ng[0] : 1),
               1e3 * grp[1][k] / (double)(ng[1] ? ng[1] : 1), 1e3 * grp[2][k] / (double)(ng[2] ? ng[2] : 1));
    printf("\n");
    free(y1);
    free(y2);
    free(mc[0]);
    free(mc[1]);
    free(t);
}

static void floor_case(const tf_opts *o, size_t ib, size_t fl, const sl_set *g, size_t nrec,
                       tf_sum *sum)
{
    const sl_building *b = &o->b[ib];
    sl_error e;
    sl_set *fm = xcalloc(nrec, sizeof *fm);
    for (size_t r = 0; r < nrec; r++)
        if (sl_building_floor(b, fl, &g[r], &fm[r], &e))
            die(&e);
    double zpa = 0, mu[NMU], f[NF];
    for (size_t r = 0; r < nrec; r++)
        zpa += sl_set_pga_h(&fm[r]) / (double)nrec;
    for (int k = 0; k < NMU; k++)
        mu[k] = 0.1 * (k + 1) * zpa / SL_G;
    for (size_t j = 0; j < NF; j++)
        f[j] = 0.1 * pow(500.0, (double)j / (NF - 1));
    char dir[] = "/tmp/seislide-tail-XXXXXX", path[64];
    if (!mkdtemp(dir)) {
        fprintf(stderr, "tailfloors: cannot make a temporary directory\n");
        exit(1);
    }
    snprintf(path, sizeof path, "%s/floor.ini", dir);
    if (sl_pf_write_floor(path, "physical floor", fm, nrec, f, NF, 0, &e))
        die(&e);
    sl_floor *flr = sl_floor_load(path, &e);
    remove(path);
    rmdir(dir);
    if (!flr)
        die(&e);
    tf_desc dp, ds;
    describe(fm, nrec, &dp);
    double pz[2], fpk[2], r25[2];
    for (int c = 0; c < 2; c++)
        spectrum_desc(flr, c, &pz[c], &fpk[c], &r25[c]);
    double s_rule = sl_scatter_sigma_of_floor(flr);
    double bw[2], fc[2], va[2];
    for (int c = 0; c < 2; c++)
        spectrum_more(flr, c, &bw[c], &fc[c], &va[c]);
    double fc_floor = sl_scatter_floor_fc_hz(flr);
    sum->sig_lo = fmin(sum->sig_lo, s_rule);
    sum->sig_hi = fmax(sum->sig_hi, s_rule);
    sum->fc_lo = fmin(sum->fc_lo, fc_floor);
    sum->fc_hi = fmax(sum->fc_hi, fc_floor);
    if (o->dump)
        fprintf(o->dump, "E %s %zu %.4f %.4f %.4f %.4f %.4f %.4f %.4f %.4f %.4f %.4f %.4f %.4f %.4f %.4f %.3f %.2f\n",
                o->bspec[ib], fl, pz[0], fpk[0], pz[1], fpk[1], bw[0], bw[1], fc[0], fc[1],
                va[0], va[1], dp.s_pga, dp.s_h1, dp.s_h2, dp.rho, dp.peaks, dp.d575);
    printf("\n%s floor %zu: ZPA %.3f g; floor spectrum (5 %%) peak/ZPA %.2f at %.2f Hz (H1), %.2f at "
           "%.2f Hz (H2), 2 %%/5 %% there %.2f %.2f; rule sigma %.3f\n",
           o->bspec[ib], fl, zpa / SL_G, pz[0], fpk[0], pz[1], fpk[1], r25[0], r25[1], s_rule);
    printf("  physical: sigma_ln larger-H PGA %.3f (H1 %.3f, H2 %.3f, correlation %.2f); peaks "
           "above 0.9 PGA %.1f (max %zu); D5-75 %.1f s\n",
           dp.s_pga, dp.s_h1, dp.s_h2, dp.rho, dp.peaks, dp.peaks_max, dp.d575);
    if (o->descr_only) {
        printf("DATA %s %zu %.3f %.3f %.3f %.3f %.3f %.3f %.3f %.3f %.3f %.3f\n", o->bspec[ib], fl,
               pz[0], fpk[0], pz[1], fpk[1], r25[0], r25[1], dp.s_pga, dp.s_h1, dp.s_h2, s_rule);
        goto done;
    }
    double *phys = slide(fm, nrec, mu, NMU);
    /* the physical motions at one intensity: H scaled to the mean larger-H PGA (V as it is) */
    sl_set *fn = xcalloc(nrec, sizeof *fn);
    for (size_t r = 0; r < nrec; r++)
        if (sl_set_scaled_h_copy(&fm[r], zpa / sl_set_pga_h(&fm[r]), &fn[r], &e))
            die(&e);
    double *physn = slide(fn, nrec, mu, NMU);
    sl_synth_set *out;
    sl_set *syn = synth(o, flr, 0, &out);
    describe(syn, o->nsyn, &ds);
    printf("  synthesized: sigma_ln larger-H PGA %.3f; peaks above 0.9 PGA %.1f (max %zu); D5-75 "
           "%.1f s\n",
           ds.s_pga, ds.peaks, ds.peaks_max, ds.d575);
    double *s0 = slide(syn, o->nsyn, mu, NMU);
    sl_scatter *lat = sl_scatter_alloc(SIG_LAT, mu, NMU, &e);
    if (!lat)
        die(&e);
    size_t nL;
    const double *L = sl_scatter_grid(lat, &nL);
    double *uL = slide(syn, o->nsyn, L, nL);
    double sig[NVAR] = {0, FORMER, dp.s_pga, s_rule, o->fixed};
    const char *nm[NVAR] = {"sigma 0", "sigma 0.30", "sigma = physical PGA's", "rule", "-R"};
    double *y[NVAR];
    for (int v = 0; v < NVAR; v++) {
        y[v] = NULL;
        if (v == 4 && !(o->fixed >= 0))
            continue;
        y[v] = xcalloc(o->nsyn * NMU, sizeof *y[v]);
        if (sig[v] > 0)
            scatter_y(sig[v], mu, o->nsyn, L, nL, uL, y[v]);
        else
            memcpy(y[v], s0, o->nsyn * NMU * sizeof *s0);
    }
    double sst = sigma_star(mu, o->nsyn, L, nL, uL, phys, nrec);
    if (o->experiments)
        experiments(o, flr, fm, fn, nrec, syn, mu, s_rule, dp.rho, phys, physn);
    if (o->dump) {
        fprintf(o->dump, "F %s %zu %.4f %.4f %.4f %.4f %.4f %.4f %.4f %.4f %.4f %.4f %.2f %.2f %.2f %.2f\n",
                o->bspec[ib], fl, pz[0], fpk[0], pz[1], fpk[1], r25[0], r25[1], dp.s_pga,
                dp.s_h1, dp.s_h2, dp.rho, dp.peaks, ds.peaks, dp.d575, ds.d575);
        dump_row(o->dump, "P", o->bspec[ib], fl, 0, phys, nrec);
        dump_row(o->dump, "Q", o->bspec[ib], fl, 0, physn, nrec);
        double *yy = xcalloc(o->nsyn * NMU, sizeof *yy);
        dump_row(o->dump, "Y", o->bspec[ib], fl, 0, s0, o->nsyn);
        for (int t = 1; t <= (int)lround(SIG_LAT * 100); t++) {
            scatter_y(0.01 * t, mu, o->nsyn, L, nL, uL, yy);
            dump_row(o->dump, "Y", o->bspec[ib], fl, 0.01 * t, yy, o->nsyn);
        }
        free(yy);
        fflush(o->dump);
    }
    printf("\n| %s floor %zu | μg/ZPA 0.1 | 0.2 | 0.3 | 0.4 | 0.5 | 0.6 | 0.7 | 0.8 | 0.9 | 1.0 "
           "|\n|---|---|---|---|---|---|---|---|---|---|---|\n| physical mean, mm (SE %%) |",
           o->bspec[ib], fl);
    double pse[NMU];
    for (int k = 0; k < NMU; k++) {
        double m, sd;
        sl_pf_mean_sd(phys + k, nrec, NMU, &m, &sd);
        pse[k] = sd / sqrt((double)nrec) / m;
        printf(" %.2f (%.0f) |", 1e3 * m, 100 * pse[k]);
    }
    printf("\n");
    for (int v = 0; v < NVAR; v++) {
        if (!y[v])
            continue;
        printf("| syn, %s (%.2f) / physical |", nm[v], sig[v]);
        for (int k = 0; k < NMU; k++) {
            double se, r = sl_pf_ratio(y[v] + k, o->nsyn, NMU, phys + k, nrec, NMU, &se);
            printf(" %.2f ± %.2f |", r, se);
            if (!(r > 0))
                r = 1e-3;
            if (k >= 4) {
                sum->lr_hi[v] += log(r);
                if (pse[k] <= SE_OK)
                    sum->min_hi[v] = fmin(sum->min_hi[v], r);
            } else {
                sum->lr_lo[v] += log(r);
            }
        }
        printf("\n");
    }
    sum->n_hi += NMU - 4;
    sum->n_lo += 4;
    printf("| physical at one PGA / physical |");
    for (int k = 0; k < NMU; k++) {
        double se, r = sl_pf_ratio(physn + k, nrec, NMU, phys + k, nrec, NMU, &se);
        printf(" %.2f ± %.2f |", r, se);
    }
    printf("\n| syn, sigma 0 / physical at one PGA |");
    for (int k = 0; k < NMU; k++) {
        double se, r = sl_pf_ratio(s0 + k, o->nsyn, NMU, physn + k, nrec, NMU, &se);
        printf(" %.2f ± %.2f |", r, se);
    }
    printf("\n  sigma that fits at μg/ZPA 0.5-1.0: %.2f\n", sst);
    printf("DATA %s %zu %.3f %.3f %.3f %.3f %.3f %.3f %.3f %.3f %.3f %.3f %.2f %.1f %.1f\n",
           o->bspec[ib], fl, pz[0], fpk[0], pz[1], fpk[1], r25[0], r25[1], dp.s_pga, dp.s_h1,
           dp.s_h2, s_rule, sst, dp.peaks, ds.peaks);
    for (int v = 0; v < NVAR; v++)
        free(y[v]);
    free(uL);
    sl_scatter_free(lat);
    free(s0);
    for (size_t k = 0; k < o->nsyn; k++)
        sl_synth_set_clear(&out[k]);
    free(out);
    free(syn);
    free(phys);
    free(physn);
    for (size_t r = 0; r < nrec; r++)
        sl_set_free_motions(&fn[r]);
    free(fn);
done:
    sl_floor_free(flr);
    for (size_t r = 0; r < nrec; r++)
        sl_set_free_motions(&fm[r]);
    free(fm);
}

/* -g: sigma of ln SA(f, zeta) over the H components of the records, each
 * record scaled to one larger horizontal PGA (method/scatter.h (R4)) */
static void ground_scatter(const sl_set *g, size_t nrec)
{
    enum { NG = 25 };
    static const double zeta[3] = {0.02, 0.05, 0.10};
    double f[NG], *ls = xcalloc(2 * nrec * NG, sizeof *ls);
    for (int j = 0; j < NG; j++)
        f[j] = 0.1 * pow(10.0, (double)j / 8.0); /* 0.1-100 Hz, 8 a decade: to 50 */
    printf("\n| f, Hz | sigma_ln SA, 2 %% | 5 %% | 10 %% |\n|---|---|---|---|\n");
    double sd[3][NG];
    for (int z = 0; z < 3; z++) {
        for (size_t q = 0; q < 2 * nrec; q++) {
            const sl_motion *m = q % 2 ? g[q / 2].h2 : g[q / 2].h1;
            sl_error e;
            if (sl_spectrum_compute(m->acc_ms2, m->n, m->dt_s, f, NG, zeta[z], ls + q * NG, NULL,
                                    NULL, &e))
                die(&e);
        }
        for (int j = 0; j < NG; j++) {
            double m = 0, v = 0;
            for (size_t q = 0; q < 2 * nrec; q++)
                m += log(ls[q * NG + j]) / (double)(2 * nrec);
            for (size_t q = 0; q < 2 * nrec; q++)
                v += pow(log(ls[q * NG + j]) - m, 2) / (double)(2 * nrec - 1);
            sd[z][j] = sqrt(v);
        }
    }
    for (int j = 0; j < NG && f[j] <= 50.5; j++)
        printf("| %.3g | %.3f | %.3f | %.3f |\n", f[j], sd[0][j], sd[1][j], sd[2][j]);
    free(ls);
}

/* -m: the summary as a markdown table; the ratios are synthesized / physical
 * (geometric means over a building's floors and the mu g/ZPA named) */
static void summary_head(FILE *md, size_t nrec, const char *rdir, size_t nsyn, uint64_t seed)
{
    fprintf(md, "Physical floor motions: %zu usable records of %s, larger horizontal PGA scaled "
            "to %.1f g, through each building (storeys, first modes of H1 / H2, damping). "
            "Synthesized: %zu sets per floor (seed %llu). Ratios: synthesized / physical mean "
            "sliding, geometric means over the building's floors at mu g/ZPA 0.5, 0.6, ..., "
            "1.0 (the threshold tail) or 0.1-0.4; the smallest point is over those at 0.5-1.0 "
            "whose physical mean has a relative SE of at most %.0f %%.\n\n",
            nrec, rdir, PGA_G, nsyn, (unsigned long long)seed, 100 * SE_OK);
    fprintf(md, "| building | floors' f_c, Hz | sigma (R4) | at 0.5-1.0: no scatter | former "
            "0.30 | **sigma (R4)** | its smallest point | at 0.1-0.4: 0.30 | sigma (R4) |\n"
            "|---|---|---|---|---|---|---|---|---|\n");
}

static void summary_row(FILE *md, const sl_building *b, const tf_sum *s)
{
    double hi = (double)s->n_hi, lo = (double)s->n_lo;
    fprintf(md, "| %zu, %.1f / %.1f Hz, %g %% | %.1f-%.1f | %.2f-%.2f | %.2f | %.2f | **%.2f** | "
            "%.2f | %.2f | %.2f |\n",
            b->storeys, b->f1_hz[0], b->f1_hz[1], 100 * b->damping, s->fc_lo, s->fc_hi,
            s->sig_lo, s->sig_hi, exp(s->lr_hi[0] / hi), exp(s->lr_hi[1] / hi),
            exp(s->lr_hi[3] / hi), s->min_hi[3], exp(s->lr_lo[1] / lo), exp(s->lr_lo[3] / lo));
}

static int parse_options(int argc, char **argv, tf_opts *o)
{
    memset(o, 0, sizeof *o);
    o->nsyn = 24;
    o->seed = 12;
    o->fixed = NAN;
    int opt;
    sl_error e;
    while ((opt = getopt(argc, argv, "r:n:s:S:b:dgxR:D:m:")) != -1) {
        switch (opt) {
        case 'r': o->records = optarg; break;
        case 'n': o->max_records = (size_t)atol(optarg); break;
        case 's': o->nsyn = (size_t)atol(optarg); break;
        case 'S': o->seed = (uint64_t)atoll(optarg); break;
        case 'd': o->descr_only = 1; break;
        case 'g': o->ground_scatter = 1; break;
        case 'x': o->experiments = 1; break;
        case 'R': o->fixed = atof(optarg); break;
        case 'D':
            if (!(o->dump = fopen(optarg, "w"))) {
                fprintf(stderr, "tailfloors: cannot write %s\n", optarg);
                return 1;
            }
            break;
        case 'm':
            if (!(o->md = fopen(optarg, "w"))) {
                fprintf(stderr, "tailfloors: cannot write %s\n", optarg);
                return 1;
            }
            break;
        case 'b':
            if (o->nb == MAX_B) {
                fprintf(stderr, "tailfloors: at most %d buildings\n", MAX_B);
                return 1;
            }
            if (sl_building_parse(optarg, &o->b[o->nb], &e))
                die(&e);
            o->bspec[o->nb++] = optarg;
            break;
        default:
            fprintf(stderr, "usage: tailfloors [-r dir] [-n max] [-s nsyn] [-S seed] "
                            "[-b N:f1_h1:f1_h2:f1_v:damping]... [-d] [-g] [-x] [-R sigma] [-D dumpfile] "
                            "[-m summary.md]\n");
            return 1;
        }
    }
    if (o->nsyn < 2) {
        fprintf(stderr, "tailfloors: -s %zu: at least 2 sets\n", o->nsyn);
        return 1;
    }
    if (!isnan(o->fixed) && !(o->fixed >= 0 && o->fixed <= SIG_LAT)) {
        fprintf(stderr, "tailfloors: -R %g outside [0, %g]\n", o->fixed, SIG_LAT);
        return 1;
    }
    for (size_t i = 0; o->nb == 0 && i < sizeof default_b / sizeof *default_b; i++) {
        if (sl_building_parse(default_b[i], &o->b[i], &e))
            die(&e);
        o->bspec[i] = default_b[i];
    }
    if (o->nb == 0)
        o->nb = sizeof default_b / sizeof *default_b;
    return 0;
}

int main(int argc, char **argv)
{
    tf_opts o;
    setvbuf(stdout, NULL, _IOLBF, 0);
    if (parse_options(argc, argv, &o))
        return 1;
    char buf[1024];
    const char *rdir = sl_pf_records_dir(o.records, buf, sizeof buf);
    sl_error e;
    sl_set *g;
    size_t nrec;
    if (sl_pf_read_records(rdir, o.max_records, PGA_G * SL_G, &g, &nrec, NULL, &e))
        die(&e);
    if (nrec < 2) {
        fprintf(stderr, "tailfloors: fewer than 2 records of %s pass the rule\n", rdir);
        return 1;
    }
    printf("records: %zu of %s, scaled to %.1f g; %zu synthesized sets per floor, seed %llu\n",
           nrec, rdir, PGA_G, o.nsyn, (unsigned long long)o.seed);
    if (o.md)
        summary_head(o.md, nrec, rdir, o.nsyn, o.seed);
    if (o.ground_scatter)
        ground_scatter(g, nrec);
    for (size_t ib = 0; !o.ground_scatter && ib < o.nb; ib++) {
        tf_sum sum;
        memset(&sum, 0, sizeof sum);
        for (int v = 0; v < NVAR; v++)
            sum.min_hi[v] = INFINITY;
        sum.sig_lo = sum.fc_lo = INFINITY;
        sum.sig_hi = sum.fc_hi = -INFINITY;
        for (size_t fl = 1; fl <= o.b[ib].storeys; fl++)
            floor_case(&o, ib, fl, g, nrec, &sum);
        if (o.descr_only)
            continue;
        printf("\nSUMMARY %s: geometric mean of synthesized / physical at μg/ZPA 0.5-1.0 "
               "(0.1-0.4), smallest point at 0.5-1.0 where the physical SE <= %.0f %%:\n",
               o.bspec[ib], 100 * SE_OK);
        const char *nm[NVAR] = {"sigma 0", "sigma 0.30", "sigma = physical PGA's", "rule", "-R"};
        for (int v = 0; v < NVAR; v++)
            if (v < 4 || o.fixed >= 0)
                printf("  %-24s %.3f (%.3f), smallest %.2f\n", nm[v],
                       exp(sum.lr_hi[v] / (double)sum.n_hi), exp(sum.lr_lo[v] / (double)sum.n_lo),
                       sum.min_hi[v]);
        if (o.md)
            summary_row(o.md, &o.b[ib], &sum);
    }
    if (o.md && fclose(o.md)) {
        fprintf(stderr, "tailfloors: cannot write the summary table\n");
        return 1;
    }
    sl_pf_sets_free(g, nrec);
    return 0;
}
