/* dynkit report: every answer of the homework, as text or JSON. */
#include <string.h>

#include "cli.h"
#include "dynkit/report.h"

static void report_help(void)
{
    puts("Usage: dynkit report [--json]\n\n"
         "Answer every question of the homework (TU Delft Advanced Dynamics, homework 8,\n"
         "problems 1 to 4), computed now: each value with its unit, how it was computed, and\n"
         "the judgements with the numbers behind them.\n\n"
         "  --json   one flat JSON object with dotted keys (pendulum.max_height_m, ...)");
}

int cli_cmd_report(int argc, char **argv)
{
    int json = 0;
    for (int i = 0; i < argc; i++) {
        if (cli_is_help(argv[i])) {
            report_help();
            return CLI_OK;
        } else if (cli_flag(argv[i], "json")) {
            json = 1;
        } else {
            return cli_usage_error("report", "unknown option '%s' (accepted: --json)", argv[i]);
        }
    }
    static dyn_homework hw;
    char err[256] = "";
    if (dyn_homework_compute(&hw, err, sizeof err)) {
        fprintf(stderr, "dynkit: report failed: %s\n", err);
        return CLI_FAILED;
    }
    int bad = json ? dyn_homework_write_json(&hw, stdout) : dyn_homework_write_text(&hw, stdout);
    if (bad || fflush(stdout)) {
        fprintf(stderr, "dynkit: error: writing the report failed\n");
        return CLI_FAILED;
    }
    return CLI_OK;
}
