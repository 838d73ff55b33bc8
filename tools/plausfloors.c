/*
 * plausfloors.c - the worst ratios of physical floor spectra, the numbers
 * behind the plausibility rules of floor files (io/floor.h,
 * SL_FLOOR_SPIKE_MAX ...; docs/formats-floor.md, "Plausibility").
 *
 *   make plausfloors          (or build/tools/plausfloors [-r DIR] [-n N] [FILE|DIR ...])
 *
 * Physical floor spectra: every three-component record of the records
 * directory (-r, default $SEISLIDE_SHARED/records or ../shared/records) that
 * passes the rule of study/physfloor.h (at most -n of them, 0 = all, after
 * skipping the first -k),
 * scaled to a larger horizontal PGA of 0.3 g, itself ("floor 0") and through
 * two 3-storey buildings of study/building.h (fundamental frequencies
 * H1/H2/V 3.0/4.2/14 Hz and 5.0/5.8/16 Hz, 5 %) to floors 1-3; the 2, 5 and
 * 10 % spectra of each single record (the most jagged a floor spectrum gets)
 * and the mean over all records, plain and broadened +-15 %, on four grids
 * (50 and 10 points per decade 0.1-50 Hz, 5 per decade 0.2-50 Hz, 80 points
 * 0.1-100 Hz), written as floor files (sl_pf_write_floor) and read back.
 * Then every floor file named on the command line (a folder: every *.ini and
 * *.csv in it, and in its sub-folders one level down).
 * Prints, per family, the number of floors, how many the reader refused by
 * the plausibility rules (must be 0) and by any other rule (the ZPA's
 * agreement with the table's end), and the worst of each ratio of
 * sl_floor_plausibility_of() with the floor that has it (over the floors
 * read; the ends of a table on a line of their own), and the range of a given ZPA over the lowest damping's value at
 * the table's last frequency (SL_FLOOR_ZPA_END_MIN/_MAX). Exit 0, or 1 on bad input.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/motion_set.h"
#include "core/units.h"
#include "io/floor.h"
#include "io/setdir.h"
#include "study/building.h"
#include "study/physfloor.h"

#define PGA_G 0.3
#define NGRID 4
#define NF_MAX 200
/* The bins of the given ZPA's ratio to the table's end: below each edge,
 * the last one above the last edge. */
#define ZBINS 9
static const double zedge[ZBINS - 1] = {0.2, 0.3, 0.4, 0.5, 0.65, 0.8, 0.95, 1.0 + 1e-9};

/* The worst of each ratio over a family, with where. */
typedef struct family {
    const char *name;
    size_t n, refused, refused_other; /* by the plausibility rules; by any other rule */
    sl_floor_plausibility w;
    char at[8][260];
    char refusal[2400];
    double zlo, zhi; /* given ZPA / lowest damping's SA at the last frequency */
    size_t zbin[ZBINS];
    char zlo_at[260], zhi_at[260];
} family;

static void family_init(family *f, const char *name)
{
    memset(f, 0, sizeof *f);
    f->name = name;
    f->w.order = INFINITY;
    f->w.order_mean = INFINITY;
    f->w.end_step_lo = f->w.end_step_hi = 1.0;
    f->zlo = INFINITY;
    f->zhi = 0;
}

/* The ratio of each given ZPA to the lowest damping's value at the
 * table's last frequency (io/floor.h, SL_FLOOR_ZPA_END_MIN/_MAX). */
static void note_zpa(family *f, const sl_floor *fl, const char *who)
{
    for (int k = 0; k < SL_FLOOR_NCOMP; k++) {
        const sl_floor_component *c = &fl->comp[k];
        if (!c->zpa_given || !c->nspec)
            continue;
        const sl_spectrum *s = &c->spec[0];
        const double r = c->zpa_ms2 / s->sa_ms2[s->n - 1];
        size_t b = 0;
        while (b < ZBINS - 1 && r >= zedge[b])
            b++;
        f->zbin[b]++;
        if (r < f->zlo) {
            f->zlo = r;
            snprintf(f->zlo_at, sizeof f->zlo_at, "%s, %s %g %% at %.3g Hz", who,
                     sl_floor_comp_name((sl_floor_comp)k), 100 * s->damping, s->f_hz[s->n - 1]);
        }
        if (r > f->zhi) {
            f->zhi = r;
            snprintf(f->zhi_at, sizeof f->zhi_at, "%s, %s %g %% at %.3g Hz", who,
                     sl_floor_comp_name((sl_floor_comp)k), 100 * s->damping, s->f_hz[s->n - 1]);
        }
    }
}

