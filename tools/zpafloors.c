/*
 * zpafloors.c - how far apart the ZPAs of one building's floors lie on
 * physical floors: the numbers behind the check of a building's floors
 * against each other (plant/intensity.h; docs/formats-floor.md, "Floors of
 * one building").
 *
 *   make zpafloors          (or build/tools/zpafloors [-r DIR] [-n N])
 *
 * Physical floors: every three-component record of the records directory
 * (-r, default $SEISLIDE_SHARED/records or ../shared/records) that passes
 * the rule of study/physfloor.h (at most -n, 0 = all), scaled to a larger
 * horizontal PGA of 0.3 g, is the ground ("floor 0", elevation 0) of every
 * building of the list below (study/building.h: uniform shear buildings of
 * N storeys, 5 % modal damping, fundamental frequencies H1/H2/V), whose
 * floors 1..N stand at elevations 1..N storeys. A floor's ZPA is the larger
 * horizontal PGA of its motion (what a floor file's ZPA is: the largest
 * horizontal value at the high-frequency end). Per building and over every
 * record (a plant: the ground and the floors of every building of the list,
 * from one record):
 *   - up:     z_i / z_j for every floor i above floor j: lowest and highest;
 *   - median: z_i / the median of the building's other floors: lowest and
 *             highest (the plant: of the plant's other floors).
 * Prints one row per building and one for the plant. Exit 0, or 1 on bad
 * input.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/motion_set.h"
#include "core/units.h"
#include "io/setdir.h"
#include "study/building.h"
#include "study/physfloor.h"

#define PGA_G 0.3
#define NB 6
#define MAXF (1 + SL_BUILDING_MAX_STOREYS)

/* The buildings: the two of tools/plausfloors.c, a stiff one (a reactor
 * building's shear walls), two taller and softer ones, a one-storey one. */
static const sl_building B[NB] = {{3, {3.0, 4.2, 14.0}, 0.05}, {3, {5.0, 5.8, 16.0}, 0.05},
                                  {3, {8.0, 9.5, 20.0}, 0.05}, {6, {2.0, 2.4, 10.0}, 0.05},
                                  {10, {1.2, 1.5, 8.0}, 0.05}, {1, {6.0, 7.0, 18.0}, 0.05}};

typedef struct range {
    double lo, hi;
    char lo_at[200], hi_at[200];
} range;

static void range_init(range *r)
{
    r->lo = INFINITY;
    r->hi = 0;
    r->lo_at[0] = r->hi_at[0] = '\0';
}

static void range_add(range *r, double x, const char *rec, size_t i, size_t j)
{
    if (x < r->lo) {
        r->lo = x;
        snprintf(r->lo_at, sizeof r->lo_at, "%s, floor %zu against %zu", rec, i, j);
    }
    if (x > r->hi) {
        r->hi = x;
        snprintf(r->hi_at, sizeof r->hi_at, "%s, floor %zu against %zu", rec, i, j);
    }
}

static int cmp_d(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* The median of z[0..n) without z[skip]. */
static double median_others(const double *z, size_t n, size_t skip)
{
    double o[NB * MAXF];
    size_t k = 0;
    for (size_t i = 0; i < n; i++)
        if (i != skip)
            o[k++] = z[i];
    qsort(o, k, sizeof *o, cmp_d);
    return k % 2 ? o[k / 2] : 0.5 * (o[k / 2 - 1] + o[k / 2]);
}

int main(int argc, char **argv)
{
    const char *rdir = NULL;
    size_t max_rec = 0;
    int opt;
    while ((opt = getopt(argc, argv, "r:n:")) != -1) {
        if (opt == 'r')
            rdir = optarg;
        else if (opt == 'n')
            max_rec = (size_t)atol(optarg);
        else {
            fprintf(stderr, "usage: zpafloors [-r RECORDS] [-n MAX]\n");
            return 1;
        }
    }
    char buf[1024];
    rdir = sl_pf_records_dir(rdir, buf, sizeof buf);
    sl_error e;
    char **names;
    size_t nd = sl_pf_list_dirs(rdir, &names, &e);
    sl_pf_rule rule;
    sl_pf_rule_default(&rule);
    range up[NB], med[NB], plant;
    for (int b = 0; b < NB; b++) {
        range_init(&up[b]);
        range_init(&med[b]);
    }
    range_init(&plant);
    size_t nrec = 0;
    for (size_t r = 0; r < nd && (!max_rec || nrec < max_rec); r++) {
        char d[4096];
        sl_set g;
        snprintf(d, sizeof d, "%s/%s", rdir, names[r]);
        if (sl_pf_read_record(d, &rule, PGA_G * SL_G, &g, &e) != SL_OK)
            continue;
        nrec++;
        double all[NB * MAXF]; /* the plant: the ground once, then every building's floors */
        size_t na = 0;
        all[na++] = sl_set_pga_h(&g);
        for (int b = 0; b < NB; b++) {
            double z[MAXF];
            z[0] = all[0];
            for (size_t j = 1; j <= B[b].storeys; j++) {
                sl_set fm;
                if (sl_building_floor(&B[b], j, &g, &fm, &e))
                    return fprintf(stderr, "zpafloors: %s\n", e.msg), 1;
                z[j] = all[na++] = sl_set_pga_h(&fm);
                sl_set_free_motions(&fm);
            }
            size_t n = B[b].storeys + 1;
            for (size_t i = 0; i < n; i++) {
                for (size_t j = 0; j < i; j++)
                    range_add(&up[b], z[i] / z[j], names[r], i, j);
                if (n >= 2)
                    range_add(&med[b], z[i] / median_others(z, n, i), names[r], i, n);
            }
        }
        for (size_t i = 0; i < na; i++)
            range_add(&plant, all[i] / median_others(all, na, i), names[r], i, na);
        sl_set_free_motions(&g);
    }
    printf("records: %zu of %zu folders in %s, scaled to %g g\n\n", nrec, nd, rdir, PGA_G);
    printf("| building (storeys; H1/H2 f1) | floor above / floor below: lowest | highest | "
           "floor / median of the others: lowest | highest |\n|---|---|---|---|---|\n");
    for (int b = 0; b < NB && nrec; b++)
        printf("| %zu; %g/%g Hz | %.3f (%s) | %.3f (%s) | %.3f (%s) | %.3f (%s) |\n", B[b].storeys,
               B[b].f1_hz[0], B[b].f1_hz[1], up[b].lo, up[b].lo_at, up[b].hi, up[b].hi_at,
               med[b].lo, med[b].lo_at, med[b].hi, med[b].hi_at);
    if (nrec)
        printf("| the plant (all of them, one ground) | | | %.3f (%s) | %.3f (%s) |\n", plant.lo,
               plant.lo_at, plant.hi, plant.hi_at);
    if (nd)
        sl_pf_names_free(names, nd);
    return 0;
}
