/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit steady MODEL --unknown NAME[,NAME...] [--cyclic NAME,...] [--init/--set ...]
 * [--t T] [--json] [--output FILE.json]: a steady motion (relative equilibrium): the named
 * unknowns (states or parameters) solved so that the derivatives of the non-cyclic states
 * vanish while the cyclic ones move at constant rates (dyn_steady_solve, dynkit/steady.h);
 * a mechanism's dependent states completed from its constraints; then the eigenvalues of
 * the linearization on the minimal coordinates and speeds, as linearize gives them.
 * docs/analysis.md, "Steady motions". */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "commands/analysis_kinds.h"
#include "commands/analysis_args.h"
#include "commands/steady_frame.h"
#include "dynkit/analysis.h"
#include "dynkit/equilibria.h"
#include "dynkit/steady.h"
#include "models/lin_constrained.h"
#include "pages/pages.h"
#include "util/out_file.h"

static void steady_help(void)
{
    puts("Usage: dynkit steady MODEL --unknown NAME[,NAME...] [--cyclic NAME,...]\n"
         "                     [--init NAME=VALUE]... [--set NAME=VALUE]... [--t T]\n"
         "                     [--json] [--output FILE.json]\n"
         "\n"
         "Finds a steady motion (a relative equilibrium) of MODEL: the unknowns, states\n"
         "or parameters, are solved (Gauss-Newton, Levenberg-Marquardt damping) from their\n"
         "values in the initial state so that the derivatives of the non-cyclic states\n"
         "vanish, while the cyclic states - those the right-hand side does not depend\n"
         "on, a mechanism's ignorable coordinates - keep moving at constant rates. A\n"
         "mechanism's states that its constraints determine are solved from them at\n"
         "every step. Then it linearizes there: the eigenvalues on the minimal\n"
         "coordinates and speeds, as "
         "linearize gives them.\n"
         "\n"
         "Options:\n"
         "  --unknown NAME,...   the states or parameters to solve for (repeatable)\n"
         "  --cyclic NAME,...    the cyclic states (default: those whose column of the\n"
         "                       linearization vanishes on the other states' rows)\n"
         "  --init NAME=VALUE    a state: the given ones and the unknowns' first guesses\n"
         "  --set NAME=VALUE     a parameter's value (repeatable)\n"
         "  --t T                the time (default: the model's start time)\n"
         "  --json               print {\"state\": {...}, \"parameters\": {...},\n"
         "                       \"eigenvalues\": [[re, im], ...], \"residual\": r, ...}\n"
         "  -o, --output FILE    write the JSON to FILE.json\n"
         "\n"
         "Examples:\n"
         "  dynkit steady examples/mechanisms/top.mech --unknown dpsi --init dpsi=1\n"
         "  dynkit steady examples/mechanisms/spherical_pendulum.mech --unknown dpsi \\\n"
         "      --init dpsi=4\n"
         "  dynkit steady examples/mechanisms/rolling_disk.mech --unknown dphi --init \\\n"
         "      theta=0.3 --init dpsi=2 --json");
}

typedef struct st_args {
    char unknown[1024], cyclic[1024], init[4096];
    const char *t_text, *output;
    int json;
} st_args;

/* Look NAME up among the states and parameters. */
static int find_name(const dyn_model *m, const char *name, dyn_steady_unknown *u)
{
    u->is_param = 0;
    u->index = dyn_model_state_index(m, name);
    if (u->index >= 0)
        return CLI_OK;
    u->is_param = 1;
    u->index = dyn_model_param_index(m, name);
    if (u->index >= 0)
        return CLI_OK;
    return cli_usage_error("steady", "--unknown %s: %s has no state or parameter '%s'", name,
                           m->name, name);
}

typedef struct st_result {
    int n_unknowns, n_eq, k;
    dyn_steady_unknown *unknowns;
    int *cyclic; /* (k) over the kept states */
    double *re, *im;
    dyn_steady_info info;
    double tol;
} st_result;

typedef struct st_out {
    const st_args *a;
    const dyn_model *m;
    const void *par;
    const double *y;
    const steady_frame *fr;
    const st_result *r;
} st_out;

