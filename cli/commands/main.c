/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit: command-line entry point; dispatches to the subcommands (cmd_*.c). */
#include <string.h>

#include "cli.h"
#include "dynkit/lang.h"
#include "util/out_file.h"
#include "pages/pages.h"

static void main_help(void)
{
    puts("dynkit - simulate mechanical systems: integrators, models, analyses.\n"
         "\n"
         "Usage: dynkit COMMAND [options]\n"
         "\n"
         "Commands:\n"
         "  run MODEL      integrate a model and write CSV (t and the states)\n"
         "  models         list the built-in models\n"
         "  methods        list the integration methods\n"
         "  info MODEL     states, parameters, units and defaults of a model\n"
         "  inverse cart|FILE.mech  inverse dynamics: the forces of a prescribed motion\n"
         "  report         every answer of the homework, computed now (--json, --html FILE)\n"
         "  animate MODEL  a run as an HTML page that plays the motion (--compare METHOD)\n"
         "  plot MODEL     a run as an SVG line plot (--y NAME,... [--x NAME])\n"
         "  verify         every method on problems with known solutions: accuracy and work\n"
         "                 per method and tolerance (--quick, --json, --problem, --method)\n"
         "  sweep MODEL    many runs, one row each: --vary NAME=A:B:N, --sample, --from FILE;\n"
         "                 --reduce final,max:NAME,event:NAME,... on every core\n"
         "  linearize MODEL the Jacobian df/dy about a state (--init, --set; --equilibrium\n"
         "                 finds one), its eigenvalues and the stability; --vary NAME=A:B:N\n"
         "                 gives one block per value\n"
         "  continue MODEL --par NAME  the bifurcation diagram: branches of equilibria,\n"
         "                 folds, Hopf and branch points located (--output, --svg)\n"
         "  derive FILE.mech the equations of motion of a mechanism file as formulas\n"
         "  equilibria MODEL every equilibrium in a box (a map's fixed points), each with\n"
         "                 its eigenvalues and type (--box NAME=A:B,..., --json)\n"
         "  lyapunov MODEL the largest Lyapunov exponent, or all (--spectrum), by\n"
         "                 Benettin's method, with an error estimate\n"
         "  steady MODEL   a steady motion: --unknown NAME,... solved so that the\n"
         "                 non-cyclic states stay put; its eigenvalues\n"
         "  bvp FILE       a model file's boundary-value problem (bdry lines) by collocation\n"
         "  help [COMMAND] this text, or the help of COMMAND (as 'dynkit COMMAND --help')\n"
         "\n"
         "MODEL is a built-in model's name ('dynkit models'), an XPPAUT .ode file, a mechanism\n"
         "file .mech (docs/mechanisms.md) or a C file defining dynkit_model() (see\n"
         "docs/model-files.md); all are compiled to native code.\n"
         "--verbose (any command) prints notes on stderr.\n"
         "\n"
         "'dynkit help COMMAND' tells more about each command; 'man dynkit' tells all.\n"
         "\n"
         "Exit status: 0 success; 1 a run failed (e.g. a state became NaN or Inf) or an output\n"
         "could not be written; 2 a bad command line (the message names the bad input and what\n"
         "is accepted); 128+N ended by signal N (130 Ctrl-C, 143 SIGTERM).\n"
         "\n"
         "Example: dynkit run vanderpol --method rk4 --step 0.01 --tspan 0:15 --final");
}

int main(int argc, char **argv)
{
    static const struct {
        const char *name;
        int (*run)(int, char **);
    } commands[] = {
        {"run", cli_cmd_run},
        {"models", cli_cmd_models},
        {"methods", cli_cmd_methods},
        {"info", cli_cmd_info},
        {"inverse", cli_cmd_inverse},
        {"report", cli_cmd_report},
        {"animate", cli_cmd_animate},
        {"plot", cli_cmd_plot},
        {"verify", cli_cmd_verify},
        {"sweep", cli_cmd_sweep},
        {"linearize", cli_cmd_linearize},
        {"continue", cli_cmd_continue},
        {"derive", cli_cmd_derive},
        {"equilibria", cli_cmd_equilibria},
        {"lyapunov", cli_cmd_lyapunov},
        {"steady", cli_cmd_steady},
        {"bvp", cli_cmd_bvp},
    };
    /* --verbose is accepted anywhere, by every command */
    int kept = 1;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--verbose") == 0)
            cli_set_verbose(1);
        else
            argv[kept++] = argv[i];
    }
    argc = kept;
    argv[argc] = NULL;
    if (argc < 2) {
        main_help();
        return CLI_USAGE;
    }
    /* dynkit help [COMMAND]: the same as dynkit [COMMAND] --help; 'help help' is this text */
    static char help_flag[] = "--help";
    if (strcmp(argv[1], "help") == 0 && argc > 2 && strcmp(argv[2], "help") == 0)
        argc = 2;
    if (strcmp(argv[1], "help") == 0) {
        argv[1] = argc > 2 ? argv[2] : help_flag;
        argv[2] = argc > 2 ? help_flag : NULL;
        argc = argc > 2 ? 3 : 2;
        argv[argc] = NULL;
    }
    if (cli_is_help(argv[1])) {
        main_help();
        return cli_stdout_check(CLI_OK);
    }
    if (strcmp(argv[1], "--version") == 0) {
        puts("dynkit 0.1.0");
        return cli_stdout_check(CLI_OK);
    }
    cli_signals_install();
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
        if (strcmp(argv[1], commands[i].name) == 0)
            return cli_stdout_check(commands[i].run(argc - 2, argv + 2));
    const char *names[sizeof commands / sizeof commands[0] + 1];
    int n = 0;
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
        names[n++] = commands[i].name;
    names[n++] = "help";
    const char *near = dyn_lang_nearest(argv[1], names, n);
    return cli_usage_error(NULL,
                           "unknown command '%s' (%s%s%saccepted: run, models, methods, info, "
                           "inverse, report, animate, plot, verify, sweep, linearize, derive, "
                           "equilibria, lyapunov, continue, steady, bvp, help)",
                           argv[1], near ? "did you mean '" : "", near ? near : "",
                           near ? "'? " : "");
}
