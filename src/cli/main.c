/* main.c - seislide: dispatch to a command. */
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "signal/spectrum_kernel.h"

typedef struct command {
    const char *name;
    int (*run)(int, char **);
    const char *summary;
} command;

static const command commands[] = {
    {"run", cmd_run, "the main job: per-floor design sliding spectra and clearance workbook"},
    {"merge", cmd_merge, "the outputs of a plant run from its shards (run --shard K/N)"},
    {"slide", cmd_slide, "sliding of a rigid block under one 1-3 component motion"},
    {"rock", cmd_rock, "rocking and overturning of a rigid block under one motion"},
    {"spectrum", cmd_spectrum, "response spectra of motions"},
    {"rg160", cmd_rg160, "Regulatory Guide 1.60 design spectra"},
    {"asce", cmd_asce, "ASCE/SEI 43-05 approximate sliding displacement"},
    {"synth", cmd_synth, "spectrum-compatible three-component motions (FFTW)"},
    {"bench", cmd_bench, "speed against error of the engine"},
    {"verify", cmd_verify, "verification of this installed program against independent references"},
    {"study", cmd_study, "reproduce the source study from recorded motions (docs/validation.md)"},
    {"components", cmd_components, "each component of a list checked against a run's floor tables"},
    {"lookup", cmd_lookup, "the required clearance of one floor at one mu, from a run's outputs"},
};
#define N_COMMANDS (sizeof commands / sizeof commands[0])

static void usage(FILE *f)
{
    fprintf(f,
            "usage: seislide COMMAND [options]\n"
            "\n"
            "Peak sliding displacement of unanchored rigid components on a floor in an\n"
            "earthquake, by nonlinear time-history analysis and the ASCE/SEI 43-05 method.\n"
            "\n"
            "commands:\n");
    for (size_t i = 0; i < N_COMMANDS; i++)
        fprintf(f, "  %-10s %s\n", commands[i].name, commands[i].summary);
    fprintf(f,
            "\n"
            "'seislide COMMAND --help' describes a command. Units: SI inside; every\n"
            "file and column names its unit. Exit status: 0 success, 1 error in the\n"
            "input or the run, 2 usage error. The manual: 'man -l docs/seislide.1' in\n"
            "the source tree, or 'man seislide' after 'make install'; more in docs/.\n");
}

int main(int argc, char **argv)
{
    /* A file size limit (ulimit -f) must not kill the program silently: with
     * SIGXFSZ ignored, the write that crosses it fails with EFBIG and the
     * command reports the file it could not write (docs/reliability.md). */
    signal(SIGXFSZ, SIG_IGN);
    /* SEISLIDE_KERNELS=baseline: the vector kernels' baseline instance (SSE2)
     * even on an AVX2 CPU, as a machine without AVX2 runs them; the outputs
     * are the same bits (docs/reliability.md, "Across machines"). */
    const char *kernels = getenv("SEISLIDE_KERNELS");
    if (kernels && !strcmp(kernels, "baseline"))
        cli_kernels_baseline();
    if (argc < 2) {
        usage(stderr);
        return CLI_EXIT_USAGE;
    }
    if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") || !strcmp(argv[1], "help")) {
        usage(stdout);
        return CLI_EXIT_OK;
    }
    if (!strcmp(argv[1], "--version")) {
        printf("%s\n", sl_build_id());
        return CLI_EXIT_OK;
    }
    for (size_t i = 0; i < N_COMMANDS; i++)
        if (!strcmp(argv[1], commands[i].name))
            return commands[i].run(argc - 1, argv + 1);
    fprintf(stderr, "seislide: unknown command '%s' (try 'seislide --help')\n", argv[1]);
    return CLI_EXIT_USAGE;
}
