/*
 * physfloors.c - the full comparison of docs/synthesis.md 10: synthesized
 * floor sets against physical floor motions made from many real records,
 * with standard errors (study/physfloor.h, study/building.h).
 *
 *   make physfloors            (or build/tools/physfloors [options])
 *   options: -r RECORDS_DIR (default $SEISLIDE_SHARED/records or
 *            ../shared/records), -n MAX_RECORDS (0 = all), -s NSYN (24),
 *            -S SEED (12), -x (swap experiments), -a PGA_SIGMA (synth.h
 *            pga_sigma), -g (ground check only), -G (no ground),
 *            -F FMAX (floor spectra end at FMAX Hz, 50), -R SIGMA (record-to-
 *            record intensity scatter of the synthesized floor sets as the run
 *            applies it, method/scatter.h (R3); default the run's: each
 *            floor's own sigma, (R4); 0 = none;
 *            -B N:f1_h1:f1_h2:f1_v:damping (the building, study/building.h;
 *            default 3:3.0:4.2:14:0.05, the building of docs/synthesis.md 10);
 *            the ground comparison has none: both sides are matched sets);
 *            -x also moves H2 peaks (coincident, records' lags) and describes
 *            the records as recorded with each H scaled to 0.3 g and prints how
 *            their 5 % spectra scatter about their mean; -0 adds
 *            "floor 0": the records themselves (scaled to 0.3 g) as the
 *            physical motions behind a floor spectrum; -c CYCLES and -H HOLD
 *            (synth.h wavelet_cycles, hold_frac), -Y SIGMA (spectral-shape
 *            scatter experiment, see Shape); -P (ground) also matches each
 *            record's two horizontals with one common correction (their
 *            geometric-mean spectrum to RG 1.60; -Q: the larger of the two
 *            spectra at each frequency), keeping its polarization, and
 *            compares. Every ensemble is described:
 *            vector peak / larger H PGA (also with the axes turned 45 deg: a
 *            population of real motions does not depend on the axes), H1-H2
 *            peak lag, sliding threshold / larger PGA (10/50/90 %), time the
 *            H vector spends above 0.9 x the larger PGA, peaks of |a| above
 *            0.9 PGA per H component (mean, max), D5-75, V/A (mean, CoV over sets)
 * Prints markdown tables; exit 0, or 1 with a message on bad input.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <fftw3.h>
#include <gsl/gsl_cdf.h>

#include "analysis.h"
#include "core/compare.h"
#include "core/units.h"
#include "io/floor.h"
#include "io/setdir.h"
#include "signal/realism.h"
#include "signal/spectrum.h"
#include "slide/slide.h"
#include "study/building.h"
#include "study/physfloor.h"
#include "study/study.h"
#include "method/scatter.h"
#include "synth/synth.h"

#define NMU 5
#define NF 136
#define PGA_G 0.3

/* What the options ask for (parse_options), passed down to every part. */
typedef struct pf_opts {
    const char *records;   /* -r: the records directory */
    size_t max_records;    /* -n: at most this many records used, 0 = all */
    size_t nsyn;           /* -s: synthesized sets per case */
    uint64_t seed;         /* -S */
    int experiments;       /* -x: the swap experiments */
    int ground_only;       /* -g */
    int no_ground;         /* -G */
    int floor0;            /* -0: "floor 0", the records themselves */
    int pair_match;        /* -P or -Q: each record's pair matched with one correction */
    int pair_max;          /* -Q: the larger of the two spectra instead of their geometric mean */
    double f_end_hz;       /* -F: the floor spectra end here */
    sl_building building;  /* -B N:f1_h1:f1_h2:f1_v:damping (study/building.h) */
    /* -R: intensity scatter of the synthesized floor sets, as `seislide run`
     * applies it (method/scatter.h (R3); default the run's) */
    double scatter;
    /* -Y: log standard deviation of a long-period spectral-shape scatter of
     * the synthesized H targets (set k: T exp(Y w z_k - Y^2 w^2/2), w = 0
     * above 5 Hz rising to 1 at 0.5 Hz in log f, z_k stratified normal
     * quantiles); an experiment only (docs/synthesis.md 12), 0 = none */
    double shape;
    sl_synth_params synth; /* -a, -H, -c: the synthesis */
} pf_opts;

static void die(const sl_error *e)
{
    char buf[2200];
    fprintf(stderr, "physfloors: %s\n", sl_error_format(e, buf, sizeof buf));
    exit(1);
}

/* peaks[i * NMU + k] of sets at mu[] */
static double *slide(const sl_set *sets, size_t n, const double *mu)
{
    sl_slide_opts so;
    sl_slide_opts_default(&so);
    sl_slide_result *res = calloc(n * NMU, sizeof *res);
    double *pk = malloc(n * NMU * sizeof *pk);
    sl_error e;
    if (!res || !pk || sl_slide_batch(sets, n, mu, NMU, &so, res, &e))
        die(&e);
    for (size_t i = 0; i < n * NMU; i++)
        pk[i] = res[i].peak_m;
    free(res);
    return pk;
}

/* As slide(), with the run's intensity scatter: each set's expected peak
 * over its intensity factor (method/scatter.h (R3)); sigma -R, or by
 * default the floor's, sigma_floor (R4). */
static double *slide_floor(const pf_opts *o, const sl_set *sets, size_t n, const double *mu,
                           double sigma_floor)
{
    const double sigma = o->scatter < 0 ? sigma_floor : o->scatter;
    printf("  intensity scatter of the synthesized sets: %.3f%s\n", sigma,
           o->scatter < 0 ? " (the floor's, method/scatter.h (R4))" : " (-R)");
    if (!(sigma > 0))
        return slide(sets, n, mu);
    sl_error e;
    sl_slide_opts so;
    sl_slide_opts_default(&so);
    sl_scatter *sc = sl_scatter_alloc(sigma, mu, NMU, &e);
    double *pk = malloc(n * NMU * sizeof *pk);
    if (!sc || !pk || sl_scatter_slide_batch(sc, sets, n, &so, pk, NULL, &e))
        die(&e);
    sl_scatter_free(sc);
    return pk;
}

