/*
 * text.h - the text helpers every reader of src/io shares (internal; not
 * installed): a file read whole into memory and walked line by line, number
 * parsing that checks a token in full, case-insensitive search, quoting of a
 * token for an error message, unit names as files write them, and growable
 * arrays.
 *
 * One way to read a file: sl_text_load() reads it whole (refusing it before
 * reading when it is larger than the caller's limit), skips a UTF-8
 * byte-order mark, and optionally refuses a file that is not text (a NUL
 * byte, reported with its line). Lines end in LF, CRLF or CR and have no
 * length limit. The motion readers (motion.c, at2.c, columns.c), the agency
 * formats (formats.c) and the floor readers (floor.c, floor_csv.c) all read
 * through it.
 *
 * Memory: sl_text_load() fills a sl_text whose buffer the caller frees with
 * sl_text_free(). Errors name the file (and the line when there is one).
 */
#ifndef SL_IO_TEXT_H
#define SL_IO_TEXT_H

#include <stddef.h>

#include "core/status.h"
#include "core/units.h"

/* Longest numeric token accepted, characters (longer ones are rejected). */
#define SL_TEXT_TOKEN_MAX 127
/* Characters of an offending token quoted in an error message. */
#define SL_TEXT_QUOTE_MAX 40

/* A file in memory, walked line by line. */
typedef struct sl_text {
    char *mem;        /* the allocation (NUL-terminated); free with sl_text_free */
    const char *buf;  /* the text after the byte-order mark */
    size_t len;       /* bytes from buf */
    size_t pos;       /* read position from buf */
    long lineno;      /* number of the line last returned (1-based) */
} sl_text;

/* What sl_text_load() checks besides the size. */
typedef struct sl_text_opts {
    long max_bytes;    /* larger files are refused before reading */
    const char *what;  /* "a motion file", "a floor file": named in the size message */
    const char *limit_name; /* the constant behind the limit, or NULL */
    int text_only;     /* 1: a NUL byte is "not a text file: NUL byte at line L", and
                          UTF-16 text (a byte-order mark FF FE / FE FF, or NUL bytes
                          at every other position) is refused as such, at line 1 */
} sl_text_opts;

/* Read `path` whole into t (NUL-terminated; BOM skipped). SL_EIO (cannot
 * open or read), SL_EINVAL (larger than max_bytes: "file of N bytes is
 * larger than the M bytes <what> may have; not read"), SL_EPARSE (a NUL
 * byte with text_only), SL_ENOMEM. On failure t is empty. */
sl_status sl_text_load(const char *path, const sl_text_opts *o, sl_text *t, sl_error *err);

void sl_text_free(sl_text *t);

/* Next line without its line end (LF, CRLF or CR); 0 at the end. */
int sl_text_next(sl_text *t, const char **s, size_t *n);

/* Blank (only white space) or a comment (first non-blank is '#'). */
int sl_text_skip_line(const char *s, size_t n);

/* ' ', '\t', '\v', '\f', '\r' (not '\n'). */
int sl_text_is_space(char c);

/* Trim blanks at both ends of [*s, *s + *n). */
void sl_text_trim(const char **s, size_t *n);

/* Case-insensitive search for `needle` in s[0..n); offset or -1. */
long sl_text_find_ci(const char *s, size_t n, const char *needle);

/* The same in a NUL-terminated string: a pointer to the match or NULL. */
const char *sl_text_find_str_ci(const char *s, const char *needle);

/* strdup of s ("" for NULL) and of n bytes of s; NULL on no memory. */
char *sl_text_dup(const char *s);
char *sl_text_dup_mem(const char *s, size_t n);

/* Length in bytes of the well-formed UTF-8 character at s[0..n) (RFC 3629:
 * no overlong forms, surrogates or code points above U+10FFFF), 0 when
 * n = 0 or the bytes are not one. */
size_t sl_text_utf8_len(const char *s, size_t n);

/* s[0..n) as written for a message, into dst (cap + 4 bytes): whole UTF-8
 * characters up to cap bytes, "..." when cut; a control character (C0, DEL,
 * C1) or a byte that is not UTF-8 shows as '?'. */
void sl_text_quote_into(char *dst, size_t cap, const char *s, size_t n);

/* A token quoted for a message: sl_text_quote_into at SL_TEXT_QUOTE_MAX
 * bytes. */
typedef struct sl_quoted {
    char s[SL_TEXT_QUOTE_MAX + 4];
} sl_quoted;
sl_quoted sl_text_quote(const char *tok, size_t n);

/* A number written with a decimal comma (a table separated by ';', as a
 * European spreadsheet saves it: the floor tables, the components list):
 * the comma becomes a point in place. 1, or 0 when the token holds both a
 * comma and a point, or two commas (a thousands separator: ambiguous,
 * refused by the caller). */
int sl_text_decimal_comma(char *tok);

/* A whole token as a finite number: strtod syntax plus a Fortran 'D'
 * exponent; hexadecimal, blanks inside and anything left over rejected. */
typedef enum sl_num_result { SL_NUM_OK, SL_NUM_BAD, SL_NUM_NONFINITE } sl_num_result;
sl_num_result sl_text_parse_num(const char *s, size_t n, double *out);

/* Fill err for a token sl_text_parse_num() refused: "value 'x' is not
 * finite" (SL_EINVAL) or "non-numeric value 'x'" (SL_EPARSE). */
sl_status sl_text_token_error(sl_error *err, const char *path, long line, const char *tok,
                              size_t n, sl_num_result r);

/* A unit as files write it ("G", "CM/SEC/SEC", "cm/s^2", "gal", "gals",
 * "m/s**2", "m/s²"); SL_UNIT_NONE if not understood. */
sl_unit sl_text_unit(const char *s, size_t n);

/* Growable arrays of doubles and of line numbers; push returns 0 or -1 (no
 * memory). Free the member v. */
typedef struct sl_dvec {
    double *v;
    size_t n, cap;
} sl_dvec;
int sl_dvec_reserve(sl_dvec *d, size_t cap);
int sl_dvec_push(sl_dvec *d, double x);

typedef struct sl_lvec {
    long *v;
    size_t n, cap;
} sl_lvec;
int sl_lvec_push(sl_lvec *d, long x);

#endif
