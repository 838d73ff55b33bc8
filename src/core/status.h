/*
 * status.h - one status enum, one message table, and an error record that
 * carries context (file, line, column) from the library to the command line.
 *
 * The library never prints: functions that can fail take an `sl_error *`
 * (which may be NULL) and fill it; the CLI prints it once as
 *   seislide: FILE:LINE: message    or    seislide: FILE:LINE:COLUMN: message
 */
#ifndef SL_STATUS_H
#define SL_STATUS_H

#include <stddef.h>

#include "core/api.h"

/* Status codes. Zero is success. Keep sl_status_message() in step. */
typedef enum sl_status {
    SL_OK = 0,
    SL_EIO,        /* a file could not be opened, read or written */
    SL_EPARSE,     /* malformed input: bad token, missing header, truncated */
    SL_EINVAL,     /* a value out of its valid range, or inconsistent inputs */
    SL_ENOMEM,     /* allocation failed */
    SL_ENOCONV,    /* an iteration did not converge within its cap */
    SL_ESOLVER,    /* a numerical solver (GSL, FFTW) failed */
    SL_EUNSUPPORTED, /* a valid request this build or model cannot do */
    SL_STATUS_COUNT
} sl_status;

/* Error record filled by the library. `line` and `col` are 0 when not
 * applicable (col is the 1-based field of a CSV row); `file` is empty when
 * the error is not about a file. */
typedef struct sl_error {
    sl_status code;
    long line;
    long col;
    char file[1024];
    char msg[1024];
} sl_error;

/* A short fixed message for a status code ("bad input value", ...). */
SL_API const char *sl_status_message(sl_status code);

/* Reset an error record to SL_OK. Harmless on NULL. */
SL_API void sl_error_clear(sl_error *err);

/* Fill `err` (if not NULL) with a code, optional file (may be NULL),
 * line (0 if none) and a printf-style message. Returns `code`. */
SL_API sl_status sl_error_set(sl_error *err, sl_status code, const char *file,
                              long line, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 5, 6)))
#endif
    ;

/* As sl_error_set() with a column (0 = none). Returns `code`. */
SL_API sl_status sl_error_set_at(sl_error *err, sl_status code, const char *file, long line,
                                 long col, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 6, 7)))
#endif
    ;

/* Format the record as "FILE:LINE:COL: message" (when col > 0),
 * "FILE:LINE: message" (or "FILE: message", or
 * "message") into buf of size n. Returns buf. */
SL_API char *sl_error_format(const sl_error *err, char *buf, size_t n);

#endif
