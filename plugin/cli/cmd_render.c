/* pointnpr render (placeholder until the renderer lands). */
#include "cli.h"
#include <stdio.h>
int cli_render(int argc, char **argv)
{
    (void)argc; (void)argv;
    fprintf(stderr, "pointnpr render: not available yet in this build\n");
    return 1;
}
