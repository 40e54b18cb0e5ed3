/* dynkit info MODEL: equations, states, parameters, outputs, units and defaults. */
#include "cli.h"

static void info_help(void)
{
    puts("Usage: dynkit info MODEL\n\n"
         "Describe MODEL: its equations, states (with default initial values), parameters\n"
         "(with default values), extra outputs, units and default run.");
}

int cli_cmd_info(int argc, char **argv)
{
    char names[512];
    if (argc >= 1 && cli_is_help(argv[0])) {
        info_help();
        return CLI_OK;
    }
    if (argc < 1)
        return cli_usage_error("info", "missing MODEL (accepted: %s)",
                               dyn_model_names(names, sizeof names));
    if (argc > 1)
        return cli_usage_error("info", "unexpected argument '%s'", argv[1]);
    const dyn_model *m;
    int open_rc = cli_model_open("info", argv[0], &m);
    if (open_rc != CLI_OK)
        return open_rc;
    printf("%s: %s\n\n%s\n\n", m->name, m->title, m->description);
    printf("States (--init NAME=VALUE):\n");
    for (int i = 0; i < m->n_states; i++)
        printf("  %-8s %-8s default %-22.17g %s\n", m->states[i].name, m->states[i].unit,
               m->y0[i], m->states[i].description);
    printf("\nParameters (--set NAME=VALUE):\n");
    for (int i = 0; i < m->n_params; i++)
        printf("  %-12s %-8s default %-22.17g %s\n", m->params[i].name, m->params[i].unit,
               m->params[i].value, m->params[i].description);
    if (m->n_outputs > 0) {
        printf("\nExtra outputs (run --outputs):\n");
        for (int i = 0; i < m->n_outputs; i++)
            printf("  %-16s %-8s %s\n", m->outputs[i].name, m->outputs[i].unit,
                   m->outputs[i].description);
    }
    printf("\nDefault run: --method %s --step %g --tspan %g:%g (times in s)\n", m->method,
           m->step, m->t0, m->t1);
    if (m->samples == DYN_SAMPLES_STEPS)
        printf("Adaptive methods without --step or --times write a sample at every accepted "
               "step;\n"
               "--step H is the step of fixed-step methods.\n");
    return CLI_OK;
}
