/*
 * rockfloors.c - rocking on synthesized floor sets against rocking on the
 * physical floor motions behind their spectra (docs/rocking.md, "Against
 * physical floor motions"; `make rockfloors` writes the tables of all six
 * buildings to docs/validation/rocking_floors.md, which `seislide study`
 * carries into docs/validation.md, section 7).
 *
 * Physical floor motions: every usable three-component record of the
 * records folder (study/physfloor.h: the quality rule, resampled, larger
 * horizontal PGA scaled to 0.3 g) through linear buildings (study/building.h)
 * of three storeys: the 5 %-damped building of docs/synthesis.md 10, a stiff
 * 3 %-damped one and a soft 2 %-damped one (first mode below 2 Hz). Per
 * floor, its spectra (the mean 2, 5 and 10 % spectra of its physical
 * motions, study/physfloor.h) are written as a floor file and read back, and
 * sets are synthesized to them as `seislide run` makes them
 * (sl_analysis_make_sets). Per block of a grid of slenderness b/h and size h
 * and per level (1.0 and 1.5 x):
 *   physical     the fraction of the records whose floor motion tips the
 *                block in its worst of 12 orientations (15 deg apart), with
 *                its binomial standard error sqrt(p (1 - p) / n);
 *   synthesized  p_tip of rock/rock_floor.h over the sets, with the
 *                intensity scatter (-R, default the run's) and, for
 *                comparison, without it (-R 0 column);
 * and z = (synthesized - physical) / sqrt(SE_s^2 + SE_p^2). A row is
 * printed where the physical fraction at that level is in [0.02, 0.98] or
 * the synthesized one is; the summary table (printed first) counts per
 * building the rows with |z| <= 2, the mean difference and the low-p rows
 * (physical fraction below 0.35: the tail the 1 % and 10 % targets are in)
 * more than 2 SE below the physical fraction.
 *
 *   make rockfloors      (or build/tools/rockfloors [options])
 *   options: -r RECORDS_DIR (default $SEISLIDE_SHARED/records or
 *            ../shared/records), -n MAX_RECORDS (0 = all), -s NSYN (24),
 *            -S SEED (1), -R SIGMA (intensity scatter, default the run's
 *            rocking scatter SL_ROCKF_SCATTER),
 *            -b BUILDINGS (letters: a 5 %, s stiff 3 %, f soft 2 %, and the
 *            held-out x 4 % at 2.4 Hz, y stiff 5 % at 8 Hz, z soft 3 % at
 *            1.2 Hz; default asf)
 * Prints markdown (progress on stderr); exit 0, or 1 with a message on bad
 * input.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "analysis.h"
#include "core/units.h"
#include "io/floor.h"
#include "core/motion_set.h"
#include "io/setdir.h"
#include "rock/rock.h"
#include "rock/rock_floor.h"
#include "study/building.h"
#include "study/physfloor.h"
#include "synth/synth.h"

#define PGA_G 0.3
#define NF 136
#define N_ORIENT 12

typedef struct bldg {
    char key;
    const char *name;
    sl_building b;
} bldg;

static const bldg BUILDINGS[] = {
    {'a', "5 % building (f1 3.0 / 4.2 Hz)", {3, {3.0, 4.2, 14.0}, 0.05}},
    {'s', "stiff 3 % building (f1 5.0 / 6.5 Hz)", {3, {5.0, 6.5, 16.0}, 0.03}},
    {'f', "soft 2 % building (f1 1.6 / 1.9 Hz)", {3, {1.6, 1.9, 12.0}, 0.02}},
    /* held out: not used to choose the scatter of rocking (-b xyz) */
    {'x', "held-out 4 % building (f1 2.4 / 3.0 Hz)", {3, {2.4, 3.0, 13.0}, 0.04}},
    {'y', "held-out stiff 5 % building (f1 8.0 / 10 Hz)", {3, {8.0, 10.0, 18.0}, 0.05}},
    {'z', "held-out soft 3 % building (f1 1.2 / 1.4 Hz)", {3, {1.2, 1.4, 11.0}, 0.03}},
};

#define NBLDG (sizeof BUILDINGS / sizeof *BUILDINGS)
#define LOW_P 0.35 /* a row in the tail the 1 % and 10 % targets are in */

/* The comparison's counts over rows. */
typedef struct tally {
    size_t rows, within, within0, low, low_below;
    double sum_d, sum_d0;
} tally;

static void tally_add(tally *t, double p_phys, double d, double z, double d0, double z0)
{
    t->rows++;
    t->within += fabs(z) <= 2;
    t->within0 += fabs(z0) <= 2;
    t->sum_d += d;
    t->sum_d0 += d0;
    t->low += p_phys < LOW_P;
    t->low_below += p_phys < LOW_P && z < -2;
}

static void tally_row(const char *name, const tally *t)
{
    double n = t->rows ? (double)t->rows : 1.0;
    printf("| %s | %zu | %zu | %+.3f | %zu of %zu | %zu | %+.3f |\n", name, t->rows, t->within,
           t->sum_d / n, t->low_below, t->low, t->within0, t->sum_d0 / n);
}

