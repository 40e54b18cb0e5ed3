/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit verify: every method on problems with known solutions (dynkit/verify.h), as a
 * table of the accuracy reached and the work spent, or as JSON. With SUNDIALS, the CVODE
 * backend is one of the methods. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cli.h"
#include "dynkit/verify.h"
#include "pages/pages.h"

#ifdef DYNKIT_HAVE_CVODE
#include "dynkit/cvode.h"

/* cvode for the table: one output time, t1; the step limit is CVODE's mxstep. */
static int verify_cvode(const dyn_system *sys, dyn_jac_fn jac, double t0, double t1,
                        const double *y0, double rtol, double atol, long max_steps, double *y,
                        dyn_result *res, void *ctx)
{
    (void)ctx;
    dyn_cvode_opts o = {0};
    o.rtol = rtol;
    o.atol = atol;
    o.jacobian = jac;
    o.max_steps = max_steps;
    return dyn_cvode_solve(sys, t0, y0, &t1, 1, &o, NULL, NULL, y, res);
}
#endif

static void verify_help(void)
{
    puts("Usage: dynkit verify [--quick] [--json] [--problem NAME] [--method NAME]\n"
         "\n"
         "Run every method on problems with known solutions and print the accuracy reached\n"
         "and the work spent, per method and tolerance (or step):\n"
         "  vanderpol-mu1     van der Pol mu = 1 to t = 15 (high-precision reference)\n"
         "  arenstorf         Arenstorf's orbit over one period (back at its start)\n"
         "  oscillator        x'' = -x, (x, x') = (1, 0) to t = 20: exact (cos 20, -sin 20)\n"
         "  vanderpol-mu1000  van der Pol mu = 1000 on [0, 3000] (stiff)\n"
         "  robertson         Robertson to t = 1e11, Test Set for IVP Solvers (stiff)\n"
         "  hires             HIRES to t = 321.8122, Test Set for IVP Solvers (stiff)\n"
         "  brusselator       Brusselator with diffusion, N = 20 (40 states) to t = 10 (stiff)\n"
         "Error: max norm of y(t1) - reference, absolute on the first three problems,\n"
         "relative per component on the stiff ones; DIGITS = -log10(error).\n"
         "Adaptive methods run at rtol = 1e-3, 1e-6, 1e-9 with atol = rtol times the\n"
         "problem's scale (1; 1e-3 for vanderpol-mu1000, 1e-6 for robertson, 1e-4 for hires);\n"
         "fixed-step methods at three step sizes, each half the one before, with the observed\n"
         "order. On the stiff problems fixed-step methods are skipped and explicit adaptive\n"
         "ones stop after 100000 steps ('too many steps'; 'stiff' when their stiffness test\n"
         "fired). cvode is included when dynkit is built with SUNDIALS.\n"
         "\n"
         "  --quick          a subset (rtol 1e-3 and 1e-6, two step sizes, 20000 steps at\n"
         "                   most on stiff problems): every problem and method\n"
         "  --json           one JSON object: {\"problems\": [...], \"rows\": [...], ...}\n"
         "  --problem NAME   only this problem\n"
         "  --method NAME    only this method\n"
         "\n"
         "Columns: PROBLEM, METHOD, TOL/STEP (rtol, or the step h), ERROR, DIGITS, ORDER\n"
         "(fixed steps), RHS and JAC (calls of f and of the Jacobian), ACC and REJ (steps\n"
         "accepted and rejected), MS (milliseconds), NOTE.\n"
         "Exit status: 0 when every run did what it should (explicit methods giving up on\n"
         "stiff problems included), 1 when a run failed unexpectedly, 2 for a bad command\n"
         "line.");
}

static double wall_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void print_header(void)
{
    printf("%-16s %-8s %-11s %9s %6s %5s %9s %7s %7s %6s %8s  %s\n", "PROBLEM", "METHOD",
           "TOL/STEP", "ERROR", "DIGITS", "ORDER", "RHS", "JAC", "ACC", "REJ", "MS", "NOTE");
}

static int print_row(const dyn_verify_row *r, void *ctx)
{
    (void)ctx;
    char tol[24], err[16], digits[16], order[16];
    if (r->adaptive)
        snprintf(tol, sizeof tol, "rtol=%.0e", r->rtol);
    else if (r->outcome == DYN_VERIFY_SKIPPED)
        snprintf(tol, sizeof tol, "-");
    else
        snprintf(tol, sizeof tol, "h=%.3g", r->h);
    if (isnan(r->error))
        snprintf(err, sizeof err, "-");
    else
        snprintf(err, sizeof err, "%.2e", r->error);
    if (isnan(r->digits))
        snprintf(digits, sizeof digits, "-");
    else if (isinf(r->digits))
        snprintf(digits, sizeof digits, "exact");
    else
        snprintf(digits, sizeof digits, "%.1f", r->digits);
    if (isnan(r->order))
        snprintf(order, sizeof order, "-");
    else
        snprintf(order, sizeof order, "%.2f", r->order);
    const char *gap = r->note[0] ? "  " : "";
    if (r->outcome == DYN_VERIFY_SKIPPED)
        printf("%-16s %-8s %-11s %9s %6s %5s %9s %7s %7s %6s %8s%s%s\n", r->problem->name,
               r->method, tol, err, digits, order, "-", "-", "-", "-", "-", gap, r->note);
    else
        printf("%-16s %-8s %-11s %9s %6s %5s %9ld %7ld %7ld %6ld %8.2f%s%s\n", r->problem->name,
               r->method, tol, err, digits, order, r->stats.rhs_calls, r->stats.jac_calls,
               r->stats.accepted, r->stats.rejected, 1e3 * r->seconds, gap, r->note);
    fflush(stdout);
    return 0;
}

