/* spectrum_output.c - the table of `seislide spectrum`. */
#include "spectrum_output.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "signal/spectrum.h"

static const char *base_name(const char *p)
{
    const char *s = strrchr(p, '/');
    return s ? s + 1 : p;
}

void spectrum_labels(char *const *files, size_t nm, char **label)
{
    int clash = 0;
    for (size_t i = 0; i < nm; i++)
        for (size_t j = i + 1; j < nm; j++)
            clash |= !strcmp(base_name(files[i]), base_name(files[j]));
    for (size_t i = 0; i < nm; i++)
        label[i] = clash ? files[i] : (char *)base_name(files[i]);
}

/* Column names: per file, per damping: psa_g [, sd_m, sa_abs_g], with
 * _z<damping> and _<file label> when there are several. */
static char (*column_names(size_t nm, char *const *label, const double *damp, size_t nd,
                           size_t nq))[320]
{
    static const char *const qname[3] = {"psa_g", "sd_m", "sa_abs_g"};
    char (*name)[320] = calloc(nm * nd * nq, sizeof *name);
    size_t col = 0;
    for (size_t i = 0; name && i < nm; i++)
        for (size_t k = 0; k < nd; k++)
            for (size_t q = 0; q < nq; q++) {
                char zs[24] = "", fs[287] = ""; /* 8 + 23 + 286 < 320 */
                if (nd > 1)
                    snprintf(zs, sizeof zs, "_z%g", damp[k]);
                if (nm > 1)
                    snprintf(fs, sizeof fs, "_%s", label[i]);
                snprintf(name[col++], sizeof name[0], "%s%s%s", qname[q], zs, fs);
            }
    return name;
}

int spectrum_print(int csv, char *const *files, sl_motion *const *m, size_t nm,
                   char *const *label, const double *damp, size_t nd, const double *f, size_t nf,
                   double *const out[3], size_t nq)
{
    char (*name)[320] = column_names(nm, label, damp, nd, nq);
    double *vals = malloc(nm * nd * nq * nf * sizeof *vals);
    if (!name || !vals) {
        free(name);
        free(vals);
        return -1;
    }
    if (!csv) {
        printf("# seislide spectrum: Nigam-Jennings, dt <= T/%g, %zu frequencies\n",
               SL_SPECTRUM_STEPS_PER_PERIOD, nf);
        for (size_t i = 0; i < nm; i++)
            printf("# %s: %zu samples at dt = %g s, PGA %.4f g\n", files[i], m[i]->n, m[i]->dt_s,
                   sl_motion_pga(m[i]) / SL_G);
    }
    size_t col = 0;
    for (size_t i = 0; i < nm; i++)
        for (size_t k = 0; k < nd; k++)
            for (size_t q = 0; q < nq; q++, col++)
                for (size_t p = 0; p < nf; p++) {
                    double v = out[q][k * nm * nf + i * nf + p];
                    vals[col * nf + p] = q == 1 ? v : v / SL_G; /* sd in m, accelerations in g */
                }
    cli_print_table(csv, f, nf, name, nm * nd * nq, vals);
    free(name);
    free(vals);
    return 0;
}
