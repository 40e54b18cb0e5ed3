/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit equilibria MODEL [--box NAME=A:B,...] [--starts N] [--init/--set ...] [--json]
 * [--output FILE]: every equilibrium of a model in a box (a map's fixed points), with its
 * eigenvalues (multipliers) and type (dyn_equilibria_find, dynkit/equilibria.h); a
 * mechanism with constraints judged on its admissible directions as linearize does.
 * The default box: the file's @ xlo..yhi for the states of its phase plane, else the range
 * of the model's default run widened by half its width (at least 1) on each side.
 * docs/analysis.md, "Equilibria". */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "commands/analysis_kinds.h"
#include "commands/analysis_args.h"
#include "commands/eq_box.h"
#include "dynkit/equilibria.h"
#include "models/lin_constrained.h"
#include "pages/pages.h"
#include "util/out_file.h"

static void equilibria_help(void)
{
    puts("Usage: dynkit equilibria MODEL [--box NAME=A:B,...] [--starts N]\n"
         "                         [--init NAME=VALUE]... [--set NAME=VALUE]... [--t T]\n"
         "                         [--jacobian SCHEME]\n"
         "                         [--json] [--output FILE.json|FILE.csv]\n"
         "\n"
         "Finds the equilibria f(t, y) = 0 of MODEL in a box (of a discrete map, the\n"
         "fixed points F(y) = y): Newton's method (Levenberg-Marquardt steps, the model's\n"
         "exact Jacobian when it has one) from the box's centre, the model's initial\n"
         "state and 255 points of Halton's sequence; solutions that agree within 1e-6 of\n"
         "the box are one. Each is given with its eigenvalues (a map: multipliers), its\n"
         "type (stable or unstable node or focus, saddle, saddle-focus, centre,\n"
         "saddle-centre, non-hyperbolic) and the dimensions of its stable, unstable and\n"
         "centre manifolds.\n"
         "A mechanism file with constraints is judged on its minimal coordinates and\n"
         "speeds, as by linearize.\n"
         "\n"
         "Options:\n"
         "  --box NAME=A:B,...   the box of a state (repeatable); states not named: the\n"
         "                       file's @ xlo, xhi (ylo, yhi) when xp (yp) names the\n"
         "                       state, else the range of the model's default run widened\n"
         "                       by half its width, at least 1, on each side\n"
         "  --starts N           starts from the box (default 256: its centre and 255\n"
         "                       Halton points), besides the initial state\n"
         "  --init NAME=VALUE    a state of the initial state (the first start, and the\n"
         "                       default run's start)\n"
         "  --set NAME=VALUE     a parameter's value (repeatable)\n"
         "  --t T                the time (default: the model's start time)\n"
         "  --jacobian SCHEME    auto (default), analytic, central, richardson (as in\n"
         "                       linearize)\n"
         "  --json               print {\"equilibria\": [{\"state\": {NAME: value},\n"
         "                       \"eigenvalues\": [[re, im], ...], \"type\": ...}, ...], ...}\n"
         "  -o, --output FILE    .json: as --json; .csv: one row per equilibrium (type,\n"
         "                       stable, unstable, centre, the states, residual)\n"
         "\n"
         "Exit status 0 also when none is found (the text says so); eigenvalues need\n"
         "LAPACK.\n"
         "\n"
         "Examples:\n"
         "  dynkit equilibria examples/models/lorenz.ode\n"
         "  dynkit equilibria examples/models/duffing.ode --set gamma=0 --json\n"
         "  dynkit equilibria examples/models/henon.ode --box x=-3:3,y=-3:3");
}

typedef struct eq_args {
    const char *output, *starts_text, *t_text, *scheme_text;
    char box[4096];
    int json;
} eq_args;

/* ---- the box ---- */

/* --box NAME=A:B,... over the default. */
static int parse_box(const dyn_model *m, const char *text, double *lo, double *hi, int *given)
{
    char copy[4096];
    snprintf(copy, sizeof copy, "%s", text);
    int rc = CLI_OK;
    for (char *tok = copy, *next = NULL; tok && rc == CLI_OK; tok = next) {
        char *comma = strchr(tok, ',');
        next = comma ? comma + 1 : NULL;
        if (comma)
            *comma = '\0';
        char name[128];
        const char *v = cli_analysis_name_value(tok, name, sizeof name);
        const char *colon = v ? strchr(v, ':') : NULL;
        char a[128];
        double A, B;
        if (!colon || (size_t)(colon - v) >= sizeof a) {
            rc = cli_usage_error("equilibria", "--box '%s': give NAME=A:B (A <= B)", tok);
            break;
        }
        memcpy(a, v, (size_t)(colon - v));
        a[colon - v] = '\0';
        const int i = dyn_model_state_index(m, name);
        if (i < 0)
            rc =
                cli_usage_error("equilibria", "--box %s: %s has no state '%s'", tok, m->name, name);
        else if (cli_parse_number(a, &A) || cli_parse_number(colon + 1, &B) || A > B)
            rc =
                cli_usage_error("equilibria", "--box '%s': give NAME=A:B with numbers A <= B", tok);
        else {
            lo[i] = A;
            hi[i] = B;
            given[i] = 2;
        }
    }
    return rc;
}

/* ---- a mechanism's reduction ---- */

typedef struct reduce_ctx {
    const cli_lin_constraints *cc;
} reduce_ctx;

static int reduce_mech(void *ctx, double t, const double *y, void *par, const double *A,
                       double *Amin, int *k, char *err, size_t errlen)
{
    const reduce_ctx *r = ctx;
    const int n = r->cc->jm.model->n_states;
    const size_t N = (size_t)n;
    double *P = malloc(N * N * sizeof *P), *rw = malloc((2 * N * N + N) * sizeof *rw);
    int *kept = malloc(N * sizeof *kept);
    int rc = !P || !rw || !kept ? -1 : cli_lin_basis(r->cc, t, y, par, P, kept, k, err, errlen);
    if (!rc)
        rc = dyn_linear_reduce(n, *k, A, P, Amin, rw);
    free(P);
    free(rw);
    free(kept);
    return rc;
}

/* ---- output ---- */

static void print_text(FILE *f, const dyn_model *m, int map, const double *lo, const double *hi,
                       const int *given, const dyn_equilibria *e)
{
    const int n = m->n_states;
    fprintf(f, "%s: %d %s in the box", m->name, e->count,
            map ? (e->count == 1 ? "fixed point" : "fixed points")
                : (e->count == 1 ? "equilibrium" : "equilibria"));
    for (int i = 0; i < n; i++)
        fprintf(f, "%s %s = [%.6g, %.6g]%s", i ? "," : "", m->states[i].name, lo[i] + 0.0,
                hi[i] + 0.0,
                given[i] == 2 ? ""
                : given[i]    ? " (@ window)"
                              : " (default run)");
    fprintf(f, "\n(%d starts: %d converged, %d of them outside the box; %ld calls of f)\n",
            e->starts, e->converged, e->outside, e->rhs_calls);
    for (int c = 0; c < e->count; c++) {
        const double *y = e->y + (size_t)c * (size_t)n;
        const int *d = e->dims + 3 * (size_t)c;
        fprintf(f, "\n%d: %s", c + 1, dyn_eq_type_name(e->type[c]));
        if (e->type[c] != DYN_EQ_UNCLASSIFIED)
            fprintf(f, " (stable %d, unstable %d, centre %d)", d[0], d[1], d[2]);
        fprintf(f, ", |%s|_inf = %.3g\n", map ? "F(y) - y" : "f", e->residual[c]);
        for (int i = 0; i < n; i++)
            fprintf(f, "  %-10s = %.15g\n", m->states[i].name, y[i] + 0.0);
        if (e->k[c] > 0)
            fprintf(f, "  %s%s:\n", map ? "multipliers" : "eigenvalues",
                    e->k[c] < n ? " (minimal coordinates and speeds)" : "");
        for (int j = 0; j < e->k[c]; j++) {
            const double re = e->re[(size_t)c * (size_t)n + (size_t)j],
                         im = e->im[(size_t)c * (size_t)n + (size_t)j];
            fprintf(f, "    %22.15g %22.15g", re + 0.0, im + 0.0);
            if (map)
                fprintf(f, "   |mu| = %.12g", hypot(re, im));
            fputc('\n', f);
        }
    }
}

static void print_json(FILE *f, const dyn_model *m, int map, const double *lo, const double *hi,
                       const dyn_equilibria *e)
{
    const int n = m->n_states;
    cli_json j;
    cli_json_init(&j, f, 17);
    cli_json_begin_object(&j);
    cli_json_key(&j, "model");
    cli_json_string(&j, m->name);
    cli_json_key(&j, "map");
    cli_json_bool(&j, map);
    cli_json_key(&j, "box");
    cli_json_begin_object(&j);
    for (int i = 0; i < n; i++) {
        const double b[2] = {lo[i], hi[i]};
        cli_json_key(&j, m->states[i].name);
        cli_json_numbers(&j, b, 2, 1);
    }
    cli_json_end_object(&j);
    cli_json_key(&j, "starts");
    cli_json_number(&j, e->starts);
    cli_json_key(&j, "converged");
    cli_json_number(&j, e->converged);
    cli_json_key(&j, "equilibria");
    cli_json_begin_array(&j);
    for (int c = 0; c < e->count; c++) {
        cli_json_begin_object(&j);
        cli_json_key(&j, "state");
        cli_json_begin_object(&j);
        for (int i = 0; i < n; i++) {
            cli_json_key(&j, m->states[i].name);
            cli_json_number(&j, e->y[(size_t)c * (size_t)n + (size_t)i]);
        }
        cli_json_end_object(&j);
        cli_json_key(&j, "eigenvalues");
        cli_json_begin_array(&j);
        for (int k = 0; k < e->k[c]; k++) {
            const double ev[2] = {e->re[(size_t)c * (size_t)n + (size_t)k],
                                  e->im[(size_t)c * (size_t)n + (size_t)k]};
            cli_json_numbers(&j, ev, 2, 1);
        }
        cli_json_end_array(&j);
        cli_json_key(&j, "type");
        cli_json_string(&j, dyn_eq_type_name(e->type[c]));
        const char *dim_names[3] = {"stable", "unstable", "centre"};
        for (int d = 0; d < 3; d++) {
            cli_json_key(&j, dim_names[d]);
            cli_json_number(&j, e->dims[3 * (size_t)c + (size_t)d]);
        }
        cli_json_key(&j, "residual");
        cli_json_number(&j, e->residual[c]);
        cli_json_end_object(&j);
    }
    cli_json_end_array(&j);
    cli_json_end_object(&j);
    fputc('\n', f);
}

static void print_csv(FILE *f, const dyn_model *m, const dyn_equilibria *e)
{
    const int n = m->n_states;
    fputs("type,stable,unstable,centre", f);
    for (int i = 0; i < n; i++)
        fprintf(f, ",%s", m->states[i].name);
    fputs(",residual\n", f);
    for (int c = 0; c < e->count; c++) {
        const int *d = e->dims + 3 * (size_t)c;
        fprintf(f, "%s,%d,%d,%d", dyn_eq_type_name(e->type[c]), d[0], d[1], d[2]);
        for (int i = 0; i < n; i++)
            fprintf(f, ",%s", CLI_NUM(e->y[(size_t)c * (size_t)n + (size_t)i]));
        fprintf(f, ",%s\n", CLI_NUM(e->residual[c]));
    }
}

typedef struct eq_out {
    const eq_args *a;
    const dyn_model *m;
    int map;
    const double *lo, *hi;
    const int *given;
    const dyn_equilibria *e;
} eq_out;

static void print_result(FILE *f, const void *ctx)
{
    const eq_out *o = ctx;
    if (o->a->json)
        print_json(f, o->m, o->map, o->lo, o->hi, o->e);
    else if (o->a->output)
        print_csv(f, o->m, o->e);
    else
        print_text(f, o->m, o->map, o->lo, o->hi, o->given, o->e);
}

static int parse_scheme(const char *text, dyn_jac_scheme *s)
{
    static const char *const names[] = {"auto", "analytic", "central", "richardson"};
    for (int k = 0; k < 4; k++)
        if (strcmp(text, names[k]) == 0) {
            *s = (dyn_jac_scheme)k;
            return CLI_OK;
        }
    return cli_usage_error("equilibria",
                           "--jacobian '%s': accepted: auto, analytic, central, richardson", text);
}

static int check_own(eq_args *a, dyn_equilibria_opts *eo, double *t, const cli_run *run)
{
    long starts = 0;
    if (a->starts_text && cli_parse_count(a->starts_text, 1, &starts))
        return cli_usage_error("equilibria", "--starts '%s': give a whole number >= 1",
                               a->starts_text);
    if (starts > 1000000)
        return cli_usage_error("equilibria", "--starts %ld: at most 1000000", starts);
    eo->starts = (int)starts;
    *t = run->t0;
    if (a->t_text && cli_parse_number(a->t_text, t))
        return cli_usage_error("equilibria", "--t '%s': give a finite number", a->t_text);
    if (a->scheme_text && parse_scheme(a->scheme_text, &eo->scheme) != CLI_OK)
        return CLI_USAGE;
    if (a->output && strcmp(a->output, "-") != 0) {
        static const char *const exts[] = {".csv", ".json", NULL};
        if (cli_out_check_extension("equilibria", "--output", a->output, exts) != CLI_OK)
            return CLI_USAGE;
        a->json |= cli_has_extension(a->output, ".json");
    }
    return CLI_OK;
}

int cli_cmd_equilibria(int argc, char **argv)
{
    eq_args a;
    memset(&a, 0, sizeof a);
    const cli_aopt own[] = {
        {"box", NULL, NULL, a.box, sizeof a.box}, {"starts", &a.starts_text, NULL, NULL, 0},
        {"t", &a.t_text, NULL, NULL, 0},          {"jacobian", &a.scheme_text, NULL, NULL, 0},
        {"output", &a.output, NULL, NULL, 0},     {"json", NULL, &a.json, NULL, 0}};
    static const char *const run_opts[] = {"--init", "--set"};
    cli_run run;
    int done;
    int rc = cli_analysis_parse("equilibria", argc, argv, equilibria_help, run_opts, 2, own, 6,
                                &run, &done);
    if (done) {
        cli_run_free(&run);
        return rc;
    }
    dyn_equilibria_opts eo;
    memset(&eo, 0, sizeof eo);
    double t = 0.0;
    if (rc == CLI_OK)
        rc = check_own(&a, &eo, &t, &run);
    if (rc == CLI_OK)
        rc = cli_kinds_refuse_markov("equilibria", run.model, "its equilibria");
    if (rc == CLI_OK)
        cli_kinds_noise_note("equilibria", run.model, NULL);
    if (rc != CLI_OK) {
        cli_run_free(&run);
        return rc;
    }
    const dyn_model *m = run.model;
    const int n = m->n_states, map = dyn_method_is_map(run.method);
    double *lo = malloc((size_t)n * sizeof *lo), *hi = malloc((size_t)n * sizeof *hi);
    int *given = calloc((size_t)n, sizeof *given);
    cli_lin_constraints cc;
    memset(&cc, 0, sizeof cc);
    if (!lo || !hi || !given)
        rc = CLI_FAILED;
    if (rc == CLI_OK) {
        cli_eq_default_box(&run, lo, hi, given);
        if (a.box[0])
            rc = parse_box(m, a.box, lo, hi, given);
    }
    if (rc == CLI_OK)
        rc = cli_lin_constraints_open(argv[0], m, &cc);
    reduce_ctx rctx = {&cc};
    dyn_equilibria e;
    memset(&e, 0, sizeof e);
    if (rc == CLI_OK) {
        eo.lo = lo;
        eo.hi = hi;
        eo.guess = run.y0;
        eo.map = map;
        eo.eig = cli_eig_solver();
        if (cc.m > 0) {
            eo.reduce = reduce_mech;
            eo.reduce_ctx = &rctx;
        }
        const int st = dyn_equilibria_find(m, t, run.par, &eo, &e);
        if (st) {
            cli_error("equilibria: %s", e.message);
            rc = st == DYN_ERR_ARG ? CLI_USAGE : CLI_FAILED;
        }
    }
    const eq_out out = {&a, m, map, lo, hi, given, &e};
    if (rc == CLI_OK)
        rc = cli_analysis_write(a.output, print_result, &out);
    if (rc == CLI_OK && !eo.eig) {
        cli_error("equilibria: eigenvalues need LAPACK, and this dynkit was built without it "
                  "(install liblapack-dev and build again); the types are not given");
        rc = CLI_FAILED;
    }
    dyn_equilibria_free(&e);
    cli_lin_constraints_close(&cc);
    free(lo);
    free(hi);
    free(given);
    cli_run_free(&run);
    return rc;
}
