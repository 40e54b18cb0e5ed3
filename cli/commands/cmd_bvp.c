/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit bvp FILE [--set/--init ...] [--tspan A:B] [--free NAME [--section NAME[=V]]]
 * [--ntst N] [--ncol K] [--step H] [--json] [--output FILE]: a model file's boundary-value
 * problem (XPPAUT's bdry lines) on
 * [t0, t0 + total] by orthogonal collocation (dyn_bvp_solve, dynkit/colloc.h): the solution
 * on the model's grid of dt (or --step) as a CSV table or JSON, the conditions' residuals
 * and the error estimate on standard error; XPPAUT's hom_bcs (homoclinic and heteroclinic
 * orbits) on [t0, t0 + 1] by default, as AUTO takes them. docs/analysis.md, "Boundary-value
 * problems". */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "commands/analysis_kinds.h"
#include "commands/bvp_guess.h"
#include "dynkit/colloc.h"
#include "pages/pages.h"
#include "util/out_file.h"

#define BVP_MAX_ROWS 10000000L

static void bvp_help(void)
{
    puts("Usage: dynkit bvp FILE [--set NAME=VALUE]... [--init NAME=VALUE]... [--tspan A:B]\n"
         "                  [--free NAME [--section NAME[=VALUE]]] [--ntst N] [--ncol K]\n"
         "                  [--step H] [--json] [-o FILE.csv|FILE.json]\n"
         "\n"
         "Solves the boundary-value problem of a model file with bdry lines (XPPAUT's\n"
         "'bdry EXPR': EXPR = 0, with NAME the state at t0 and NAME' the state at the end\n"
         "t0 + total) by orthogonal collocation, AUTO's method: N mesh intervals of K Gauss\n"
         "points, the mesh adapted to the solution, Newton's method from the initial-value\n"
         "problem's solution (from the file's initial state, with --init). Writes t and the\n"
         "states on the grid t0 + k*dt (the file's dt, or --step) as CSV on standard output;\n"
         "standard error gets the Newton iterations, each condition's residual and the\n"
         "error estimate (the largest difference at the mesh points from a solve on twice\n"
         "as many intervals).\n"
         "\n"
         "XPPAUT's 'bdry hom_bcs(K)' lines (a homoclinic or heteroclinic orbit on a\n"
         "truncated interval) are the projections of the ends onto the unstable subspace\n"
         "of the left equilibrium and the stable subspace of the right one, held in the\n"
         "states with x'=0 that the other conditions use; such a file has one condition\n"
         "fewer than states, AUTO's integral phase condition against the first guess\n"
         "being the last, and its interval is [t0, t0 + 1] (time scaled by a parameter, as\n"
         "AUTO takes it) unless --tspan gives one.\n"
         "\n"
         "A discrete map, a delay or a Volterra model is refused; noise is taken as 0 and\n"
         "Markov states are held, with a note.\n"
         "\n"
         "Options:\n"
         "  --set NAME=VALUE     a parameter's value (repeatable)\n"
         "  --init NAME=VALUE    a state's value in the first guess (repeatable)\n"
         "  --tspan A:B          the interval [t0, t1] (default: the file's t0 and total;\n"
         "                       with hom_bcs t0 + 1)\n"
         "  --guess FILE         the first guess: a CSV table of t and the states (dynkit\n"
         "                       bvp's output at parameters near these), its first to last t\n"
         "                       onto the interval; Newton's method from it, no homotopy\n"
         "  --free NAME          a parameter solved for too (XPPAUT's periodic option: a\n"
         "                       frequency or period), fixed by the section condition\n"
         "  --section NAME[=V]   with --free: the condition NAME(t0) = V (default V: its\n"
         "                       initial value; default NAME: the state moving fastest at\n"
         "                       the initial state)\n"
         "  --ntst N             mesh intervals (default 40)\n"
         "  --ncol K             Gauss points per interval, 2 to 7 (default 4)\n"
         "  --step H             the output grid's spacing (default: the file's dt)\n"
         "  --json               one JSON object: the conditions with their residuals, the\n"
         "                       error estimate, t and each state's values\n"
         "  -o, --output FILE    .csv or .json; '-': standard output\n"
         "\n"
         "Examples:\n"
         "  dynkit bvp examples/models/cable.ode\n"
         "  dynkit bvp examples/models/cable.ode --set a=0 --set b=1 --json\n"
         "  dynkit bvp examples/models/vdp_bvp.ode --free om\n"
         "  dynkit bvp examples/models/homoclinic.ode --set per=30");
}

