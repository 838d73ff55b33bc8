/*
 * synthstat.c - statistics and cost of synthesized sets, in one process
 * (docs/synthesis.md 3.7 and 4):
 *
 *     make build/tools/synthstat
 *     build/tools/synthstat N SEED [FLOOR.ini] [--no-slide] [--spread N]
 *
 * Makes sets 0 .. N-1 of SEED one at a time on one thread (RG 1.60 at 0.3 g,
 * 20 s at 200/s, or the floor file's targets) and prints: the CPU time of the
 * process per set (not wall time: valid on a shared machine), the sets that
 * pass every check, the extra attempts per set; per component the set mean
 * 5 % spectrum / target (mean over the grid, lowest and highest), PGD/PGA in
 * m per g and the local maxima of |a| above 0.9 PGA, each mean with its
 * standard error, and the most peaks; D5-75, V/A, A D/V^2 and the largest
 * |rho| with the other components, each mean with its standard error; then (unless --no-slide) the NLTHA mean
 * peak sliding (2-D + vertical, engine defaults) at mu g/ZPA 0.1, 0.2, 0.3,
 * 0.5 with its standard error. --spread N sets the least number of packets
 * sharing the start's energy (synth.h wavelet_spread; 0: the log-uniform start).
 */
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core/units.h"
#include "io/floor.h"
#include "slide/slide.h"
#include "synth/synth.h"

#define NMU 4

static double cpu_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* mean and standard error of the mean from sum and sum of squares of k values */
static void mean_se(double s, double s2, int k, double *m, double *se)
{
    *m = s / k;
    *se = k > 1 ? sqrt(fmax(s2 / k - *m * *m, 0) / (k - 1)) : NAN;
}

