/*
 * cli.h - shared pieces of the seislide command line: the command table,
 * message printing, strict number and list parsing.
 *
 * Exit codes (documented in --help and docs/seislide.1):
 *   0 success, 1 error in input or in the run, 2 usage error.
 */
#ifndef SL_CLI_H
#define SL_CLI_H

#include <getopt.h>
#include <stddef.h>
#include <stdio.h>

#include "core/status.h"
#include "core/units.h"
#include "core/version.h"
#include "signal/spectrum.h"

#define CLI_EXIT_OK 0
#define CLI_EXIT_ERROR 1
#define CLI_EXIT_USAGE 2

/* The program's version is the library's (core/version.h); the program line
 * of every output is the build's identity, sl_build_id(): "seislide 0.1.0
 * (source 60785011e55b)". */
#define SEISLIDE_VERSION SEISLIDE_VERSION_STRING

/* Commands: each takes argc/argv with argv[0] the command name. */
int cmd_run(int argc, char **argv);
int cmd_merge(int argc, char **argv);
int cmd_slide(int argc, char **argv);
int cmd_rock(int argc, char **argv);
int cmd_spectrum(int argc, char **argv);
int cmd_rg160(int argc, char **argv);
int cmd_asce(int argc, char **argv);
int cmd_synth(int argc, char **argv);
int cmd_bench(int argc, char **argv);
int cmd_study(int argc, char **argv);
int cmd_components(int argc, char **argv);
int cmd_lookup(int argc, char **argv);
int cmd_verify(int argc, char **argv);

/*
 * Options: one table per command, from which the parser, the checks of
 * every value and the option lines of --help are generated. A command
 * keeps its settings in one struct and declares
 *
 *     typedef struct args { double fs; int csv; const char *out; cli_mu mu; } args;
 *     #define A(f) offsetof(args, f)
 *     static const cli_opt opts[] = {
 *         {.head = "options:"},
 *         {"fs", OPT_FS, "F", "factor of safety (default %g)", {SL_ASCE_FS},
 *          .kind = CLI_POSITIVE, .off = A(fs)},
 *         {"output", 'o', "DIR", "folder", .kind = CLI_STRING, .off = A(out)},
 *         {"csv", OPT_CSV, NULL, "CSV output", .kind = CLI_FLAG, .off = A(csv)},
 *         {"mu", OPT_MU, "LIST", "coefficients", .kind = CLI_MU_LIST, .off = A(mu)},
 *     };
 *
 * and calls cli_parse("asce", opts, CLI_NOPTS(opts), argc, argv, &a, NULL,
 * NULL). Kinds: CLI_STRING (const char *, not empty), CLI_FLAG (int set to 1),
 * CLI_POSITIVE / CLI_NONNEG (double > 0 / >= 0; `unit` named in the
 * message), CLI_COUNT1 (unsigned long >= 1), CLI_UNITS (sl_unit),
 * CLI_MU_LIST / CLI_MU_RANGE (cli_mu: --mu 0.1,0.2 or --mu-range A:B:S, one of them once),
 * CLI_LIST (cli_list: a comma list of numbers), CLI_GRID (cli_grid: the
 * frequency options, see CLI_GRID_OPTS), CLI_CALL (handed to the command's
 * callback with its key and value: options that need more).
 *
 * --help prints the command's own usage and prose around
 * cli_help_options(stdout, opts, n, col): for each option "  --fs F"
 * padded to column `col` (at least two spaces), then the help text, a
 * printf format given def[0..2] (defaults come from the constants, never
 * retyped; a literal percent sign is %%); a newline in the text continues
 * at the column. `show` replaces the generated "--name ARG" (letter keys
 * give "-o, --output DIR"); help NULL hides an option another line
 * describes; an entry with only `head` prints that line; one with `show`
 * and no name documents an operand ("FILE...") and is not parsed. --help and -h
 * need no entry. Option ids start at CLI_OPT_ID; a letter key is also -x.
 */