typedef struct bvp_opts {
    const char *output;
    const char *free_name, *section; /* --free NAME, --section NAME[=VALUE] */
    int json, ntst, ncol;
    int tspan;         /* --tspan given */
    const char *guess; /* --guess FILE */
} bvp_opts;

#define BVP_N_OPTIONS 10

static int parse_args(int argc, char **argv, char **pass, int *n_pass, bvp_opts *o)
{
    static const char *const options[BVP_N_OPTIONS] = {
        "--init", "--set", "--ntst", "--ncol", "--step", "--json", "--output", "--tspan",
        "--free", "--section"};
    pass[(*n_pass)++] = argv[0];
    for (int i = 1; i < argc; i++) {
        const char *v = NULL;
        int r = 0, done = 0;
        const char *passed[] = {"init", "set", "step", "tspan"};
        const int pass_index[] = {0, 1, 4, 7};
        for (int k = 0; k < 4 && !done; k++)
            if ((r = cli_option(argc, argv, &i, passed[k], &v)) != 0) {
                if (r < 0)
                    return cli_usage_error("bvp", "option --%s needs a value", passed[k]);
                pass[(*n_pass)++] = (char *)options[pass_index[k]];
                pass[(*n_pass)++] = (char *)v;
                o->tspan |= k == 3;
                done = 1;
            }
        if (done)
            continue;
        const char *counts[] = {"ntst", "ncol"};
        for (int k = 0; k < 2 && !done; k++)
            if ((r = cli_option(argc, argv, &i, counts[k], &v)) != 0) {
                long c;
                if (r < 0)
                    return cli_usage_error("bvp", "option --%s needs a value", counts[k]);
                const long lo = k == 0 ? 1 : 2, hi = k == 0 ? 100000 : DYN_COLLOC_MAX_NCOL;
                if (cli_parse_count(v, lo, &c) || c > hi)
                    return cli_usage_error("bvp", "--%s '%s': give a whole number from %ld to "
                                           "%ld", counts[k], v, lo, hi);
                *(k == 0 ? &o->ntst : &o->ncol) = (int)c;
                done = 1;
            }
        if (done)
            continue;
        if ((r = cli_option(argc, argv, &i, "guess", &v)) != 0) {
            if (r < 0)
                return cli_usage_error("bvp", "option --guess needs a CSV file (t and the "
                                       "states, dynkit bvp's output)");
            o->guess = v;
        } else if ((r = cli_option(argc, argv, &i, "free", &v)) != 0) {
            if (r < 0)
                return cli_usage_error("bvp", "option --free needs a parameter's name");
            o->free_name = v;
        } else if ((r = cli_option(argc, argv, &i, "section", &v)) != 0) {
            if (r < 0)
                return cli_usage_error("bvp", "option --section needs NAME or NAME=VALUE");
            o->section = v;
        } else if ((r = cli_option(argc, argv, &i, "output", &v)) != 0) {
            if (r < 0)
                return cli_usage_error("bvp", "option --output needs a value");
            o->output = v;
        } else if (strcmp(argv[i], "-o") == 0 && i + 1 < argc) {
            o->output = argv[++i];
        } else if (cli_flag(argv[i], "json")) {
            o->json = 1;
        } else {
            return cli_unknown_option("bvp", argv[i], options, BVP_N_OPTIONS);
        }
    }
    if (o->section && !o->free_name)
        return cli_usage_error("bvp", "--section goes with --free NAME (the free parameter's "
                               "one more condition)");
    if (o->output && strcmp(o->output, "-") != 0) {
        static const char *const both[] = {".csv", ".json", NULL};
        if (cli_out_check_extension("bvp", "--output", o->output, both) != CLI_OK)
            return CLI_USAGE;
        const size_t len = strlen(o->output);
        if (len >= 5 && strcmp(o->output + len - 5, ".json") == 0)
            o->json = 1;
    }
    return CLI_OK;
}

