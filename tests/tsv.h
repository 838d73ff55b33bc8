/*
 * tsv.h - a tab-separated table in memory (MANIFEST.tsv, SUMMARY.tsv of
 * ../shared/records), for the tests that check readers against them.
 */
#ifndef SL_TEST_TSV_H
#define SL_TEST_TSV_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A tab-separated table in memory: rows of fields (NUL-terminated). */
typedef struct tsv {
    char *buf;
    char **f;      /* nrow * ncol fields */
    size_t nrow, ncol;
} tsv;

static void tsv_free(tsv *t)
{
    free(t->buf);
    free(t->f);
}

static int tsv_read(const char *path, tsv *t)
{
    memset(t, 0, sizeof *t);
    FILE *fp = fopen(path, "rb");
    if (!fp)
        return -1;
    fseek(fp, 0, SEEK_END);
    long sz = ftell(fp);
    fseek(fp, 0, SEEK_SET);
    t->buf = malloc((size_t)sz + 1);
    if (!t->buf || fread(t->buf, 1, (size_t)sz, fp) != (size_t)sz) {
        fclose(fp);
        tsv_free(t);
        return -1;
    }
    fclose(fp);
    t->buf[sz] = '\0';
    size_t lines = 0, tabs = 0;
    for (char *p = t->buf; *p; p++) {
        lines += *p == '\n';
        tabs += *p == '\t';
    }
    t->f = calloc(tabs + lines + 2, sizeof *t->f);
    if (!t->f) {
        tsv_free(t);
        return -1;
    }
    size_t k = 0, ncol = 0, col = 0;
    char *p = t->buf;
    while (*p) {
        t->f[k++] = p;
        col++;
        char *e = p + strcspn(p, "\t\n");
        char c = *e;
        *e = '\0';
        p = c ? e + 1 : e;
        if (c != '\t') {
            if (ncol == 0)
                ncol = col;
            if (col != ncol) {
                tsv_free(t);
                return -1;
            }
            col = 0;
        }
    }
    t->ncol = ncol;
    t->nrow = ncol ? k / ncol : 0;
    return 0;
}

/* Column index by header name, or -1. */
static long tsv_col(const tsv *t, const char *name)
{
    for (size_t j = 0; j < t->ncol; j++)
        if (!strcmp(t->f[j], name))
            return (long)j;
    return -1;
}

static const char *tsv_get(const tsv *t, size_t row, long col)
{
    return t->f[row * t->ncol + (size_t)col];
}

#endif
