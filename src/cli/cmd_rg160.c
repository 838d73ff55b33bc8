/* cmd_rg160.c - placeholder until the command lands (issue 3). */
#include "cli.h"
int cmd_rg160(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    cli_msg("rg160: not built yet");
    return CLI_EXIT_ERROR;
}
