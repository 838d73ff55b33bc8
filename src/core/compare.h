/*
 * compare.h - comparison functions for qsort(3) and bsearch(3).
 *
 * sl_cmp_double orders doubles ascending (-1, 0, +1; NaN compares equal to
 * everything, so sort only finite values). sl_cmp_str orders an array of
 * char * by strcmp of the strings pointed to.
 */
#ifndef SL_COMPARE_H
#define SL_COMPARE_H

/* a, b point to doubles: -1 if *a < *b, +1 if *a > *b, else 0. */
int sl_cmp_double(const void *a, const void *b);

/* a, b point to char * (an array of strings): strcmp of the strings. */
int sl_cmp_str(const void *a, const void *b);

#endif