#define CLI_OPT_ID 256 /* first key of an option without a letter */
#define CLI_OPT_END (-1)
#define CLI_OPT_HELP (-2)
#define CLI_OPT_BAD (-3) /* unknown option or missing value: usage error printed */
#define CLI_MAX_OPTS 48

typedef enum cli_kind {
    CLI_CALL = 0, CLI_STRING, CLI_FLAG, CLI_POSITIVE, CLI_NONNEG, CLI_COUNT1, CLI_UNITS,
    CLI_MU_LIST, CLI_MU_RANGE, CLI_LIST, CLI_GRID
} cli_kind;

/* Values given as a list (--damping 0.05,0.1) or by --mu / --mu-range
 * (v owned; free(v)). */
typedef struct cli_mu {
    double *v;
    size_t n;
} cli_mu;
typedef cli_mu cli_list;

typedef struct cli_opt {
    const char *name;  /* long name without "--"; NULL for a heading */
    int key;           /* a letter (also -x) or an id >= CLI_OPT_ID */
    const char *arg;   /* value name for help ("DIR"); NULL for a flag */
    const char *help;  /* printf format of the help text; NULL: not listed */
    double def[3];     /* the arguments of the format (defaults) */
    const char *show;  /* left column instead of the generated one */
    const char *head;  /* a heading line (name NULL) */
    cli_kind kind;     /* how cli_parse() takes the value */
    size_t off;        /* where: offsetof in the command's settings */
    const char *unit;  /* unit named in a CLI_POSITIVE message, NULL if none */
} cli_opt;
#define CLI_NOPTS(t) (sizeof(t) / sizeof((t)[0]))

typedef struct cli_parser {
    const char *cmd;
    const char *arg; /* the value of the option cli_next() returned */
    struct option lo[CLI_MAX_OPTS + 2];
    char so[3 * CLI_MAX_OPTS + 4];
} cli_parser;

/* Build the parser of command cmd from its table (at most CLI_MAX_OPTS
 * options) and reset getopt. */
void cli_parser_init(cli_parser *p, const char *cmd, const cli_opt *opts, size_t n);
/* The next option's key (its value in p->arg), CLI_OPT_HELP, CLI_OPT_END
 * after the last option (operands start at optind), or CLI_OPT_BAD after
 * printing a usage error. */
int cli_next(cli_parser *p, int argc, char **argv);
/* Parse every option into the settings struct dst by its kind; CLI_CALL
 * options go to call(dst, key, value), which returns CLI_EXIT_OK or a
 * usage error. Returns CLI_EXIT_OK (operands start at optind), CLI_OPT_HELP
 * (the caller prints its help) or CLI_EXIT_USAGE (message printed). */
int cli_parse(const char *cmd, const cli_opt *opts, size_t n, int argc, char **argv, void *dst,
              int (*call)(void *dst, int key, const char *arg));
/* CLI_EXIT_OK when no operand follows the options, else a usage error. */
int cli_no_operands(const char *cmd, int argc, char **argv);
/* The option lines of a help text, generated from the table. */
void cli_help_options(FILE *f, const cli_opt *opts, size_t n, int col);

/* A command's front end, the same for every command: parse by its table,
 * print its --help (head, the option lines at column col, tail), refuse
 * operands unless it takes them, then apply the rules across options. */
typedef struct cli_command {
    const char *name;               /* "slide": in usage messages */
    const char *head, *tail;        /* --help text before and after the option lines */
    const cli_opt *opts;
    size_t nopts;
    int col;                        /* help column of the option texts */
    int (*call)(void *dst, int key, const char *arg); /* CLI_CALL options, or NULL */
    int (*check)(void *dst);        /* rules across options, or NULL */
    int operands;                   /* 1: operands may follow (from optind) */
} cli_command;
/* Parse argv into the settings dst. Returns CLI_EXIT_OK (operands, if
 * allowed, start at optind), CLI_OPT_HELP after printing the help on
 * stdout, or CLI_EXIT_USAGE (message printed; also what check returns). */
