/* dynkit models, dynkit methods: what is available, one line each. */
#include "cli.h"

int cli_cmd_models(int argc, char **argv)
{
    if (argc >= 1 && cli_is_help(argv[0])) {
        puts("Usage: dynkit models\n\nList the built-in models. 'dynkit info MODEL' tells more.");
        return CLI_OK;
    }
    if (argc >= 1)
        return cli_usage_error("models", "unexpected argument '%s'", argv[0]);
    printf("%-12s %-7s %s\n", "MODEL", "STATES", "DESCRIPTION");
    for (int i = 0; i < dyn_model_count(); i++) {
        const dyn_model *m = dyn_model_at(i);
        printf("%-12s %-7d %s\n", m->name, m->n_states, m->title);
    }
    return CLI_OK;
}

int cli_cmd_methods(int argc, char **argv)
{
    if (argc >= 1 && cli_is_help(argv[0])) {
        puts("Usage: dynkit methods\n\n"
             "List the integration methods: name, alias, order, stages (right-hand-side calls\n"
             "per step), whether the step size adapts, and a description.");
        return CLI_OK;
    }
    if (argc >= 1)
        return cli_usage_error("methods", "unexpected argument '%s'", argv[0]);
    printf("%-10s %-15s %5s %6s %-8s %s\n", "METHOD", "ALIAS", "ORDER", "STAGES", "STEP",
           "DESCRIPTION");
    for (int i = 0; i < dyn_method_count(); i++) {
        const dyn_tableau *m = dyn_method_at(i);
        printf("%-10s %-15s %5d %6d %-8s %s\n", m->name, m->alias ? m->alias : "-", m->order,
               m->stages, "fixed", m->title);
    }
    return CLI_OK;
}
