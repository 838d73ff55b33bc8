/* cmd_spectrum.c - placeholder until the command lands (issue 3). */
#include "cli.h"
int cmd_spectrum(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    cli_msg("spectrum: not built yet");
    return CLI_EXIT_ERROR;
}