static void print_result(FILE *f, const void *ctx)
{
    const st_out *o = ctx;
    const st_args *a = o->a;
    const dyn_model *m = o->m;
    const void *par = o->par;
    const double *y = o->y;
    const steady_frame *fr = o->fr;
    const st_result *r = o->r;
    const int n = m->n_states;
    if (a->json) {
        cli_json j;
        cli_json_init(&j, f, 17);
        cli_json_begin_object(&j);
        cli_json_key(&j, "model");
        cli_json_string(&j, m->name);
        cli_json_key(&j, "state");
        cli_json_begin_object(&j);
        for (int i = 0; i < n; i++) {
            cli_json_key(&j, m->states[i].name);
            cli_json_number(&j, y[i]);
        }
        cli_json_end_object(&j);
        cli_json_key(&j, "parameters");
        cli_json_begin_object(&j);
        for (int i = 0; i < m->n_params; i++) {
            cli_json_key(&j, m->params[i].name);
            cli_json_number(&j, dyn_model_get_param(m, par, i));
        }
        cli_json_end_object(&j);
        cli_json_key(&j, "unknowns");
        cli_json_begin_array(&j);
        for (int u = 0; u < r->n_unknowns; u++)
            cli_json_string(&j, r->unknowns[u].is_param ? m->params[r->unknowns[u].index].name
                                                        : m->states[r->unknowns[u].index].name);
        cli_json_end_array(&j);
        cli_json_key(&j, "cyclic");
        cli_json_begin_array(&j);
        for (int c = 0; c < fr->k; c++)
            if (r->cyclic[c])
                cli_json_string(&j, m->states[fr->kept[c]].name);
        cli_json_end_array(&j);
        cli_json_key(&j, "kept");
        cli_json_begin_array(&j);
        for (int c = 0; c < fr->k; c++)
            cli_json_string(&j, m->states[fr->kept[c]].name);
        cli_json_end_array(&j);
        cli_json_key(&j, "eigenvalues");
        cli_json_begin_array(&j);
        for (int c = 0; c < r->k; c++) {
            const double ev[2] = {r->re[c], r->im[c]};
            cli_json_numbers(&j, ev, 2, 1);
        }
        cli_json_end_array(&j);
        cli_json_key(&j, "stability");
        cli_json_string(&j, dyn_stability_name(dyn_classify(r->k, r->re, r->tol)));
        cli_json_key(&j, "residual");
        cli_json_number(&j, r->info.residual);
        cli_json_key(&j, "iterations");
        cli_json_number(&j, r->info.iterations);
        cli_json_end_object(&j);
        fputc('\n', f);
        return;
    }
    fprintf(f, "%s: a steady motion (%d iterations, residual %.3g)\n", m->name, r->info.iterations,
            r->info.residual);
    fputs("cyclic (moving at constant rates):", f);
    int n_cyclic = 0;
    for (int c = 0; c < fr->k; c++)
        if (r->cyclic[c]) {
            fprintf(f, " %s", m->states[fr->kept[c]].name);
            n_cyclic++;
        }
    fputs(n_cyclic ? "\n" : " none\n", f);
    for (int u = 0; u < r->n_unknowns; u++) {
        const dyn_steady_unknown *x = &r->unknowns[u];
        fprintf(f, "  %-10s = %.15g   (unknown)\n",
                x->is_param ? m->params[x->index].name : m->states[x->index].name,
                (x->is_param ? dyn_model_get_param(m, par, x->index) : y[x->index]) + 0.0);
    }
    fputs("state:\n", f);
    for (int i = 0; i < n; i++)
        fprintf(f, "  %-10s = %.15g\n", m->states[i].name, y[i] + 0.0);
    fprintf(f, "eigenvalues%s:\n", fr->k < n ? " (minimal coordinates and speeds)" : "");
    for (int c = 0; c < r->k; c++)
        fprintf(f, "  %22.15g %22.15g\n", r->re[c] + 0.0, r->im[c] + 0.0);
    fprintf(f, "stability: %s\n", dyn_stability_name(dyn_classify(r->k, r->re, r->tol)));
}

