/* SPDX-License-Identifier: BSD-3-Clause */
/* The command-line conventions of docs/cli.md:
 * - `dynkit help [COMMAND]` is the overview or COMMAND --help; a misspelt command gets the
 *   nearest one;
 * - -o and -m are --output and --method;
 * - method names ignore case; MATLAB's names: ode45 = dp45, ode23 = bs23, ode15s and ode23s
 *   select rodas4 (the same numbers), ode113 is refused with a pointer to dop853;
 * - "did you mean" for misspelt methods, options (run, verify, inverse), parameters and
 *   states; a state given to --set is named as one;
 * - angles in degrees (45deg is pi/4 exactly as the parser computes it);
 * - --output - is standard output (run, inverse, animate, plot);
 * - run --help names each option once and gives the tolerances a model that names none runs
 *   at (DYN_MODEL_RTOL, DYN_MODEL_ATOL of model.h), as info does. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "dynkit/io.h"
#include "dynkit/model.h"
#include "test_cli_run.h"
#include "test_util.h"

static void test_help_command(void **state)
{
    (void)state;
    static const char *const commands[] = {"run",     "models",  "methods", "info",  "inverse",
                                           "report",  "animate", "plot",    "verify"};
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++) {
        cli_result a = cli("help %s", commands[i]), b = cli("%s --help", commands[i]);
        CHECK(a.status == 0 && b.status == 0 && strcmp(a.out, b.out) == 0 && a.out_len > 40,
              "dynkit help %s differs from %s --help", commands[i], commands[i]);
        cli_free(&a);
        cli_free(&b);
    }
    cli_result a = cli("help"), b = cli("--help");
    CHECK(a.status == 0 && strcmp(a.out, b.out) == 0 && strstr(a.out, "help [COMMAND]"),
          "dynkit help: %s", a.out);
    cli_free(&a);
    /* the help of help is the overview */
    a = cli("help help");
    CHECK(a.status == 0 && strcmp(a.out, b.out) == 0, "dynkit help help (exit %d): %s%s",
          a.status, a.out, a.err);
    cli_free(&a);
    cli_free(&b);
    a = cli("hlep");
    CHECK(a.status == 2 && strstr(a.err, "did you mean 'help'"), "dynkit hlep: %s", a.err);
    cli_free(&a);
    a = cli("help rnu");
    CHECK(a.status == 2 && strstr(a.err, "did you mean 'run'"), "dynkit help rnu: %s", a.err);
    cli_free(&a);
}

/* The output of a run, which must succeed. */
static char *run_out(const char *args)
{
    cli_result r = cli("%s", args);
    CHECK(r.status == 0, "dynkit %s: exit %d: %s", args, r.status, r.err);
    free(r.err);
    return r.out;
}

static void same_output(const char *a, const char *b)
{
    char *x = run_out(a), *y = run_out(b);
    CHECK(strcmp(x, y) == 0, "'%s' and '%s' differ:\n%.200s\n---\n%.200s", a, b, x, y);
    free(x);
    free(y);
}

static void test_short_options_and_method_names(void **state)
{
    (void)state;
    same_output("run vanderpol -m rk4 --step 0.1 --tspan 0:1",
                "run vanderpol --method rk4 --step 0.1 --tspan 0:1");
    same_output("run vanderpol -m RK4 --step 0.1 --tspan 0:1",
                "run vanderpol --method=rk4 --step 0.1 --tspan 0:1");
    same_output("run vanderpol -m ODE45 --tspan 0:2 --final",
                "run vanderpol -m dp45 --tspan 0:2 --final");
    same_output("run vanderpol -m ode23 --tspan 0:2 --final",
                "run vanderpol -m bs23 --tspan 0:2 --final");
    same_output("run robertson -m ode15s --tspan 0:10 --final",
                "run robertson -m rodas4 --tspan 0:10 --final");
    same_output("run robertson -m Ode23s --tspan 0:10 --final",
                "run robertson -m rodas4 --tspan 0:10 --final");
    cli_result r = cli("run vanderpol -m ode113");
    CHECK(r.status == 2 && strstr(r.err, "ode113") && strstr(r.err, "dop853"),
          "ode113: %s", r.err);
    cli_free(&r);
    r = cli("run vanderpol -m dp54");
    CHECK(r.status == 2 && strstr(r.err, "did you mean 'dp45'"), "dp54: %s", r.err);
    cli_free(&r);
    r = cli("animate vanderpol --compare EULER -o -");
    CHECK(r.status == 0 && strstr(r.out, "\"label\":\"euler, h = "), "--compare EULER: %s",
          r.err);
    cli_free(&r);
    r = cli("run vanderpol -m");
    CHECK(r.status == 2 && strstr(r.err, "needs a value"), "-m without a value: %s", r.err);
    cli_free(&r);
}

