/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit lyapunov MODEL [--spectrum | --exponents K] [--tspan T0:T1] [--transient T]
 * [--tau T] [--rtol R] [--atol A] [--init/--set ...] [--json] [--output FILE.json]: the
 * Lyapunov exponents of any model (a map's too) along the trajectory from its initial
 * state by Benettin's method (dyn_lyapunov, dynkit/lyapunov.h), with the error estimate of
 * the block means. docs/analysis.md, "Lyapunov exponents". */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "commands/analysis_args.h"
#include "commands/analysis_kinds.h"
#include "dynkit/lyapunov.h"
#include "pages/pages.h"
#include "util/out_file.h"

static void lyapunov_help(void)
{
    puts("Usage: dynkit lyapunov MODEL [--spectrum | --exponents K] [--tspan T0:T1]\n"
         "                       [--transient T] [--tau T] [--rtol R] [--atol A]\n"
         "                       [--init NAME=VALUE]... [--set NAME=VALUE]... [--json]\n"
         "                       [--output FILE.json]\n"
         "\n"
         "Computes the largest Lyapunov exponent of MODEL (or the K largest, or all of\n"
         "them) along the trajectory from its initial state, by Benettin's method: the\n"
         "variational equations Q' = J Q with the model's exact Jacobian (differences\n"
         "along Q when it has none) integrated with the trajectory (dop853), Q\n"
         "orthonormalized by Gram-Schmidt every tau and the logarithms of R's diagonal\n"
         "averaged after the transient. For a discrete map Q <- dF/dy Q at each\n"
         "iteration, exponents per iteration. The error estimate is the spread of the\n"
         "means over 10 equal blocks of the averaging time (their standard deviation\n"
         "over sqrt(10)).\n"
         "\n"
         "Options:\n"
         "  --spectrum           every exponent (as many as states)\n"
         "  --exponents K        the K largest (default 1)\n"
         "  --tspan T0:T1        the run (default: the model's span; a map: iterations)\n"
         "  --transient T        the time discarded first (default: a tenth of the span)\n"
         "  --tau T              the interval between orthonormalizations (default: 10\n"
         "                       times the model's step, at most a tenth of the averaging\n"
         "                       time)\n"
         "  --rtol R, --atol A   the integrator's tolerances (default 1e-10, 1e-10)\n"
         "  --init NAME=VALUE    a state of the initial state (repeatable)\n"
         "  --set NAME=VALUE     a parameter's value (repeatable)\n"
         "  --json               print {\"exponents\": [...], \"errors\": [...], ...}, largest\n"
         "                       first\n"
         "  -o, --output FILE    write the JSON to FILE.json\n"
         "\n"
         "Examples:\n"
         "  dynkit lyapunov examples/models/lorenz.ode --spectrum --tspan 0:1000\n"
         "  dynkit lyapunov examples/models/henon.ode --spectrum --tspan 0:100000 --json");
}

typedef struct ly_args {
    const char *exponents_text, *transient_text, *tau_text, *rtol_text, *atol_text, *output;
    int spectrum, json;
} ly_args;

static int positive(const char *option, const char *text, double *out, int zero_ok)
{
    if (!text)
        return CLI_OK;
    if (cli_parse_number(text, out) || !(*out > 0.0 || (zero_ok && *out == 0.0)))
        return cli_usage_error("lyapunov", "%s '%s': give a finite number %s 0", option, text,
                               zero_ok ? ">=" : ">");
    return CLI_OK;
}

static int check_own(ly_args *a, const cli_run *run, dyn_lyapunov_opts *lo)
{
    const dyn_model *m = run->model;
    long k = 1;
    if (a->spectrum && a->exponents_text)
        return cli_usage_error("lyapunov", "--spectrum and --exponents: give one of them");
    if (a->exponents_text && (cli_parse_count(a->exponents_text, 1, &k) || k > m->n_states))
        return cli_usage_error("lyapunov", "--exponents '%s': give a whole number from 1 to %d",
                               a->exponents_text, m->n_states);
    lo->k = a->spectrum ? m->n_states : (int)k;
    const double span = run->t1 - run->t0;
    lo->t_trans = 0.1 * span;
    int rc = positive("--transient", a->transient_text, &lo->t_trans, 1);
    if (rc == CLI_OK && !(lo->t_trans < span))
        rc = cli_usage_error("lyapunov", "--transient %.17g: less than the span %.17g", lo->t_trans,
                             span);
    lo->t_avg = span - lo->t_trans;
    lo->tau = fmin(10.0 * run->step, lo->t_avg / DYN_LYAPUNOV_BLOCKS);
    if (rc == CLI_OK)
        rc = positive("--tau", a->tau_text, &lo->tau, 0);
    if (rc == CLI_OK)
        rc = positive("--rtol", a->rtol_text, &lo->rtol, 0);
    if (rc == CLI_OK)
        rc = positive("--atol", a->atol_text, &lo->atol, 0);
    if (rc == CLI_OK && a->output && strcmp(a->output, "-") != 0) {
        static const char *const exts[] = {".json", NULL};
        rc = cli_out_check_extension("lyapunov", "--output", a->output, exts);
        a->json = 1;
    }
    return rc;
}

typedef struct ly_out {
    const ly_args *a;
    const cli_run *run;
    const dyn_lyapunov_opts *lo;
    const double *ex, *err;
    const dyn_lyapunov_info *info;
} ly_out;

static void print_result(FILE *f, const void *ctx)
{
    const ly_out *o = ctx;
    const ly_args *a = o->a;
    const cli_run *run = o->run;
    const dyn_lyapunov_opts *lo = o->lo;
    const double *ex = o->ex, *err = o->err;
    const dyn_lyapunov_info *info = o->info;
    const dyn_model *m = run->model;
    double sum = 0.0;
    for (int j = 0; j < lo->k; j++)
        sum += ex[j];
    const double t_start = run->t0 + lo->t_trans;
    if (a->json) {
        cli_json j;
        cli_json_init(&j, f, 17);
        cli_json_begin_object(&j);
        cli_json_key(&j, "model");
        cli_json_string(&j, m->name);
        cli_json_key(&j, "map");
        cli_json_bool(&j, lo->map);
        cli_json_key(&j, "exponents");
        cli_json_numbers(&j, ex, lo->k, 1);
        cli_json_key(&j, "errors");
        cli_json_numbers(&j, err, lo->k, 1);
        cli_json_key(&j, "sum");
        cli_json_number(&j, sum);
        cli_json_key(&j, "t_transient");
        cli_json_number(&j, t_start);
        cli_json_key(&j, "t_end");
        cli_json_number(&j, info->t_end);
        cli_json_key(&j, "tau");
        cli_json_number(&j, lo->map ? 1.0 : lo->tau);
        cli_json_key(&j, "orthonormalizations");
        cli_json_number(&j, (double)info->orthonormalizations);
        cli_json_key(&j, "jacobian");
        cli_json_string(&j, info->exact_jacobian ? "exact" : "differences");
        cli_json_end_object(&j);
        fputc('\n', f);
        return;
    }
    fprintf(f,
            "%s: Lyapunov exponents %s from %s = %.12g to %.12g (after a transient from "
            "%.12g); %ld orthonormalizations",
            m->name, lo->map ? "per iteration" : "per unit of time", lo->map ? "step" : "t",
            t_start, info->t_end, run->t0, info->orthonormalizations);
    if (!lo->map)
        fprintf(f, " every %.6g", lo->tau);
    fprintf(f, ", %s Jacobian\n", info->exact_jacobian ? "the exact" : "a difference");
    for (int k = 0; k < lo->k; k++)
        fprintf(f, "  %d: %22.12g   +- %.2g\n", k + 1, ex[k] + 0.0, err[k]);
    if (lo->k > 1)
        fprintf(f, "sum: %.12g\n", sum);
}

/* A note when the largest exponent's error estimate is over 5% of its value (and not a
 * rounding-level zero against the largest |exponent|): the averaging time that would bring
 * it to about 2%, the error falling like 1/sqrt(T), at most 100 times the one used; when
 * the value is within its error of 0, that it is 0 within it. */
static void note_wide_error(const cli_run *run, const dyn_lyapunov_opts *lo, const double *ex,
                            const double *err, const dyn_lyapunov_info *info)
{
    double biggest = 0.0;
    for (int k = 0; k < lo->k; k++)
        biggest = fmax(biggest, fabs(ex[k]));
    if (!(err[0] > 1e-3 * biggest))
        return;
    if (!(fabs(ex[0]) > err[0])) {
        /* no relative error of a value that may be 0 */
        cli_note("lyapunov: the largest exponent is 0 within its error estimate %.2g (as on a "
                 "periodic or quasi-periodic motion); a longer --tspan narrows it", err[0]);
        return;
    }
    const double rel = err[0] / fabs(ex[0]);
    if (!(rel > 0.05))
        return;
    /* the whole span scaled: with the default transient (a tenth of it) the averaging
     * time scales the same */
    const double factor = fmin(100.0, ceil((rel / 0.02) * (rel / 0.02)));
    cli_note("lyapunov: the largest exponent's error estimate is %.2g%% of its value; the "
             "error falls like 1/sqrt(T): averaging %.3g times longer (--tspan %.6g:%.6g) "
             "brings it to about %.2g%%",
             100.0 * rel, factor, run->t0, run->t0 + factor * (info->t_end - run->t0),
             100.0 * rel / sqrt(factor));
}

int cli_cmd_lyapunov(int argc, char **argv)
{
    ly_args a;
    memset(&a, 0, sizeof a);
    const cli_aopt own[] = {{"exponents", &a.exponents_text, NULL, NULL, 0},
                            {"transient", &a.transient_text, NULL, NULL, 0},
                            {"tau", &a.tau_text, NULL, NULL, 0},
                            {"rtol", &a.rtol_text, NULL, NULL, 0},
                            {"atol", &a.atol_text, NULL, NULL, 0},
                            {"output", &a.output, NULL, NULL, 0},
                            {"spectrum", NULL, &a.spectrum, NULL, 0},
                            {"json", NULL, &a.json, NULL, 0}};
    static const char *const run_opts[] = {"--init", "--set", "--tspan"};
    cli_run run;
    int done;
    int rc =
        cli_analysis_parse("lyapunov", argc, argv, lyapunov_help, run_opts, 3, own, 8, &run, &done);
    if (done) {
        cli_run_free(&run);
        return rc;
    }
    dyn_lyapunov_opts lo;
    memset(&lo, 0, sizeof lo);
    if (rc == CLI_OK) {
        lo.map = dyn_method_is_map(run.method);
        rc = check_own(&a, &run, &lo);
    }
    double *ex = NULL, *err = NULL;
    if (rc == CLI_OK) {
        ex = calloc((size_t)lo.k, sizeof *ex);
        err = calloc((size_t)lo.k, sizeof *err);
        rc = ex && err ? CLI_OK : CLI_FAILED;
    }
    if (rc == CLI_OK) {
        if (lo.map)
            lo.tau = run.step;
        dyn_lyapunov_info info;
        cli_kinds_noise_note("lyapunov", run.model, NULL);
        const int st = dyn_lyapunov(run.model, run.par, run.t0, run.y0, &lo, ex, err, &info);
        if (st) {
            cli_error("lyapunov: %s", info.message);
            rc = st == DYN_ERR_ARG ? CLI_USAGE : CLI_FAILED;
        } else {
            const ly_out out = {&a, &run, &lo, ex, err, &info};
            rc = cli_analysis_write(a.output, print_result, &out);
            if (rc == CLI_OK)
                note_wide_error(&run, &lo, ex, err, &info);
        }
    }
    free(ex);
    free(err);
    cli_run_free(&run);
    return rc;
}