/* The blocks: b/h x h (centre of mass), m. */
static const double BH[] = {0.15, 0.20, 0.25, 0.30};
static const double H_M[] = {0.5, 1.0, 2.0};
#define NBH (sizeof BH / sizeof *BH)
#define NH (sizeof H_M / sizeof *H_M)
#define NB (NBH * NH)

static void die(const sl_error *e)
{
    fprintf(stderr, "rockfloors: %s%s%s\n", e->file[0] ? e->file : "", e->file[0] ? ": " : "",
            e->msg);
    exit(1);
}

/* Does floor motion set s tip block blk at level L, worst of N_ORIENT
 * orientations? */
static int tips(const sl_set *s, const sl_rock_block *blk, double L, double *work)
{
    sl_rock_opts ro;
    sl_rock_opts_default(&ro);
    const size_t n = s->h1->n;
    for (int k = 0; k < N_ORIENT; k++) {
        sl_rock_project(s->h1->acc_ms2, s->h2 ? s->h2->acc_ms2 : NULL, n, 15.0 * k, work);
        sl_rock_result r;
        sl_error e;
        if (sl_rock_run(blk, work, s->v ? s->v->acc_ms2 : NULL, n, s->h1->dt_s, L, L, &ro, &r,
                        &e))
            die(&e);
        if (r.tipped)
            return 1;
    }
    return 0;
}