static void test_did_you_mean(void **state)
{
    (void)state;
    static const struct {
        const char *args, *expect;
    } cases[] = {
        {"run pendulum --tpsan 0:1", "did you mean '--tspan'"},
        {"run pendulum --outptu=x.csv", "did you mean '--output'"},
        {"run pendulum --init ph=1", "did you mean 'phi'"},
        {"run plane --set M=1", "did you mean 'm'"},
        {"run pendulum --set phi=1", "phi is a state of model pendulum: give it with --init"},
        {"run pendulum --init l=1", "l is a parameter of model pendulum: give it with --set"},
        {"run pendulm", "did you mean 'pendulum'"},
        {"verify --quik", "did you mean '--quick'"},
        {"inverse cart --quite", "did you mean '--quiet'"},
        {"plot vanderpol --y y1 --compar euler", "did you mean '--compare'"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        cli_result r = cli("%s", cases[i].args);
        CHECK(r.status == 2 && strstr(r.err, cases[i].expect), "dynkit %s: exit %d: %s",
              cases[i].args, r.status, r.err);
        cli_free(&r);
    }
}

static void test_degrees(void **state)
{
    (void)state;
    same_output("run pendulum --init phi=45deg --init dphi=-90deg --tspan 0:0.2",
                "run pendulum --init phi=pi/4 --init dphi=-pi/2 --tspan 0:0.2");
    same_output("run pendulum --init phi=180deg --tspan 0:0.2",
                "run pendulum --init phi=pi --tspan 0:0.2");
    cli_result r = cli("run pendulum --init phi=45degrees");
    CHECK(r.status == 2, "45degrees accepted");
    cli_free(&r);
}

static void test_output_dash_is_stdout(void **state)
{
    (void)state;
    same_output("run pendulum --tspan 0:0.4 -o -", "run pendulum --tspan 0:0.4");
    same_output("inverse cart --quiet -o -", "inverse cart --quiet");
    char *svg = run_out("plot vanderpol --y y1 -o -");
    CHECK(strncmp(svg, "<svg", 4) == 0 || strstr(svg, "<svg") != NULL, "plot -o -: %.80s", svg);
    free(svg);
    CHECK(access("-", F_OK) != 0, "a file named '-' was made");
}

static int teardown(void **state)
{
    (void)state;
    return cli_teardown_files(NULL);
}

/* run --help: every option at the start of a line once, and the default tolerances those of
 * model.h (what info prints for a model that names none) */
static void test_run_help_says_what_is_so(void **state)
{
    (void)state;
    cli_result h = cli("run --help");
    CHECK(h.status == 0, "%s", h.err);
    char *seen = calloc(1, h.out_len + 1);
    size_t seen_len = 0;
    for (const char *line = h.out; line && *line; line = strchr(line, '\n')) {
        if (*line == '\n')
            line++;
        const char *p = line;
        while (*p == ' ')
            p++;
        if (p - line != 2 || strncmp(p, "--", 2) != 0)
            continue;
        size_t n = strcspn(p, " \n");
        char name[64];
        snprintf(name, sizeof name, "|%.*s|", (int)n, p);
        CHECK(!strstr(seen, name), "run --help lists %s twice", name);
        memcpy(seen + seen_len, name, strlen(name));
        seen_len += strlen(name);
    }
    free(seen);
    char rtol[64], atol[64];
    snprintf(rtol, sizeof rtol, "else %s", dyn_shortest(DYN_MODEL_RTOL).s);
    snprintf(atol, sizeof atol, "else %s", dyn_shortest(DYN_MODEL_ATOL).s);
    CHECK(strstr(h.out, rtol) && strstr(h.out, atol), "run --help does not say '%s' and '%s'",
          rtol, atol);
    cli_result info = cli("info %s/examples/models/lorenz.ode", DYNKIT_SOURCE_DIR);
    snprintf(rtol, sizeof rtol, "--rtol %s (dynkit's default", dyn_shortest(DYN_MODEL_RTOL).s);
    CHECK(info.status == 0 && strstr(info.out, rtol), "info: %s%s", info.out, info.err);
    cli_free(&info);
    cli_free(&h);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_help_command),
        cmocka_unit_test(test_short_options_and_method_names),
        cmocka_unit_test(test_did_you_mean),
        cmocka_unit_test(test_degrees),
        cmocka_unit_test(test_output_dash_is_stdout),
        cmocka_unit_test(test_run_help_says_what_is_so),
    };
    return cmocka_run_group_tests(tests, cli_setup, teardown);
}
