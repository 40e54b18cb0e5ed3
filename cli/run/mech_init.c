/* SPDX-License-Identifier: BSD-3-Clause */
/* The initial state of a mechanism's run (docs/mechanisms.md, "Initial values"): checked
 * against the constraints after --set and --init (refused with the constraint's name and
 * value), or moved onto them with --project-init (dyn_project_constraints), printing each
 * state it changed. The constraints' values come from dyn_mech_constraints_to_c's model,
 * compiled beside the run's (lin_constrained.c). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/analysis.h"
#include "models/lin_constrained.h"
#include "run/mech_init.h"

/* the name of the r-th constraint among the outputs "holonomic"/"speeds" */
static const char *constraint_name(const dyn_model *cm, int r)
{
    for (int i = 0; i < cm->n_outputs; i++) {
        const char *u = cm->outputs[i].unit;
        if (u && (strcmp(u, "holonomic") == 0 || strcmp(u, "speeds") == 0) && r-- == 0)
            return cm->outputs[i].name;
    }
    return "?";
}

static int check(const char *command, const dyn_model *cm, const cli_run *run)
{
    const int N = cm->n_states, n = N / 2, no = cm->n_outputs + 1;
    double *h = malloc((size_t)no * 2 * sizeof *h);
    int *hol = malloc((size_t)no * sizeof *hol);
    int m = h && hol ? dyn_constraint_values(cm, run->par, run->t0, run->y0, h, h + no, hol)
                     : -1;
    double sq = 1.0, su = 1.0;
    for (int j = 0; j < n; j++) {
        sq = fmax(sq, fabs(run->y0[j]));
        su = fmax(su, fabs(run->y0[n + j]));
    }
    int rc = m < 0 ? cli_usage_error(command, "the constraints' values failed at the "
                                              "initial state")
                   : CLI_OK;
    for (int r = 0; r < m && rc == CLI_OK; r++) {
        const double f = h[no + r];
        if (hol[r] && !(fabs(f) <= 1e-9 * sq))
            rc = cli_usage_error(command, "the initial state does not hold constraint '%s': "
                                 "its value is %s, not 0 (give --project-init to move the "
                                 "initial state onto the constraints, or other --init "
                                 "values)", constraint_name(cm, r), CLI_NUM(f));
        else if (!(fabs(h[r]) <= 1e-9 * su))
            rc = cli_usage_error(command, "the initial state does not hold constraint '%s': "
                                 "its %s is %s, not 0 (give --project-init to move the "
                                 "initial state onto the constraints, or other --init "
                                 "values)", constraint_name(cm, r),
                                 hol[r] ? "rate" : "value", CLI_NUM(h[r]));
    }
    free(h);
    free(hol);
    return rc;
}

static int project(const char *command, const dyn_model *cm, cli_run *run)
{
    const int N = cm->n_states;
    double *y = malloc((size_t)N * sizeof *y);
    if (!y) {
        fprintf(stderr, "dynkit: error: out of memory\n");
        return CLI_FAILED;
    }
    memcpy(y, run->y0, (size_t)N * sizeof *y);
    double res[2] = {0.0, 0.0};
    int bad = -1;
    char err[256] = "";
    if (dyn_project_constraints(cm, run->par, run->t0, y, res, &bad, err, sizeof err)) {
        free(y);
        if (bad >= 0)
            return cli_usage_error(command, "--project-init: %s at the initial state: "
                                   "constraint '%s' depends on the ones before it (remove "
                                   "one, or start away from this configuration)", err,
                                   constraint_name(cm, bad));
        return cli_usage_error(command, "--project-init: %s", err);
    }
    if (!run->quiet) {
        int changed = 0;
        for (int i = 0; i < N; i++)
            if (y[i] != run->y0[i]) {
                fprintf(stderr, "%s %s %s -> ", changed ? "," : "dynkit: --project-init:",
                        run->model->states[i].name, CLI_NUM(run->y0[i]));
                fprintf(stderr, "%s", CLI_NUM(y[i]));
                changed = 1;
            }
        if (changed)
            fprintf(stderr, " (the constraints hold within %s, their rates within %s)\n", CLI_NUM(res[0]),
                    CLI_NUM(res[1]));
        else
            fprintf(stderr, "dynkit: --project-init: the initial state holds the "
                            "constraints; nothing changed\n");
    }
    memcpy(run->y0, y, (size_t)N * sizeof *y);
    free(y);
    return CLI_OK;
}

int cli_mech_initial(const char *command, const char *spec, cli_run *run, int projected)
{
    cli_lin_constraints cc;
    int rc = cli_lin_constraints_open(spec, run->model, &cc);
    if (rc != CLI_OK)
        return rc;
    if (cc.loaded && cc.m > 0)
        rc = projected ? project(command, cc.jm.model, run) : check(command, cc.jm.model, run);
    else if (cc.loaded && projected && !run->quiet)
        fprintf(stderr, "dynkit: --project-init: %s has no constraints; nothing changed\n",
                spec);
    cli_lin_constraints_close(&cc);
    return rc;
}