static void describe(const char *what, const sl_set *sets, size_t n)
{
    if (n == 0) {
        fprintf(stderr, "physfloors: %s: no sets to describe\n", what);
        exit(1);
    }
    sl_slide_opts so;
    sl_slide_opts_default(&so);
    size_t nth = 0, npk_max = 0;
    double npk = 0, th = 0, pg = 0, pc = 0, s50 = 0, f50 = 50.0, hw = 0, vr = 0, ct = 0, d575 = 0, vr45 = 0, va1 = 0, va2 = 0;
    double *lag = malloc(n * sizeof *lag), *thr = malloc(n * sizeof *thr), *exc = malloc(n * sizeof *exc);
    for (size_t i = 0; i < n; i++) {
        size_t ipk[2] = {0, 0};
        for (int c = 0; c < 2; c++) {
            const sl_motion *m = c ? sets[i].h2 : sets[i].h1;
            /* duration of the half-cycle holding the PGA (sign change to sign change) */
            size_t ip = 0;
            for (size_t j = 0; j < m->n; j++)
                ip = fabs(m->acc_ms2[j]) > fabs(m->acc_ms2[ip]) ? j : ip;
            size_t j0 = ip, j1 = ip;
            while (j0 > 0 && (m->acc_ms2[j0 - 1] > 0) == (m->acc_ms2[ip] > 0))
                j0--;
            while (j1 + 1 < m->n && (m->acc_ms2[j1 + 1] > 0) == (m->acc_ms2[ip] > 0))
                j1++;
            hw += m->dt_s * (double)(j1 - j0 + 1) / (2.0 * (double)n);
            ipk[c] = ip;
            double sa;
            sl_error e;
            if (sl_spectrum_compute(m->acc_ms2, m->n, m->dt_s, &f50, 1, 0.05, &sa, NULL, NULL,
                                    &e) == SL_OK)
                s50 += sa / sl_motion_pga(m) / (2.0 * (double)n);
        }
        double th_i = sl_slide_mu_threshold(&sets[i], &so);
        if (isfinite(th_i)) /* infinite when the vertical lifts the block */
            th += th_i, nth++;
        thr[i] = th_i * SL_G / sl_set_pga_h(&sets[i]);
        lag[i] = fabs((double)ipk[0] - (double)ipk[1]) * sets[i].h1->dt_s;
        double vp = 0, p45a = 0, p45b = 0; /* vector peak; PGAs of the axes turned 45 deg */
        for (size_t j = 0; j < sets[i].h1->n && j < sets[i].h2->n; j++) {
            double x = sets[i].h1->acc_ms2[j], y = sets[i].h2->acc_ms2[j];
            vp = fmax(vp, hypot(x, y));
            p45a = fmax(p45a, fabs(x + y) / sqrt(2.0));
            p45b = fmax(p45b, fabs(y - x) / sqrt(2.0));
        }
        vr45 += vp / fmax(p45a, p45b) / (double)n;
        vr += vp / sl_set_pga_h(&sets[i]) / (double)n;
        d575 += 0.5 * (sl_motion_d5_75(sets[i].h1) + sl_motion_d5_75(sets[i].h2)) / (double)n;
        /* V/A of a set: the mean of its two H components, m/s per g; its
         * scatter over the sets (one value per set: the two H of a record
         * are not independent) */
        double va = 0;
        for (int c = 0; c < 2; c++) {
            const sl_motion *mc = c ? sets[i].h2 : sets[i].h1;
            va += 0.5 * sl_motion_pgv(mc) / sl_motion_pga(mc) * SL_G;
        }
        va1 += va / (double)n;
        va2 += va * va;
        for (int c = 0; c < 2; c++) { /* peaks of |a| above 0.9 PGA per H component */
            const sl_motion *mc = c ? sets[i].h2 : sets[i].h1;
            size_t np = sl_realism_peaks_above(mc->acc_ms2, mc->n, 0.9);
            npk += (double)np / (2.0 * (double)n);
            npk_max = np > npk_max ? np : npk_max;
        }
        for (int c = 0; c < 2; c++) { /* each H component's time above 0.9 x its PGA */
            const sl_motion *mc = c ? sets[i].h2 : sets[i].h1;
            double pm = sl_motion_pga(mc);
            for (size_t j = 0; j < mc->n; j++)
                ct += mc->dt_s * (fabs(mc->acc_ms2[j]) > 0.9 * pm) / (2.0 * (double)n);
        }
        exc[i] = 0; /* time the H vector spends above 0.9 x the larger H PGA */
        const double lvl = 0.9 * sl_set_pga_h(&sets[i]);
        for (size_t j = 0; j < sets[i].h1->n && j < sets[i].h2->n; j++)
            exc[i] += sets[i].h1->dt_s *
                      (hypot(sets[i].h1->acc_ms2[j], sets[i].h2->acc_ms2[j]) > lvl);
        pg += sl_set_pga_h(&sets[i]) / SL_G / (double)n;
        pc += 0.5 * (sl_motion_pga(sets[i].h1) + sl_motion_pga(sets[i].h2)) / SL_G / (double)n;
    }
    th = nth ? th / (double)nth : NAN;
    /* sample standard deviation of the per-set V/A (n - 1) */
    double va_sd = n > 1 ? sqrt(fmax(va2 - (double)n * va1 * va1, 0) / (double)(n - 1)) : 0;
    printf("  %s (%zu sets): mean threshold mu %.3f (of the %zu finite), mean larger H PGA %.3f g, mean H component "
           "PGA %.3f g, ratio %.3f, SA(50 Hz)/PGA %.3f, PGA half-cycle %.3f s\n",
           what, n, th, nth, pg, pc, pg / pc, s50, hw);
    qsort(lag, n, sizeof *lag, sl_cmp_double);
    size_t w01 = 0, w05 = 0;
    for (size_t i = 0; i < n; i++)
        w01 += lag[i] <= 0.1, w05 += lag[i] <= 0.5;
    double lag_med = n % 2 ? lag[n / 2] : 0.5 * (lag[n / 2 - 1] + lag[n / 2]);
    printf("    H vector peak / larger H PGA %.3f (axes turned 45 deg: %.3f); |time between the H1 and H2 peaks|: median %.2f s, "
           "<= 0.1 s in %.0f %%, <= 0.5 s in %.0f %%\n", vr, vr45, lag_med,
           100.0 * (double)w01 / (double)n, 100.0 * (double)w05 / (double)n);
    qsort(thr, n, sizeof *thr, sl_cmp_double);
    qsort(exc, n, sizeof *exc, sl_cmp_double);
    printf("    threshold mu g / larger H PGA: 10/50/90 %% %.3f %.3f %.3f; H vector time above 0.9 "
           "larger PGA: 10/50/90 %% %.3f %.3f %.3f s; H component above 0.9 PGA: mean %.3f s, peaks above 0.9 PGA mean %.1f (max %zu), D5-75 %.1f s; H V/A mean %.2f m/s per g, CoV %.2f\n", thr[n / 10], thr[n / 2], thr[9 * n / 10],
           exc[n / 10], exc[n / 2], exc[9 * n / 10], ct, npk, npk_max, d575, va1, va_sd / va1);
    free(lag);
    free(thr);
    free(exc);
}