int main(int argc, char **argv)
{
    int slide = 1, npos = 0;
    double spread = SL_SYNTH_WAVELET_SPREAD;
    const char *pos[3] = {NULL, NULL, NULL};
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--no-slide"))
            slide = 0;
        else if (!strcmp(argv[i], "--spread") && i + 1 < argc)
            spread = atof(argv[++i]);
        else if (npos < 3)
            pos[npos++] = argv[i];
    }
    if (npos < 2 || atoi(pos[0]) < 2) {
        fprintf(stderr, "usage: synthstat N SEED [FLOOR.ini] [--no-slide] [--spread N]  (N >= 2)\n");
        return 2;
    }
    const int nsets = atoi(pos[0]);
    const uint64_t seed = strtoull(pos[1], NULL, 10);
    sl_error e;
    sl_error_clear(&e);
    sl_synth_params p;
    sl_synth_params_default(&p);
    p.wavelet_spread = spread;
    sl_spectrum *spec[SL_SYNTH_NCOMP] = {NULL, NULL, NULL};
    sl_synth_target tgt[SL_SYNTH_NCOMP];
    sl_floor *fl = NULL;
    if (pos[2]) {
        fl = sl_floor_load(pos[2], &e);
        if (!fl || sl_synth_targets_floor(fl, 0, tgt, &e)) {
            fprintf(stderr, "synthstat: %s\n", e.msg);
            return 1;
        }
    } else if (sl_synth_targets_rg160(0.3 * SL_G, SL_SYNTH_DAMPING, &p, spec, tgt, &e)) {
        fprintf(stderr, "synthstat: %s\n", e.msg);
        return 1;
    }
    const size_t n = (size_t)(SL_SYNTH_DURATION_S / SL_SYNTH_DT_S + 0.5) + 1;
    sl_synth *s = sl_synth_alloc(n, SL_SYNTH_DT_S, &p, &e);
    if (!s) {
        fprintf(stderr, "synthstat: %s\n", e.msg);
        return 1;
    }
    omp_set_num_threads(1);
    size_t ng;
    const double *grid = sl_synth_grid(s, &ng);
    double *ratio = calloc(SL_SYNTH_NCOMP * ng, sizeof *ratio), *psa = malloc(ng * sizeof *psa);
    int *cnt = calloc(SL_SYNTH_NCOMP * ng, sizeof *cnt);
    double pgd[SL_SYNTH_NCOMP][2] = {{0}}, pk[SL_SYNTH_NCOMP][2] = {{0}}, sl[NMU][2] = {{0}};
    size_t pkmax[SL_SYNTH_NCOMP] = {0};
    /* D5-75, V/A, A D/V^2 and the largest |rho| per component: sum, sum of squares */
    double rz[SL_SYNTH_NCOMP][4][2] = {{{0}}};
    const double mu_frac[NMU] = {0.1, 0.2, 0.3, 0.5};
    double cpu = 0;
    int passed = 0, extra = 0;
    for (int k = 0; k < nsets; k++) {
        sl_synth_set set;
        double t0 = cpu_s();
        sl_status st = sl_synth_make_sets(s, tgt, seed, (size_t)k, 1, &set, NULL, NULL, &e);
        cpu += cpu_s() - t0;
        if (st && st != SL_ENOCONV) {
            fprintf(stderr, "synthstat: set %d: %s\n", k, e.msg);
            return 1;
        }
        passed += set.pass;
        for (int c = 0; c < SL_SYNTH_NCOMP; c++) {
            const sl_synth_check *ck = &set.check[c];
            const sl_motion *mo = sl_synth_set_motion(&set, (sl_synth_comp)c);
            const sl_spectrum *ts = tgt[c].spec;
            double x = ck->pgd_m / (ck->pga_ms2 / SL_G);
            extra += (int)ck->attempt;
            pgd[c][0] += x;
            pgd[c][1] += x * x;
            pk[c][0] += (double)ck->peaks;
            pk[c][1] += (double)ck->peaks * (double)ck->peaks;
            pkmax[c] = ck->peaks > pkmax[c] ? ck->peaks : pkmax[c];
            const double rv[4] = {ck->d5_75_s, ck->va_s, ck->adv2, ck->max_corr};
            for (int q = 0; q < 4; q++) {
                rz[c][q][0] += rv[q];
                rz[c][q][1] += rv[q] * rv[q];
            }
            sl_spectrum_compute(mo->acc_ms2, mo->n, mo->dt_s, grid, ng, ts->damping, psa, NULL,
                                NULL, &e);
            for (size_t j = 0; j < ng; j++)
                if (grid[j] >= ts->f_hz[0] && grid[j] <= ts->f_hz[ts->n - 1]) {
                    ratio[c * ng + j] += psa[j] / sl_spectrum_interp(ts, grid[j]);
                    cnt[c * ng + j]++;
                }
        }
        if (slide) {
            sl_slide_opts o;
            sl_slide_opts_default(&o);
            sl_slide_result r[NMU];
            double mu[NMU];
            for (int q = 0; q < NMU; q++)
                mu[q] = mu_frac[q] * tgt[0].zpa_ms2 / SL_G;
            if (sl_slide_run(&set.set, mu, NMU, &o, r, &e)) {
                fprintf(stderr, "synthstat: set %d: %s\n", k, e.msg);
                return 1;
            }
            for (int q = 0; q < NMU; q++) {
                sl[q][0] += r[q].peak_m;
                sl[q][1] += r[q].peak_m * r[q].peak_m;
            }
        }
        sl_synth_set_clear(&set);
    }
    printf("%d sets of seed %llu: CPU %.2f ms per set (one thread), %d pass every check, "
           "%.2f extra attempts per set\n",
           nsets, (unsigned long long)seed, 1e3 * cpu / nsets, passed, (double)extra / nsets);
    for (int c = 0; c < SL_SYNTH_NCOMP; c++) {
        double lo = INFINITY, hi = 0, avg = 0, m, se, mk, sek;
        int nn = 0;
        for (size_t j = 0; j < ng; j++)
            if (cnt[c * ng + j]) {
                double r = ratio[c * ng + j] / cnt[c * ng + j];
                lo = fmin(lo, r);
                hi = fmax(hi, r);
                avg += r;
                nn++;
            }
        mean_se(pgd[c][0], pgd[c][1], nsets, &m, &se);
        mean_se(pk[c][0], pk[c][1], nsets, &mk, &sek);
        printf("%-2s: mean spectrum / target %.4f (lowest %.4f, highest %.4f), PGD/PGA %.3f +- "
               "%.3f m per g, peaks above 0.9 PGA %.2f +- %.2f (most %zu)\n",
               sl_synth_comp_name((sl_synth_comp)c), avg / (nn ? nn : 1), lo, hi, m, se, mk, sek,
               pkmax[c]);
        double rm[4], rse[4];
        for (int q = 0; q < 4; q++)
            mean_se(rz[c][q][0], rz[c][q][1], nsets, &rm[q], &rse[q]);
        printf("%-2s: D5-75 %.3f +- %.3f s, V/A %.4f +- %.4f s, A D/V^2 %.3f +- %.3f, "
               "largest |rho| %.4f +- %.4f\n",
               sl_synth_comp_name((sl_synth_comp)c), rm[0], rse[0], rm[1], rse[1], rm[2], rse[2],
               rm[3], rse[3]);
    }
    for (int q = 0; slide && q < NMU; q++) {
        double m, se;
        mean_se(sl[q][0], sl[q][1], nsets, &m, &se);
        printf("mu g/ZPA %.1f: NLTHA mean peak %.5f +- %.5f m\n", mu_frac[q], m, se);
    }
    free(ratio);
    free(psa);
    free(cnt);
    for (int c = 0; c < SL_SYNTH_NCOMP; c++)
        sl_spectrum_free(spec[c]);
    sl_floor_free(fl);
    sl_synth_free(s);
    return 0;
}
