/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit models, dynkit methods: what is available, one line each. */
#include "cli.h"
#include "dynkit/brusselator.h"

int cli_cmd_models(int argc, char **argv)
{
    if (argc >= 1 && cli_is_help(argv[0])) {
        puts("Usage: dynkit models\n\nList the built-in models. 'dynkit info MODEL' tells more.\n"
             "The Brusselator's size is chosen with its name: brusselator:N has 2N states.");
        return CLI_OK;
    }
    if (argc >= 1)
        return cli_usage_error("models", "unexpected argument '%s'", argv[0]);
    printf("%-12s %-7s %s\n", "MODEL", "STATES", "DESCRIPTION");
    for (int i = 0; i < dyn_model_count(); i++) {
        const dyn_model *m = dyn_model_at(i);
        printf("%-12s %-7d %s\n", m->name, m->n_states, m->title);
    }
    /* a model whose size the user chooses (dynkit/brusselator.h) */
    printf("%-12s %-7s %s (stiff; HNW II sec. IV.10): brusselator:N, N = %d by default\n",
           "brusselator", "2N", "1-D Brusselator with diffusion, banded Jacobian",
           DYN_BRUSSELATOR_DEFAULT_N);
    return CLI_OK;
}

int cli_cmd_methods(int argc, char **argv)
{
    if (argc >= 1 && cli_is_help(argv[0])) {
        puts("Usage: dynkit methods\n\n"
             "List the integration methods: name, alias, order (adaptive pairs: order of the\n"
             "solution and, in parentheses, of the embedded one), stages, right-hand-side calls\n"
             "per accepted step (FSAL pairs reuse their last stage; rodas4: f(t, y), five more\n"
             "stages and one call for df/dt), Jacobian evaluations per accepted step (rodas4\n"
             "forms one per step: the model's, or n more calls of f by differences), the order\n"
             "of the dense output (3: cubic Hermite), whether the step size adapts to\n"
             "--rtol/--atol, whether the method is meant for stiff problems, and a description.\n"
             "A rejected step costs its stages again (rodas4: 5 calls, no new Jacobian).\n"
             "\n"
             "cvode is listed when dynkit is built with SUNDIALS (libsundials-dev): the CVODE\n"
             "backend, BDF of variable order 1-5 with Newton iteration and a dense LU, adaptive,\n"
             "for stiff problems; its calls per step vary (one or two per Newton iteration, the\n"
             "Jacobian reused over many steps), its samples come from CVODE's interpolation, and\n"
             "it runs without --event and --trace. Without SUNDIALS --method cvode is an error\n"
             "that says so.");
        return CLI_OK;
    }
    if (argc >= 1)
        return cli_usage_error("methods", "unexpected argument '%s'", argv[0]);
    printf("%-10s %-15s %-6s %6s %6s %6s %5s %-8s %-5s %s\n", "METHOD", "ALIAS", "ORDER",
           "STAGES", "F/STEP", "J/STEP", "DENSE", "STEP", "STIFF", "DESCRIPTION");
    for (int i = 0; i < dyn_method_count(); i++) {
        const dyn_tableau *m = dyn_method_at(i);
        char order[16];
        const int adaptive = dyn_method_is_adaptive(m);
        if (adaptive && m->embedded_order > 0)
            snprintf(order, sizeof order, "%d(%d)", m->order, m->embedded_order);
        else if (dyn_method_is_map(m))
            snprintf(order, sizeof order, "-");
        else
            snprintf(order, sizeof order, "%d", m->order);
        printf("%-10s %-15s %-6s %6d %6d %6d %5d %-8s %-5s %s\n", m->name,
               m->alias ? m->alias : "-", order, m->stages, dyn_method_calls_per_step(m),
               dyn_method_jac_per_step(m), dyn_method_dense_degree(m),
               adaptive ? "adaptive" : dyn_method_is_map(m) ? "map" : "fixed",
               dyn_method_is_stiff(m) ? "yes" : "no", m->title);
    }
    const dyn_tableau *cv = cli_cvode_method();
    if (cv)
        printf("%-10s %-15s %-6s %6s %6s %6s %5s %-8s %-5s %s\n", cv->name, "-", "1-5", "-",
               "var", "<1", "var", "adaptive", "yes", cv->title);
    return CLI_OK;
}