/* How the 5 % spectra of the H components of sets[0..n-1] scatter about
 * their mean (docs/synthesis.md 12): sigma of ln(SA / mean SA) at a few
 * frequencies, and the correlation of the residuals with those at 0.5 Hz. */
static void shape_scatter(const sl_set *sets, size_t n)
{
    enum { NS = 9, REF = 2 };
    static const double f[NS] = {0.1, 0.2, 0.5, 1, 2, 5, 10, 20, 50};
    const size_t m = 2 * n;
    double *ls = malloc(m * NS * sizeof *ls), mean[NS] = {0}, lr[NS] = {0};
    if (!ls || m < 3) {
        free(ls);
        return;
    }
    for (size_t q = 0; q < m; q++) {
        const sl_motion *mo = q % 2 ? sets[q / 2].h2 : sets[q / 2].h1;
        sl_error e;
        if (sl_spectrum_compute(mo->acc_ms2, mo->n, mo->dt_s, f, NS, 0.05, ls + q * NS, NULL,
                                NULL, &e))
            die(&e);
        for (int j = 0; j < NS; j++)
            mean[j] += ls[q * NS + j] / (double)m;
    }
    for (size_t q = 0; q < m; q++)
        for (int j = 0; j < NS; j++) {
            ls[q * NS + j] = log(ls[q * NS + j] / mean[j]);
            lr[j] += ls[q * NS + j] / (double)m;
        }
    printf("    5 %% spectra of the %zu H components about their mean: f Hz / sigma of ln(SA/mean) / "
           "correlation with 0.5 Hz:", m);
    for (int j = 0; j < NS; j++) {
        double sjj = 0, srr = 0, sjr = 0;
        for (size_t q = 0; q < m; q++) {
            double a = ls[q * NS + j] - lr[j], b = ls[q * NS + REF] - lr[REF];
            sjj += a * a, srr += b * b, sjr += a * b;
        }
        printf(" %g/%.2f/%.2f", f[j], sqrt(sjj / (double)(m - 1)), sjr / sqrt(sjj * srr));
    }
    printf("\n");
    free(ls);
}

/* -P: a pair of horizontals matched to the target T (5 %) with ONE
 * correction for both (docs/synthesis.md 12): each iteration multiplies
 * the DFT of both components by r(f) = T(f) / sqrt(S1(f) S2(f)) (the
 * geometric mean of their spectra; -Q: T / max(S1, S2); log-linear in log f between 60 grid
 * points over 0.1-50 Hz, fading to 1 one octave outside; the first
 * iteration also applies the zero-phase Butterworth high-pass of the
 * synthesis), so the record's polarization (the ratio and the phase of the
 * two components at each frequency) is kept. Returns the largest
 * |ln(S / T)| left; *o1, *o2 the matched motions. */
static double pair_match(const pf_opts *o, const sl_motion *h1, const sl_motion *h2,
                         const sl_spectrum *T, sl_motion **o1, sl_motion **o2)
{
    enum { NG = 60, ITER = 20 };
    double dt = sl_synth_match_dt(h1->dt_s);
    sl_motion *m1 = sl_synth_resample_motion(h1, dt), *m2 = sl_synth_resample_motion(h2, dt);
    if (!m1 || !m2) {
        fprintf(stderr, "physfloors: cannot resample %s\n", h1->label);
        exit(1);
    }
    size_t n = m1->n < m2->n ? m1->n : m2->n, nfft = 1;
    while (nfft < n + (size_t)ceil(1.0 / (0.1 * dt)))
        nfft *= 2;
    size_t nb = nfft / 2 + 1;
    double *a[2] = {m1->acc_ms2, m2->acc_ms2}, *buf = fftw_malloc(nfft * sizeof *buf);
    fftw_complex *X = fftw_malloc(nb * sizeof *X);
    /* r on the grid, as a spectrum so that sl_spectrum_interp gives its
     * log-log interpolation at each bin */
    sl_spectrum *r = sl_spectrum_alloc(NG, 0.05);
    if (!buf || !X || !r) {
        fprintf(stderr, "physfloors: out of memory\n");
        exit(1);
    }
    fftw_plan fw = fftw_plan_dft_r2c_1d((int)nfft, buf, X, FFTW_ESTIMATE);
    fftw_plan bw = fftw_plan_dft_c2r_1d((int)nfft, X, buf, FFTW_ESTIMATE);
    double *f = r->f_hz, t[NG], s1[NG], s2[NG], worst = INFINITY;
    for (int j = 0; j < NG; j++) {
        f[j] = 0.1 * pow(500.0, (double)j / (NG - 1));
        t[j] = sl_spectrum_interp(T, f[j]);
    }
    const double fc = o->synth.hp_frac * 0.1;
    for (int it = 0; it <= ITER; it++) {
        sl_error e;
        if (sl_spectrum_compute(a[0], n, dt, f, NG, 0.05, s1, NULL, NULL, &e) ||
            sl_spectrum_compute(a[1], n, dt, f, NG, 0.05, s2, NULL, NULL, &e))
            die(&e);
        worst = 0;
        for (int j = 0; j < NG; j++) {
            r->sa_ms2[j] = t[j] / (o->pair_max ? fmax(s1[j], s2[j]) : sqrt(s1[j] * s2[j]));
            worst = fmax(worst, fabs(log(r->sa_ms2[j])));
        }
        if (it == ITER || worst < 0.02)
            break;
        for (int c = 0; c < 2; c++) {
            for (size_t k = 0; k < nfft; k++)
                buf[k] = k < n ? a[c][k] : 0.0;
            fftw_execute(fw);
            X[0][0] = X[0][1] = 0;
            for (size_t k = 1; k < nb; k++) {
                double fk = (double)k / ((double)nfft * dt), g;
                if (fk <= f[0]) /* fading to 1 over one octave outside */
                    g = pow(r->sa_ms2[0], fmax(0.0, 1.0 - log2(f[0] / fk)));
                else if (fk >= f[NG - 1])
                    g = pow(r->sa_ms2[NG - 1], fmax(0.0, 1.0 - log2(fk / f[NG - 1])));
                else
                    g = sl_spectrum_interp(r, fk);
                if (it == 0 && fc > 0)
                    g /= sqrt(1 + pow(fc / fk, 2 * o->synth.hp_order));
                X[k][0] *= g;
                X[k][1] *= g;
            }
            fftw_execute(bw);
            for (size_t k = 0; k < n; k++)
                a[c][k] = buf[k] / (double)nfft;
        }
    }
    *o1 = sl_motion_from_array(a[0], n, dt, h1->label);
    *o2 = sl_motion_from_array(a[1], n, dt, h2->label);
    fftw_destroy_plan(fw);
    fftw_destroy_plan(bw);
    fftw_free(buf);
    fftw_free(X);
    sl_spectrum_free(r);
    sl_motion_free(m1);
    sl_motion_free(m2);
    return worst;
}

