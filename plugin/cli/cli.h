/* pointnpr CLI: one cmd_<name>.c per subcommand, each exporting `int cli_<name>(int argc, char **argv)`
 * where argv[0] is the subcommand name. Exit codes: 0 ok, 1 runtime error, 2 usage error. */
#ifndef PNPR_CLI_H
#define PNPR_CLI_H

#include <pointnpr/io.h>

int cli_info(int argc, char **argv);
int cli_convert(int argc, char **argv);
int cli_features(int argc, char **argv);
int cli_render(int argc, char **argv);
int cli_lines(int argc, char **argv);
int cli_segment(int argc, char **argv);

/* Progress on stderr; never cancels. user: a cli_progress_state (zeroed before first use).
 * On a terminal: one updating "\r<stage> 42%" line per stage; otherwise (logs, CI) one line
 * when a stage ends. */
typedef struct cli_progress_state {
    char stage[64];
    int last_pct;
    int tty;      /* 0 unknown, 1 yes, 2 no */
} cli_progress_state;
int cli_progress_stderr(void *user, const char *stage, double fraction);
/* Prints "pointnpr <cmd>: <message>" for a failed status (with pnpr_error detail when set). */
void cli_report_error(const char *cmd, pnpr_status st, const pnpr_error *err);

#endif
