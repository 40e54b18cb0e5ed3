/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit linearize MODEL [--init/--set ...] [--t T] [--vary NAME=A:B:N] [--output FILE]
 * [--matrix] [--json] [--jacobian SCHEME]: the Jacobian A = df/dy of any model about a
 * state (dyn_linearize, dynkit/analysis.h), its eigenvalues (LAPACK's dgeev when the tool
 * is built with it), frequencies and damping ratios of the oscillating pairs, and the
 * stability; one block per value of --vary. docs/analysis.md. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "commands/analysis_kinds.h"
#include "dynkit/analysis.h"
#include "dynkit/sweep.h"
#include "models/lin_constrained.h"
#include "util/out_file.h"
#include "pages/pages.h"

#define LIN_MAX_POINTS 1000000L

static void linearize_help(void)
{
    puts("Usage: dynkit linearize MODEL [--init NAME=VALUE]... [--set NAME=VALUE]... [--t T]\n"
         "                        [--vary NAME=A:B:N] [--output FILE.csv|FILE.json]\n"
         "                        [--matrix] [--json] [--jacobian SCHEME] [--equilibrium]\n"
         "\n"
         "Linearizes MODEL about a state: prints the Jacobian A = df/dy at (t, y) with the\n"
         "states' names, its eigenvalues (re, im; for an oscillating pair the natural\n"
         "frequency wn = |lambda| and the damping ratio zeta = -re/|lambda|), and the\n"
         "stability: asymptotically stable (every re < -tol), unstable (some re > tol) or\n"
         "marginal, with tol = 1e-8 ||A||_inf. The state is the model's default initial state\n"
         "with the --init values; it need not be an equilibrium (the printed f(t, y) says\n"
         "how far it is from one).\n"
         "\n"
         "A mechanism file with constraints (FILE.mech) is linearized in its minimal\n"
         "coordinates and speeds: the eigenvalues are those of A_min = P^+ A P on the\n"
         "directions that keep the constraints (the states kept are printed); a steady\n"
         "motion such as rolling at a speed is given by --init or --set (docs/analysis.md).\n"
         "\n"
         "A discrete map is refused (dynkit equilibria gives its fixed points and their\n"
         "multipliers; --matrix prints dF/dy); noise is taken as 0 and Markov states are\n"
         "held, with a note (--equilibrium refuses Markov states).\n"
         "\n"
         "Options:\n"
         "  --init NAME=VALUE    a state's value (repeatable; as in dynkit run)\n"
         "  --project-init       a mechanism file: that state moved onto its constraints\n"
         "                       first (as in dynkit run)\n"
         "  --set NAME=VALUE     a parameter's value (repeatable)\n"
         "  --forces FILE        the model's input table (as in dynkit run), read at T\n"
         "  --t T                the time (default: the model's start time)\n"
         "  --equilibrium        first find an equilibrium f(t, y) = 0 from the state as a\n"
         "                       guess (Levenberg-Marquardt; along --vary of a parameter,\n"
         "                       from the previous value's), and linearize there\n"
         "  --vary NAME=A:B:N    one block per value: N values from A to B (or NAME=V1,V2,...);\n"
         "                       NAME a parameter or a state, as in dynkit sweep\n"
         "  --jacobian SCHEME    auto (default: the model's analytic Jacobian when it has one,\n"
         "                       else richardson), analytic, central (differences, step\n"
         "                       eps^(1/3)), richardson (central differences extrapolated)\n"
         "  -o, --output FILE    .csv: one row per eigenvalue, columns [NAME,]re,im (sorted\n"
         "                       by im, then re); .json: as --json; '-': the CSV on\n"
         "                       standard output\n"
         "  --matrix             print A alone as CSV: a column 'state' (the row's state),\n"
         "                       then one column per state ([NAME,] first with --vary)\n"
         "  --json               print everything as one JSON object\n"
         "\n"
         "Eigenvalues need LAPACK (dynkit built with liblapack-dev); without it the matrix is\n"
         "printed and the eigenvalues are refused (exit status 1).\n"
         "\n"
         "Examples:\n"
         "  dynkit linearize pendulum --init dphi=0           # the bottom: +-i sqrt(g/l)\n"
         "  dynkit linearize pendulum --init phi=pi --init dphi=0   # the top: unstable\n"
         "  dynkit linearize vanderpol --init y1=0 --vary mu=0:3:7 --output vdp-eig.csv\n"
         "  dynkit linearize examples/models/lorenz.ode --init x=0 --init y=0 --init z=0\n"
         "  dynkit linearize examples/models/lorenz.ode --equilibrium --init x=8 --init y=8 "
         "--init z=25 --vary rho=20:30:6");
}