int main(int argc, char **argv)
{
    const char *records = NULL, *which = "asf";
    size_t max_records = 0, nsyn = 24;
    uint64_t seed = 1;
    double sigma = SL_ROCKF_SCATTER;
    int c;
    setvbuf(stdout, NULL, _IOLBF, 0);
    while ((c = getopt(argc, argv, "r:n:s:S:R:b:")) != -1)
        switch (c) {
        case 'r': records = optarg; break;
        case 'n': max_records = strtoul(optarg, NULL, 10); break;
        case 's': nsyn = strtoul(optarg, NULL, 10); break;
        case 'S': seed = strtoull(optarg, NULL, 10); break;
        case 'R': sigma = atof(optarg); break;
        case 'b': which = optarg; break;
        default:
            fprintf(stderr, "usage: rockfloors [-r DIR] [-n MAX] [-s NSYN] [-S SEED] [-R SIGMA] "
                            "[-b asf]\n");
            return 1;
        }
    char buf[1024];
    records = sl_pf_records_dir(records, buf, sizeof buf);
    if (nsyn < 2 || !(sigma >= 0 && sigma <= 1)) {
        fprintf(stderr, "rockfloors: bad -s or -R\n");
        return 1;
    }
    sl_error e;
    sl_set *g;
    size_t nrec, nd;
    if (sl_pf_read_records(records, max_records, PGA_G * SL_G, &g, &nrec, &nd, &e))
        die(&e);
    printf("Physical floor motions: %zu usable records of the %zu folders in %s, larger "
           "horizontal PGA scaled to %.1f g, through each building. Synthesized: %zu sets per "
           "floor (seed %llu) with the intensity scatter %.2f. Blocks: b/h %.2f-%.2f by h "
           "%.1f-%.1f m, at 1.0 and 1.5 x, the worst of %d orientations.\n",
           nrec, nd, records, PGA_G, nsyn, (unsigned long long)seed, sigma, BH[0], BH[NBH - 1],
           H_M[0], H_M[NH - 1], N_ORIENT);
    if (nrec < 2) {
        fprintf(stderr, "rockfloors: fewer than 2 usable records in %s\n", records);
        return 1;
    }
    double f[NF];
    for (size_t j = 0; j < NF; j++)
        f[j] = 0.1 * pow(50.0 / 0.1, (double)j / (double)(NF - 1));
    char dir[] = "/tmp/seislide-rf-XXXXXX";
    if (!mkdtemp(dir)) {
        fprintf(stderr, "rockfloors: cannot make a temporary folder\n");
        return 1;
    }
    sl_rockf_item items[NB];
    for (size_t i = 0; i < NBH; i++)
        for (size_t j = 0; j < NH; j++)
            items[i * NH + j] = (sl_rockf_item){{BH[i] * H_M[j], H_M[j], -1.0}, NAN};
    tally all = {0}, per[NBLDG] = {{0}};
    char *tab_buf = NULL;
    size_t tab_len = 0;
    FILE *tab = open_memstream(&tab_buf, &tab_len); /* the per-floor tables, after the summary */
    sl_set *fm = calloc(nrec, sizeof *fm);
    if (!tab || !fm) {
        fprintf(stderr, "rockfloors: out of memory\n");
        return 1;
    }
    for (size_t bi = 0; bi < NBLDG; bi++) {
        const bldg *B = &BUILDINGS[bi];
        if (!strchr(which, B->key))
            continue;
        for (size_t fl = 1; fl <= B->b.storeys; fl++) {
            fprintf(stderr, "rockfloors: %s, floor %zu\n", B->name, fl);
            double zpa = 0;
            for (size_t r = 0; r < nrec; r++) {
                if (sl_building_floor(&B->b, fl, &g[r], &fm[r], &e))
                    die(&e);
                zpa += sl_set_pga_h(&fm[r]) / (double)nrec;
            }
            /* physical fractions */
            double p_phys[NB][SL_ROCKF_NLEVELS];
            size_t n_max = 0;
            for (size_t r = 0; r < nrec; r++)
                n_max = fm[r].h1->n > n_max ? fm[r].h1->n : n_max;
            double *work = malloc(n_max * sizeof *work);
            if (!work) {
                fprintf(stderr, "rockfloors: out of memory\n");
                return 1;
            }
            for (size_t b = 0; b < NB; b++)
                for (int l = 0; l < SL_ROCKF_NLEVELS; l++) {
                    size_t k = 0;
                    double L = l ? SL_ROCKF_LEVEL_2 : SL_ROCKF_LEVEL_1;
                    for (size_t r = 0; r < nrec; r++)
                        k += (size_t)tips(&fm[r], &items[b].block, L, work);
                    p_phys[b][l] = (double)k / (double)nrec;
                }
            free(work);
            /* synthesized */
            char path[256];
            snprintf(path, sizeof path, "%s/floor.ini", dir);
            if (sl_pf_write_floor(path, "physical floor", fm, nrec, f, NF, 0, &e))
                die(&e);
            sl_floor *flr = sl_floor_load(path, &e);
            if (!flr)
                die(&e);
            sl_rockf_opts o;
            sl_rockf_opts_default(&o);
            sl_rockf_result rs[NB], r0[NB];
            o.sigma_ln = sigma;
            if (sl_rockf_floor_run(flr, seed, nsyn, NULL, items, NB, &o, rs, &e))
                die(&e);
            o.sigma_ln = 0;
            if (sl_rockf_floor_run(flr, seed, nsyn, NULL, items, NB, &o, r0, &e))
                die(&e);
            fprintf(tab, "\n%s, floor %zu: ZPA (mean larger H PGA) %.3f g\n\n", B->name, fl,
                    zpa / SL_G);
            fprintf(tab, "| b/h | h, m | level | physical ± SE | synthesized ± SE | z | without "
                    "scatter | z |\n|---|---|---|---|---|---|---|---|\n");
            for (size_t b = 0; b < NB; b++)
                for (int l = 0; l < SL_ROCKF_NLEVELS; l++) {
                    double pp = p_phys[b][l], sp = sqrt(pp * (1 - pp) / (double)nrec);
                    double ps = rs[b].level[l].p_tip, ss = rs[b].level[l].p_tip_se;
                    double p0 = r0[b].level[l].p_tip, s0 = r0[b].level[l].p_tip_se;
                    if (!((pp >= 0.02 && pp <= 0.98) || (ps >= 0.02 && ps <= 0.98)))
                        continue;
                    /* the SE of the smaller sample floored at one outcome's worth */
                    double den = sqrt(sp * sp + ss * ss + 0.25 / ((double)nrec * (double)nrec));
                    double den0 = sqrt(sp * sp + s0 * s0 + 0.25 / ((double)nrec * (double)nrec));
                    double z = (ps - pp) / den, z0 = (p0 - pp) / den0;
                    fprintf(tab, "| %.2f | %.1f | %.1f x | %.3f ± %.3f | %.3f ± %.3f | %+.1f | "
                            "%.3f ± %.3f | %+.1f |\n",
                            BH[b / NH], H_M[b % NH], l ? SL_ROCKF_LEVEL_2 : SL_ROCKF_LEVEL_1,
                            pp, sp, ps, ss, z, p0, s0, z0);
                    tally_add(&per[bi], pp, ps - pp, z, p0 - pp, z0);
                    tally_add(&all, pp, ps - pp, z, p0 - pp, z0);
                }
            sl_floor_free(flr);
            remove(path);
            for (size_t r = 0; r < nrec; r++)
                sl_set_free_motions(&fm[r]);
        }
    }
    rmdir(dir);
    if (fclose(tab)) {
        fprintf(stderr, "rockfloors: out of memory\n");
        return 1;
    }
    printf("\n| building | rows | within 2 SE | mean difference | low-p rows (physical < %.2f) "
           "more than 2 SE below | without scatter: within 2 SE | without scatter: mean "
           "difference |\n|---|---|---|---|---|---|---|\n", LOW_P);
    for (size_t bi = 0; bi < NBLDG; bi++)
        if (strchr(which, BUILDINGS[bi].key))
            tally_row(BUILDINGS[bi].name, &per[bi]);
    tally_row("all", &all);
    printf("\nPer floor: the rows where either fraction is in [0.02, 0.98].\n");
    fwrite(tab_buf, 1, tab_len, stdout);
    free(tab_buf);
    sl_pf_sets_free(g, nrec);
    free(fm);
    return 0;
}
