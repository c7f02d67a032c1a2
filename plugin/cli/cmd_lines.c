/* pointnpr lines (placeholder until it lands). */
#include "cli.h"
#include <stdio.h>
int cli_lines(int argc, char **argv)
{
    (void)argc; (void)argv;
    fprintf(stderr, "pointnpr lines: not available yet in this build\n");
    return 1;
}