static void json_string(FILE *f, const char *s)
{
    fputc('"', f);
    for (; *s; s++) {
        const unsigned char ch = (unsigned char)*s;
        if (ch == '"' || ch == '\\')
            fprintf(f, "\\%c", ch);
        else if (ch < 0x20)
            fprintf(f, "\\u%04x", ch);
        else
            fputc(ch, f);
    }
    fputc('"', f);
}

static void write_result(FILE *f, const dyn_model *m, const dyn_bvp_result *r, double step,
                         long rows, const bvp_opts *o, int ifree)
{
    const int n = m->n_states;
    double *u = malloc((size_t)n * sizeof *u);
    if (!u)
        return;
    const double len = r->t1 - r->t0;
    if (o->json) {
        fputs("{\"model\": ", f);
        json_string(f, m->name);
        fprintf(f, ", \"t0\": %s, \"t1\": %s, \"ntst\": %d, \"ncol\": %d, \"iterations\": %d, "
                   "\"error_estimate\": %s, \"conditions\": [",
                CLI_NUM(r->t0), CLI_NUM(r->t1), r->sol.ntst, r->sol.ncol, r->iterations,
                isfinite(r->err_est) ? CLI_NUM(r->err_est) : "null");
        for (int k = 0; k < m->n_bdry; k++) {
            fputs(k ? ", {\"condition\": " : "{\"condition\": ", f);
            json_string(f, m->bdry_text[k]);
            fprintf(f, ", \"residual\": %s}", CLI_NUM(r->residuals[k]));
        }
        fputc(']', f);
        if (ifree >= 0 && r->section >= 0) {
            fputs(", \"free\": {", f);
            json_string(f, m->params[ifree].name);
            fprintf(f, ": %s}, \"section\": {\"state\": ", CLI_NUM(r->sol.par[0]));
            json_string(f, m->states[r->section].name);
            fprintf(f, ", \"value\": %s}", CLI_NUM(r->section_value));
        }
        if (m->hom)
            fprintf(f, ", \"projections\": {\"left\": {\"state\": \"%s\", \"conditions\": %d}, "
                       "\"right\": {\"state\": \"%s\", \"conditions\": %d}}",
                    m->states[m->hom->left].name, r->hom_left, m->states[m->hom->right].name,
                    r->hom_right);
        fputs(", \"t\": [", f);
        for (long k = 0; k < rows; k++)
            fprintf(f, "%s%s", k ? ", " : "", CLI_NUM(k == rows - 1 ? r->t1 : r->t0 + k * step));
        fputs("], \"states\": {", f);
        for (int i = 0; i < n; i++) {
            fputs(i ? ", " : "", f);
            json_string(f, m->states[i].name);
            fputs(": [", f);
            for (long k = 0; k < rows; k++) {
                const double t = k == rows - 1 ? r->t1 : r->t0 + k * step;
                dyn_colloc_eval(&r->sol, fmin(1.0, (t - r->t0) / len), u);
                fprintf(f, "%s%s", k ? ", " : "", CLI_NUM(u[i]));
            }
            fputc(']', f);
        }
        fputs("}}\n", f);
    } else {
        fputs("t", f);
        for (int i = 0; i < n; i++)
            fprintf(f, ",%s", m->states[i].name);
        fputc('\n', f);
        for (long k = 0; k < rows; k++) {
            const double t = k == rows - 1 ? r->t1 : r->t0 + k * step;
            dyn_colloc_eval(&r->sol, fmin(1.0, (t - r->t0) / len), u);
            fputs(CLI_NUM(t), f);
            for (int i = 0; i < n; i++)
                fprintf(f, ",%s", CLI_NUM(u[i]));
            fputc('\n', f);
        }
    }
    free(u);
}

