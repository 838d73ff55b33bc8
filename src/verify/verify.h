/*
 * verify.h - verification problems: the installed program against
 * references that do not come from the program (closed forms, values of a
 * guide's tables, hand calculations written out in docs/verification.md).
 * `seislide verify` runs them and files the record (docs/verification.md).
 *
 * A problem computes one quantity with the library and states its
 * reference; the checker (sl_verify_judge) compares them:
 *
 *   SL_VERIFY_CLOSE     error = |computed - reference|,
 *                       tolerance = abs_tol + rel_tol |reference|
 *   SL_VERIFY_AT_MOST   a limit: error = max(0, computed - reference)
 *   SL_VERIFY_AT_LEAST  a limit: error = max(0, reference - computed)
 *                       (for both, tolerance = abs_tol)
 *   SL_VERIFY_BITS      64-bit fingerprints: error 0 when equal, else 1;
 *                       tolerance 0
 *
 * pass when error <= tolerance, written so that NaN fails. A problem whose
 * computation fails (a status other than SL_OK) fails with its message.
 *
 * The inputs are built in the program (formulas and short tables in the
 * problem functions, floor files as embedded text written to a scratch
 * folder); nothing is read from a source tree, the network or recorded
 * motions.
 */
#ifndef SL_VERIFY_H
#define SL_VERIFY_H

#include <stddef.h>
#include <stdint.h>

#include "core/status.h"

typedef enum sl_verify_kind {
    SL_VERIFY_CLOSE = 0,
    SL_VERIFY_AT_MOST,
    SL_VERIFY_AT_LEAST,
    SL_VERIFY_BITS
} sl_verify_kind;

/* What a problem computes: the value, its reference and the tolerance. */
typedef struct sl_verify_value {
    sl_verify_kind kind;
    double reference, computed;  /* in the unit the problem's text names */
    double abs_tol, rel_tol;     /* see the header comment */
    uint64_t ref_bits, got_bits; /* SL_VERIFY_BITS */
} sl_verify_value;

/* Where a problem runs: a scratch folder it may write files into (it
 * removes what it writes), owned by the caller. */
typedef struct sl_verify_ctx {
    const char *scratch_dir;
} sl_verify_ctx;

/* One problem: its area and id ("engine", "E01"), what it checks (with the
 * unit), the reference's source, why the tolerance is what it is, whether
 * it is in the quick subset, and the function that fills v (returns SL_OK,
 * or a status with err filled). */
typedef struct sl_verify_problem {
    const char *area, *id, *checks, *reference_source, *tolerance_basis;
    int quick;
    sl_status (*run)(const sl_verify_ctx *ctx, sl_verify_value *v, sl_error *err);
} sl_verify_problem;

/* Text of a number in the record: "%.10g", hex for fingerprints. */
#define SL_VERIFY_TEXT 48

/* One verdict. */
typedef struct sl_verify_result {
    const sl_verify_problem *problem;
    sl_verify_value value;
    double error, tolerance;
    char reference[SL_VERIFY_TEXT], computed[SL_VERIFY_TEXT];
    char error_text[SL_VERIFY_TEXT], tolerance_text[SL_VERIFY_TEXT];
    int pass;                    /* 1 pass, 0 fail */
    sl_status status;            /* of the computation */
    char msg[1100];              /* its message when status != SL_OK */
    double seconds;              /* wall time of the problem */
} sl_verify_result;

/* The program's problems, in order; *n their count. */
const sl_verify_problem *sl_verify_problems(size_t *n);

/* The checker: fill r's error, tolerance, texts and verdict from v (and
 * r->problem = p). */
void sl_verify_judge(const sl_verify_problem *p, const sl_verify_value *v,
                     sl_verify_result *r);

/* Called after each problem (may be NULL). */
typedef void (*sl_verify_done_fn)(void *cb_ctx, const sl_verify_result *r, size_t k,
                                  size_t total);

/* Run problems tab[0..n-1] (only those with quick set when quick != 0)
 * into out (room for n), *n_run of them; counts in *n_pass and *n_fail.
 * Returns SL_OK when every problem ran passes, SL_ENOCONV when one or more
 * failed (the command line exits 1), SL_EINVAL on a NULL table or output. */
sl_status sl_verify_run(const sl_verify_problem *tab, size_t n, int quick,
                        const sl_verify_ctx *ctx, sl_verify_result *out, size_t *n_run,
                        size_t *n_pass, size_t *n_fail, sl_verify_done_fn done, void *cb_ctx);

/* FNV-1a 64-bit fingerprint of n doubles' bytes (the release bits of a
 * synthesized motion). */
uint64_t sl_verify_fingerprint(const double *x, size_t n);

#endif
