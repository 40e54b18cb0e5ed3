/* SPDX-License-Identifier: BSD-3-Clause */
/* cont_steady.c — dynkit continue on a mechanism file with constraints or cyclic
 * coordinates: its steady motions followed in the parameter (dyn_steady_continue,
 * dynkit/steady.h) on the equations dynkit steady solves (steady_frame.c: the kept states,
 * the dependent ones from the constraints, the cyclic ones). The unknowns: --unknown, else
 * the non-cyclic kept states whose initial value does not follow the parameter; the states
 * whose initial value follows it (a bicycle's wheel rates from its speed v) are held at
 * that value. docs/analysis.md, "Steady motions in a parameter". */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "commands/cont_steady.h"
#include "commands/steady_frame.h"
#include "dynkit/steady.h"
#include "util/out_file.h"

static int basis(void *ctx, double t, const double *y, const void *par, double *P, int *kept,
                 int *k, char *err, size_t errlen)
{
    return cli_lin_basis(ctx, t, y, par, P, kept, k, err, errlen);
}

/* follows[i] = 1 for the states whose initial value moves with parameter ip */
static int following(const dyn_model *m, const void *par, int ip, int *follows)
{
    const int n = m->n_states;
    void *p2 = malloc(m->par_size ? m->par_size : 1);
    double *a = malloc(2 * (size_t)n * sizeof *a);
    int rc = p2 && a ? CLI_OK : CLI_FAILED;
    if (rc == CLI_OK) {
        memcpy(p2, par, m->par_size);
        const double v = dyn_model_get_param(m, par, ip);
        dyn_model_set_param(m, p2, ip, v + 0.125 * fmax(fabs(v), 1.0));
        char err[256];
        if (m->prepare && m->prepare(p2, err, sizeof err)) {
            cli_error("continue: %s", err);
            rc = CLI_FAILED;
        }
    }
    if (rc == CLI_OK) {
        dyn_model_initial_state(m, par, a);
        dyn_model_initial_state(m, p2, a + n);
        for (int i = 0; i < n; i++)
            follows[i] = a[i] != a[n + i];
    }
    free(p2);
    free(a);
    return rc;
}

static void append_names(char *buf, size_t len, const dyn_model *m, const int *idx, int count)
{
    size_t used = strlen(buf);
    for (int i = 0; i < count && used + 2 < len; i++)
        used += (size_t)snprintf(buf + used, len - used, "%s%s", i ? ", " : "",
                                 m->states[idx[i]].name);
    if (count == 0 && used + 5 < len)
        snprintf(buf + used, len - used, "none");
}

