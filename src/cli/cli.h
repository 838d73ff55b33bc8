/*
 * cli.h - shared pieces of the seislide command line: the command table,
 * message printing, strict number and list parsing.
 *
 * Exit codes (documented in --help and docs/seislide.1):
 *   0 success, 1 error in input or in the run, 2 usage error.
 */
#ifndef SL_CLI_H
#define SL_CLI_H

#include <stddef.h>
#include <stdio.h>

#include "core/status.h"
#include "core/units.h"

#define CLI_EXIT_OK 0
#define CLI_EXIT_ERROR 1
#define CLI_EXIT_USAGE 2

#ifndef SEISLIDE_VERSION
#define SEISLIDE_VERSION "0.1.0"
#endif

/* Commands: each takes argc/argv with argv[0] the command name. */
int cmd_run(int argc, char **argv);
int cmd_slide(int argc, char **argv);
int cmd_spectrum(int argc, char **argv);
int cmd_rg160(int argc, char **argv);
int cmd_asce(int argc, char **argv);
int cmd_synth(int argc, char **argv);
int cmd_bench(int argc, char **argv);
int cmd_study(int argc, char **argv);

/* Print "seislide: FILE:LINE: message" for a library error. */
void cli_print_error(const sl_error *err);
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

/* Monotonic wall-clock time, s (for the timings commands report). */
double cli_now_s(void);

/* Strict parse of a finite double (whole string). Returns 0 on success. */
int cli_parse_double(const char *s, double *out);
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
void cli_grid_free(cli_grid *g);
/* Take one frequency option. Returns CLI_EXIT_OK or (message printed)
 * CLI_EXIT_USAGE. */
int cli_grid_option(const char *cmd, cli_grid_opt which, const char *arg, cli_grid *g);
/* The frequencies to use: *f (malloc'd, the caller frees) and *nf. Returns
 * CLI_EXIT_OK, CLI_EXIT_USAGE or CLI_EXIT_ERROR (message printed). */
int cli_grid_make(const char *cmd, cli_grid *g, double **f, size_t *nf);
/* Strict parse of a non-negative integer. Returns 0 on success. */
int cli_parse_ulong(const char *s, unsigned long *out);
/* "0.05,0.1,0.2": comma list of finite doubles; *vals malloc'd. */
int cli_parse_list(const char *s, double **vals, size_t *n);
/* "A:B:S": A, A+S, ..., up to B inclusive (B included when within
 * 1e-9 S); S > 0, B >= A. *vals malloc'd. */
int cli_parse_range(const char *s, double **vals, size_t *n);

#endif
