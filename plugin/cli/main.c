/* pointnpr command-line tool (placeholder until the subcommands land). */
#include <pointnpr/core.h>
#include <stdio.h>

int main(int argc, char **argv)
{
    (void)argc; (void)argv;
    printf("pointnpr %s\n", PNPR_VERSION_STRING);
    return 0;
}
