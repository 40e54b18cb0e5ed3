/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit info MODEL: equations, states, parameters, outputs, events, units and defaults.
 * Numbers are printed in their shortest form that reads back exactly (9.81, 321.8122), and
 * each table's columns are as wide as their longest entry; text of the model with its
 * control bytes escaped (escape.h). */
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "dynkit/io.h"
#include "dynkit/volterra.h"
#include "util/escape.h"

static void info_help(void)
{
    puts("Usage: dynkit info MODEL [--table NAME=FILE]...\n\n"
         "Describe MODEL: its equations, states (with default initial values), parameters\n"
         "(with default values), extra outputs, events (for run --event\n"
         "NAME[:stop|:continue]), units, and the default run with its tolerances. Numbers are\n"
         "shown in their shortest form that reads back to the same double.\n\n"
         "Options:\n"
         "  --table NAME=FILE    a model file's 'table NAME FILE' read from FILE instead\n"
         "                       (repeatable; as for run)");
}

/* The shortest decimal of v that reads back to v (dyn_format_double's digits), in the plain
 * or the scientific layout, whichever has fewer characters (9.81, 10, 0.01, 3e7, 1e-10),
 * into buf; returns buf. */
static char *shortest(double v, char *buf, size_t size)
{
    char s[DYN_DOUBLE_CHARS], sci[DYN_DOUBLE_CHARS + 8], digits[DYN_DOUBLE_CHARS];
    dyn_format_double(v, s);
    if (!isfinite(v) || v == 0.0 || strchr(s, 'e')) {
        snprintf(buf, size, "%s", s);
        return buf;
    }
    /* the plain form's significant digits and the decimal exponent of the first */
    const char *p = s + (s[0] == '-');
    const char *point = strchr(p, '.');
    int n = 0, x10 = (int)(point ? point - p : (ptrdiff_t)strlen(p)) - 1, leading = 1;
    for (const char *c = p; *c; c++) {
        if (*c == '.')
            continue;
        if (leading && *c == '0') {
            x10--; /* 0.00ddd: the first digit is further right */
            continue;
        }
        leading = 0;
        digits[n++] = *c;
    }
    while (n > 1 && digits[n - 1] == '0')
        n--;
    snprintf(sci, sizeof sci, "%s%c%s%.*se%d", s[0] == '-' ? "-" : "", digits[0],
             n > 1 ? "." : "", n - 1, digits + 1, x10);
    const char *best = strlen(sci) < strlen(s) ? sci : s;
    size_t len = strlen(best);
    if (len >= size)
        len = size - 1;
    memcpy(buf, best, len);
    buf[len] = '\0';
    return buf;
}

/* Width of the widest of n strings (at least min). */
static int widest(int n, const char *(*get)(const void *, int), const void *ctx, int min)
{
    int w = min;
    for (int i = 0; i < n; i++) {
        const char *s = get(ctx, i);
        int len = s ? (int)strlen(s) : 0;
        if (len > w)
            w = len;
    }
    return w;
}

/* Text of the model as shown on a terminal, control bytes escaped (escape.h), from a ring
 * of buffers: one line shows several. */
static const char *term(const char *s)
{
    static char ring[8][1024];
    static unsigned next;
    char *buf = ring[next++ % 8];
    return cli_terminal_text(s, 0, buf, sizeof ring[0]);
}

/* A unit as shown: "-" when the model gives none (a model file without a #: unit). */
static const char *shown_unit(const char *unit) { return unit && *unit ? term(unit) : "-"; }
/* A description as shown: "" when there is none. */
static const char *shown_text(const char *text) { return text ? term(text) : ""; }

static const char *state_name(const void *m, int i)
{
    return term(((const dyn_model *)m)->states[i].name);
}
static const char *state_unit(const void *m, int i)
{
    return shown_unit(((const dyn_model *)m)->states[i].unit);
}
static const char *param_name(const void *m, int i)
{
    return term(((const dyn_model *)m)->params[i].name);
}
static const char *param_unit(const void *m, int i)
{
    return shown_unit(((const dyn_model *)m)->params[i].unit);
}
static const char *output_name(const void *m, int i)
{
    return term(((const dyn_model *)m)->outputs[i].name);
}
static const char *output_unit(const void *m, int i)
{
    return shown_unit(((const dyn_model *)m)->outputs[i].unit);
}
static const char *event_name(const void *m, int i)
{
    return term(((const dyn_model *)m)->events[i].name);
}

/* One table of named values: NAME UNIT default VALUE DESCRIPTION, aligned. */
static void print_values(const char *title, const dyn_model *m, int n,
                         const char *(*name)(const void *, int),
                         const char *(*unit)(const void *, int), const double *values,
                         const char *const *descriptions)
{
    char num[32];
    int wv = 1;
    for (int i = 0; i < n; i++) {
        int len = (int)strlen(shortest(values[i], num, sizeof num));
        if (len > wv)
            wv = len;
    }
    const int wn = widest(n, name, m, 4), wu = widest(n, unit, m, 4);
    printf("\n%s\n", title);
    for (int i = 0; i < n; i++) {
        const char *desc = shown_text(descriptions[i]);
        printf("  %-*s  %-*s  default %-*s%s%s\n", wn, name(m, i), wu, unit(m, i), *desc ? wv : 0,
               shortest(values[i], num, sizeof num), *desc ? "  " : "", desc);
    }
}