typedef struct lin_opts {
    const char *output, *vary, *scheme_text;
    int matrix, json, equilibrium;
    dyn_jac_scheme scheme;
    int t_given;
    double t;
} lin_opts;

/* One linearization: A, its eigenvalues (when a solver exists), the stability. */
typedef struct lin_point {
    double value; /* of the varied name */
    double *y, *f, *A, *re, *im;
    dyn_linearize_info info;
    int have_eig;
    int have_eq; /* --equilibrium: y was found by dyn_equilibrium */
    dyn_equilibrium_info eq;
    double tol;
    dyn_stability stability;
    /* a mechanism with constraints: the eigenvalues (k of them) are those of A_min = P^+ A P
     * on the admissible directions, the states kept their coordinates (lin_constrained.c) */
    int k;
    int *kept;
    double *Amin;
} lin_point;

/* --jacobian's words, in the order of dyn_jac_scheme */
static const char *const scheme_names[] = {"auto", "analytic", "central", "richardson"};

static int parse_scheme(const char *text, dyn_jac_scheme *s)
{
    for (int k = 0; k < 4; k++)
        if (strcmp(text, scheme_names[k]) == 0) {
            *s = (dyn_jac_scheme)k;
            return CLI_OK;
        }
    return cli_usage_error("linearize",
                           "--jacobian '%s': accepted: auto, analytic, central, richardson", text);
}

static const char *scheme_words(dyn_jac_scheme s)
{
    switch (s) {
    case DYN_JAC_ANALYTIC: return "the model's analytic Jacobian";
    case DYN_JAC_CENTRAL: return "central differences";
    default: return "central differences, Richardson extrapolation";
    }
}

/* Linearize at the point p (its y, par prepared); eigenvalues when solver is not NULL. */
static int linearize_point(const dyn_model *m, double t, void *par, const lin_opts *o,
                           const dyn_eig_solver *solver, const cli_lin_constraints *cc,
                           double *work, double *scratch, lin_point *p)
{
    const int n = m->n_states;
    p->k = n;
    const dyn_linearize_opts lo = {o->scheme, NULL};
    int rc = dyn_linearize(m, t, p->y, par, &lo, p->A, work, &p->info);
    if (rc) {
        cli_error("linearize: %s", p->info.message);
        return rc == DYN_ERR_ARG ? CLI_USAGE : CLI_FAILED;
    }
    rc = m->rhs(t, p->y, p->f, par);
    if (rc) {
        cli_error("the right-hand side of %s failed at the state "
                "(status %d)",
                m->name, rc);
        return CLI_FAILED;
    }
    p->tol = dyn_stability_tol(n, p->A, 0.0);
    if (!solver || o->matrix) /* --matrix: A alone, no eigenvalues to compute */
        return CLI_OK;
    char err[256] = "";
    const double *Ause = p->A;
    if (cc->m > 0) {
        const size_t N = (size_t)n;
        double *P = malloc(N * N * sizeof *P), *rw = malloc((N * N + N * N + N) * sizeof *rw);
        p->kept = malloc(N * sizeof *p->kept);
        p->Amin = malloc(N * N * sizeof *p->Amin);
        rc = !P || !rw || !p->kept || !p->Amin ? -1
             : cli_lin_basis(cc, t, p->y, par, P, p->kept, &p->k, err, sizeof err);
        if (!rc)
            rc = dyn_linear_reduce(n, p->k, p->A, P, p->Amin, rw);
        free(P);
        free(rw);
        if (rc) {
            cli_error("linearize: the admissible directions: %s",
                    err[0] ? err : "their basis is singular");
            return CLI_FAILED;
        }
        Ause = p->Amin;
        p->tol = dyn_stability_tol(p->k, p->Amin, 0.0);
    }
    const int k = p->k;
    memcpy(scratch, Ause, (size_t)k * (size_t)k * sizeof *scratch);
    if (k > 0 && solver->eigenvalues(k, scratch, p->re, p->im, err, sizeof err)) {
        cli_error("eigenvalues: %s", err);
        return CLI_FAILED;
    }
    dyn_eig_sort(k, p->re, p->im);
    p->have_eig = 1;
    p->stability = dyn_classify(k, p->re, p->tol);
    return CLI_OK;
}

