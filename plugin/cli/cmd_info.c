/* pointnpr info (placeholder until it lands) */
#include "cli.h"
#include <stdio.h>
int cli_info(int argc, char **argv)
{
    (void)argc; (void)argv;
    fprintf(stderr, "pointnpr info: not implemented yet\n");
    return 1;
}