static void print_states(const dyn_model *m, const double *y0)
{
    const char **desc = malloc((size_t)m->n_states * sizeof *desc);
    if (!desc)
        return;
    for (int i = 0; i < m->n_states; i++)
        desc[i] = m->states[i].description;
    print_values("States (--init NAME=VALUE):", m, m->n_states, state_name, state_unit, y0, desc);
    free(desc);
}

static void print_params(const dyn_model *m)
{
    double *v = malloc((size_t)(m->n_params > 0 ? m->n_params : 1) * sizeof *v);
    const char **desc = malloc((size_t)(m->n_params > 0 ? m->n_params : 1) * sizeof *desc);
    if (v && desc) {
        for (int i = 0; i < m->n_params; i++) {
            v[i] = m->params[i].value;
            desc[i] = m->params[i].description;
        }
        print_values("Parameters (--set NAME=VALUE):", m, m->n_params, param_name, param_unit, v,
                     desc);
    }
    free(v);
    free(desc);
}

static void print_outputs(const dyn_model *m)
{
    if (m->n_outputs <= 0)
        return;
    const int wn = widest(m->n_outputs, output_name, m, 4);
    const int wu = widest(m->n_outputs, output_unit, m, 4);
    printf("\nExtra outputs (run --outputs):\n");
    for (int i = 0; i < m->n_outputs; i++) {
        const char *desc = shown_text(m->outputs[i].description);
        printf("  %-*s  %-*s%s%s\n", wn, output_name(m, i), *desc ? wu : 0, output_unit(m, i),
               *desc ? "  " : "", desc);
    }
}

static void print_events(const dyn_model *m)
{
    if (m->n_events <= 0 || !m->events)
        return;
    const int wn = widest(m->n_events, event_name, m, 4);
    printf("\nEvents (run --event NAME[:stop|:continue]):\n");
    printf("  %-*s  %-9s  %-8s  %s\n", wn, "NAME", "DIRECTION", "TERMINAL", "DESCRIPTION");
    for (int i = 0; i < m->n_events; i++) {
        const dyn_event *e = &m->events[i];
        const char *dir = e->direction == DYN_EVENT_JUMPS ? "by resets only"
                          : e->direction > 0                ? "rising"
                          : e->direction < 0                ? "falling"
                                                            : "both";
        printf("  %-*s  %-9s  %-8s  %s%s\n", wn, event_name(m, i), dir, e->terminal ? "yes" : "no",
               shown_text(e->description), e->reset ? " (resets the state)" : "");
    }
}

/* A delay model: its constant lags with the default parameters (each value once), the
 * maximal delay. */
static void print_delays(const dyn_model *m, const void *par)
{
    const dyn_delay_model *dm = m->delay;
    if (!dm)
        return;
    char a[32];
    printf("\nDelays: delay(x, tau) reads the past; ");
    double *lags = dm->n_lags > 0 && dm->lags ? malloc((size_t)dm->n_lags * sizeof *lags) : NULL;
    if (lags) {
        dm->lags(par, lags);
        printf("constant lags:");
        for (int k = 0, shown = 0; k < dm->n_lags; k++) {
            int seen = 0;
            for (int j = 0; j < k; j++)
                seen |= lags[j] == lags[k];
            if (!seen)
                printf("%s %s", shown++ ? "," : "", shortest(lags[k], a, sizeof a));
        }
        printf(" (the steps land on t0 + k*lag)");
        free(lags);
    } else {
        printf("lags of the states or t only (not tracked)");
    }
    printf(";\n  ");
    if (dm->max_delay > 0.0)
        printf("maximal delay %s (@ delay=), a longer lag stops the run; ",
               shortest(dm->max_delay, a, sizeof a));
    printf("every method but cvode\n  (docs/model-files.md, \"Delay equations\")\n");
}

/* A model with Volterra integrals: how many, its integral equations, the points kept. */
static void print_volterra(const dyn_model *m)
{
    const dyn_volterra_model *vm = m->volterra;
    if (!vm)
        return;
    printf("\nVolterra integrals: %d (int{...}); integral equations:", vm->n_int);
    int k = 0;
    for (int i = 0; i < m->n_states; i++)
        if (vm->is_int[i])
            printf("%s %s", k++ ? "," : "", m->states[i].name);
    printf("%s;\n  --method volterra only, on the grid of --step; the integrals keep the last "
           "%ld grid points%s\n  (docs/model-files.md, \"Volterra integrals\")\n",
           k ? "" : " none", vm->max_points > 0 ? vm->max_points : DYN_VOLTERRA_MAX_POINTS_DEFAULT,
           vm->max_points > 0 ? " (@ vmaxpts)" : "");
}

