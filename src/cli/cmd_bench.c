/* cmd_bench.c - placeholder until the benchmark lands. */
#include "cli.h"
int cmd_bench(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    cli_msg("bench: not built yet");
    return CLI_EXIT_ERROR;
}
