/*
 * harness.h - a tiny test harness: each test is a function; a test fails
 * when any CHECK in it fails. main() runs them with RUN() and ends with
 * HARNESS_END(), which prints "NAME: N passed, N failed, N skipped" and
 * returns the exit code.
 *
 * Floats are compared honestly: pass when
 *   |got - exp| <= abs_tol + rel_tol * |exp|
 * written so that NaN fails; both values printed with %.17g.
 */
#ifndef SL_TEST_HARNESS_H
#define SL_TEST_HARNESS_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static int h_pass, h_fail, h_skip;
static int h_cur_failed, h_cur_skipped;
static const char *h_cur_name;

#define CHECK(cond, ...)                                                     \
    do {                                                                     \
        if (!(cond)) {                                                       \
            h_cur_failed = 1;                                                \
            fprintf(stderr, "  FAIL %s (%s:%d): %s: ", h_cur_name, __FILE__, \
                    __LINE__, #cond);                                        \
            fprintf(stderr, __VA_ARGS__);                                    \
            fputc('\n', stderr);                                             \
        }                                                                    \
    } while (0)

#define CHECK_CLOSE(got, exp, abs_tol, rel_tol)                                    \
    do {                                                                           \
        double h_g_ = (got), h_e_ = (exp);                                         \
        if (!(fabs(h_g_ - h_e_) <= (abs_tol) + (rel_tol) * fabs(h_e_))) {          \
            h_cur_failed = 1;                                                      \
            fprintf(stderr,                                                        \
                    "  FAIL %s (%s:%d): %s = %.17g, expected %s = %.17g "         \
                    "(abs %.3g, rel %.3g)\n",                                      \
                    h_cur_name, __FILE__, __LINE__, #got, h_g_, #exp, h_e_,        \
                    (double)(abs_tol), (double)(rel_tol));                         \
        }                                                                          \
    } while (0)

/* Mark the running test skipped, with a reason, and return from it. */
#define SKIP(...)                                                  \
    do {                                                           \
        h_cur_skipped = 1;                                         \
        fprintf(stderr, "  SKIP %s: ", h_cur_name);                \
        fprintf(stderr, __VA_ARGS__);                              \
        fputc('\n', stderr);                                       \
        return;                                                    \
    } while (0)

#define RUN(fn)                                                    \
    do {                                                           \
        h_cur_name = #fn;                                          \
        h_cur_failed = 0;                                          \
        h_cur_skipped = 0;                                         \
        fn();                                                      \
        if (h_cur_failed)                                          \
            h_fail++;                                              \
        else if (h_cur_skipped)                                    \
            h_skip++;                                              \
        else                                                       \
            h_pass++;                                              \
        if (getenv("SEISLIDE_TEST_VERBOSE"))                       \
            fprintf(stderr, "  %s %s\n",                           \
                    h_cur_failed ? "FAIL" : h_cur_skipped ? "SKIP" \
                                                          : "ok",  \
                    #fn);                                          \
    } while (0)

#define HARNESS_END(suite)                                                   \
    (printf("%s: %d passed, %d failed, %d skipped\n", suite, h_pass, h_fail, \
            h_skip),                                                         \
     h_fail ? 1 : 0)

/* The shared data folder (../shared from the repository root, or
 * $SEISLIDE_SHARED); NULL when absent, so tests that need it can SKIP. */
static inline const char *harness_shared_dir(void)
{
    const char *d = getenv("SEISLIDE_SHARED");
    static const char *fallback = "../shared";
    struct stat st;
    if (!d || !*d)
        d = fallback;
    if (stat(d, &st) != 0 || !S_ISDIR(st.st_mode))
        return NULL;
    return d;
}

/* Write text to a temporary file; returns its path (static buffer per
 * call slot, 8 slots). */
static inline const char *harness_tmpfile(const char *name, const char *text)
{
    static char paths[8][512];
    static int slot;
    char *p = paths[slot++ % 8];
    const char *dir = getenv("TMPDIR");
    snprintf(p, 512, "%s/seislide-test-%ld-%s", dir && *dir ? dir : "/tmp",
             (long)getpid(), name);
    FILE *f = fopen(p, "wb");
    if (!f)
        return NULL;
    fputs(text, f);
    fclose(f);
    return p;
}

#endif