/* "| label | R ± SE ... |", '*' where |R - 1| > 2 SE */
static void row(const char *label, const double *a, size_t na, const double *b, size_t nb)
{
    printf("| %s |", label);
    for (int k = 0; k < NMU; k++) {
        double se, r = sl_pf_ratio(a + k, na, NMU, b + k, nb, NMU, &se);
        printf(" %.2f ± %.2f%s |", r, se, fabs(r - 1) > 2 * se ? "*" : "");
    }
    printf("\n");
}

/* o->nsyn sets for tgt; shape > 0: the -Y experiment (floors only) */
static sl_synth_set *synth(const pf_opts *o, const sl_synth_target *tgt, double shape,
                           sl_set *sets)
{
    const size_t nsyn = o->nsyn;
    const uint64_t seed = o->seed;
    sl_error e;
    sl_synth *s = sl_synth_alloc(4001, 0.005, &o->synth, &e);
    sl_synth_set *out = calloc(nsyn, sizeof *out);
    if (!s || !out)
        die(&e);
    if (shape > 0) { /* -Y: spectral-shape scatter experiment (docs/synthesis.md 12) */
        for (size_t k = 0; k < nsyn; k++) {
            double z = gsl_cdf_ugaussian_Pinv(((double)k + 0.5) / (double)nsyn);
            sl_synth_target tk[3] = {tgt[0], tgt[1], tgt[2]};
            sl_spectrum *sp[2];
            for (int c = 0; c < 2; c++) {
                const sl_spectrum *t0 = tgt[c].spec;
                sp[c] = sl_spectrum_alloc(t0->n, t0->damping);
                for (size_t j = 0; j < t0->n; j++) {
                    double w = log10(5.0 / t0->f_hz[j]);
                    w = w < 0 ? 0 : w > 1 ? 1 : w;
                    sp[c]->f_hz[j] = t0->f_hz[j];
                    sp[c]->sa_ms2[j] = t0->sa_ms2[j] * exp(shape * w * z - 0.5 * shape * shape * w * w);
                }
                tk[c].spec = sp[c];
            }
            sl_status st = sl_synth_make_sets(s, tk, seed, k, 1, &out[k], NULL, NULL, &e);
            if (st && st != SL_ENOCONV)
                die(&e);
            sl_spectrum_free(sp[0]);
            sl_spectrum_free(sp[1]);
        }
    } else {
        sl_status st = sl_synth_make_sets(s, tgt, seed, 0, nsyn, out, NULL, NULL, &e);
        if (st && st != SL_ENOCONV)
            die(&e);
    }
    size_t nfail = 0;
    double pz = 0, lo = 0, hi = 0, fhi = 0;
    for (size_t k = 0; k < nsyn; k++) {
        sets[k] = out[k].set;
        nfail += !out[k].pass;
        for (int c = 0; c < 2; c++) {
            pz += out[k].check[c].pga_zpa / (2.0 * (double)nsyn);
            lo += out[k].check[c].min_ratio / (2.0 * (double)nsyn);
            hi += out[k].check[c].max_ratio / (2.0 * (double)nsyn);
            fhi += (out[k].check[c].f_min_ratio_hz > 25) / (2.0 * (double)nsyn);
        }
    }
    printf("  synthesized H components: mean PGA/ZPA %.3f, mean lowest S/T %.3f (above 25 Hz "
           "in %.0f %%), highest %.3f\n",
           pz, lo, 100 * fhi, hi);
    if (nfail)
        printf("  (%zu of %zu synthesized sets fail a check)\n", nfail, nsyn);
    sl_synth_free(s);
    return out;
}

/* a copy of m delayed by lag samples (zeros before; the last lag dropped) */
static sl_motion *delayed(const sl_motion *m, size_t lag)
{
    double *a = calloc(m->n, sizeof *a);
    for (size_t i = lag; i < m->n; i++)
        a[i] = m->acc_ms2[i - lag];
    sl_motion *o = sl_motion_from_array(a, m->n, m->dt_s, m->label);
    free(a);
    return o;
}

static size_t peak_index(const sl_motion *m)
{
    size_t ip = 0;
    for (size_t i = 0; i < m->n; i++)
        ip = fabs(m->acc_ms2[i]) > fabs(m->acc_ms2[ip]) ? i : ip;
    return ip;
}

