/* SPDX-License-Identifier: BSD-3-Clause */
/* Teaching trace: each stage of the first steps of a Runge–Kutta method, written so a
 * student can redo the step by hand (stage state, stage derivative, combination).
 * Heun's stages are named as in the homework: predictor ytilde_{n+1}, then the corrector. */
#include <string.h>

#include "cli.h"

static void print_vector(const char *label, const double *v, int n)
{
    cli_stderr("%s[", label);
    for (int i = 0; i < n; i++)
        cli_stderr("%s%s", i ? ", " : "", CLI_NUM(v[i]));
    fputs("]\n", stderr);
}

/* "h*(a1*k1 + a2*k2)" from a row of coefficients, skipping zeros. */
static void print_combination(const double *coef, int count)
{
    int first = 1;
    fputs("h*(", stderr);
    for (int j = 0; j < count; j++) {
        if (coef[j] == 0.0)
            continue;
        cli_stderr("%s%s*k%d", first ? "" : " + ", CLI_NUM(coef[j]), j + 1);
        first = 0;
    }
    fputs(")", stderr);
}

void cli_print_trace(const dyn_trace_stage *st, void *ctx)
{
    const cli_run *run = ctx;
    const dyn_tableau *m = st->method;
    const int s = m->stages, i = st->stage;
    const int heun = strcmp(m->name, "heun") == 0;
    char label[160];
    if (i == 0) {
        cli_stderr("trace %s, step %ld: t_n = %s, h = %s\n  states (", m->name, st->step + 1,
                   CLI_NUM(st->t_n), CLI_NUM(st->h));
        for (int q = 0; q < st->n; q++)
            cli_stderr("%s%s", q ? ", " : "", run->model->states[q].name);
        fputs(")\n", stderr);
        print_vector("  y_n = ", st->y_n, st->n);
    }
    if (dyn_method_is_map(m)) { /* stage 0 carries f(t_n, y_n), the next state itself */
        if (i == 0)
            print_vector("  y_{n+1} = f(t_n, y_n) = ", st->k, st->n);
        else
            cli_stderr("  (t_{n+1} = %s)\n", CLI_NUM(st->t_stage));
    } else if (i < s) {
        char stage_name[32];
        snprintf(stage_name, sizeof stage_name, heun ? "ytilde_{n+1}" : "Y%d", i + 1);
        if (i > 0) {
            cli_stderr("  %s%s = y_n + ", heun ? "predictor " : "", stage_name);
            print_combination(m->a + (size_t)i * (size_t)s, i);
            print_vector("\n      = ", st->Y, st->n);
        }
        snprintf(label, sizeof label, "  k%d = f(t_n + %s*h = %s, %s) = ", i + 1, CLI_NUM(m->c[i]),
                 CLI_NUM(st->t_stage), i == 0 ? "y_n" : stage_name);
        print_vector(label, st->k, st->n);
    } else {
        cli_stderr("  %s = y_n + ", heun ? "corrector y_{n+1}" : "y_{n+1}");
        print_combination(m->b, s);
        print_vector("\n      = ", st->Y, st->n);
        cli_stderr("  (t_{n+1} = %s)\n", CLI_NUM(st->t_stage));
    }
}
