/* cli.c - message printing and strict parsing for the command line. */
#include "cli.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "outdir.h"
#include "signal/spectrum.h"
#include "signal/spectrum_kernel.h"
#include "slide/kernel2d.h"

void cli_print_error(const sl_error *err)
{
    char buf[2200];
    sl_error named = *err; /* a file of the fresh output folder named as in the final one */
    cli_outdir_final_name(named.file, sizeof named.file);
    fprintf(stderr, "seislide: %s\n", sl_error_format(&named, buf, sizeof buf));
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

int cli_parse_created(const char *s, double *out)
{
    double v;
    if (cli_parse_double(s, &v) || v < 0 || v > 4e12)
        return -1;
    *out = v;
    return 0;
}

double cli_created_default(void)
{
    const char *sde = getenv("SOURCE_DATE_EPOCH");
    double v;
    return (sde && !cli_parse_double(sde, &v) && v >= 0) ? v : (double)time(NULL);
}

int cli_parse_ulong(const char *s, unsigned long *out)
{
    if (!s || !(*s >= '0' && *s <= '9')) /* strtoul would take " 5", "+5" and "-5" */
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

int cli_units(const char *cmd, const char *arg, sl_unit *out)
{
    sl_unit u = sl_unit_parse(arg);
    if (u == SL_UNIT_NONE)
        return cli_usage(cmd, "unknown unit '%s' (g, m/s2, cm/s2 = gal, mm/s2)", arg);
    *out = u;
    return CLI_EXIT_OK;
}

int cli_friction(const char *cmd, int is_range, const char *arg, double **mu, size_t *n)
{
    free(*mu);
    *mu = NULL;
    *n = 0;
    if (is_range ? cli_parse_range(arg, mu, n) : cli_parse_list(arg, mu, n))
        return cli_usage(cmd, "bad %s '%s'", is_range ? "--mu-range" : "--mu", arg);
    return CLI_EXIT_OK;
}

void cli_grid_init(cli_grid *g)
{
    g->fmin_hz = SL_SPECTRUM_FMIN_HZ;
    g->fmax_hz = SL_SPECTRUM_FMAX_HZ;
    g->per_decade = SL_SPECTRUM_PER_DECADE;
    g->freq = NULL;
    g->nfreq = 0;
    g->grid_opts = 0;
}

void cli_grid_free(cli_grid *g)
{
    free(g->freq);
    g->freq = NULL;
    g->nfreq = 0;
}

int cli_grid_option(const char *cmd, cli_grid_opt which, const char *arg, cli_grid *g)
{
    static const char *const names[] = {"--fmin", "--fmax", "--per-decade", "--freq"};
    if (which == CLI_GRID_FREQ) {
        cli_grid_free(g);
        if (cli_parse_list(arg, &g->freq, &g->nfreq))
            return cli_usage(cmd, "bad --freq '%s'", arg);
        return CLI_EXIT_OK;
    }
    double v;
    if (cli_parse_double(arg, &v) || !(v > 0))
        return cli_usage(cmd, "%s '%s' must be a number > 0", names[which], arg);
    if (which == CLI_GRID_FMIN)
        g->fmin_hz = v;
    else if (which == CLI_GRID_FMAX)
        g->fmax_hz = v;
    else
        g->per_decade = v;
    g->grid_opts = 1;
    return CLI_EXIT_OK;
}

int cli_grid_make(const char *cmd, cli_grid *g, double **f, size_t *nf)
{
    if (g->freq && g->grid_opts)
        return cli_usage(cmd, "--freq excludes --fmin, --fmax and --per-decade");
    if (g->freq) {
        for (size_t j = 0; j < g->nfreq; j++)
            if (!(g->freq[j] > 0))
                return cli_usage(cmd, "frequency %g must be > 0", g->freq[j]);
        *f = g->freq;
        *nf = g->nfreq;
        g->freq = NULL;
        g->nfreq = 0;
        return CLI_EXIT_OK;
    }
    if (g->fmax_hz < g->fmin_hz)
        return cli_usage(cmd, "--fmax %g is below --fmin %g", g->fmax_hz, g->fmin_hz);
    *f = sl_spectrum_grid(g->fmin_hz, g->fmax_hz, g->per_decade, nf);
    if (!*f) {
        cli_msg("cannot make the frequency grid");
        return CLI_EXIT_ERROR;
    }
    return CLI_EXIT_OK;
}

int cli_stdout_done(void)
{
    if (fflush(stdout) || ferror(stdout)) {
        cli_msg("error writing the output");
        return CLI_EXIT_ERROR;
    }
    return CLI_EXIT_OK;
}

void cli_parser_init(cli_parser *p, const char *cmd, const cli_opt *opts, size_t n)
{
    memset(p, 0, sizeof *p);
    p->cmd = cmd;
    size_t k = 0, s = 0;
    p->so[s++] = ':'; /* a missing value is reported as ':' */
    for (size_t i = 0; i < n && k < CLI_MAX_OPTS; i++) {
        if (!opts[i].name)
            continue;
        p->lo[k++] = (struct option){opts[i].name, opts[i].arg ? required_argument : no_argument,
                                     NULL, opts[i].key};
        if (opts[i].key > 0 && opts[i].key < CLI_OPT_ID) {
            p->so[s++] = (char)opts[i].key;
            if (opts[i].arg)
                p->so[s++] = ':';
        }
    }
    p->lo[k++] = (struct option){"help", no_argument, NULL, 'h'};
    p->lo[k] = (struct option){NULL, 0, NULL, 0};
    p->so[s++] = 'h';
    p->so[s] = '\0';
    optind = 1;
    opterr = 0;
}

int cli_next(cli_parser *p, int argc, char **argv)
{
    int c = getopt_long(argc, argv, p->so, p->lo, NULL);
    p->arg = optarg;
    if (c == -1)
        return CLI_OPT_END;
    if (c == 'h')
        return CLI_OPT_HELP;
    if (c == ':') {
        cli_usage(p->cmd, "option '%s' needs a value", argv[optind - 1]);
        return CLI_OPT_BAD;
    }
    if (c == '?') {
        cli_usage(p->cmd, "unknown option '%s'", argv[optind - 1]);
        return CLI_OPT_BAD;
    }
    return c;
}

int cli_no_operands(const char *cmd, int argc, char **argv)
{
    if (optind < argc)
        return cli_usage(cmd, "unexpected argument '%s'", argv[optind]);
    return CLI_EXIT_OK;
}

/* Take one option's value into dst by its kind. */
static int take(const char *cmd, const cli_opt *o, const char *arg, void *dst)
{
    char *at = (char *)dst + o->off;
    char opt[64];
    snprintf(opt, sizeof opt, "--%s", o->name);
    switch (o->kind) {
    case CLI_STRING:
        if (!*arg)
            return cli_usage(cmd, "%s needs a value, not an empty text", opt);
        *(const char **)(void *)at = arg;
        return CLI_EXIT_OK;
    case CLI_FLAG: *(int *)(void *)at = 1; return CLI_EXIT_OK;
    case CLI_POSITIVE: return cli_positive(cmd, opt, arg, o->unit, (double *)(void *)at);
    case CLI_NONNEG: {
        double v;
        if (cli_parse_double(arg, &v) || !(v >= 0))
            return cli_usage(cmd, "%s '%s' must be a number >= 0%s%s%s", opt, arg,
                             o->unit ? " (" : "", o->unit ? o->unit : "", o->unit ? ")" : "");
        *(double *)(void *)at = v;
        return CLI_EXIT_OK;
    }
    case CLI_LIST: {
        cli_list *l = (cli_list *)(void *)at;
        free(l->v);
        if (cli_parse_list(arg, &l->v, &l->n))
            return cli_usage(cmd, "bad %s '%s'", opt, arg);
        return CLI_EXIT_OK;
    }
    case CLI_GRID:
        return cli_grid_option(cmd, (cli_grid_opt)(o->key - CLI_OPT_GRID), arg,
                               (cli_grid *)(void *)at);
    case CLI_UNITS: return cli_units(cmd, arg, (sl_unit *)(void *)at);
    case CLI_MU_LIST:
    case CLI_MU_RANGE: {
        cli_mu *m = (cli_mu *)(void *)at;
        if (m->v)
            return cli_usage(cmd, "give the friction values once, by --mu or by --mu-range");
        return cli_friction(cmd, o->kind == CLI_MU_RANGE, arg, &m->v, &m->n);
    }
    case CLI_COUNT1: {
        unsigned long v;
        if (cli_parse_ulong(arg, &v) || v < 1)
            return cli_usage(cmd, "%s '%s' must be an integer >= 1", opt, arg);
        *(unsigned long *)(void *)at = v;
        return CLI_EXIT_OK;
    }
    default: return CLI_EXIT_USAGE;
    }
}

int cli_parse(const char *cmd, const cli_opt *opts, size_t n, int argc, char **argv, void *dst,
              int (*call)(void *dst, int key, const char *arg))
{
    cli_parser p;
    cli_parser_init(&p, cmd, opts, n);
    for (int c; (c = cli_next(&p, argc, argv)) != CLI_OPT_END;) {
        if (c == CLI_OPT_HELP)
            return CLI_OPT_HELP;
        if (c == CLI_OPT_BAD)
            return CLI_EXIT_USAGE;
        size_t i = 0;
        while (i < n && !(opts[i].name && opts[i].key == c))
            i++;
        int rc = i == n                        ? CLI_EXIT_USAGE
                 : opts[i].kind == CLI_CALL ? (call ? call(dst, c, p.arg) : CLI_EXIT_USAGE)
                                            : take(cmd, &opts[i], p.arg, dst);
        if (rc != CLI_EXIT_OK)
            return CLI_EXIT_USAGE;
    }
    return CLI_EXIT_OK;
}

int cli_command_parse(const cli_command *c, int argc, char **argv, void *dst)
{
    int rc = cli_parse(c->name, c->opts, c->nopts, argc, argv, dst, c->call);
    if (rc == CLI_OPT_HELP) {
        fputs(c->head, stdout);
        cli_help_options(stdout, c->opts, c->nopts, c->col);
        fputs(c->tail, stdout);
    }
    if (rc || (!c->operands && (rc = cli_no_operands(c->name, argc, argv))))
        return rc;
    return c->check ? c->check(dst) : CLI_EXIT_OK;
}

/* Append s to buf (size n, holding `used` bytes) as one POSIX shell word:
 * as it is when it holds only characters no shell treats specially, else in
 * single quotes (a quote inside written '\''). Returns the new length, or n
 * when it does not fit (buf unchanged then). */
static size_t shell_word(char *buf, size_t used, size_t n, const char *s)
{
    int plain = *s != '\0';
    for (const char *p = s; *p; p++)
        if (!isalnum((unsigned char)*p) && !strchr("-_./:=,+@%", *p))
            plain = 0;
    size_t k = used;
    if (k + 1 >= n)
        return n;
    buf[k++] = ' ';
    if (!plain && k < n)
        buf[k++] = '\'';
    for (const char *p = s; *p && k < n; p++) {
        if (*p == '\'' && !plain) {
            for (const char *q = "'\\''"; *q && k < n; q++)
                buf[k++] = *q;
        } else {
            buf[k++] = *p;
        }
    }
    if (!plain && k < n)
        buf[k++] = '\'';
    if (k >= n) {
        buf[used] = '\0';
        return n;
    }
    buf[k] = '\0';
    return k;
}

void cli_command_line(char *buf, size_t n, int argc, char **argv)
{
    snprintf(buf, n, "seislide");
    size_t used = strlen(buf);
    for (int i = 0; i < argc && used < n; i++)
        used = shell_word(buf, used, n, argv[i]);
}

int cli_mu_check(const char *cmd, const cli_mu *mu)
{
    for (size_t k = 0; k < mu->n; k++) {
        if (!(mu->v[k] > 0))
            return cli_usage(cmd, "friction coefficient %g must be above 0 (a block without "
                             "friction never stops)", mu->v[k]);
        if (!(mu->v[k] <= CLI_MU_MAX * (1 + CLI_MU_ROUND))) /* 0.05:1.5:0.05 ends at 1.5 */
            return cli_usage(cmd, "friction coefficient %.10g is above %g: not a friction "
                             "coefficient of an equipment base (a typo, or a percent?)",
                             mu->v[k], CLI_MU_MAX);
        if (k > 0 && !(mu->v[k] > mu->v[k - 1]))
            return cli_usage(cmd, "friction values must increase: %g follows %g", mu->v[k],
                             mu->v[k - 1]);
    }
    return CLI_EXIT_OK;
}

void cli_help_options(FILE *f, const cli_opt *opts, size_t n, int col)
{
    for (size_t i = 0; i < n; i++) {
        const cli_opt *o = &opts[i];
        if (!o->name && !o->show) {
            if (o->head)
                fprintf(f, "%s\n", o->head);
            continue;
        }
        if (!o->help)
            continue;
        char left[128];
        if (o->show)
            snprintf(left, sizeof left, "%s", o->show);
        else if (o->key > 0 && o->key < CLI_OPT_ID)
            snprintf(left, sizeof left, "-%c, --%s%s%s", o->key, o->name, o->arg ? " " : "",
                     o->arg ? o->arg : "");
        else
            snprintf(left, sizeof left, "--%s%s%s", o->name, o->arg ? " " : "",
                     o->arg ? o->arg : "");
        int pad = col - 2 - (int)strlen(left);
        fprintf(f, "  %s%*s", left, pad < 2 ? 2 : pad, "");
        char text[1024];
        snprintf(text, sizeof text, o->help, o->def[0], o->def[1], o->def[2]);
        for (const char *t = text; *t; t++) {
            fputc(*t, f);
            if (*t == '\n')
                fprintf(f, "%*s", col, "");
        }
        fputc('\n', f);
    }
}

void cli_put_num(const char *fmt, double v, int width)
{
    if (isnan(v))
        printf("%*s", width, "nan");
    else
        printf(fmt, width, v);
}

void cli_put_csv(double v, int last)
{
    if (isnan(v))
        fputs("nan", stdout);
    else
        printf("%.8g", v);
    putchar(last ? '\n' : ',');
}

void cli_put_field(const char *s)
{
    if (!strpbrk(s, ",\" \t\r\n")) {
        fputs(s, stdout);
        return;
    }
    putchar('"');
    for (; *s; s++) {
        if (*s == '"')
            putchar('"');
        putchar(*s);
    }
    putchar('"');
}

void cli_print_table(int csv, const double *f, size_t nf, char (*names)[320], size_t ncol,
                     const double *vals)
{
    int w = 12;
    for (size_t j = 0; j < ncol; j++)
        if ((int)strlen(names[j]) > w)
            w = (int)strlen(names[j]);
    fputs(csv ? "f_hz" : "      f_hz", stdout);
    for (size_t j = 0; j < ncol; j++) {
        if (csv) {
            putchar(',');
            cli_put_field(names[j]);
        } else {
            printf(" %*s", w, names[j]);
        }
    }
    putchar('\n');
    for (size_t p = 0; p < nf; p++) {
        printf(csv ? "%.6g" : "%10.5g", f[p]);
        for (size_t j = 0; j < ncol; j++) {
            if (csv)
                printf(",%.8g", vals[j * nf + p]);
            else
                printf(" %*.6g", w, vals[j * nf + p]);
        }
        putchar('\n');
    }
}

void cli_kernels_baseline(void)
{
    sl_spectrum_kernel_baseline(1);
    sl_kernel2d_baseline(1);
}
