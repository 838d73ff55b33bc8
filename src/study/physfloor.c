/* physfloor.c - records for physical floor motions, ratio statistics and
 * floor files from sets (see physfloor.h, equation P1). */
#include "study/physfloor.h"
#include "core/compare.h"

#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/units.h"
#include "io/atomic.h"
#include "io/setdir.h"
#include "signal/spectrum.h"
#include "synth/synth.h"

void sl_pf_rule_default(sl_pf_rule *r)
{
    r->min_pga_g = SL_PF_MIN_PGA_G;
    r->min_duration_s = SL_PF_MIN_DURATION_S;
    r->max_dt_s = SL_PF_MAX_DT_S;
}

void sl_pf_names_free(char **names, size_t n)
{
    for (size_t i = 0; names && i < n; i++)
        free(names[i]);
    free(names);
}

size_t sl_pf_list_dirs(const char *dir, char ***names, sl_error *err)
{
    *names = NULL;
    DIR *d = opendir(dir);
    if (!d) {
        sl_error_set(err, SL_EIO, dir, 0, "cannot open the records directory");
        return 0;
    }
    size_t n = 0, cap = 0;
    char **v = NULL;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (e->d_name[0] == '.')
            continue;
        char path[4096];
        struct stat st;
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        if (stat(path, &st) || !S_ISDIR(st.st_mode))
            continue;
        if (n == cap) {
            cap = cap ? 2 * cap : 64;
            char **nv = realloc(v, cap * sizeof *v);
            if (!nv)
                break;
            v = nv;
        }
        v[n] = malloc(strlen(e->d_name) + 1);
        if (!v[n])
            break;
        strcpy(v[n++], e->d_name);
    }
    closedir(d);
    if (n)
        qsort(v, n, sizeof *v, sl_cmp_str);
    *names = v;
    return n;
}

sl_status sl_pf_read_record(const char *dir, const sl_pf_rule *rule, double pga_ms2,
                            sl_set *out, sl_error *err)
{
    memset(out, 0, sizeof *out);
    sl_set raw;
    sl_status st = sl_set_read_dir(dir, &raw, err);
    if (st)
        return st;
    st = sl_set_check(&raw, 1, err);
    if (!st && (!raw.h1 || !raw.h2 || !raw.v))
        st = sl_error_set(err, SL_EINVAL, dir, 0, "not a three-component set");
    if (!st) {
        double pga = sl_set_pga_h(&raw) / SL_G, dt = raw.h1->dt_s;
        double dur = dt * (double)(raw.h1->n - 1);
        if (pga < rule->min_pga_g)
            st = sl_error_set(err, SL_EINVAL, dir, 0, "horizontal PGA %.3g g < %.3g g", pga,
                              rule->min_pga_g);
        else if (dur < rule->min_duration_s)
            st = sl_error_set(err, SL_EINVAL, dir, 0, "duration %.3g s < %.3g s", dur,
                              rule->min_duration_s);
        else if (dt > rule->max_dt_s * (1 + 1e-9))
            st = sl_error_set(err, SL_EINVAL, dir, 0, "dt %.3g s > %.3g s", dt,
                              rule->max_dt_s);
    }
    if (!st) {
        double dt = sl_synth_match_dt(raw.h1->dt_s);
        out->h1 = sl_synth_resample_motion(raw.h1, dt);
        out->h2 = sl_synth_resample_motion(raw.h2, dt);
        out->v = sl_synth_resample_motion(raw.v, dt);
        if (!out->h1 || !out->h2 || !out->v)
            st = sl_error_set(err, SL_ENOMEM, dir, 0, "out of memory");
        else
            st = sl_set_check(out, 1, err);
    }
    if (!st) {
        double s = pga_ms2 / sl_set_pga_h(out);
        sl_motion_scale(out->h1, s);
        sl_motion_scale(out->h2, s);
        sl_motion_scale(out->v, s);
    } else {
        sl_set_free_motions(out);
    }
    sl_set_free_motions(&raw);
    return st;
}


const char *sl_pf_records_dir(const char *dir, char *buf, size_t n)
{
    if (dir)
        return dir;
    const char *sh = getenv("SEISLIDE_SHARED");
    snprintf(buf, n, "%s/records", sh && *sh ? sh : "../shared");
    return buf;
}

sl_status sl_pf_read_records(const char *dir, size_t max, double pga_ms2, sl_set **sets,
                             size_t *n, size_t *n_dirs, sl_error *err)
{
    *sets = NULL;
    *n = 0;
    char **names;
    sl_error_clear(err);
    size_t nd = sl_pf_list_dirs(dir, &names, err);
    if (n_dirs)
        *n_dirs = nd;
    if (err->code)
        return err->code;
    sl_set *g = calloc(nd ? nd : 1, sizeof *g);
    if (!g) {
        sl_pf_names_free(names, nd);
        return sl_error_set(err, SL_ENOMEM, dir, 0, "out of memory");
    }
    sl_pf_rule rule;
    sl_pf_rule_default(&rule);
    size_t k = 0;
    for (size_t i = 0; i < nd && (!max || k < max); i++) {
        char d[4096];
        sl_error skip;
        snprintf(d, sizeof d, "%s/%s", dir, names[i]);
        if (sl_pf_read_record(d, &rule, pga_ms2, &g[k], &skip) == SL_OK)
            k++;
    }
    sl_pf_names_free(names, nd);
    *sets = g;
    *n = k;
    return SL_OK;
}

