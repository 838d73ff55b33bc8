/* spectrum_output.h - the table of `seislide spectrum`: column names and
 * labels of the files, values converted to g (formatting only). */
#ifndef SL_CLI_SPECTRUM_OUTPUT_H
#define SL_CLI_SPECTRUM_OUTPUT_H

#include <stddef.h>

#include "io/motion.h"

/* Labels of the nm files for column names: their base names, or the paths
 * as given when two base names coincide (pointers into files[]). */
void spectrum_labels(char *const *files, size_t nm, char **label);
/* The table (or CSV): f, then every column; out[q] holds quantity q
 * (psa, sd, sa; nq of them) as out[q][k * nm * nf + i * nf + j] for
 * damping k, file i, frequency j. Returns 0 or -1 (no memory). */
int spectrum_print(int csv, char *const *files, sl_motion *const *m, size_t nm,
                   char *const *label, const double *damp, size_t nd, const double *f, size_t nf,
                   double *const out[3], size_t nq);

#endif