/* A and its reduction at the solution, eigenvalues into r. */
static int eigenvalues(const dyn_model *m, double t, const double *y, void *par, steady_frame *fr,
                       st_result *r)
{
    const int n = m->n_states;
    const size_t N = (size_t)n;
    const dyn_eig_solver *solver = cli_eig_solver();
    if (!solver) {
        cli_error("steady: eigenvalues need LAPACK, and this dynkit was built without it "
                  "(install liblapack-dev and build again)");
        return CLI_FAILED;
    }
    double *A = malloc(N * N * sizeof *A), *Amin = malloc(N * N * sizeof *Amin),
           *w = malloc((dyn_linearize_work_size(n) + 2 * N * N + N) * sizeof *w);
    int rc = A && Amin && w ? steady_frame_at("steady", fr, t, y, par) : CLI_FAILED;
    dyn_linearize_info li;
    if (rc == CLI_OK && dyn_linearize(m, t, y, par, NULL, A, w, &li)) {
        cli_error("steady: %s", li.message);
        rc = CLI_FAILED;
    }
    if (rc == CLI_OK && dyn_linear_reduce(n, fr->k, A, fr->P, Amin, w)) {
        cli_error("steady: the admissible directions are dependent");
        rc = CLI_FAILED;
    }
    char err[256] = "";
    r->k = fr->k;
    if (rc == CLI_OK) {
        r->tol = dyn_stability_tol(r->k, Amin, 0.0);
        if (r->k > 0 && solver->eigenvalues(r->k, Amin, r->re, r->im, err, sizeof err)) {
            cli_error("steady: eigenvalues: %s", err);
            rc = CLI_FAILED;
        }
        dyn_eig_sort(r->k, r->re, r->im);
    }
    free(A);
    free(Amin);
    free(w);
    return rc;
}

static int solve(const char *spec, st_args *a, cli_run *run, double t)
{
    const dyn_model *m = run->model;
    const int n = m->n_states;
    const size_t N = (size_t)n;
    cli_lin_constraints cc;
    int rc = cli_lin_constraints_open(spec, m, &cc);
    if (rc != CLI_OK)
        return rc;
    steady_frame fr;
    const int fr_bad = steady_frame_alloc(&fr, &cc, n);
    st_result r;
    memset(&r, 0, sizeof r);
    r.unknowns = malloc(N * sizeof *r.unknowns + (size_t)m->n_params * sizeof *r.unknowns);
    r.cyclic = calloc(N, sizeof *r.cyclic);
    r.re = calloc(N, sizeof *r.re);
    r.im = calloc(N, sizeof *r.im);
    int *eqs = malloc(N * sizeof *eqs);
    if (fr_bad || !r.unknowns || !r.cyclic || !r.re || !r.im || !eqs)
        rc = CLI_FAILED;
    if (rc == CLI_OK)
        rc = steady_frame_prepare("steady", &fr, m, t, run->y0, run->par, a->cyclic, r.cyclic,
                                  eqs, &r.n_eq);
    char *names[256];
    const int nu = rc == CLI_OK ? steady_split_names(a->unknown, names, 256) : 0;
    for (int u = 0; u < nu && rc == CLI_OK; u++) {
        rc = find_name(m, names[u], &r.unknowns[u]);
        if (rc == CLI_OK && !r.unknowns[u].is_param) {
            int is_eq = 0;
            for (int i = 0; i < r.n_eq; i++)
                is_eq |= eqs[i] == r.unknowns[u].index;
            if (!is_eq)
                rc = cli_usage_error("steady", "--unknown %s: %s", names[u],
                                     "a cyclic state (its value does not enter) or one that the "
                                     "constraints determine; give another state or a parameter");
        }
        if (rc == CLI_OK && r.unknowns[u].is_param && cli_param_is_size(m, names[u]))
            rc = cli_usage_error("steady", "--unknown %s: the size of the model", names[u]);
        r.n_unknowns = u + 1;
    }
    if (rc == CLI_OK) {
        const dyn_steady_opts so = {
            r.n_unknowns, r.unknowns, r.n_eq, eqs, fr.nd ? steady_complete_dependent : NULL, &fr, 0.0, 0};
        const int st = dyn_steady_solve(m, t, run->y0, run->par, &so, &r.info);
        if (st) {
            cli_error("steady: %s", r.info.message);
            rc = st == DYN_ERR_ARG ? CLI_USAGE : CLI_FAILED;
        }
    }
    if (rc == CLI_OK)
        rc = eigenvalues(m, t, run->y0, run->par, &fr, &r);
    const st_out out = {a, m, run->par, run->y0, &fr, &r};
    if (rc == CLI_OK)
        rc = cli_analysis_write(a->output, print_result, &out);
    if (!fr_bad)
        steady_frame_free(&fr);
    free(r.unknowns);
    free(r.cyclic);
    free(r.re);
    free(r.im);
    free(eqs);
    cli_lin_constraints_close(&cc);
    return rc;
}