/* --free NAME and --section NAME[=VALUE] into bo: the parameter's and state's indices */
static int resolve_free(const char *file, const dyn_model *m, const cli_run *run,
                        const bvp_opts *o, dyn_bvp_opts *bo)
{
    const int ip = dyn_model_param_index(m, o->free_name);
    if (ip < 0)
        return cli_usage_error("bvp", "--free '%s': %s has no parameter of that name (%d "
                               "parameters%s%s)", o->free_name, file, m->n_params,
                               m->n_params ? ", the first " : "",
                               m->n_params ? m->params[0].name : "");
    bo->free_par = ip + 1;
    if (!o->section)
        return CLI_OK;
    const char *eq = strchr(o->section, '=');
    const size_t len = eq ? (size_t)(eq - o->section) : strlen(o->section);
    int is = -1;
    for (int i = 0; i < m->n_states; i++)
        if (strlen(m->states[i].name) == len && strncmp(m->states[i].name, o->section, len) == 0)
            is = i;
    if (is < 0)
        return cli_usage_error("bvp", "--section '%s': give NAME or NAME=VALUE with NAME one "
                               "of the states of %s", o->section, file);
    bo->section = is + 1;
    bo->section_value = run->y0[is];
    if (eq) {
        char why[160];
        cli_formula_params(m, run->par);
        if (cli_parse_value(eq + 1, &bo->section_value, why, sizeof why))
            return cli_usage_error("bvp", "--section '%s': the value: %s", o->section, why);
    }
    return CLI_OK;
}