static void print_default_run(const dyn_model *m)
{
    char a[32], b[32], c[32], from[3][96];
    const char *method = cli_model_method(m);
    printf("\nDefault run: --method %s --step %s --tspan %s:%s (times in %s)\n", method,
           shortest(m->step, a, sizeof a), shortest(m->t0, b, sizeof b),
           shortest(m->t1, c, sizeof c), cli_time_unit(m));
    printf("Method: %s (%s)\n", method,
           cli_model_default_source(m, CLI_DEFAULT_METHOD, from[0], sizeof from[0]));
    if (m->n_noise > 0) {
        int w = 0;
        for (int j = 0; j < m->n_noise; j++)
            w += m->noise_kinds[j] == DYN_NOISE_WIENER;
        printf("Noise: %d Wiener process%s, %d other random number%s per step (normal(), "
               "ran(), %s); %s (docs/solvers.md, \"Noise\")\n",
               w, w == 1 ? "" : "es", m->n_noise - w, m->n_noise - w == 1 ? "" : "s",
               m->jump ? "the Markov states' jumps at each step's start, gill" : "gill",
               m->noise_class == DYN_NOISE_ADDITIVE      ? "additive: euler, rkmil or sriw1"
               : m->noise_class == DYN_NOISE_COMMUTATIVE ? "scalar or diagonal: euler, rkmil or sriw1"
                                                         : "euler (Euler-Maruyama) only");
    }
    if (!dyn_method_is_map(cli_method_find(method)))
        printf("Tolerances of adaptive methods: --rtol %s (%s) --atol %s (%s)\n",
               shortest(cli_model_rtol(m), a, sizeof a),
               cli_model_default_source(m, CLI_DEFAULT_RTOL, from[1], sizeof from[1]),
               shortest(cli_model_atol(m), b, sizeof b),
               cli_model_default_source(m, CLI_DEFAULT_ATOL, from[2], sizeof from[2]));
    if (m->jac_banded)
        printf("Jacobian: banded, %d below and %d above the diagonal (%s); rodas4 and cvode "
               "use band matrices\n",
               m->jac_lower, m->jac_upper,
               m->jacobian_band ? "analytic" : "by banded differences");
    else if (m->jac_pattern.nnz > 0 && m->jacobian_sparse)
        printf("Jacobian: sparse, %d of %d entries (the exact Jacobian's pattern); rodas4 and "
               "cvode use sparse matrices when dynkit is built with KLU\n",
               m->jac_pattern.nnz, m->n_states * m->n_states);
    else if (m->jac_pattern.nnz > 0)
        printf("Jacobian: sparse, %d of %d entries (the pattern the model declares; the values "
               "by differences in groups of columns); rodas4 uses sparse matrices when dynkit "
               "is built with KLU\n",
               m->jac_pattern.nnz, m->n_states * m->n_states);
    if (m->samples == DYN_SAMPLES_STEPS)
        printf("Adaptive methods without --step or --times write a sample at every accepted "
               "step;\n"
               "--step H is the step of fixed-step methods.\n");
}

int cli_cmd_info(int argc, char **argv)
{
    char names[512], err[256];
    if (argc >= 1 && cli_is_help(argv[0])) {
        info_help();
        return CLI_OK;
    }
    if (argc < 1)
        return cli_usage_error("info", "missing MODEL (accepted: %s)",
                               dyn_model_names(names, sizeof names));
    for (int i = 1; i < argc; i++) {
        const char *v;
        if (cli_option(argc, argv, &i, "table", &v) == 0)
            return cli_usage_error("info", "unexpected argument '%s' (accepted: --table NAME=FILE)",
                                   argv[i]);
    }
    const dyn_model *m;
    int open_rc = cli_model_table_options("info", argc, argv);
    if (open_rc == CLI_OK) {
        /* a description, not a run: a mechanism whose file's initial state does not hold
         * its constraints is described too (run says so and offers --project-init) */
        cli_model_set_unchecked(1);
        open_rc = cli_model_open("info", argv[0], &m);
        cli_model_set_unchecked(0);
    }
    if (open_rc != CLI_OK)
        return open_rc;
    /* the default initial state of the default parameters (it may depend on them) */
    void *par = calloc(1, m->par_size > 0 ? m->par_size : 1);
    double *y0 = calloc((size_t)m->n_states, sizeof *y0);
    if (!par || !y0) {
        free(par);
        free(y0);
        cli_error("out of memory");
        return CLI_FAILED;
    }
    if (dyn_model_default_params(m, par, err, sizeof err) == 0)
        dyn_model_initial_state(m, par, y0);
    else
        memcpy(y0, m->y0, (size_t)m->n_states * sizeof *y0);
    printf("%s: %s\n", term(m->name), shown_text(m->title));
    if (m->description && *m->description) {
        /* its lines kept, every other control byte escaped */
        const size_t size = 4 * strlen(m->description) + 8;
        char *shown = malloc(size);
        if (shown)
            printf("\n%s\n", cli_terminal_text(m->description, 1, shown, size));
        free(shown);
    }
    print_states(m, y0);
    print_params(m);
    print_outputs(m);
    print_events(m);
    print_delays(m, par);
    print_volterra(m);
    print_default_run(m);
    free(par);
    free(y0);
    return CLI_OK;
}