void sl_pf_sets_free(sl_set *sets, size_t n)
{
    for (size_t i = 0; sets && i < n; i++)
        sl_set_free_motions(&sets[i]);
    free(sets);
}

void sl_pf_mean_sd(const double *x, size_t n, size_t stride, double *mean, double *sd)
{
    double m = 0, q = 0;
    for (size_t i = 0; i < n; i++)
        m += x[i * stride];
    m = n ? m / (double)n : NAN;
    for (size_t i = 0; i < n; i++)
        q += (x[i * stride] - m) * (x[i * stride] - m);
    *mean = m;
    *sd = n > 1 ? sqrt(q / (double)(n - 1)) : NAN;
}

double sl_pf_ratio(const double *a, size_t n_a, size_t sa, const double *b, size_t n_b,
                   size_t sb, double *se)
{
    double ma, sda, mb, sdb;
    sl_pf_mean_sd(a, n_a, sa, &ma, &sda);
    sl_pf_mean_sd(b, n_b, sb, &mb, &sdb);
    if (n_a < 2 || n_b < 2 || !(mb > 0) || !(ma > 0)) {
        *se = NAN;
        return mb > 0 ? ma / mb : NAN;
    }
    double r = ma / mb; /* (P1) */
    *se = r * sqrt(sda * sda / ((double)n_a * ma * ma) + sdb * sdb / ((double)n_b * mb * mb));
    return r;
}

static const sl_motion *comp_of(const sl_set *s, int c)
{
    return c == 0 ? s->h1 : c == 1 ? s->h2 : s->v;
}

/* "key = v, v, ..." with continuation lines (inih, < 197 chars a line). */
static void write_list(FILE *f, const char *key, const double *v, size_t n)
{
    fprintf(f, "%s =", key);
    for (size_t i = 0; i < n; i++)
        fprintf(f, "%s %.6g%s", (i && i % 8 == 0) ? "\n   " : "", v[i], i + 1 < n ? "," : "");
    fputc('\n', f);
}

sl_status sl_pf_write_floor(const char *path, const char *name, const sl_set *sets, size_t n,
                            const double *f_hz, size_t nf, int broaden, sl_error *err)
{
    static const double damp[3] = {0.02, 0.05, 0.10};
    static const char *const key[3] = {"sa_0.02", "sa_0.05", "sa_0.1"};
    double *sa = calloc(2 * nf, sizeof *sa), *psa = malloc(nf * sizeof *psa);
    if (!sa || !psa || !n) {
        free(sa);
        free(psa);
        return sl_error_set(err, n ? SL_ENOMEM : SL_EINVAL, path, 0,
                            n ? "out of memory" : "no sets");
    }
    sl_atomic *a = sl_atomic_open(path, err);
    sl_status st = a ? SL_OK : SL_EIO;
    FILE *out = a ? sl_atomic_file(a) : NULL;
    if (out)
        fprintf(out, "[floor]\nname = %s\nunits = m/s2\n", name);
    for (int c = 0; c < 3 && !st; c++) {
        double zpa = 0;
        double *b = sa + nf;
        fprintf(out, "[%s]\n", c == 0 ? "h1" : c == 1 ? "h2" : "v");
        write_list(out, "f_hz", f_hz, nf);
        for (int d = 0; d < 3 && !st; d++) {
            memset(sa, 0, nf * sizeof *sa);
            for (size_t r = 0; r < n && !st; r++) {
                const sl_motion *m = comp_of(&sets[r], c);
                if (d == 0)
                    zpa += sl_motion_pga(m) / (double)n;
                st = sl_spectrum_compute(m->acc_ms2, m->n, m->dt_s, f_hz, nf, damp[d], psa,
                                         NULL, NULL, err);
                for (size_t j = 0; j < nf; j++)
                    sa[j] += psa[j] / (double)n;
            }
            for (size_t j = 0; j < nf; j++) { /* broadened: max over [f/1.15, 1.15 f] */
                b[j] = sa[j];
                for (size_t q = 0; broaden && q < nf; q++)
                    if (f_hz[q] >= f_hz[j] / 1.15 && f_hz[q] <= f_hz[j] * 1.15 && sa[q] > b[j])
                        b[j] = sa[q];
            }
            write_list(out, key[d], b, nf);
        }
        fprintf(out, "zpa = %.6g\n", zpa);
    }
    free(sa);
    free(psa);
    if (st) {
        if (a)
            sl_atomic_abort(a);
        return st;
    }
    return sl_atomic_commit(a, err);
}