int cli_cmd_bvp(int argc, char **argv)
{
    for (int i = 0; i < argc; i++)
        if (cli_is_help(argv[i])) {
            bvp_help();
            return CLI_OK;
        }
    if (argc < 1 || argv[0][0] == '-')
        return cli_usage_error("bvp", "missing FILE (a model file with bdry lines)");
    char **pass = calloc((size_t)(2 * argc + 1), sizeof *pass);
    if (!pass)
        return CLI_FAILED;
    int n_pass = 0;
    bvp_opts o;
    memset(&o, 0, sizeof o);
    int rc = parse_args(argc, argv, pass, &n_pass, &o);
    cli_run run;
    memset(&run, 0, sizeof run);
    if (rc == CLI_OK)
        rc = cli_run_parse("bvp", n_pass, pass, &run);
    free(pass);
    if (rc != CLI_OK) {
        cli_run_free(&run);
        return rc;
    }
    const dyn_model *m = run.model;
    if (m->n_bdry == 0) {
        rc = cli_usage_error("bvp", "%s has no boundary conditions (bdry lines); 'dynkit run' "
                             "integrates its initial-value problem", argv[0]);
        cli_run_free(&run);
        return rc;
    }
    /* collocation reads f at its nodes: a map's next state is not a derivative, a delayed
     * or integrated state needs the past of a run */
    if (dyn_method_is_map(run.method))
        rc = cli_usage_error("bvp", "%s is a discrete map: bvp solves differential equations "
                             "by collocation, not maps' boundary conditions; not supported "
                             "('dynkit run' iterates it)", m->name);
    if (rc == CLI_OK)
        rc = cli_kinds_refuse_history("bvp", m, "collocation",
                                      "'dynkit run' integrates its initial-value problem");
    if (rc != CLI_OK) {
        cli_run_free(&run);
        return rc;
    }
    cli_kinds_noise_note("bvp", m, NULL);
    cli_kinds_markov_note("bvp", m);
    dyn_bvp_opts bo = {o.ntst, o.ncol, 0.0, 0, 0, 0.0, NULL, NULL, 0};
    if (o.free_name && resolve_free(argv[0], m, &run, &o, &bo) != CLI_OK) {
        cli_run_free(&run);
        return CLI_USAGE;
    }
    if (m->hom && !o.tspan) /* AUTO's interval; the file's total is for integrating it */
        run.t1 = run.t0 + 1.0;
    double *guess_t = NULL, *guess_u = NULL;
    if (o.guess) {
        char err[512];
        if (bvp_guess_read(o.guess, m, &guess_t, &guess_u, &bo.guess_rows, err, sizeof err)) {
            rc = cli_usage_error("bvp", "--guess %s", err);
            cli_run_free(&run);
            return rc;
        }
        bo.guess_t = guess_t;
        bo.guess_u = guess_u;
    }
    dyn_bvp_result r;
    const int st = dyn_bvp_solve(m, run.par, run.y0, run.t0, run.t1, &bo, &r);
    free(guess_t);
    free(guess_u);
    if (st) {
        cli_error("bvp: %s: %s", argv[0], r.message);
        if (!o.free_name && !m->hom && !o.guess &&
            (st == DYN_COLLOC_ERR_NEWTON || st == DYN_COLLOC_ERR_SINGULAR))
            cli_note("bvp: a periodic solution at an unknown frequency or period needs that "
                     "parameter freed: --free NAME (docs/analysis.md)");
        dyn_bvp_result_free(&r);
        cli_run_free(&run);
        return st == DYN_COLLOC_ERR_ARG ? CLI_USAGE : CLI_FAILED;
    }
    double step = run.step > 0 ? run.step : (run.t1 - run.t0) / 100;
    long rows = (long)floor((run.t1 - run.t0) / step + 1e-9) + 1;
    if ((double)(rows - 1) * step < (run.t1 - run.t0) * (1 - 1e-12))
        rows++; /* the end itself */
    if (rows > BVP_MAX_ROWS) {
        rc = cli_usage_error("bvp", "--step %g gives %ld rows (at most %ld)", step, rows,
                             BVP_MAX_ROWS);
    } else {
        cli_stderr("dynkit: bvp: %s on [%s, %s]: %d Newton iterations on %d intervals of "
                   "%d Gauss points; error estimate %.3g\n",
                   m->name, CLI_NUM(r.t0), CLI_NUM(r.t1), r.iterations, r.sol.ntst, r.sol.ncol,
                   r.err_est);
        for (int k = 0; k < m->n_bdry; k++)
            cli_stderr("dynkit: bvp: condition (line %s) = %.3g\n", m->bdry_text[k],
                       r.residuals[k]);
        if (m->hom)
            cli_stderr("dynkit: bvp: hom_bcs on [%s, %s]%s: %d projection condition%s at the "
                       "left end (equilibrium in %s..), %d at the right (in %s..), and the "
                       "integral phase condition against the first guess\n",
                       CLI_NUM(r.t0), CLI_NUM(r.t1), o.tspan ? "" : " (AUTO's interval)",
                       r.hom_left, r.hom_left == 1 ? "" : "s", m->states[m->hom->left].name,
                       r.hom_right, m->states[m->hom->right].name);
        if (r.section >= 0)
            cli_stderr("dynkit: bvp: free parameter %s = %s with the section %s(%s) = %s\n",
                       m->params[bo.free_par - 1].name, CLI_NUM(r.sol.par[0]),
                       m->states[r.section].name, CLI_NUM(r.t0), CLI_NUM(r.section_value));
        cli_out out;
        const char *path = o.output && strcmp(o.output, "-") != 0 ? o.output : NULL;
        rc = cli_out_open(&out, "--output", path);
        if (rc == CLI_OK) {
            write_result(out.f, m, &r, step, rows, &o, bo.free_par - 1);
            const int bad = fflush(out.f) != 0 || ferror(out.f);
            if (out.f != stdout)
                rc = cli_out_close(&out, !bad);
            else if (bad)
                rc = CLI_FAILED;
        }
    }
    dyn_bvp_result_free(&r);
    cli_run_free(&run);
    return rc;
}
