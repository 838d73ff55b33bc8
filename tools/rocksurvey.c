/*
 * rocksurvey.c - the rocking engine's accuracy over recorded motions
 * (docs/integrators.md, "Rocking"): every three-component set under
 * RECORDS (io/setdir.h), H1 and H2 each along the weak axis of five blocks
 * (two families: 0.3-2 m and 0.02-0.1 m tall), each scaled so that its peak
 * is kappa g tan(alpha) for three kappa. Per case: the engine at RTOL
 * against the engine at 1e-12 (the converged reference), and the
 * reference's sensitivity (its peak under inputs scaled by 1 +- 1e-6,
 * 2e-6, 5e-6, 1e-5; a case is chaotic when one of them moves the peak by
 * more than 1e-4 or changes the tipped or overturned flag). Prints, per
 * family, the number of cases, of non-chaotic cases, the distribution and
 * the worst relative error of the non-chaotic peaks, and the time.
 *
 *   make build/tools/rocksurvey && build/tools/rocksurvey ../shared/records [RTOL]
 */
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/clock.h"
#include "core/units.h"
#include "io/setdir.h"
#include "rock/rock.h"

#define MAX_DIRS 1000

static int by_name(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

typedef struct family {
    const char *name;
    double b[5], h[5], kappa[3];
    size_t cases, calm, bins[8];
    double worst, time_s, time_ref_s;
} family;

static void one(family *f, const sl_motion *m, const double *av, double rtol)
{
    double pga = 0;
    for (size_t i = 0; i < m->n; i++)
        pga = fmax(pga, fabs(m->acc_ms2[i]));
    if (!(pga > 0))
        return;
    for (int bi = 0; bi < 5; bi++)
        for (int ki = 0; ki < 3; ki++) {
            const sl_rock_block blk = {f->b[bi], f->h[bi], -1};
            const double sc = f->kappa[ki] * SL_G * f->b[bi] / f->h[bi] / pga;
            sl_rock_opts o, oref;
            sl_rock_opts_default(&o);
            sl_rock_opts_default(&oref);
            o.rtol = rtol;
            oref.rtol = 1e-12;
            sl_rock_result r, rr, rp;
            double t0 = sl_clock_s();
            if (sl_rock_run(&blk, m->acc_ms2, av, m->n, m->dt_s, sc, 1, &o, &r, NULL))
                continue;
            f->time_s += sl_clock_s() - t0;
            t0 = sl_clock_s();
            if (sl_rock_run(&blk, m->acc_ms2, av, m->n, m->dt_s, sc, 1, &oref, &rr, NULL))
                continue;
            f->time_ref_s += sl_clock_s() - t0;
            f->cases++;
            int chaotic = 0;
            const double d[] = {1e-6, -1e-6, 2e-6, -2e-6, 5e-6, -5e-6, 1e-5, -1e-5};
            for (int q = 0; q < 8 && !chaotic; q++) {
                if (sl_rock_run(&blk, m->acc_ms2, av, m->n, m->dt_s, sc * (1 + d[q]), 1, &oref,
                                &rp, NULL))
                    chaotic = 1;
                else
                    chaotic = rp.tipped != rr.tipped || rp.overturned != rr.overturned ||
                              !(fabs(rp.peak_theta_rad - rr.peak_theta_rad) <=
                                1e-4 * rr.peak_theta_rad);
            }
            if (chaotic)
                continue;
            f->calm++;
            const double er = rr.peak_theta_rad > 0
                                  ? fabs(r.peak_theta_rad / rr.peak_theta_rad - 1)
                                  : fabs(r.peak_theta_rad);
            f->worst = fmax(f->worst, er);
            int bin = 0;
            while (bin < 7 && !(er < pow(10.0, -9 + bin)))
                bin++;
            f->bins[bin]++;
        }
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: rocksurvey RECORDS [RTOL]\n");
        return 2;
    }
    const double rtol = argc > 2 ? atof(argv[2]) : SL_ROCK_DEFAULT_RTOL;
    DIR *d = opendir(argv[1]);
    if (!d) {
        fprintf(stderr, "rocksurvey: cannot read %s\n", argv[1]);
        return 1;
    }
    char *names[MAX_DIRS];
    size_t nn = 0;
    struct dirent *e;
    while ((e = readdir(d)) && nn < MAX_DIRS)
        if (e->d_name[0] != '.')
            names[nn++] = strdup(e->d_name);
    closedir(d);
    qsort(names, nn, sizeof *names, by_name);
    family fam[2] = {
        {"blocks 0.3-2 m tall (b/h 0.1-0.3), peak 1.5, 3, 6 g tan(alpha)",
         {0.15, 0.25, 0.045, 0.6, 0.05}, {1.0, 1.0, 0.3, 2.0, 0.5}, {1.5, 3, 6}, 0, 0, {0}, 0, 0,
         0},
        {"blocks 0.02-0.1 m tall (b/h 0.2-0.3), peak 1.05, 1.2, 1.5 g tan(alpha)",
         {0.01, 0.004, 0.03, 0.02, 0.012}, {0.05, 0.02, 0.1, 0.08, 0.06}, {1.05, 1.2, 1.5}, 0,
         0, {0}, 0, 0, 0},
    };
    size_t sets = 0;
    for (size_t i = 0; i < nn; i++) {
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", argv[1], names[i]);
        sl_set set;
        sl_error err;
        if (sl_set_read_dir(path, &set, &err) == SL_OK) {
            sets++;
            for (int q = 0; q < 2; q++) {
                one(&fam[q], set.h1, set.v ? set.v->acc_ms2 : NULL, rtol);
                one(&fam[q], set.h2, set.v ? set.v->acc_ms2 : NULL, rtol);
            }
            sl_set_free_motions(&set);
        }
        free(names[i]);
    }
    printf("rtol %g, %zu three-component sets, H1 and H2 with the vertical\n", rtol, sets);
    for (int q = 0; q < 2; q++) {
        family *f = &fam[q];
        printf("%s: %zu cases, %zu non-chaotic; worst relative error of their peaks %.2e;\n"
               "  errors <1e-9 <1e-8 <1e-7 <1e-6 <1e-5 <1e-4 <1e-3 >=1e-3:", f->name, f->cases,
               f->calm, f->worst);
        for (int b = 0; b < 8; b++)
            printf(" %zu", f->bins[b]);
        printf("\n  engine %.2f s, reference %.2f s (one thread)\n", f->time_s, f->time_ref_s);
    }
    return 0;
}