int cli_command_parse(const cli_command *c, int argc, char **argv, void *dst);
/* "seislide" and the words of argv (argv[0] the command name), joined by
 * blanks into buf of size n, up to the first word that does not fit; a word
 * with a blank or another character a shell treats specially is single-quoted,
 * so that the recorded line can be pasted into a shell and runs the same. */
void cli_command_line(char *buf, size_t n, int argc, char **argv);
/* The largest friction coefficient --mu and --mu-range take. Static friction
 * of equipment bases on concrete lies below about 1 (steel on concrete or
 * grout about 0.4-0.7, ACI 318-19 Table 22.9.4.2 gives 0.7 against as-rolled
 * steel; rubber on dry concrete up to about 1); the largest coefficient of
 * that table, 1.4, is concrete cast monolithically (a crack, not a base). A
 * value above 1.5 is a slip (3 for 0.3, a percent), not a friction. */
#define CLI_MU_MAX 1.5
/* Relative round-off allowed at CLI_MU_MAX (a range's last value is A + k S). */
#define CLI_MU_ROUND 1e-9
/* CLI_EXIT_OK when every friction value of mu is above 0, at most
 * CLI_MU_MAX, and above the one before; else a usage error naming the first
 * value that is not. */
int cli_mu_check(const char *cmd, const cli_mu *mu);

/* Print "seislide: FILE:LINE: message" for a library error. */
void cli_print_error(const sl_error *err);

/* The vector kernels' baseline instance (SSE2) for the engine and the
 * oscillator bank, even on an AVX2 CPU: SEISLIDE_KERNELS=baseline for any
 * command, `verify --baseline` (docs/reliability.md, "Across machines"). */
