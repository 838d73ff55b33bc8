/*
 * fuzz_common.h - shared by the fuzz targets of tests/fuzz (libFuzzer's
 * LLVMFuzzerTestOneInput, built by `make fuzz` with clang and ASan + UBSan,
 * and replayed over the corpus by `make test` through replay.c).
 *
 * The readers under test take a path (their extension selects the format,
 * as for a user), so each input is written to a file of the given name in
 * a private temporary folder first. A reader may refuse an input (that is
 * its job); what it must never do is crash, read out of bounds, leak, or
 * return an object that breaks its documented invariants: fuzz_require()
 * aborts then, which libFuzzer reports as a finding.
 */
#ifndef SL_FUZZ_COMMON_H
#define SL_FUZZ_COMMON_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* Abort with the broken invariant named (a finding). */
#define fuzz_require(cond)                                                               \
    do {                                                                                 \
        if (!(cond)) {                                                                   \
            fprintf(stderr, "fuzz: invariant broken: %s (%s:%d)\n", #cond, __FILE__,     \
                    __LINE__);                                                           \
            abort();                                                                     \
        }                                                                                \
    } while (0)

static char fuzz_dir[256], fuzz_last[512];

/* Remove the last file written and the folder (at exit). */
static void fuzz_cleanup(void)
{
    if (fuzz_last[0])
        remove(fuzz_last);
    if (fuzz_dir[0])
        rmdir(fuzz_dir);
}

/* Write data to DIR/name, DIR a folder made once per process; returns the
 * path (static buffer) or NULL when the file cannot be written. */
static inline const char *fuzz_write(const char *name, const uint8_t *data, size_t size)
{
    char *dir = fuzz_dir, *path = fuzz_last;
    if (!dir[0]) {
        const char *t = getenv("TMPDIR");
        snprintf(dir, sizeof fuzz_dir, "%s/seislide-fuzz-XXXXXX", t && *t ? t : "/tmp");
        if (!mkdtemp(dir)) {
            dir[0] = '\0';
            return NULL;
        }
        atexit(fuzz_cleanup);
    }
    if (path[0] && strcmp(strrchr(path, '/') + 1, name) != 0)
        remove(path); /* one file at a time in the folder, so that it can be removed at exit */
    snprintf(path, sizeof fuzz_last, "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    if (!f)
        return NULL;
    int ok = fwrite(data, 1, size, f) == size;
    ok = (fclose(f) == 0) && ok;
    return ok ? path : NULL;
}

/* The one byte that picks a variant, and the rest as the file. */
static inline unsigned fuzz_select(const uint8_t **data, size_t *size, unsigned n)
{
    if (*size == 0)
        return 0;
    unsigned k = (*data)[0] % n;
    (*data)++;
    (*size)--;
    return k;
}

static inline int fuzz_all_finite(const double *x, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (!isfinite(x[i]))
            return 0;
    return 1;
}

#endif
