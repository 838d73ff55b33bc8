/* cmd_asce.c - placeholder until the command lands (issue 3). */
#include "cli.h"
int cmd_asce(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    cli_msg("asce: not built yet");
    return CLI_EXIT_ERROR;
}