int cont_steady_run(const char *spec, const cli_run *run, const cont_steady_args *a,
                    const dyn_cont_opts *o, dyn_diagram *d, dyn_cont_info *info, int *used)
{
    const dyn_model *m = run->model;
    const int n = m->n_states;
    const size_t N = (size_t)n;
    *used = 0;
    const char *path = cli_model_path(m);
    if (!path || !cli_has_extension(path, ".mech"))
        return CLI_OK;
    cli_lin_constraints cc;
    int rc = cli_lin_constraints_open(spec, m, &cc);
    if (rc != CLI_OK)
        return rc;
    steady_frame fr;
    const int fr_bad = steady_frame_alloc(&fr, &cc, n);
    int *ints = malloc(5 * N * sizeof *ints);
    double *y = malloc(N * sizeof *y);
    char cyclic_list[1024], unknown_list[1024];
    snprintf(cyclic_list, sizeof cyclic_list, "%s", a->cyclic ? a->cyclic : "");
    snprintf(unknown_list, sizeof unknown_list, "%s", a->unknown ? a->unknown : "");
    if (fr_bad || !ints || !y)
        rc = CLI_FAILED;
    int *cyclic = ints, *follows = ints + N, *eqs = ints + 2 * N, *unk = ints + 3 * N,
        *held = ints + 4 * N;
    int ne = 0, nu = 0, nh = 0;
    if (rc == CLI_OK) {
        memcpy(y, run->y0, N * sizeof *y);
        rc = steady_frame_prepare("continue", &fr, m, run->t0, y, run->par, cyclic_list, cyclic,
                                  eqs, &ne);
    }
    /* no cyclic state: every kept state is an equation */
    if (rc == CLI_OK && ne == fr.k && cc.m == 0 && !a->unknown) {
        /* an equilibrium problem: dyn_continue as for any model */
        free(ints);
        free(y);
        steady_frame_free(&fr);
        cli_lin_constraints_close(&cc);
        return CLI_OK;
    }
    *used = 1;
    if (rc == CLI_OK)
        rc = following(m, run->par, o->ip, follows);
    /* the states that follow the second parameter too (held's space, filled later) */
    if (rc == CLI_OK && o->ip2 >= 0) {
        rc = following(m, run->par, o->ip2, held);
        for (int i = 0; i < n && rc == CLI_OK; i++)
            follows[i] |= held[i];
    }
    /* a state given by --init is held at that value */
    for (int g = 0; g < a->n_init && rc == CLI_OK; g++) {
        const char *eq = strchr(a->init[g], '=');
        char name[128];
        snprintf(name, sizeof name, "%.*s", eq ? (int)(eq - a->init[g]) : 0, a->init[g]);
        const int s = dyn_model_state_index(m, name);
        if (s >= 0)
            follows[s] = 0;
    }
    if (rc == CLI_OK && a->unknown) {
        char *names[256];
        const int c = steady_split_names(unknown_list, names, 256);
        for (int u = 0; u < c && rc == CLI_OK; u++) {
            const int s = dyn_model_state_index(m, names[u]);
            int ok = 0;
            for (int e = 0; e < ne; e++)
                ok |= eqs[e] == s;
            if (!ok) {
                char list[512] = "";
                append_names(list, sizeof list, m, eqs, ne);
                rc = cli_usage_error("continue",
                                     "--unknown %s: not a state whose derivative must vanish in "
                                     "a steady motion of %s (accepted: %s)",
                                     names[u], m->name, list);
            }
            unk[nu++] = s;
        }
        if (rc == CLI_OK && c <= 0)
            rc = cli_usage_error("continue", "--unknown: give NAME[,NAME...]");
    } else if (rc == CLI_OK) {
        for (int e = 0; e < ne; e++)
            if (!follows[eqs[e]])
                unk[nu++] = eqs[e];
        if (nu == 0)
            rc = cli_usage_error("continue",
                                 "every state of the steady equations follows %s: name the "
                                 "unknowns with --unknown",
                                 m->params[o->ip].name);
    }
    for (int e = 0; e < ne && rc == CLI_OK; e++) {
        int is_unknown = 0;
        for (int u = 0; u < nu; u++)
            is_unknown |= unk[u] == eqs[e];
        if (!is_unknown)
            held[nh++] = eqs[e];
    }
    if (rc == CLI_OK) {
        const dyn_steady_problem sp = {nu,
                                       unk,
                                       ne,
                                       eqs,
                                       follows,
                                       fr.nd ? steady_complete_dependent : NULL,
                                       &fr,
                                       cc.m > 0 ? basis : NULL,
                                       (void *)&cc};
        char note[1024] = "steady motions: unknowns ";
        append_names(note, sizeof note, m, unk, nu);
        snprintf(note + strlen(note), sizeof note - strlen(note), "; held: ");
        append_names(note, sizeof note, m, held, nh);
        fprintf(stderr, "dynkit: note: %s\n", note);
        if (dyn_steady_continue(m, run->par, y, o, &sp, d, info)) {
            char list[512] = "";
            append_names(list, sizeof list, m, eqs, ne);
            if (a->unknown)
                cli_error("continue: %s", info->message);
            else
                cli_error("continue: %s; --unknown NAME,... names the unknowns among %s", info->message,
                          list);
            rc = CLI_FAILED;
        }
    }
    free(ints);
    free(y);
    if (!fr_bad)
        steady_frame_free(&fr);
    cli_lin_constraints_close(&cc);
    return rc;
}
