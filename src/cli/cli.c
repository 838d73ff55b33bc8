/* cli.c - message printing and strict parsing for the command line. */
#include "cli.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

void cli_print_error(const sl_error *err)
{
    char buf[2200];
    fprintf(stderr, "seislide: %s\n", sl_error_format(err, buf, sizeof buf));
}

void cli_msg(const char *fmt, ...)
{
    va_list ap;
    fputs("seislide: ", stderr);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
}

int cli_usage(const char *cmd, const char *fmt, ...)
{
    va_list ap;
    fprintf(stderr, "seislide %s: ", cmd);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fprintf(stderr, " (try 'seislide %s --help')\n", cmd);
    return CLI_EXIT_USAGE;
}

int cli_parse_double(const char *s, double *out)
{
    if (!s || !*s)
        return -1;
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (errno || *end || !isfinite(v))
        return -1;
    *out = v;
    return 0;
}

int cli_parse_ulong(const char *s, unsigned long *out)
{
    if (!s || !*s || *s == '-')
        return -1;
    char *end;
    errno = 0;
    unsigned long v = strtoul(s, &end, 10);
    if (errno || *end)
        return -1;
    *out = v;
    return 0;
}

int cli_parse_list(const char *s, double **vals, size_t *n)
{
    *vals = NULL;
    *n = 0;
    if (!s || !*s)
        return -1;
    size_t cap = 1;
    for (const char *p = s; *p; p++)
        cap += (*p == ',');
    double *v = malloc(cap * sizeof *v);
    char *copy = strdup(s);
    if (!v || !copy) {
        free(v);
        free(copy);
        return -1;
    }
    size_t k = 0;
    char *save = NULL;
    int bad = 0;
    for (char *tok = strtok_r(copy, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        if (cli_parse_double(tok, &v[k]) != 0) {
            bad = 1;
            break;
        }
        k++;
    }
    free(copy);
    if (bad || k == 0 || k != cap) {
        free(v);
        return -1;
    }
    *vals = v;
    *n = k;
    return 0;
}

int cli_parse_range(const char *s, double **vals, size_t *n)
{
    *vals = NULL;
    *n = 0;
    if (!s)
        return -1;
    char *copy = strdup(s);
    if (!copy)
        return -1;
    char *a = copy, *b = strchr(a, ':');
    char *c = b ? strchr(b + 1, ':') : NULL;
    double lo, hi, step;
    int bad = !b || !c;
    if (!bad) {
        *b = '\0';
        *c = '\0';
        bad = cli_parse_double(a, &lo) || cli_parse_double(b + 1, &hi) ||
              cli_parse_double(c + 1, &step);
    }
    free(copy);
    if (bad || !(step > 0) || hi < lo)
        return -1;
    double count = floor((hi - lo) / step + 1e-9) + 1.0;
    if (count > 1e7)
        return -1;
    size_t m = (size_t)count;
    double *v = malloc(m * sizeof *v);
    if (!v)
        return -1;
    for (size_t i = 0; i < m; i++)
        v[i] = lo + (double)i * step; /* computed from i, no accumulated round-off */
    *vals = v;
    *n = m;
    return 0;
}

int cli_positive(const char *cmd, const char *opt, const char *arg, const char *unit, double *out)
{
    double v;
    if (cli_parse_double(arg, &v) || !(v > 0))
        return cli_usage(cmd, "%s '%s' must be a number > 0%s%s%s", opt, arg, unit ? " (" : "",
                         unit ? unit : "", unit ? ")" : "");
    *out = v;
    return CLI_EXIT_OK;
}
