/* SPDX-License-Identifier: BSD-3-Clause */
/* analysis_kinds.c — the analysis commands on models with noise, Markov states, delays or
 * Volterra integrals (analysis_kinds.h): outside a run a model's noise slots read 0
 * (dynkit/model.h, n_noise) and its Markov states do not jump, so the right-hand side is the
 * deterministic part with the Markov states held; a delayed or integrated state needs the
 * past of a run. Each command either says what it assumed or refuses. */
#include "analysis_kinds.h"

void cli_kinds_noise_note(const char *command, const dyn_model *m, const char *what)
{
    /* a model with Markov states has noise slots for their jumps: cli_kinds_markov_note */
    if (m->n_noise > 0 && !m->jump)
        cli_note("%s: %s has noise (wiener, normal() or ran()): %s", command, m->name,
                 what ? what
                      : "this is the answer of its deterministic part, every noise term "
                        "taken as 0");
}

int cli_kinds_refuse_markov(const char *command, const dyn_model *m, const char *what)
{
    if (!m->jump)
        return CLI_OK;
    return cli_usage_error(command, "%s has Markov states (markov lines: they jump at random "
                           "between their values): %s would treat them as continuous states; "
                           "not supported (dynkit run simulates it; linearize takes a state "
                           "with the Markov states held)", m->name, what);
}

void cli_kinds_markov_note(const char *command, const dyn_model *m)
{
    if (m->jump)
        cli_note("%s: %s has Markov states: they are held at their values here (their rows "
                 "of df/dy are 0, an eigenvalue 0 each) and any other noise term is 0; only a "
                 "run makes them jump", command, m->name);
}

int cli_kinds_refuse_history(const char *command, const dyn_model *m, const char *what,
                             const char *instead)
{
    if (!m->delay && !m->volterra)
        return CLI_OK;
    return cli_usage_error(command, "%s has %s: %s reads the right-hand side at states away "
                           "from a run, where the past it needs is not defined; not supported "
                           "(%s)", m->name,
                           m->delay ? "delays (delay(x, tau))" : "Volterra integrals (int{...})",
                           what, instead);
}