static void print_intro(const dyn_verify_opts *o, long limit)
{
    printf("dynkit verify%s: every method on problems with known solutions\n",
           o->quick ? " --quick" : "");
    printf("error = max norm of y(t1) - reference: absolute (abs) or relative per component "
           "(rel); digits = -log10(error)\n");
    printf("adaptive: atol = scale * rtol; fixed steps: h halved, order = log2(e(2h)/e(h)); "
           "explicit adaptive methods on stiff problems stop after %ld steps\n\n",
           limit);
    printf("%-16s %-3s %7s  %s\n", "PROBLEM", "ERR", "SCALE", "REFERENCE");
    for (int i = 0; i < dyn_verify_problem_count(); i++) {
        const dyn_verify_problem *p = dyn_verify_problem_at(i);
        if (o->problem && strcmp(o->problem, p->name) != 0)
            continue;
        printf("%-16s %-3s %7.0e  %s\n", p->name, p->relative ? "rel" : "abs", p->atol_scale,
               p->title);
        printf("%-16s %-3s %7s  reference: %s\n", "", "", "", p->reference);
    }
    putchar('\n');
}

static void write_json(FILE *out, const dyn_verify_opts *o, const dyn_verify_row *rows, long n,
                       double seconds, long limit)
{
    cli_json j;
    cli_json_init(&j, out, 17);
    cli_json_begin_object(&j);
    cli_json_key(&j, "quick");
    cli_json_bool(&j, o->quick);
    cli_json_key(&j, "seconds");
    cli_json_number(&j, seconds);
    cli_json_key(&j, "explicit_max_steps");
    cli_json_number(&j, (double)limit);
    cli_json_key(&j, "rtols");
    cli_json_numbers(&j, dyn_verify_rtols, o->quick ? 2 : DYN_VERIFY_N_RTOL, 1);
    cli_json_key(&j, "problems");
    cli_json_begin_array(&j);
    for (int i = 0; i < dyn_verify_problem_count(); i++) {
        const dyn_verify_problem *p = dyn_verify_problem_at(i);
        if (o->problem && strcmp(o->problem, p->name) != 0)
            continue;
        double ref[64]; /* the largest problem: the Brusselator, 40 states */
        cli_json_begin_object(&j);
        cli_json_key(&j, "name");
        cli_json_string(&j, p->name);
        cli_json_key(&j, "title");
        cli_json_string(&j, p->title);
        cli_json_key(&j, "reference");
        cli_json_string(&j, p->reference);
        cli_json_key(&j, "t0");
        cli_json_number(&j, p->t0);
        cli_json_key(&j, "t1");
        cli_json_number(&j, p->t1);
        cli_json_key(&j, "stiff");
        cli_json_bool(&j, p->stiff);
        cli_json_key(&j, "error_norm");
        cli_json_string(&j, p->relative ? "relative" : "absolute");
        cli_json_key(&j, "atol_scale");
        cli_json_number(&j, p->atol_scale);
        cli_json_key(&j, "y_reference");
        if (p->n <= (int)(sizeof ref / sizeof ref[0]) && dyn_verify_reference(p, ref, NULL, 0) == 0)
            cli_json_numbers(&j, ref, p->n, 1);
        else
            cli_json_null(&j);
        cli_json_end_object(&j);
    }
    cli_json_end_array(&j);
    cli_json_key(&j, "rows");
    cli_json_begin_array(&j);
    static const char *const outcomes[] = {"done", "skipped", "limit", "failed"};
    for (long k = 0; k < n; k++) {
        const dyn_verify_row *r = &rows[k];
        cli_json_begin_object(&j);
        cli_json_key(&j, "problem");
        cli_json_string(&j, r->problem->name);
        cli_json_key(&j, "method");
        cli_json_string(&j, r->method);
        cli_json_key(&j, "adaptive");
        cli_json_bool(&j, r->adaptive);
        if (r->adaptive) {
            cli_json_key(&j, "rtol");
            cli_json_number(&j, r->rtol);
            cli_json_key(&j, "atol");
            cli_json_number(&j, r->atol);
        } else {
            cli_json_key(&j, "h");
            cli_json_number(&j, r->outcome == DYN_VERIFY_SKIPPED ? NAN : r->h);
            cli_json_key(&j, "steps");
            cli_json_number(&j, (double)r->steps);
        }
        cli_json_key(&j, "outcome");
        cli_json_string(&j, outcomes[r->outcome]);
        cli_json_key(&j, "status");
        cli_json_string(&j, dyn_status_name(r->status));
        cli_json_key(&j, "ok");
        cli_json_bool(&j, r->ok);
        cli_json_key(&j, "error");
        cli_json_number(&j, r->error);
        cli_json_key(&j, "digits");
        cli_json_number(&j, r->digits);
        cli_json_key(&j, "order");
        cli_json_number(&j, r->order);
        cli_json_key(&j, "rhs_calls");
        cli_json_number(&j, (double)r->stats.rhs_calls);
        cli_json_key(&j, "jac_calls");
        cli_json_number(&j, (double)r->stats.jac_calls);
        cli_json_key(&j, "accepted");
        cli_json_number(&j, (double)r->stats.accepted);
        cli_json_key(&j, "rejected");
        cli_json_number(&j, (double)r->stats.rejected);
        cli_json_key(&j, "seconds");
        cli_json_number(&j, r->seconds);
        cli_json_key(&j, "t_reached");
        cli_json_number(&j, r->t_reached);
        cli_json_key(&j, "stiff_detected");
        cli_json_bool(&j, r->stiff_detected);
        cli_json_key(&j, "note");
        cli_json_string(&j, r->note);
        cli_json_end_object(&j);
    }
    cli_json_end_array(&j);
    cli_json_end_object(&j);
    fputc('\n', out);
}

