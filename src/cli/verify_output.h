/* verify_output.h - the record of `seislide verify`: verification.csv and
 * verification.xlsx (a printable page to sign and file). */
#ifndef SL_CLI_VERIFY_OUTPUT_H
#define SL_CLI_VERIFY_OUTPUT_H

#include <stddef.h>
#include <time.h>

#include "core/status.h"
#include "verify/verify.h"

/* What the record says about the run, besides the problems. */
typedef struct verify_info {
    char version[64], compiler[160], flags[512], vector[96], host[640], date[64];
    char checked_by[256], command[1024];
    char docs[1200];          /* where verification.md is (the installed copy) */
    time_t created;           /* the date, as the CSV trace lines give it */
    int quick;
    size_t n_pass, n_fail;
} verify_info;

/* Where the explanations of the problems are, into buf: the installed
 * PREFIX/share/doc/seislide/verification.md when the program runs from
 * PREFIX/bin (make install), docs/verification.md beside a program run from
 * its source tree, else a sentence saying where to find it. */
void verify_docs_path(char *buf, size_t n);

/* Write dir/verification.csv and dir/verification.xlsx (each atomically:
 * complete or absent). Returns SL_OK or SL_EIO with err naming the file. */
sl_status verify_write_record(const char *dir, const verify_info *info,
                              const sl_verify_result *res, size_t n, sl_error *err);

#endif
