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
             "List the integration methods: name, alias, order (adaptive pairs: order of the\n"
             "solution and, in parentheses, of the embedded one), stages, right-hand-side calls\n"
             "per step (FSAL pairs reuse their last stage), the order of the dense output\n"
             "(3: cubic Hermite), whether the step size adapts to --rtol/--atol, whether the\n"
             "method is meant for stiff problems, and a description.");
        return CLI_OK;
    }
    if (argc >= 1)
        return cli_usage_error("methods", "unexpected argument '%s'", argv[0]);
    printf("%-10s %-15s %-6s %6s %6s %5s %-8s %-5s %s\n", "METHOD", "ALIAS", "ORDER",
           "STAGES", "F/STEP", "DENSE", "STEP", "STIFF", "DESCRIPTION");
    for (int i = 0; i < dyn_method_count(); i++) {
        const dyn_tableau *m = dyn_method_at(i);
        char order[16];
        const int adaptive = dyn_method_is_adaptive(m);
        if (adaptive && m->embedded_order > 0)
            snprintf(order, sizeof order, "%d(%d)", m->order, m->embedded_order);
        else
            snprintf(order, sizeof order, "%d", m->order);
        printf("%-10s %-15s %-6s %6d %6d %5d %-8s %-5s %s\n", m->name, m->alias ? m->alias : "-",
               order, m->stages, dyn_method_calls_per_step(m), dyn_method_dense_degree(m),
               adaptive ? "adaptive" : "fixed", dyn_method_is_stiff(m) ? "yes" : "no", m->title);
    }
    return CLI_OK;
}