static void note(family *f, const char *path, const char *label)
{
    sl_error e;
    sl_floor *fl = sl_floor_load(path, &e);
    f->n++;
    if (!fl) { /* the plausibility rules' messages (io/floor.c) */
        int plaus = strstr(e.msg, "of its neighbour") || strstr(e.msg, "higher damping's") ||
                    strstr(e.msg, "below the rigid range") || strstr(e.msg, "on average over") ||
                    strstr(e.msg, "gives the ZPA (none is given)");
        if (plaus ? !f->refused++ : !f->refused_other++ && !f->refused)
            snprintf(f->refusal, sizeof f->refusal, "%s (%s): %s:%ld: %s", label, path,
                     e.file, e.line, e.msg);
        return;
    }
    sl_floor_plausibility p;
    sl_floor_plausibility_of(fl, &p);
    const char *who = label ? label : path;
    note_zpa(f, fl, who);
    const int worse[8] = {p.spike > f->w.spike, p.dip > f->w.dip, p.order < f->w.order,
                          p.spread > f->w.spread, p.order_mean < f->w.order_mean,
                          p.dip_first > f->w.dip_first, p.end_step_lo < f->w.end_step_lo,
                          p.end_step_hi > f->w.end_step_hi};
    const double v[8] = {p.spike, p.dip, p.order, p.spread, p.order_mean, p.dip_first,
                         p.end_step_lo, p.end_step_hi};
    double *w[8] = {&f->w.spike, &f->w.dip, &f->w.order, &f->w.spread, &f->w.order_mean,
                    &f->w.dip_first, &f->w.end_step_lo, &f->w.end_step_hi};
    for (int i = 0; i < 8; i++)
        if (worse[i]) {
            *w[i] = v[i];
            snprintf(f->at[i], sizeof f->at[i], "%s, %s %g %% at %.3g Hz", who,
                     sl_floor_comp_name((sl_floor_comp)p.at_comp[i]), 100 * p.at_damping[i],
                     p.at_f_hz[i]);
        }
    sl_floor_free(fl);
}

static void print_family(const family *f)
{
    printf("| %s | %zu | %zu | %zu | %.3f (%s) | %.3f (%s) | %.3f (%s) | %.3f (%s) | %.3f (%s) "
           "|\n",
           f->name, f->n, f->refused, f->refused_other, f->w.spike, f->at[0], f->w.dip, f->at[1],
           f->w.order, f->at[2], f->w.spread, f->at[3], f->w.order_mean, f->at[4]);
    printf("  the ends: dip at the first frequency %.3f (%s); last step in the rigid range "
           "%.3f (%s) to %.3f (%s)\n",
           f->w.dip_first, f->at[5], f->w.end_step_lo, f->at[6], f->w.end_step_hi, f->at[7]);
    if (f->zhi > 0)
        printf("  given ZPA / lowest damping's SA at the last frequency: %.3f (%s) to %.3f "
               "(%s)\n",
               f->zlo, f->zlo_at, f->zhi, f->zhi_at);
    if (f->zhi > 0) {
        printf("  directions with a given ZPA per ratio:");
        for (size_t b = 0; b < ZBINS; b++)
            printf(" %s%.3g: %zu", b == ZBINS - 1 ? ">= " : "< ",
                   zedge[b < ZBINS - 1 ? b : ZBINS - 2], f->zbin[b]);
        printf("\n");
    }
    if (f->refused || f->refused_other)
        printf("  first refused: %s\n", f->refusal);
}

/* Floor files named by arg: a file, or a folder's *.ini / *.csv and those
 * of its sub-folders. */
static void files(family *f, const char *arg, int depth)
{
    char *paths[4096];
    size_t n = 0;
    sl_error e;
    if (sl_floor_list(arg, paths, &n, 4096, &e) == SL_OK)
        for (size_t i = 0; i < n; i++)
            note(f, paths[i], NULL);
    for (size_t i = 0; i < n; i++)
        free(paths[i]);
    if (depth > 0) {
        char **sub;
        size_t ns = sl_pf_list_dirs(arg, &sub, &e);
        for (size_t i = 0; i < ns; i++) {
            char d[4096];
            snprintf(d, sizeof d, "%s/%s", arg, sub[i]);
            files(f, d, depth - 1);
        }
        if (ns)
            sl_pf_names_free(sub, ns);
    }
}

static size_t grid(int g, double *f)
{
    /* 50 / decade 0.1-50; 10 / decade 0.1-50; 5 / decade 0.2-50; 80 points 0.1-100 */
    static const double lo[NGRID] = {0.1, 0.1, 0.2, 0.1}, hi[NGRID] = {50, 50, 50, 100};
    static const double per_dec[NGRID] = {50, 10, 5, 0};
    size_t n = per_dec[g] > 0 ? (size_t)lround(per_dec[g] * log10(hi[g] / lo[g])) + 1 : 80;
    for (size_t j = 0; j < n; j++)
        f[j] = lo[g] * pow(hi[g] / lo[g], (double)j / (double)(n - 1));
    return n;
}