int cli_cmd_verify(int argc, char **argv)
{
    dyn_verify_opts o = {0};
    int json = 0;
    for (int i = 0; i < argc; i++) {
        const char *v = NULL;
        int r;
        if (cli_is_help(argv[i])) {
            verify_help();
            return CLI_OK;
        } else if (cli_flag(argv[i], "quick")) {
            o.quick = 1;
        } else if (cli_flag(argv[i], "json")) {
            json = 1;
        } else if ((r = cli_option(argc, argv, &i, "problem", &v)) != 0) {
            if (r < 0)
                return cli_usage_error("verify", "option --problem needs a value (a name)");
            o.problem = v;
        } else if ((r = cli_option(argc, argv, &i, "method", &v)) != 0) {
            if (r < 0)
                return cli_usage_error("verify", "option --method needs a value (a name)");
            const dyn_tableau *named = cli_method_find(v); /* any case, MATLAB's names */
            o.method = named ? named->name : v;
        } else {
            static const char *const options[] = {"--quick", "--json", "--problem", "--method"};
            return cli_unknown_option("verify", argv[i], options, 4);
        }
    }
#ifdef DYNKIT_HAVE_CVODE
    static const dyn_verify_method extra[] = {{"cvode", 1, verify_cvode, NULL}};
    o.extra = extra;
    o.n_extra = 1;
#else
    if (o.method && strcmp(o.method, "cvode") == 0)
        return cli_method_error("verify", "--method", o.method);
#endif
    char err[768];
    const long count = dyn_verify_count(&o, err, sizeof err);
    if (count < 0)
        return cli_usage_error("verify", "%s", err);
    dyn_verify_row *rows = calloc(count > 0 ? (size_t)count : 1, sizeof *rows);
    if (!rows) {
        cli_error("out of memory");
        return CLI_FAILED;
    }
    const long limit = o.quick ? 20000L : 100000L;
    if (!json) {
        print_intro(&o, limit);
        print_header();
        o.on_row = print_row;
    }
    long n = 0;
    const double start = wall_seconds();
    int rc = dyn_verify_run(&o, rows, count, &n, err, sizeof err);
    const double seconds = wall_seconds() - start;
    if (rc != DYN_OK) {
        cli_error("verify: %s", err);
        free(rows);
        return CLI_FAILED;
    }
    long bad = 0, done = 0, skipped = 0, limited = 0;
    for (long k = 0; k < n; k++) {
        bad += !rows[k].ok;
        done += rows[k].outcome == DYN_VERIFY_DONE;
        skipped += rows[k].outcome == DYN_VERIFY_SKIPPED;
        limited += rows[k].outcome == DYN_VERIFY_LIMIT;
    }
    if (json) {
        write_json(stdout, &o, rows, n, seconds, limit);
    } else {
        printf("\n%ld runs in %.2f s: %ld reached t1, %ld stopped at their limit (explicit "
               "methods on stiff problems), %ld skipped; %s\n",
               n, seconds, done, limited, skipped,
               bad ? "FAILURES (see the NOTE column)" : "every run as expected");
    }
    for (long k = 0; k < n; k++)
        if (!rows[k].ok)
            cli_stderr("dynkit: verify: %s with %s failed unexpectedly: %s\n",
                       rows[k].problem->name, rows[k].method, rows[k].note);
    int status = fflush(stdout) == 0 ? (bad ? CLI_FAILED : CLI_OK) : CLI_FAILED;
    free(rows);
    return status;
}