void cli_kernels_baseline(void);
/* Print "seislide: " + message to stderr. */
void cli_msg(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;
/* Print a usage error "seislide CMD: message (try 'seislide CMD --help')";
 * returns CLI_EXIT_USAGE. */
int cli_usage(const char *cmd, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* Tables on stdout. A number in a column of `width` with fmt ("%*.3f"),
 * or "nan" (never "-nan"). */
void cli_put_num(const char *fmt, double v, int width);
/* A CSV number (8 significant digits, or "nan"), then ',' or, when last,
 * a newline. */
void cli_put_csv(double v, int last);
/* A CSV field, quoted when it holds a comma, quote or blank. */
void cli_put_field(const char *s);
/* A table of ncol columns over the frequencies f (nf rows): header "f_hz"
 * and names[j]; values vals[j * nf + p]. CSV (",%.8g") or aligned (each
 * column as wide as its name, at least 12; "%.6g"). */
void cli_print_table(int csv, const double *f, size_t nf, char (*names)[320], size_t ncol,
                     const double *vals);

/* After the last output: flush stdout. CLI_EXIT_OK, or CLI_EXIT_ERROR after
 * "error writing the output" when stdout failed (a full disk, a closed pipe). */
int cli_stdout_done(void);

/* Strict parse of a finite double (whole string). Returns 0 on success. */
int cli_parse_double(const char *s, double *out);
/* The --created option (a workbook date, s since 1970) of the commands that
 * write workbooks, its value and its default. */
#define CLI_OPT_CREATED(key)                                                                    \
    {"created", (key), "EPOCH", "workbook date, s since 1970 (default SOURCE_DATE_EPOCH,\n"  \
     "else now)", .kind = CLI_CALL}
/* Parse a --created value: a number 0..4e12. Returns 0 on success. */
int cli_parse_created(const char *s, double *out);
/* The default date: SOURCE_DATE_EPOCH when it is a number >= 0, else now. */
double cli_created_default(void);
/* Parse option `opt` of command `cmd` as a finite number > 0 (in `unit`,
 * NULL if dimensionless) into *out. Returns CLI_EXIT_OK, or prints a usage
 * error naming the option and value and returns CLI_EXIT_USAGE. */
int cli_positive(const char *cmd, const char *opt, const char *arg, const char *unit,
                 double *out);
/* Parse a unit name for command cmd into *out. Returns CLI_EXIT_OK, or
 * prints a usage error and returns CLI_EXIT_USAGE. */
int cli_units(const char *cmd, const char *arg, sl_unit *out);
/* Replace *mu (freed) by the friction values of --mu LIST (is_range 0) or
 * --mu-range A:B:S (is_range 1). Returns CLI_EXIT_OK, or prints a usage
 * error and returns CLI_EXIT_USAGE. */
int cli_friction(const char *cmd, int is_range, const char *arg, double **mu, size_t *n);
/* The frequency options shared by `spectrum` and `rg160`: --fmin, --fmax,
 * --per-decade (the default grid of spectrum.h) or an explicit --freq list. */
typedef enum cli_grid_opt { CLI_GRID_FMIN, CLI_GRID_FMAX, CLI_GRID_PER_DECADE, CLI_GRID_FREQ } cli_grid_opt;
typedef struct cli_grid {
    double fmin_hz, fmax_hz, per_decade;
    double *freq;  /* --freq list (owned), NULL when not given */
    size_t nfreq;
    int grid_opts; /* 1 when --fmin, --fmax or --per-decade was given */
} cli_grid;
void cli_grid_init(cli_grid *g);
/* The four table entries of the frequency options (keys CLI_OPT_GRID + a
 * cli_grid_opt), for a cli_grid at offsetof(settings, field) `off`. */
#define CLI_OPT_GRID 900
#define CLI_GRID_OPTS(grid_off)                                                                  \
    {"fmin", CLI_OPT_GRID + CLI_GRID_FMIN, "HZ", "frequency range (default %g to %g Hz)",   \
     {SL_SPECTRUM_FMIN_HZ, SL_SPECTRUM_FMAX_HZ}, .show = "--fmin HZ, --fmax HZ",           \
     .kind = CLI_GRID, .off = (grid_off)},                                                        \
    {"fmax", CLI_OPT_GRID + CLI_GRID_FMAX, "HZ", NULL, .kind = CLI_GRID, .off = (grid_off)},      \
    {"per-decade", CLI_OPT_GRID + CLI_GRID_PER_DECADE, "N",                                 \
     "log-spaced points per decade (default %g)", {SL_SPECTRUM_PER_DECADE},                 \
     .kind = CLI_GRID, .off = (grid_off)},                                                        \
    {"freq", CLI_OPT_GRID + CLI_GRID_FREQ, "LIST",                                           \
     "explicit frequencies, Hz, instead of the grid", .kind = CLI_GRID, .off = (grid_off)}
void cli_grid_free(cli_grid *g);
/* Take one frequency option. Returns CLI_EXIT_OK or (message printed)
 * CLI_EXIT_USAGE. */
int cli_grid_option(const char *cmd, cli_grid_opt which, const char *arg, cli_grid *g);
/* The frequencies to use: *f (malloc'd, the caller frees) and *nf. Returns
 * CLI_EXIT_OK, CLI_EXIT_USAGE or CLI_EXIT_ERROR (message printed). */
int cli_grid_make(const char *cmd, cli_grid *g, double **f, size_t *nf);
/* Strict parse of a non-negative integer (digits only: no sign, no blank).
 * Returns 0 on success. */
int cli_parse_ulong(const char *s, unsigned long *out);
/* "0.05,0.1,0.2": comma list of finite doubles; *vals malloc'd. */
int cli_parse_list(const char *s, double **vals, size_t *n);
/* "A:B:S": A, A+S, ..., up to B inclusive (B included when within
 * 1e-9 S); S > 0, B >= A. *vals malloc'd. */
int cli_parse_range(const char *s, double **vals, size_t *n);

#endif