/* a copy of m shifted circularly so that its largest |a| falls lag samples
 * after ref's (lag may be negative) */
static sl_motion *lagged(const sl_motion *m, const sl_motion *ref, long lag)
{
    long n = (long)m->n, sh = (long)peak_index(ref) + lag - (long)peak_index(m);
    double *a = malloc(m->n * sizeof *a);
    for (long i = 0; i < n; i++)
        a[((i + sh) % n + n) % n] = m->acc_ms2[i];
    sl_motion *o = sl_motion_from_array(a, m->n, m->dt_s, m->label);
    free(a);
    return o;
}

static sl_motion *scaled(const sl_motion *m, double s)
{
    sl_motion *o = sl_motion_from_array(m->acc_ms2, m->n, m->dt_s, m->label);
    sl_motion_scale(o, s);
    return o;
}

static void free_tmp(sl_set *v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        sl_set_free_motions(&v[i]);
}

/* Swap experiments (docs/synthesis.md 10): sliding of modified sets
 * relative to the unmodified ones. */

static void experiments(const sl_set *fm, size_t nrec, const sl_set *syn,
                        const sl_synth_set *so, size_t nsyn, const double *mu,
                        const double *phys, const double *sy)
{
    sl_set *t = calloc(nrec > nsyn ? nrec : nsyn, sizeof *t);
    /* physical without V */
    for (size_t i = 0; i < nrec; i++)
        t[i] = (sl_set){fm[i].h1, fm[i].h2, NULL};
    double *p_nov = slide(t, nrec, mu);
    describe("physical, no V", t, nrec);
    for (size_t i = 0; i < nsyn; i++)
        t[i] = (sl_set){syn[i].h1, syn[i].h2, NULL};
    double *s_nov = slide(t, nsyn, mu);
    describe("synthesized, no V", t, nsyn);
    row("synthesized / physical, both without V", s_nov, nsyn, p_nov, nrec);
    row("physical without V / physical", p_nov, nrec, phys, nrec);
    row("synthesized without V / synthesized", s_nov, nsyn, sy, nsyn);
    /* synthesized with H2's peak moved onto H1's (coincident horizontal peaks) */
    for (size_t i = 0; i < nsyn; i++)
        t[i] = (sl_set){scaled(syn[i].h1, 1), lagged(syn[i].h2, syn[i].h1, 0), scaled(syn[i].v, 1)};
    double *s_al = slide(t, nsyn, mu);
    describe("synthesized, H2 peak on H1 peak", t, nsyn);
    row("synthesized, H peaks coincident / synthesized", s_al, nsyn, sy, nsyn);
    row("synthesized, H peaks coincident / physical", s_al, nsyn, phys, nrec);
    free_tmp(t, nsyn);
    free(s_al);
    /* synthesized with the H1-H2 peak lag of the physical sets (stratified
     * quantiles of their |lag|, alternating sign) */
    {
        double *lg = malloc(nrec * sizeof *lg);
        for (size_t i = 0; i < nrec; i++)
            lg[i] = fabs((double)peak_index(fm[i].h1) - (double)peak_index(fm[i].h2)) *
                    fm[i].h1->dt_s;
        qsort(lg, nrec, sizeof *lg, sl_cmp_double);
        for (size_t i = 0; i < nsyn; i++) {
            size_t j = (size_t)(((double)i + 0.5) / (double)nsyn * (double)nrec);
            long l = lround(lg[j < nrec ? j : nrec - 1] / syn[i].h1->dt_s) * (i % 2 ? 1 : -1);
            t[i] = (sl_set){scaled(syn[i].h1, 1), lagged(syn[i].h2, syn[i].h1, l),
                            scaled(syn[i].v, 1)};
        }
        free(lg);
        double *s_lg = slide(t, nsyn, mu);
        describe("synthesized, H2 peak at the physical sets' lag", t, nsyn);
        row("synthesized, physical peak lags / synthesized", s_lg, nsyn, sy, nsyn);
        row("synthesized, physical peak lags / physical", s_lg, nsyn, phys, nrec);
        free_tmp(t, nsyn);
        free(s_lg);
    }
    /* physical with V delayed 1 s (peaks of V no longer with those of H) */
    for (size_t i = 0; i < nrec; i++) {
        size_t lag = (size_t)lround(1.0 / fm[i].h1->dt_s);
        t[i] = (sl_set){scaled(fm[i].h1, 1), scaled(fm[i].h2, 1), delayed(fm[i].v, lag)};
    }
    double *p_vd = slide(t, nrec, mu);
    describe("physical, V delayed 1 s", t, nrec);
    row("physical V delayed 1 s / physical", p_vd, nrec, phys, nrec);
    free_tmp(t, nrec);
    /* physical with H2 delayed 1 s (H1 and H2 peaks apart) */
    for (size_t i = 0; i < nrec; i++) {
        size_t lag = (size_t)lround(1.0 / fm[i].h1->dt_s);
        t[i] = (sl_set){scaled(fm[i].h1, 1), delayed(fm[i].h2, lag), scaled(fm[i].v, 1)};
    }
    double *p_hd = slide(t, nrec, mu);
    describe("physical, H2 delayed 1 s", t, nrec);
    row("physical H2 delayed 1 s / physical", p_hd, nrec, phys, nrec);
    free_tmp(t, nrec);
    /* physical with H1, H2 scaled to equal PGA (their mean): no strong direction */
    for (size_t i = 0; i < nrec; i++) {
        double p1 = sl_motion_pga(fm[i].h1), p2 = sl_motion_pga(fm[i].h2), pm = 0.5 * (p1 + p2);
        t[i] = (sl_set){scaled(fm[i].h1, pm / p1), scaled(fm[i].h2, pm / p2), scaled(fm[i].v, 1)};
    }
    double *p_eq = slide(t, nrec, mu);
    describe("physical, H1 and H2 at equal PGA", t, nrec);
    row("physical H equal PGA / physical", p_eq, nrec, phys, nrec);
    free_tmp(t, nrec);
    /* synthesized with H scaled exp(+-0.15) (one direction stronger) */
    for (size_t i = 0; i < nsyn; i++) {
        double s = exp(i % 2 ? 0.15 : -0.15);
        t[i] = (sl_set){scaled(syn[i].h1, s), scaled(syn[i].h2, 1 / s), scaled(syn[i].v, 1)};
    }
    double *s_sc = slide(t, nsyn, mu);
    describe("synthesized, H1/H2 scaled exp(+-0.15)", t, nsyn);
    row("synthesized H scaled exp(+-0.15) / synthesized", s_sc, nsyn, sy, nsyn);
    free_tmp(t, nsyn);
    /* synthesized with each H component scaled to PGA = ZPA (floor file's) */
    double z1 = 0, z2 = 0;
    for (size_t i = 0; i < nrec; i++) {
        z1 += sl_motion_pga(fm[i].h1) / (double)nrec;
        z2 += sl_motion_pga(fm[i].h2) / (double)nrec;
    }
    for (size_t i = 0; i < nsyn; i++)
        t[i] = (sl_set){scaled(syn[i].h1, z1 / sl_motion_pga(syn[i].h1)),
                        scaled(syn[i].h2, z2 / sl_motion_pga(syn[i].h2)), scaled(syn[i].v, 1)};
    double *s_pz = slide(t, nsyn, mu);
    describe("synthesized, H scaled to PGA = ZPA", t, nsyn);
    row("synthesized H at PGA = ZPA / physical", s_pz, nsyn, phys, nrec);
    free_tmp(t, nsyn);
    free(s_pz);
    /* as far as SRP 3.7.1 lets a per-motion aim go: H1 x exp(+0.15), H2 x
     * exp(-0.15) (alternating), each clamped to [0.9/min S/T, 1.3/max S/T] */
    double fmean = 0;
    for (size_t i = 0; i < nsyn; i++) {
        double f[2];
        for (int c = 0; c < 2; c++) {
            double want = exp((i % 2) == (size_t)c ? 0.15 : -0.15);
            double lo = 0.9 / so[i].check[c].min_ratio, hi = 1.3 / so[i].check[c].max_ratio;
            f[c] = want < lo ? lo : want > hi ? hi : want;
            fmean += f[c] / (2.0 * (double)nsyn);
        }
        t[i] = (sl_set){scaled(syn[i].h1, f[0]), scaled(syn[i].h2, f[1]), scaled(syn[i].v, 1)};
    }
    double *s_cl = slide(t, nsyn, mu);
    printf("  SRP-clamped direction scatter: mean factor %.3f (mean spectrum bias)\n", fmean);
    describe("synthesized, SRP-clamped exp(+-0.15)", t, nsyn);
    row("synthesized SRP-clamped scatter / synthesized", s_cl, nsyn, sy, nsyn);
    free_tmp(t, nsyn);
    free(s_cl);
    /* record-to-record intensity: synthesized set k scaled by the physical
     * sets' larger-H-PGA / ZPA at quantile (k + 0.5)/nsyn (stratified) */
    double *q = malloc(nrec * sizeof *q), zp = 0;
    for (size_t i = 0; i < nrec; i++)
        zp += (q[i] = sl_set_pga_h(&fm[i])) / (double)nrec;
    qsort(q, nrec, sizeof *q, sl_cmp_double);
    double cv = 0;
    for (size_t i = 0; i < nrec; i++)
        cv += (q[i] / zp - 1) * (q[i] / zp - 1) / (double)(nrec - 1);
    for (size_t i = 0; i < nsyn; i++) {
        size_t j = (size_t)(((double)i + 0.5) / (double)nsyn * (double)nrec);
        double f = q[j < nrec ? j : nrec - 1] / zp;
        t[i] = (sl_set){scaled(syn[i].h1, f), scaled(syn[i].h2, f), scaled(syn[i].v, f)};
    }
    double *s_rr = slide(t, nsyn, mu);
    printf("  physical larger-H PGA / ZPA: coefficient of variation %.3f\n", sqrt(cv));
    row("synthesized x physical PGA scatter / synthesized", s_rr, nsyn, sy, nsyn);
    row("synthesized x physical PGA scatter / physical", s_rr, nsyn, phys, nrec);
    free_tmp(t, nsyn);
    free(s_rr);
    free(q);
    free(p_nov);
    free(s_nov);
    free(p_vd);
    free(p_hd);
    free(p_eq);
    free(s_sc);
    free(t);
}