/* ---- text ---- */

static void print_text(FILE *f, const dyn_model *m, double t, const char *vname, const lin_point *p)
{
    const int n = m->n_states;
    fprintf(f, "%s at t = %.12g", m->name, t);
    if (vname)
        fprintf(f, ", %s = %.12g", vname, p->value);
    fputs(":\n", f);
    int w = 5;
    for (int i = 0; i < n; i++)
        w = (int)fmax(w, (double)strlen(m->states[i].name) + 1);
    for (int i = 0; i < n; i++)
        fprintf(f, "  %-*s = %-14.12g %-8s f = %.6g\n", w, m->states[i].name, p->y[i] + 0.0,
                m->states[i].unit, p->f[i] + 0.0);
    if (p->have_eq)
        fprintf(f, "equilibrium: %d iterations, |f|_inf = %.3g (tolerance %.3g)\n",
                p->eq.iterations, p->eq.residual, p->eq.tol);
    fprintf(f, "A = df/dy (%s", scheme_words(p->info.scheme));
    if (p->info.scheme == DYN_JAC_RICHARDSON)
        fprintf(f, "; estimated relative error %.1e", p->info.err_est);
    fputs("):\n", f);
    fprintf(f, "  %*s", w + 2, "");
    for (int j = 0; j < n; j++)
        fprintf(f, " %13s", m->states[j].name);
    fputc('\n', f);
    for (int i = 0; i < n; i++) {
        fprintf(f, "  %s'%*s", m->states[i].name, w + 1 - (int)strlen(m->states[i].name), "");
        for (int j = 0; j < n; j++)
            fprintf(f, " %13.6g", p->A[(size_t)i * (size_t)n + (size_t)j] + 0.0); /* no -0 */
        fputc('\n', f);
    }
    if (!p->have_eig)
        return;
    if (p->kept) {
        fprintf(f, "minimal coordinates and speeds (%d of %d, the constraints' directions "
                   "removed):", p->k, n);
        for (int k = 0; k < p->k; k++)
            fprintf(f, " %s", m->states[p->kept[k]].name);
        fputc('\n', f);
    }
    fputs(p->kept ? "eigenvalues of A_min:\n" : "eigenvalues:\n", f);
    fprintf(f, "  %22s %22s %14s %10s\n", "re [1/s]", "im [rad/s]", "wn [rad/s]", "zeta");
    for (int k = 0; k < p->k; k++) {
        fprintf(f, "  %22.15g %22.15g", p->re[k] + 0.0, p->im[k] + 0.0);
        if (p->im[k] != 0.0) {
            double wn, zeta;
            dyn_eig_mode(p->re[k], p->im[k], &wn, &zeta);
            fprintf(f, " %14.8g %10.6g", wn, zeta + 0.0);
        }
        fputc('\n', f);
    }
    double top = -INFINITY;
    for (int k = 0; k < p->k; k++)
        top = fmax(top, p->re[k]);
    fprintf(f, "stability: %s (largest re = %.6g; |re| <= %.3g = 1e-8 ||A%s||_inf counts as 0)\n",
            dyn_stability_name(p->stability), top + 0.0, p->tol, p->kept ? "_min" : "");
}

/* ---- tables ---- */

static void csv_header(FILE *f, const char *vname, const char *rest)
{
    if (vname)
        fprintf(f, "%s,", vname);
    fputs(rest, f);
}