/* --init NAME=VALUE,... into y (states only: a parameter is given with --set). */
static int apply_init(const dyn_model *m, char *list, double *y)
{
    char *items[256];
    const int c = steady_split_names(list, items, 256);
    if (c < 0)
        return cli_usage_error("steady", "--init: too many values");
    for (int i = 0; i < c; i++) {
        char name[128];
        const char *v = cli_analysis_name_value(items[i], name, sizeof name);
        const int s = v ? dyn_model_state_index(m, name) : -1;
        double x;
        if (!v)
            return cli_usage_error("steady", "--init '%s': give NAME=VALUE", items[i]);
        if (s < 0)
            return cli_usage_error(
                "steady", "--init %s: %s has no state '%s'%s", items[i], m->name, name,
                dyn_model_param_index(m, name) >= 0 ? " (a parameter: give it with --set)" : "");
        if (cli_parse_number(v, &x))
            return cli_usage_error("steady", "--init %s: give a finite number", items[i]);
        y[s] = x;
    }
    return CLI_OK;
}

int cli_cmd_steady(int argc, char **argv)
{
    st_args a;
    memset(&a, 0, sizeof a);
    const cli_aopt own[] = {{"init", NULL, NULL, a.init, sizeof a.init},
                            {"unknown", NULL, NULL, a.unknown, sizeof a.unknown},
                            {"cyclic", NULL, NULL, a.cyclic, sizeof a.cyclic},
                            {"t", &a.t_text, NULL, NULL, 0},
                            {"output", &a.output, NULL, NULL, 0},
                            {"json", NULL, &a.json, NULL, 0}};
    /* --init is applied here, not by the run's parser: a mechanism's dependent states
     * are solved from its constraints below, so the given state need not hold them */
    static const char *const run_opts[] = {"--set"};
    cli_run run;
    int done;
    int rc =
        cli_analysis_parse("steady", argc, argv, steady_help, run_opts, 1, own, 6, &run, &done);
    if (done) {
        cli_run_free(&run);
        return rc;
    }
    double t = run.t0;
    if (rc == CLI_OK && a.init[0])
        rc = apply_init(run.model, a.init, run.y0);
    if (rc == CLI_OK && !a.unknown[0])
        rc = cli_usage_error("steady", "missing --unknown NAME[,NAME...] (states or parameters "
                                       "to solve for)");
    if (rc == CLI_OK && a.t_text && cli_parse_number(a.t_text, &t))
        rc = cli_usage_error("steady", "--t '%s': give a finite number", a.t_text);
    if (rc == CLI_OK && a.output && strcmp(a.output, "-") != 0) {
        static const char *const exts[] = {".json", NULL};
        rc = cli_out_check_extension("steady", "--output", a.output, exts);
        a.json = 1;
    }
    if (rc == CLI_OK && dyn_method_is_map(run.method))
        rc = cli_usage_error("steady",
                             "%s is a discrete map: its fixed points are found by "
                             "dynkit equilibria",
                             run.model->name);
    if (rc == CLI_OK)
        rc = cli_kinds_refuse_markov("steady", run.model, "a steady motion");
    if (rc == CLI_OK) {
        cli_kinds_noise_note("steady", run.model, NULL);
        rc = solve(argv[0], &a, &run, t);
    }
    cli_run_free(&run);
    return rc;
}