static void header(const char *first)
{
    printf("\n| %s | μg/ZPA 0.1 | 0.3 | 0.5 | 0.7 | 0.9 |\n|---|---|---|---|---|---|\n", first);
}

static void usage(void)
{
    fprintf(stderr, "usage: physfloors [-r dir] [-n max] [-s nsyn] [-S seed] [-x] "
                    "[-a sigma] [-g|-G] [-0] [-P|-Q] [-F f_end] [-R scatter] [-c cycles] "
                    "[-H hold_frac] [-Y shape_sigma] [-B N:f1_h1:f1_h2:f1_v:damping]\n");
}

/* The options into *o (defaults first); 0, or 1 with a message. */
static int parse_options(int argc, char **argv, pf_opts *o)
{
    memset(o, 0, sizeof *o);
    o->nsyn = 24;
    o->seed = 12;
    o->f_end_hz = 50.0;
    o->scatter = SL_ANALYSIS_SCATTER_FLOOR;
    o->building = (sl_building){3, {3.0, 4.2, 14.0}, 0.05};
    sl_synth_params_default(&o->synth);
    int opt;
    sl_error e;
    while ((opt = getopt(argc, argv, "r:n:s:S:xa:gG0PQF:R:H:c:Y:B:")) != -1) {
        switch (opt) {
        case 'r': o->records = optarg; break;
        case 'n': o->max_records = (size_t)atol(optarg); break;
        case 's': o->nsyn = (size_t)atol(optarg); break;
        case 'S': o->seed = (uint64_t)atoll(optarg); break;
        case 'x': o->experiments = 1; break;
        case 'a': o->synth.pga_sigma = atof(optarg); break;
        case 'H': o->synth.hold_frac = atof(optarg); break;
        case 'c': o->synth.wavelet_cycles = atof(optarg); break;
        case 'Y': o->shape = atof(optarg); break;
        case 'g': o->ground_only = 1; break;
        case '0': o->floor0 = 1; break;
        case 'P': o->pair_match = 1; break;
        case 'Q': o->pair_match = 1, o->pair_max = 1; break;
        case 'G': o->no_ground = 1; break;
        case 'F': o->f_end_hz = atof(optarg); break;
        case 'R': o->scatter = atof(optarg); break;
        case 'B':
            if (sl_building_parse(optarg, &o->building, &e))
                die(&e);
            break;
        default:
            usage();
            return 1;
        }
    }
    if (o->nsyn < 2) {
        fprintf(stderr, "physfloors: -s %zu: at least 2 synthesized sets (a standard error needs two)\n",
                o->nsyn);
        return 1;
    }
    if (o->shape > 0 && o->ground_only)
        fprintf(stderr, "physfloors: -Y applies to floors only; ignored with -g\n");
    if (!(o->shape >= 0 && o->shape <= 1)) {
        fprintf(stderr, "physfloors: -Y %g: the shape scatter is a log standard deviation in [0, 1]\n",
                o->shape);
        return 1;
    }
    if (!(o->f_end_hz > 1 && o->f_end_hz <= 50)) {
        fprintf(stderr, "physfloors: -F %g: the floor spectrum ends in (1, 50] Hz\n", o->f_end_hz);
        return 1;
    }
    return 0;
}