static void print_matrix_csv(FILE *f, const dyn_model *m, const char *vname, const lin_point *p,
                             int header)
{
    const int n = m->n_states;
    if (header) {
        csv_header(f, vname, "state");
        for (int j = 0; j < n; j++)
            fprintf(f, ",%s", m->states[j].name);
        fputc('\n', f);
    }
    for (int i = 0; i < n; i++) {
        if (vname)
            fprintf(f, "%s,", CLI_NUM(p->value));
        fputs(m->states[i].name, f);
        for (int j = 0; j < n; j++)
            fprintf(f, ",%s", CLI_NUM(p->A[(size_t)i * (size_t)n + (size_t)j]));
        fputc('\n', f);
    }
}

static void print_eig_csv(FILE *f, int n, const char *vname, const lin_point *p, int header)
{
    if (header)
        csv_header(f, vname, "re,im\n");
    for (int k = 0; k < n; k++) {
        if (vname)
            fprintf(f, "%s,", CLI_NUM(p->value));
        fprintf(f, "%s,%s\n", CLI_NUM(p->re[k]), CLI_NUM(p->im[k]));
    }
}

static void print_json(FILE *f, const dyn_model *m, double t, const char *vname,
                       const lin_point *pts, long n_pts)
{
    const int n = m->n_states;
    cli_json j;
    cli_json_init(&j, f, 17);
    cli_json_begin_object(&j);
    cli_json_key(&j, "model");
    cli_json_string(&j, m->name);
    cli_json_key(&j, "t");
    cli_json_number(&j, t);
    cli_json_key(&j, "states");
    cli_json_begin_array(&j);
    for (int i = 0; i < n; i++)
        cli_json_string(&j, m->states[i].name);
    cli_json_end_array(&j);
    if (vname) {
        cli_json_key(&j, "vary");
        cli_json_string(&j, vname);
    }
    cli_json_key(&j, "points");
    cli_json_begin_array(&j);
    for (long k = 0; k < n_pts; k++) {
        const lin_point *p = &pts[k];
        cli_json_begin_object(&j);
        if (vname) {
            cli_json_key(&j, vname);
            cli_json_number(&j, p->value);
        }
        cli_json_key(&j, "y");
        cli_json_numbers(&j, p->y, n, 1);
        cli_json_key(&j, "f");
        cli_json_numbers(&j, p->f, n, 1);
        if (p->have_eq) {
            cli_json_key(&j, "equilibrium");
            cli_json_begin_object(&j);
            cli_json_key(&j, "iterations");
            cli_json_number(&j, p->eq.iterations);
            cli_json_key(&j, "residual");
            cli_json_number(&j, p->eq.residual);
            cli_json_key(&j, "tol");
            cli_json_number(&j, p->eq.tol);
            cli_json_end_object(&j);
        }
        cli_json_key(&j, "jacobian");
        cli_json_string(&j, scheme_names[p->info.scheme]);
        cli_json_key(&j, "error_estimate");
        cli_json_number(&j, p->info.err_est);
        cli_json_key(&j, "rhs_calls");
        cli_json_number(&j, (double)p->info.rhs_calls);
        cli_json_key(&j, "A");
        cli_json_begin_array(&j);
        for (int i = 0; i < n; i++)
            cli_json_numbers(&j, p->A + (size_t)i * (size_t)n, n, 1);
        cli_json_end_array(&j);
        if (p->kept) {
            cli_json_key(&j, "kept");
            cli_json_begin_array(&j);
            for (int i = 0; i < p->k; i++)
                cli_json_string(&j, m->states[p->kept[i]].name);
            cli_json_end_array(&j);
            cli_json_key(&j, "A_min");
            cli_json_begin_array(&j);
            for (int i = 0; i < p->k; i++)
                cli_json_numbers(&j, p->Amin + (size_t)i * (size_t)p->k, p->k, 1);
            cli_json_end_array(&j);
        }
        cli_json_key(&j, "re");
        cli_json_numbers(&j, p->re, p->k, 1);
        cli_json_key(&j, "im");
        cli_json_numbers(&j, p->im, p->k, 1);
        cli_json_key(&j, "tol");
        cli_json_number(&j, p->tol);
        cli_json_key(&j, "stability");
        cli_json_string(&j, dyn_stability_name(p->stability));
        cli_json_end_object(&j);
    }
    cli_json_end_array(&j);
    cli_json_end_object(&j);
    fputc('\n', f);
}

