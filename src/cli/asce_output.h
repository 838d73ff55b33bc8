/* asce_output.h - `seislide asce`: its settings, the method's input from
 * the chosen source (method/asce_input.h) with a one-line description,
 * and the printed rows (formatting only). */
#ifndef SL_CLI_ASCE_OUTPUT_H
#define SL_CLI_ASCE_OUTPUT_H

#include <stddef.h>

#include "cli.h"
#include "method/asce_input.h"

typedef struct asce_args {
    const char *h1, *h2, *v, *floor;
    double rg_pga_g, fs, pgd_m, pgv_ms;
    sl_read_opts ro;
    int truncate, csv;
    cli_mu mu;
} asce_args;

/* The method's input from whichever source, its description and the PGV
 * for Newmark's estimates. Returns 0 or -1 (err filled). */
int asce_make_source(const asce_args *a, sl_asce_source *src, sl_floor **fl, sl_motion *m[3],
                     double *pgv_ms, char *what, size_t nw, sl_error *err);
/* The header: the CSV column names, or the comment lines (FS, input, the
 * --pgd given (NaN if not), whether a cap applies) and the column names. */
void asce_print_head(int csv, double fs, const char *what, double pgd_opt_m, int capped);
/* One result row with Newmark's two estimates: CSV, or the aligned table. */
void asce_print_row(const sl_asce_result *r, double nm1, double nm2, int csv);

#endif
