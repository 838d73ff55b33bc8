/*
 * benchplant.c - the plant of `make bench-plant` (docs/plant.md,
 * "Speed: make bench-plant"): N floor files from a simple building model.
 *
 *   build/tools/benchplant GROUND_DIR N OUT
 *
 * GROUND_DIR holds ground sets setNN_{h1,h2,v}.AT2 spectrum-compatible with
 * RG 1.60 at 1 g (`seislide synth --rg160 1 --count 3 --seed 1 -o DIR`). The
 * plant is made of blocks of 6 floors: ground level l (PGA 0.10, 0.15, ...
 * 0.55 g, then again with the buildings 10 % stiffer), two buildings (fundamental
 * frequencies H1/H2/V 3.0/3.5/14 Hz and 5.0/5.8/16 Hz), each a 3-storey uniform
 * shear building of 5 %-damped modes (study/building.h, (B1)-(B5)); floor j
 * of a building is the mean 2, 5 and 10 % spectra of the ground sets through
 * the building, on 80 log-spaced frequencies 0.1-100 Hz (to the Nyquist frequency of the
 * 200 samples/s ground sets, so that the 2 % spectrum reaches the ZPA the floor
 * file states), broadened +-15 %
 * (study/physfloor.h, sl_pf_write_floor). Written as
 * OUT/L<l>-B<b>/floor<j>.ini (one folder per building and ground level), the
 * first N floors in that order. Exit 0, or 1 with a message.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/units.h"
#include "io/setdir.h"
#include "study/building.h"
#include "study/physfloor.h"

#define MAX_SETS 16
#define NF 80

static int die(const sl_error *e)
{
    fprintf(stderr, "benchplant: %s:%ld: %s\n", e->file, e->line, e->msg);
    return 1;
}

/* A copy of m scaled by s (NULL stays NULL). */
static sl_motion *scaled(const sl_motion *m, double s)
{
    if (!m)
        return NULL;
    sl_motion *c = calloc(1, sizeof *c);
    if (!c || !(c->acc_ms2 = malloc(m->n * sizeof *c->acc_ms2)))
        exit(1);
    c->n = m->n;
    c->dt_s = m->dt_s;
    c->path = strdup("");
    c->label = strdup("");
    for (size_t i = 0; i < m->n; i++)
        c->acc_ms2[i] = s * m->acc_ms2[i];
    return c;
}

int main(int argc, char **argv)
{
    if (argc != 4 || atoi(argv[2]) < 1) {
        fprintf(stderr, "usage: benchplant GROUND_DIR N OUT\n");
        return 2;
    }
    const char *gdir = argv[1], *out = argv[3];
    size_t nfloors = (size_t)atoi(argv[2]);
    sl_set g[MAX_SETS], gs[MAX_SETS], fm[MAX_SETS];
    size_t ng = 0;
    sl_error e;
    for (; ng < MAX_SETS; ng++) {
        char p[3][4200];
        const char *pp[3];
        static const char *const cn[3] = {"h1", "h2", "v"};
        for (int c = 0; c < 3; c++) {
            snprintf(p[c], sizeof p[c], "%s/set%02zu_%s.AT2", gdir, ng + 1, cn[c]);
            pp[c] = p[c];
        }
        struct stat st;
        if (stat(p[0], &st) != 0)
            break;
        sl_read_opts ro;
        memset(&ro, 0, sizeof ro);
        if (sl_set_read_files(pp, &ro, 0, &g[ng], NULL, &e))
            return die(&e);
    }
    if (ng == 0) {
        fprintf(stderr, "benchplant: no ground sets set01_h1.AT2 ... in %s\n", gdir);
        return 1;
    }
    double f[NF];
    for (size_t j = 0; j < NF; j++)
        f[j] = 0.1 * pow(1000.0, (double)j / (NF - 1));
    static const double f1[2][3] = {{3.0, 3.5, 14.0}, {5.0, 5.8, 16.0}};
    if (mkdir(out, 0777) != 0) {
        fprintf(stderr, "benchplant: cannot create %s (it must be new)\n", out);
        return 1;
    }
    size_t made = 0;
    for (size_t l = 0; made < nfloors; l++) {
        double pga = 0.10 + 0.05 * (double)(l % 10), stiff = 1.0 + 0.1 * (double)(l / 10);
        for (size_t r = 0; r < ng; r++)
            gs[r] = (sl_set){scaled(g[r].h1, pga), scaled(g[r].h2, pga), scaled(g[r].v, pga)};
        for (int b = 0; b < 2 && made < nfloors; b++) {
            sl_building bl = {3, {stiff * f1[b][0], stiff * f1[b][1], stiff * f1[b][2]}, 0.05};
            char dir[4200], path[4300], name[128];
            snprintf(dir, sizeof dir, "%s/L%02zu-B%d", out, l + 1, b + 1);
            if (mkdir(dir, 0777) != 0) {
                fprintf(stderr, "benchplant: cannot create %s\n", dir);
                return 1;
            }
            for (size_t j = 1; j <= 3 && made < nfloors; j++, made++) {
                for (size_t r = 0; r < ng; r++)
                    if (sl_building_floor(&bl, j, &gs[r], &fm[r], &e))
                        return die(&e);
                snprintf(path, sizeof path, "%s/floor%zu.ini", dir, j);
                snprintf(name, sizeof name, "ground %.2f g, building %d, floor %zu", pga, b + 1, j);
                if (sl_pf_write_floor(path, name, fm, ng, f, NF, 1, &e))
                    return die(&e);
                for (size_t r = 0; r < ng; r++)
                    sl_set_free_motions(&fm[r]);
            }
        }
        for (size_t r = 0; r < ng; r++)
            sl_set_free_motions(&gs[r]);
    }
    for (size_t r = 0; r < ng; r++)
        sl_set_free_motions(&g[r]);
    printf("benchplant: %zu floors in %s\n", made, out);
    return 0;
}
