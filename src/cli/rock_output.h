/* rock_output.h - what `seislide rock` prints and writes: one row per
 * orientation (CSV or aligned), the verdict line, the history file.
 * Formatting only; the numbers come from rock/rock.h. */
#ifndef SL_CLI_ROCK_OUTPUT_H
#define SL_CLI_ROCK_OUTPUT_H

#include <stddef.h>

#include "core/motion_set.h"
#include "rock/rock.h"

/* "stands", "rocks", "tips" or "overturns". */
const char *rock_status_word(const sl_rock_result *r);
/* 1 when a governs b: overturns before tips before the larger theta/alpha. */
int rock_worse(const sl_rock_result *a, const sl_rock_result *b);
/* The CSV: '#' lines (program, content, command), the header, one row per
 * orientation. */
void rock_print_csv(const char *command, const double *orient_deg, const sl_rock_result *res,
                    size_t n);
/* The aligned table after comment lines naming the input and the block,
 * and the one-line verdict of the governing orientation k. */
void rock_print_table(const sl_set *set, const char *const path[3], const sl_rock_block *blk,
                      const double *orient_deg, const sl_rock_result *res, size_t n, size_t k);
/* Write the history atomically: t_s, theta_rad, omega_rad_s, event,
 * omega_before_rad_s (the samples and the events in time order). Returns
 * CLI_EXIT_OK or CLI_EXIT_ERROR (message printed). */
int rock_write_history(const char *path, const sl_rock_history *h);

#endif
