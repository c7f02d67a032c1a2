/* pointnpr features (placeholder until it lands) */
#include "cli.h"
#include <stdio.h>
int cli_features(int argc, char **argv)
{
    (void)argc; (void)argv;
    fprintf(stderr, "pointnpr features: not implemented yet\n");
    return 1;
}
