/* pointnpr convert (placeholder until it lands) */
#include "cli.h"
#include <stdio.h>
int cli_convert(int argc, char **argv)
{
    (void)argc; (void)argv;
    fprintf(stderr, "pointnpr convert: not implemented yet\n");
    return 1;
}