/* Ground: the nrec records g matched to RG 1.60 (the study's method) against
 * synthesized sets (syn: room for o->nsyn). */
static void ground(const pf_opts *o, const sl_set *g, size_t nrec, sl_set *syn)
{
    const size_t nsyn = o->nsyn;
    sl_error e;
    double mu[NMU];
    sl_synth_set *ms = calloc(nrec, sizeof *ms);
    sl_set *mset = calloc(nrec, sizeof *mset);
    size_t nm = 0, *src = calloc(nrec, sizeof *src);
    for (size_t r = 0; r < nrec; r++) {
        sl_status st = sl_study_match_rg160(&g[r], 0.05, PGA_G * SL_G, &ms[nm], &e);
        if (st == SL_OK || st == SL_ENOCONV)
            mset[nm] = ms[nm].set, src[nm] = r, nm++;
    }
    for (int k = 0; k < NMU; k++)
        mu[k] = (0.1 + 0.2 * k) * PGA_G;
    double *real = slide(mset, nm, mu);
    describe("ground, records as recorded (scaled)", g, nrec);
    if (o->experiments) { /* the records' spectral scatter; per-component PGA equalized (what
                           * component-wise matching does to the pair) */
        shape_scatter(g, nrec);
        sl_set *eq = calloc(nrec, sizeof *eq);
        for (size_t r = 0; r < nrec; r++)
            eq[r] = (sl_set){scaled(g[r].h1, PGA_G * SL_G / sl_motion_pga(g[r].h1)),
                             scaled(g[r].h2, PGA_G * SL_G / sl_motion_pga(g[r].h2)),
                             scaled(g[r].v, 1)};
        describe("ground, records as recorded, each H scaled to 0.3 g", eq, nrec);
        free_tmp(eq, nrec);
        free(eq);
    }
    describe("ground, records matched to RG 1.60", mset, nm);
    sl_spectrum *sp[3];
    sl_synth_target tgt[3];
    if (sl_synth_targets_rg160(PGA_G * SL_G, 0.05, &o->synth, sp, tgt, &e))
        die(&e);
    sl_synth_set *out = synth(o, tgt, 0.0, syn); /* -Y: floors only */
    double *sy = slide(syn, nsyn, mu);
    describe("ground, synthesized RG 1.60", syn, nsyn);
    header("ground RG 1.60 0.3 g: synthesized / matched (μg/PGA)");
    row("ratio ± SE", sy, nsyn, real, nm);
    if (o->scatter != 0) { /* what `seislide run` reports for a ground floor: with its scatter */
        const sl_spectrum *h[2] = {tgt[0].spec, tgt[1].spec};
        const double zh[2] = {tgt[0].zpa_ms2, tgt[1].zpa_ms2};
        double *syr = slide_floor(o, syn, nsyn, mu, sl_scatter_sigma_of_fc(sl_scatter_fc_hz(h, zh)));
        header("ground: synthesized slid the run's way (intensity scatter) / matched");
        row("ratio ± SE", syr, nsyn, real, nm);
        free(syr);
    }
    if (o->pair_match) { /* -P: the pair matched with one correction, V as matched */
        sl_set *pset = calloc(nm, sizeof *pset);
        double wmax = 0;
        for (size_t i = 0; i < nm; i++) {
            sl_motion *p1, *p2;
            wmax = fmax(wmax, pair_match(o, g[src[i]].h1, g[src[i]].h2, sp[0], &p1, &p2));
            /* the V of the component-wise match, on the pair's samples */
            sl_motion *vr = sl_synth_resample_motion(mset[i].v, p1->dt_s);
            double *va = calloc(p1->n, sizeof *va);
            if (!vr || !va) {
                fprintf(stderr, "physfloors: cannot resample the vertical of %s\n",
                        mset[i].v->label);
                exit(1);
            }
            for (size_t j = 0; j < p1->n && j < vr->n; j++)
                va[j] = vr->acc_ms2[j];
            pset[i] = (sl_set){p1, p2, sl_motion_from_array(va, p1->n, p1->dt_s, "v")};
            free(va);
            sl_motion_free(vr);
        }
        printf("  pair matching: largest |ln(%s / target)| left %.3f\n",
               o->pair_max ? "larger H spectrum" : "geometric mean", wmax);
        describe(o->pair_max ? "ground, records pair-matched to RG 1.60 (one correction, the larger H spectrum)"
                             : "ground, records pair-matched to RG 1.60 (one correction, the geometric mean)",
                 pset, nm);
        double *pr = slide(pset, nm, mu);
        header("ground RG 1.60 0.3 g: synthesized / pair-matched records (μg/PGA)");
        row("ratio ± SE", sy, nsyn, pr, nm);
        header("ground: pair-matched / component-matched records (μg/PGA)");
        row("ratio ± SE", pr, nm, real, nm);
        free(pr);
        free_tmp(pset, nm);
        free(pset);
    }
    free(src);
    if (o->experiments)
        experiments(mset, nm, syn, out, nsyn, mu, real, sy);
    free(real);
    free(sy);
    for (size_t k = 0; k < nsyn; k++)
        sl_synth_set_clear(&out[k]);
    free(out);
    for (size_t r = 0; r < nm; r++)
        sl_synth_set_clear(&ms[r]);
    for (int c = 0; c < 3; c++)
        sl_spectrum_free(sp[c]);
    free(ms);
    free(mset);
}

