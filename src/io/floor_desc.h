/*
 * floor_desc.h - what a floor file says, before it is checked (internal;
 * not installed). The INI reader (floor_ini.c) and the CSV reader
 * (floor_csv.c) only read: each fills a sl_floor_desc with the values as
 * written and where they stand (line, and the CSV column), then calls
 * sl_floor_desc_finish(), the one place every rule of a floor lives
 * (floor.c): key values (number, seed, units, h2, name), frequency range
 * and order, positive finite values, damping range and duplicates, the
 * sections or columns present, sizes, the SA and ZPA limits and the ZPA's
 * agreement with the spectrum's high-frequency end. So a rule is written
 * once and an INI file and a CSV file with the same spectra give the same
 * floor, bit for bit.
 */
#ifndef SL_IO_FLOOR_DESC_H
#define SL_IO_FLOOR_DESC_H

#include "io/floor.h"
#include "io/text.h"

/* A list of numbers with where each was written. */
typedef struct sl_floor_vals {
    size_t n, cap;
    double *v;
    long *line, *col;
} sl_floor_vals;

/* One spectrum as written: its damping and values. */
typedef struct sl_floor_sa_desc {
    double damping;    /* ratio of critical */
    char key[40];      /* the key or column that gave it: "sa_0.05", "h1_5" */
    long line, col;    /* where that key or column header is */
    sl_floor_vals sa;  /* values in the file's units */
} sl_floor_sa_desc;

/* One direction as written. */
typedef struct sl_floor_comp_desc {
    long line;          /* INI: section header; CSV: header row; 0 = absent */
    long f_line, f_col; /* the f_hz key or column; 0 = absent */
    sl_floor_vals f;    /* frequencies, Hz */
    size_t nsa;
    sl_floor_sa_desc sa[SL_FLOOR_MAX_DAMPINGS];
    double zpa;         /* in the file's units */
    long zpa_line, zpa_col; /* 0 = not given */
    char zpa_key[16];   /* "zpa" or "zpa_h1" */
} sl_floor_comp_desc;

/* The floor keys both formats share (INI [floor] keys, CSV "# key:"
 * comment lines), and the per-direction zpa. */
typedef enum sl_floor_key {
    SL_FK_NAME, SL_FK_ELEV, SL_FK_UNITS, SL_FK_H2, SL_FK_DESC, SL_FK_SEED, SL_FK_BUILDING,
    SL_FK_COUNT
} sl_floor_key;
extern const char *const sl_floor_key_names[SL_FK_COUNT];

typedef struct sl_floor_desc {
    const char *path;
    sl_floor_format format; /* chooses the wording of messages only */
    sl_error *err;
    int failed;
    long eof_line;          /* last line of the file */
    long floor_line;        /* INI: the [floor] header; CSV: 1 */
    char *text[SL_FK_COUNT];/* values of the text keys as written (NULL: absent) */
    long key_line[SL_FK_COUNT], key_col[SL_FK_COUNT];
    double elevation_m;
    unsigned long long seed;
    sl_floor_comp_desc comp[SL_FLOOR_NCOMP];
    long fail_line, fail_col; /* where the recorded error is */
    int periods;            /* CSV: the first column was T_s (periods, s), now 1/T */
} sl_floor_desc;

void sl_floor_desc_init(sl_floor_desc *d, const char *path, sl_floor_format fmt,
                        sl_error *err);
void sl_floor_desc_free(sl_floor_desc *d);

/* Record an error (the first one wins); returns 0 so a reader can
 * `return sl_floor_desc_fail(...)`. col 0 = no column. */
int sl_floor_desc_fail(sl_floor_desc *d, sl_status code, long line, long col, const char *fmt,
                       ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 5, 6)))
#endif
    ;

/* The key named `name` (SL_FK_COUNT if none). */
sl_floor_key sl_floor_desc_key(const char *name);

/* Set a floor key from its written value: stored as text; elevation_m must
 * be a finite number, seed an integer 0..2^64-1, h2 'same_as_h1'; a key
 * given twice is an error naming the first line. 1, or 0 on error. */
int sl_floor_desc_set(sl_floor_desc *d, sl_floor_key k, const char *value, long line,
                      long col);

/* A written number (whole token, finite); `key` names it in the message
 * "<key>: '<token>' is not a finite number". 1, or 0 on error. */
int sl_floor_desc_number(sl_floor_desc *d, const char *key, const char *tok, long line,
                         long col, double *out);

/* Append a value to a list. 1, or 0 (no memory). */
int sl_floor_desc_push(sl_floor_desc *d, sl_floor_vals *l, double x, long line, long col);

/* A new spectrum of component c at damping ratio `damping` (unchecked)
 * written as `key` at line/col; NULL when the component already has
 * SL_FLOOR_MAX_DAMPINGS. */
sl_floor_sa_desc *sl_floor_desc_add_sa(sl_floor_desc *d, sl_floor_comp c, double damping,
                                       const char *key, long line, long col);

/* The given ZPA of component c (positive is checked later). 1 or 0. */
int sl_floor_desc_set_zpa(sl_floor_desc *d, sl_floor_comp c, const char *key, const char *tok,
                          long line, long col);

/* Check everything and build the floor (floor.c). NULL with err filled on
 * the first error (by line, for value errors). d is left for the caller to
 * free. */
sl_floor *sl_floor_desc_finish(sl_floor_desc *d);

/* The readers: fill d from the file in memory. 1, or 0 with d->failed. */
int sl_floor_read_ini(sl_floor_desc *d, sl_text *t);
int sl_floor_read_csv(sl_floor_desc *d, sl_text *t);

#endif