/* ---- options ---- */

/* Split argv into the run options passed on (MODEL, --init, --set, --forces, --interp) and
 * linearize's own. */
static int parse_args(int argc, char **argv, char **pass, int *n_pass, lin_opts *o)
{
    static const char *const options[] = {"--init", "--set",      "--forces",     "--interp",
                                          "--t",    "--vary",     "--output",     "--matrix",
                                          "--json", "--jacobian", "--equilibrium",
                                          "--project-init"};
    pass[(*n_pass)++] = argv[0];
    for (int i = 1; i < argc; i++) {
        const char *v = NULL;
        int r = 0;
        const char *passed[] = {"init", "set", "forces", "interp"};
        int done = 0;
        for (int k = 0; k < 4 && !done; k++)
            if ((r = cli_option(argc, argv, &i, passed[k], &v)) != 0) {
                if (r < 0)
                    return cli_usage_error("linearize", "option --%s needs a value", passed[k]);
                pass[(*n_pass)++] = (char *)options[k];
                pass[(*n_pass)++] = (char *)v;
                done = 1;
            }
        if (done)
            continue;
        const char *own[] = {"t", "vary", "output", "jacobian"};
        const char **dest[] = {NULL, &o->vary, &o->output, &o->scheme_text};
        for (int k = 0; k < 4 && !done; k++)
            if ((r = cli_option(argc, argv, &i, own[k], &v)) != 0) {
                if (r < 0)
                    return cli_usage_error("linearize", "option --%s needs a value", own[k]);
                if (k == 0) {
                    if (cli_parse_number(v, &o->t))
                        return cli_usage_error("linearize", "--t '%s': give a finite number", v);
                    o->t_given = 1;
                } else if (k == 1 && o->vary) {
                    return cli_usage_error("linearize", "--vary is given once (one name)");
                } else {
                    *dest[k] = v;
                }
                done = 1;
            }
        if (done)
            continue;
        if (cli_flag(argv[i], "matrix"))
            o->matrix = 1;
        else if (cli_flag(argv[i], "json"))
            o->json = 1;
        else if (cli_flag(argv[i], "equilibrium"))
            o->equilibrium = 1;
        else if (cli_flag(argv[i], "project-init"))
            pass[(*n_pass)++] = (char *)options[11];
        else
            return cli_unknown_option("linearize", argv[i], options, 12);
    }
    if (o->scheme_text && parse_scheme(o->scheme_text, &o->scheme) != CLI_OK)
        return CLI_USAGE;
    if (o->matrix && o->json)
        return cli_usage_error("linearize", "--matrix and --json: give one of them");
    if (o->output && strcmp(o->output, "-") != 0) {
        static const char *const csv[] = {".csv", NULL}, *const both[] = {".csv", ".json", NULL};
        if (cli_out_check_extension("linearize", "--output", o->output, o->matrix ? csv : both) !=
            CLI_OK)
            return CLI_USAGE;
        if (cli_has_extension(o->output, ".json"))
            o->json = 1;
    }
    return CLI_OK;
}

/* The varied name and its values (one value, the start, without --vary). */
static int vary_values(const cli_run *run, const lin_opts *o, dyn_sweep_var *var, double **values,
                       long *count)
{
    const dyn_model *m = run->model;
    if (!o->vary) {
        *values = malloc(sizeof **values);
        if (!*values)
            return CLI_FAILED;
        **values = 0.0;
        *count = 1;
        return CLI_OK;
    }
    const char *eq = strchr(o->vary, '=');
    char name[128], err[1024];
    if (!eq || eq == o->vary || (size_t)(eq - o->vary) >= sizeof name)
        return cli_usage_error("linearize", "--vary '%s': give NAME=A:B:N or NAME=V1,V2,...",
                               o->vary);
    memcpy(name, o->vary, (size_t)(eq - o->vary));
    name[eq - o->vary] = '\0';
    if (dyn_sweep_var_find(m, name, var, err, sizeof err))
        return cli_usage_error("linearize", "--vary %s: %s", name, err);
    if (cli_param_is_size(m, name))
        return cli_usage_error(
            "linearize", "--vary %s: %s is the size of the model and cannot be varied", name, name);
    return cli_parse_values("linearize", o->vary, eq + 1, LIN_MAX_POINTS, values, count);
}