/* Floors 1-3 (and floor 0 with -0) of the building over the nrec records
 * g: physical floor motions against sets synthesized to their spectra
 * (syn: room for o->nsyn). Returns 0, or 1 with a message. */
static int floors(const pf_opts *o, const sl_set *g, size_t nrec, sl_set *syn)
{
    const size_t nsyn = o->nsyn;
    const double f_end = o->f_end_hz;
    sl_error e;
    double mu[NMU];
    double f[NF];
    const size_t nf = (size_t)lround(50.0 * log10(f_end / 0.1)) + 1;
    for (size_t j = 0; j < nf; j++)
        f[j] = 0.1 * pow(f_end / 0.1, (double)j / (double)(nf - 1));
    const sl_building b = o->building;
    char dir[] = "/tmp/seislide-pf-XXXXXX";
    if (!mkdtemp(dir)) {
        fprintf(stderr, "physfloors: cannot make a temporary directory\n");
        return 1;
    }
    sl_set *fm = calloc(nrec, sizeof *fm);
    for (size_t fl = o->floor0 ? 0 : 1; fl <= b.storeys; fl++) {
        for (size_t r = 0; r < nrec; r++)
            if (fl == 0) /* the ground: the records themselves, as recorded */
                fm[r] = (sl_set){scaled(g[r].h1, 1), scaled(g[r].h2, 1), scaled(g[r].v, 1)};
            else if (sl_building_floor(&b, fl, &g[r], &fm[r], &e))
                die(&e);
        double zpa = 0;
        for (size_t r = 0; r < nrec; r++)
            zpa += sl_set_pga_h(&fm[r]) / (double)nrec;
        for (int k = 0; k < NMU; k++)
            mu[k] = (0.1 + 0.2 * k) * zpa / SL_G;
        double *phys = slide(fm, nrec, mu);
        printf("\nfloor %zu of the building %zu:%g:%g:%g:%g: ZPA (mean larger H PGA) %.3f g\n", fl,
               b.storeys, b.f1_hz[0], b.f1_hz[1], b.f1_hz[2], b.damping, zpa / SL_G);
        describe("physical", fm, nrec);
        for (int broaden = 0; broaden < 2; broaden++) {
            char path[256], label[64];
            snprintf(path, sizeof path, "%s/floor%zu%s.ini", dir, fl, broaden ? "b" : "");
            if (sl_pf_write_floor(path, "physical floor", fm, nrec, f, nf, broaden, &e))
                die(&e);
            sl_floor *flr = sl_floor_load(path, &e);
            sl_synth_target tgt[3];
            if (!flr || sl_synth_targets_floor(flr, 0, tgt, &e))
                die(&e);
            sl_synth_set *out = synth(o, tgt, o->shape, syn);
            double *sy = slide_floor(o, syn, nsyn, mu, sl_scatter_sigma_of_floor(flr));
            describe(broaden ? "synthesized, broadened" : "synthesized", syn, nsyn);
            header(broaden ? "synthesized (broadened ±15 %) / physical"
                           : "synthesized / physical");
            snprintf(label, sizeof label, "floor %zu%s", fl, broaden ? " broadened" : "");
            row(label, sy, nsyn, phys, nrec);
            if (o->experiments && !broaden)
                experiments(fm, nrec, syn, out, nsyn, mu, phys, sy);
            free(sy);
            for (size_t k = 0; k < nsyn; k++)
                sl_synth_set_clear(&out[k]);
            free(out);
            sl_floor_free(flr);
            remove(path);
        }
        free(phys);
        free_tmp(fm, nrec);
    }
    rmdir(dir);
    free(fm);
    return 0;
}

int main(int argc, char **argv)
{
    pf_opts o;
    setvbuf(stdout, NULL, _IOLBF, 0);
    if (parse_options(argc, argv, &o))
        return 1;
    char buf[1024];
    const char *rdir = sl_pf_records_dir(o.records, buf, sizeof buf);
    sl_error e;
    if (sl_synth_params_check(&o.synth, &e))
        die(&e);
    sl_set *g;
    size_t nrec, nd;
    if (sl_pf_read_records(rdir, o.max_records, PGA_G * SL_G, &g, &nrec, &nd, &e))
        die(&e);
    sl_pf_rule rule;
    sl_pf_rule_default(&rule);
    printf("records: %zu used of %zu directories in %s (rule: three components, larger H PGA "
           ">= %.2f g, duration >= %.0f s, dt <= %.2f s); scaled to %.1f g; %zu synthesized "
           "sets per case, seed %llu, pga_sigma %.2f, wavelet cycles %.1f, envelope hold %.2f, floor spectra to %g Hz, scatter %.2f (< 0: each floor's), "
           "floor-spectrum shape scatter %.2f%s\n",
           nrec, nd, rdir, rule.min_pga_g, rule.min_duration_s, rule.max_dt_s, PGA_G, o.nsyn,
           (unsigned long long)o.seed, o.synth.pga_sigma, o.synth.wavelet_cycles,
           o.synth.hold_frac, o.f_end_hz, o.scatter, o.shape,
           o.floor0 ? ", floor 0 (the records themselves) included" : "");
    if (nrec == 0) {
        fprintf(stderr, "physfloors: no record of %s passes the rule\n", rdir);
        return 1;
    }
    sl_set *syn = calloc(o.nsyn, sizeof *syn);
    int rc = 0;
    if (!o.no_ground)
        ground(&o, g, nrec, syn);
    if (!o.ground_only)
        rc = floors(&o, g, nrec, syn);
    sl_pf_sets_free(g, nrec);
    free(syn);
    return rc;
}
