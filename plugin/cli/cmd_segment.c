/* pointnpr segment (placeholder until it lands). */
#include "cli.h"
#include <stdio.h>
int cli_segment(int argc, char **argv)
{
    (void)argc; (void)argv;
    fprintf(stderr, "pointnpr segment: not available yet in this build\n");
    return 1;
}
