/*
 * csvread.h - CSV tables read record by record (RFC 4180): fields quoted
 * when they hold a comma, a quote (doubled) or a line break; LF, CRLF or CR
 * line ends; blank lines and lines starting with '#' (outside a quoted
 * field) skipped; each record and field with the line it starts on, for
 * messages "file:line:column" (the column is the field's number). The
 * components check (components.c) reads its list and the run's tables with
 * it. Internal to src/report.
 */
#ifndef SL_REPORT_CSVREAD_H
#define SL_REPORT_CSVREAD_H

#include <stddef.h>

#include "core/status.h"
#include "io/text.h"

typedef struct sl_csvread {
    const char *path, *buf;
    size_t len, pos;
    long line;               /* the line at pos */
    char sep;                /* the field separator; 0 is ',' */
} sl_csvread;

typedef struct sl_csvrec {
    char **f;
    long *fline;             /* the line each field starts on */
    size_t n, cap;
    long line;               /* the line the record starts on */
} sl_csvrec;

/* The next record into r (its fields replace r's): 1, 0 at the end, or a
 * negated status with err filled (a quoted field left open, text after a
 * closing quote, no memory). */
int sl_csvread_next(sl_csvread *c, sl_csvrec *r, sl_error *err);
/* The separator of the table from its header row (the first line that is
 * neither blank nor a comment), as the floor tables find it
 * (io/floor_csv.c): ';' when it holds ';' and no ',' outside quotes (a
 * European spreadsheet's CSV, with decimal commas), else ','; set in c.
 * Both: SL_EPARSE naming the line. */
sl_status sl_csvread_detect_sep(sl_csvread *c, sl_error *err);
/* Free r's fields and arrays (r zeroed). */
void sl_csvrec_free(sl_csvrec *r);
/* s without blanks at either end, into buf of size n (cut to fit). */
const char *sl_csv_trimmed(const char *s, char *buf, size_t n);
/* Read path whole (sl_text_load: BOM skipped, NUL refused, at most max bytes). */
sl_status sl_csv_load(const char *path, long max, sl_text *t, sl_error *err);
/* sl_csv_load, then *rd set to read t from its first line (path is kept:
 * it must outlive rd). */
sl_status sl_csv_open(const char *path, long max, sl_text *t, sl_csvread *rd, sl_error *err);
/* The column of header h named `name` (trimmed, without case), or -1. */
int sl_csv_header_col(const sl_csvrec *h, const char *name);
/* The header record: cols[k] the column of names[k]; SL_EPARSE naming the
 * first missing one. */
sl_status sl_csv_header(sl_csvread *rd, sl_csvrec *h, const char *const *names, size_t nn,
                        int *cols, sl_error *err);
/* Field col of record w as a number (empty: NAN when empty_nan, else an
 * error); SL_EPARSE / SL_EINVAL naming line, column and value. */
sl_status sl_csv_num(const sl_csvread *rd, const sl_csvrec *w, int col, double *v, int empty_nan,
                     sl_error *err);

#endif