static void free_points(lin_point *pts, long n)
{
    for (long k = 0; k < n && pts; k++) {
        free(pts[k].y);
        free(pts[k].f);
        free(pts[k].A);
        free(pts[k].re);
        free(pts[k].im);
        free(pts[k].kept);
        free(pts[k].Amin);
    }
    free(pts);
}

static int write_all(FILE *f, const dyn_model *m, double t, const char *vname, const lin_opts *o,
                     const lin_point *pts, long n_pts)
{
    const int table = o->output != NULL; /* "-": the table on standard output */
    if (o->json)
        print_json(f, m, t, vname, pts, n_pts);
    else if (o->matrix)
        for (long k = 0; k < n_pts; k++)
            print_matrix_csv(f, m, vname, &pts[k], k == 0);
    else if (table)
        for (long k = 0; k < n_pts; k++)
            print_eig_csv(f, pts[k].k, vname, &pts[k], k == 0);
    else
        for (long k = 0; k < n_pts; k++) {
            if (k > 0)
                fputc('\n', f);
            print_text(f, m, t, vname, &pts[k]);
        }
    return CLI_OK;
}

int cli_cmd_linearize(int argc, char **argv)
{
    for (int i = 0; i < argc; i++)
        if (cli_is_help(argv[i])) {
            linearize_help();
            return CLI_OK;
        }
    if (argc < 1 || argv[0][0] == '-') {
        char names[512];
        return cli_usage_error("linearize", "missing MODEL (accepted: %s, or a model file)",
                               dyn_model_names(names, sizeof names));
    }
    char **pass = calloc((size_t)(2 * argc + 1), sizeof *pass);
    if (!pass)
        return CLI_FAILED;
    int n_pass = 0;
    lin_opts o;
    memset(&o, 0, sizeof o);
    int rc = parse_args(argc, argv, pass, &n_pass, &o);
    cli_run run;
    memset(&run, 0, sizeof run);
    if (rc == CLI_OK)
        rc = cli_run_parse("linearize", n_pass, pass, &run);
    int init_given = 0;
    for (int k = 0; k < n_pass; k++)
        init_given |= strcmp(pass[k], "--init") == 0;
    free(pass);
    if (rc != CLI_OK) {
        cli_run_free(&run);
        return rc;
    }
    const dyn_model *m = run.model;
    const int n = m->n_states;
    const double t = o.t_given ? o.t : run.t0;
    if (dyn_method_is_map(run.method) && !o.matrix)
        rc = cli_usage_error("linearize", "%s is a discrete map: its eigenvalues here would be "
                             "judged as a flow's; its fixed points and their multipliers are "
                             "found by dynkit equilibria (dynkit continue follows them, dynkit "
                             "lyapunov gives its exponents); --matrix prints dF/dy alone",
                             m->name);
    if (rc == CLI_OK && o.equilibrium)
        rc = cli_kinds_refuse_markov("linearize", m, "--equilibrium");
    if (rc == CLI_OK) {
        cli_kinds_noise_note("linearize", m, NULL);
        cli_kinds_markov_note("linearize", m);
    }
    cli_lin_constraints cc;
    memset(&cc, 0, sizeof cc);
    if (rc == CLI_OK)
        rc = cli_lin_constraints_open(argv[0], m, &cc);
    dyn_sweep_var var = {DYN_SWEEP_PARAM, -1};
    double *values = NULL;
    long n_pts = 0;
    if (rc == CLI_OK)
        rc = vary_values(&run, &o, &var, &values, &n_pts);
    const char *vname = rc == CLI_OK && o.vary ? dyn_sweep_var_name(m, &var) : NULL;
    const dyn_eig_solver *solver = cli_eig_solver();
    if (rc == CLI_OK && !solver && (o.json || (o.output && !o.matrix))) {
        cli_error("linearize: eigenvalues need LAPACK, and this dynkit "
                        "was built without it (install liblapack-dev and build again); "
                        "--matrix prints A alone");
        rc = CLI_FAILED;
    }
    const size_t N = (size_t)n;
    lin_point *pts = rc == CLI_OK ? calloc((size_t)n_pts, sizeof *pts) : NULL;
    void *par = rc == CLI_OK ? malloc(m->par_size) : NULL;
    /* the equilibrium's workspace holds the linearization's and A's copy for dgeev */
    double *work =
        rc == CLI_OK ? malloc((dyn_equilibrium_work_size(n) + N * N) * sizeof *work) : NULL;
    if (rc == CLI_OK && (!pts || !par || !work)) {
        cli_error("out of memory");
        rc = CLI_FAILED;
    }
    for (long k = 0; k < n_pts && rc == CLI_OK; k++) {
        lin_point *p = &pts[k];
        p->value = values[k];
        p->y = malloc(N * sizeof *p->y);
        p->f = malloc(N * sizeof *p->f);
        p->A = malloc(N * N * sizeof *p->A);
        p->re = calloc(N, sizeof *p->re);
        p->im = calloc(N, sizeof *p->im);
        if (!p->y || !p->f || !p->A || !p->re || !p->im) {
            cli_error("out of memory");
            rc = CLI_FAILED;
            break;
        }
        memcpy(par, run.par, m->par_size);
        memcpy(p->y, run.y0, N * sizeof *p->y);
        if (o.vary && var.kind == DYN_SWEEP_PARAM) {
            char err[256];
            dyn_model_set_param(m, par, var.index, p->value);
            if (m->prepare && m->prepare(par, err, sizeof err)) {
                rc = cli_usage_error("linearize", "--vary %s=%.17g: %s", vname, p->value, err);
                break;
            }
            if (m->initial_state && !init_given)
                dyn_model_initial_state(m, par, p->y);
        } else if (o.vary) {
            p->y[var.index] = p->value;
        }
        if (o.equilibrium) {
            /* along a parameter, each search starts from the equilibrium before it */
            if (k > 0 && var.kind == DYN_SWEEP_PARAM)
                memcpy(p->y, pts[k - 1].y, N * sizeof *p->y);
            const dyn_equilibrium_opts eo = {{o.scheme, NULL}, 0.0, 0};
            p->have_eq = 1;
            int st = dyn_equilibrium(m, t, p->y, par, &eo, work, &p->eq);
            if (st) {
                cli_stderr("dynkit: error: linearize --equilibrium");
                if (vname)
                    cli_stderr(" at %s = %.17g", vname, p->value);
                cli_stderr(": %s\n", p->eq.message);
                rc = st == DYN_ERR_ARG ? CLI_USAGE : CLI_FAILED;
                break;
            }
        }
        rc = linearize_point(m, t, par, &o, solver, &cc, work,
                             work + dyn_linearize_work_size(n), p);
    }
    if (rc == CLI_OK) {
        cli_out out;
        const char *path = o.output && strcmp(o.output, "-") != 0 ? o.output : NULL;
        rc = cli_out_open(&out, "--output", path);
        if (rc == CLI_OK) {
            write_all(out.f, m, t, vname, &o, pts, n_pts);
            int bad = fflush(out.f) != 0 || ferror(out.f);
            if (out.f != stdout)
                rc = cli_out_close(&out, !bad);
            else if (bad)
                rc = CLI_FAILED;
        }
    }
    if (rc == CLI_OK && !solver && !o.matrix) {
        cli_error("linearize: eigenvalues need LAPACK, and this dynkit "
                        "was built without it (install liblapack-dev and build again)");
        rc = CLI_FAILED;
    }
    free_points(pts, n_pts);
    cli_lin_constraints_close(&cc);
    free(values);
    free(par);
    free(work);
    cli_run_free(&run);
    return rc;
}