static void free_sets(sl_set *s, size_t n)
{
    for (size_t i = 0; i < n; i++)
        sl_set_free_motions(&s[i]);
}

int main(int argc, char **argv)
{
    const char *rdir = NULL;
    size_t max_rec = 0, skip = 0;
    int opt;
    while ((opt = getopt(argc, argv, "r:n:k:")) != -1) {
        if (opt == 'r')
            rdir = optarg;
        else if (opt == 'n')
            max_rec = (size_t)atol(optarg);
        else if (opt == 'k')
            skip = (size_t)atol(optarg);
        else {
            fprintf(stderr, "usage: plausfloors [-r RECORDS] [-n MAX] [-k SKIP] [FILE|DIR ...]\n");
            return 1;
        }
    }
    char buf[1024], dir[] = "/tmp/seislide-plaus-XXXXXX";
    rdir = sl_pf_records_dir(rdir, buf, sizeof buf);
    if (!mkdtemp(dir))
        return fprintf(stderr, "plausfloors: cannot make a temporary folder\n"), 1;
    sl_error e;
    char **names;
    size_t nd = sl_pf_list_dirs(rdir, &names, &e);
    sl_pf_rule rule;
    sl_pf_rule_default(&rule);
    sl_set *g = calloc(nd ? nd : 1, sizeof *g);
    size_t nrec = 0, passed = 0;
    char **used = calloc(nd ? nd : 1, sizeof *used); /* the name of record r */
    for (size_t i = 0; i < nd && (!max_rec || nrec < max_rec); i++) {
        char d[4096];
        snprintf(d, sizeof d, "%s/%s", rdir, names[i]);
        if (sl_pf_read_record(d, &rule, PGA_G * SL_G, &g[nrec], &e) != SL_OK)
            continue;
        if (passed++ < skip) {
            sl_set_free_motions(&g[nrec]);
            continue;
        }
        used[nrec++] = names[i];
    }
    printf("records: %zu of %zu folders in %s\n\n", nrec, nd, rdir);
    printf("| floors | count | refused by the plausibility rules | by other rules | spike "
           "(worst) | dip | order (lowest) | spread | order on average (lowest) |\n"
           "|---|---|---|---|---|---|---|---|---|\n");
    const sl_building b[2] = {{3, {3.0, 4.2, 14.0}, 0.05}, {3, {5.0, 5.8, 16.0}, 0.05}};
    family one, mean;
    family_init(&one, "single record");
    family_init(&mean, "mean of all records");
    sl_set *fm = calloc(nrec ? nrec : 1, sizeof *fm);
    double f[NF_MAX];
    char path[4200], label[160];
    snprintf(path, sizeof path, "%s/f.ini", dir);
    for (int bi = 0; bi < 2 && nrec; bi++)
        for (size_t fl = 0; fl <= 3; fl++) {
            if (fl == 0 && bi == 1)
                continue; /* the ground once */
            for (size_t r = 0; fl > 0 && r < nrec; r++)
                if (sl_building_floor(&b[bi], fl, &g[r], &fm[r], &e))
                    return fprintf(stderr, "plausfloors: %s\n", e.msg), 1;
            const sl_set *src = fl == 0 ? g : fm;
            for (int gi = 0; gi < NGRID; gi++) {
                size_t nf = grid(gi, f);
                for (int br = 0; br < (fl ? 2 : 1); br++) {
                    for (size_t r = 0; r < nrec; r++) {
                        snprintf(label, sizeof label, "%s building %d floor %zu grid %d%s",
                                 used[r], bi + 1, fl, gi, br ? " broadened" : "");
                        if (sl_pf_write_floor(path, "single record", &src[r], 1, f, nf, br, &e))
                            return fprintf(stderr, "plausfloors: %s\n", e.msg), 1;
                        note(&one, path, label);
                    }
                    snprintf(label, sizeof label, "building %d floor %zu grid %d%s", bi + 1, fl,
                             gi, br ? " broadened" : "");
                    if (sl_pf_write_floor(path, "mean", src, nrec, f, nf, br, &e))
                        return fprintf(stderr, "plausfloors: %s\n", e.msg), 1;
                    note(&mean, path, label);
                }
            }
            if (fl > 0)
                free_sets(fm, nrec);
        }
    remove(path);
    rmdir(dir);
    if (nrec) {
        print_family(&one);
        print_family(&mean);
    }
    for (int i = optind; i < argc; i++) {
        family ff;
        family_init(&ff, argv[i]);
        files(&ff, argv[i], 1);
        print_family(&ff);
    }
    free_sets(g, nrec);
    free(g);
    free(fm);
    free(used);
    if (nd)
        sl_pf_names_free(names, nd);
    return 0;
}
