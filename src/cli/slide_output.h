/* slide_output.h - what `seislide slide` prints and writes: the result
 * table (CSV or aligned), the time history file and the note on padded or
 * cut components. Formatting only; the numbers come from slide/slide.h. */
#ifndef SL_CLI_SLIDE_OUTPUT_H
#define SL_CLI_SLIDE_OUTPUT_H

#include <stddef.h>

#include "slide/slide.h"

/* "ok", "no_sliding", "never_stops" or "liftoff" for a result's flags. */
const char *slide_status_word(const sl_slide_result *r);
/* Write the history to path atomically (CSV: t_s, ux_m, uy_m, vx_m_s,
 * vy_m_s, fx_over_w, fy_over_w). Returns CLI_EXIT_OK or CLI_EXIT_ERROR
 * (message printed). */
int slide_write_history(const char *path, const sl_history *h);
/* On stderr, one line per component of path[] whose length fit changed. */
void slide_report_fit(const sl_set *set, const char *const path[3], const sl_set_fit *fit);
/* One CSV row per result, with the header. */
void slide_print_csv(const sl_slide_result *res, size_t n);
/* The aligned table, after two comment lines naming the input (path[],
 * the set's peak horizontal acceleration pga_ms2 and the no-sliding
 * threshold mu_thr). */
void slide_print_table(const sl_set *set, const char *const path[3], const sl_slide_opts *so,
                       double pga_ms2, double mu_thr, const sl_slide_result *res, size_t n);

#endif
