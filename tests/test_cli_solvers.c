/* SPDX-License-Identifier: BSD-3-Clause */
/* test_cli_solvers.c — the command line with the stiff solvers and long spans:
 * - --method cvode (when dynkit is built with SUNDIALS; skipped otherwise, where it must be
 *   a usage error that says so): Robertson to 1e11 against the Test Set's reference, samples
 *   on the grid, at --times and at every step, per-state tolerances, --stats with jac=,
 *   --event and --trace refused, listed by 'dynkit methods', --compare cvode in a plot;
 * - the default output of adaptive runs over long spans: every accepted step instead of a
 *   grid of 2e14 samples, a note when the grid was too long, --step still gives the grid;
 * - the defaults of robertson and hires (rodas4, a sample at every accepted step) in run,
 *   info, plot and animate, and fixed-step methods keeping the model's step;
 * - tolerances in animate/plot when a --compare run is adaptive, refused otherwise with the
 *   rule in the message;
 * - progress on a terminal when an adaptive run goes through a long grid of samples
 *   (1e8 samples in a few steps, about 1.5 s; needs script(1)). */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "dynkit/dynkit.h"
#include "test_cli_run.h"
#include "test_util.h"

/* The values of the last CSV row (t first) into v (at most max); returns the count. */
static int last_row(const char *text, double *v, int max)
{
    const char *end = text + strlen(text);
    while (end > text && end[-1] == '\n')
        end--;
    const char *p = end;
    while (p > text && p[-1] != '\n')
        p--;
    int k = 0;
    char *q;
    while (p < end && k < max) {
        v[k++] = strtod(p, &q);
        if (q == p)
            return k - 1;
        p = q;
        if (*p == ',')
            p++;
    }
    return k;
}

static double rel_err(const double *y, const double *ref, int n)
{
    double w = 0.0;
    for (int i = 0; i < n; i++)
        w = fmax(w, fabs(y[i] - ref[i]) / fabs(ref[i]));
    return w;
}

/* stats "steps=N accepted=N rejected=N rhs=N jac=N" from stderr; 0 if found. */
static int stats_of(const char *err, long *steps, long *acc, long *rej, long *rhs, long *jac)
{
    const char *s = strstr(err, "steps=");
    *jac = -1;
    if (!s || sscanf(s, "steps=%ld accepted=%ld rejected=%ld rhs=%ld", steps, acc, rej, rhs) != 4)
        return -1;
    const char *j = strstr(s, " jac=");
    if (j)
        sscanf(j, " jac=%ld", jac);
    return 0;
}

/* ---- an exact Jacobian that cannot be evaluated ---- */

/* x' = -x + 1/(1 + kb (1 + 1/p)), p' = -p, p(0) = 0: p stays 0, where the fraction is 0 and
 * x = exp(-t); the exact Jacobian's d/dp entry is NaN there (0 * inf). rodas4 and cvode take
 * that column by differences (jac_fd_columns in --stats) and agree with dp45 and with
 * exp(-5) at tight tolerances. */
static void test_jacobian_not_finite_where_f_is(void **state)
{
    (void)state;
    FILE *f = fopen(cli_path("pole.ode"), "w");
    assert_non_null(f);
    fputs("par kb=0.4\nx'=-x+1/(1+kb*(1+1/p))\np'=-p\ninit x=1,p=0\ndone\n", f);
    fclose(f);
    const double exact = exp(-5.0);
    double dp45 = NAN;
    static const char *const methods[] = {"dp45", "rodas4", "cvode"};
    const int n_methods = cli_has_cvode() ? 3 : 2;
    for (int k = 0; k < n_methods; k++) {
        cli_result r = cli("run %s --method %s --tspan 0:5 --rtol 1e-10 --atol 1e-12 --final "
                           "--stats",
                           cli_path("pole.ode"), methods[k]);
        CHECK(r.status == 0, "%s: exit %d: %s", methods[k], r.status, r.err);
        double v[3];
        assert_int_equal(last_row(r.out, v, 3), 3);
        assert_true(v[0] == 5.0 && v[2] == 0.0);
        const double tol = k == 2 ? 1e-9 : 1e-11; /* cvode's BDF: 2e-10 measured */
        CHECK(fabs(v[1] - exact) < tol, "%s: x(5) = %.17g, exp(-5) = %.17g", methods[k], v[1],
              exact);
        if (k == 0)
            dp45 = v[1];
        else
            CHECK(fabs(v[1] - dp45) < tol, "%s: x(5) = %.17g, dp45 %.17g", methods[k], v[1], dp45);
        const char *cols = strstr(r.err, " jac_fd_columns=");
        if (k == 0)
            CHECK(!cols, "dp45 has no Jacobian: %s", r.err);
        else
            CHECK(cols && atol(cols + 16) > 0, "%s: no jac_fd_columns > 0 in: %s", methods[k],
                  r.err);
        cli_free(&r);
    }
}

/* ---- cvode ---- */

static void test_cvode_robertson(void **state)
{
    (void)state;
    if (!cli_has_cvode()) {
        cli_result r = cli("run robertson --method cvode --final");
        assert_int_equal(r.status, 2);
        CHECK(strstr(r.err, "built without SUNDIALS") != NULL, "%s", r.err);
        assert_int_equal(r.out_len, 0);
        cli_free(&r);
        r = cli("plot vanderpol --y y1 --compare cvode --output %s", cli_path("p.svg"));
        assert_int_equal(r.status, 2);
        assert_non_null(strstr(r.err, "without SUNDIALS"));
        cli_free(&r);
        skip();
    }
    const dyn_reference *ref = dyn_reference_find("robertson-1e11");
    assert_non_null(ref);
    /* the Test Set's run to 1e11, at every step (the model's default output) */
    cli_result r = cli("run robertson --method cvode --tspan 0:1e11 --rtol 1e-9 "
                       "--atol 1e-14,1e-20,1e-14 --stats");
    CHECK(r.status == 0, "exit %d: %s", r.status, r.err);
    double v[4];
    assert_int_equal(last_row(r.out, v, 4), 4);
    assert_true(v[0] == 1e11);
    const double e = rel_err(v + 1, ref->y, 3);
    CHECK(e < 1e-5, "cvode: relative error %.3g at 1e11", e);
    long steps, acc, rej, rhs, jac;
    assert_int_equal(stats_of(r.err, &steps, &acc, &rej, &rhs, &jac), 0);
    assert_true(steps == acc + rej && acc > 100 && jac > 0 && rhs > acc);
    /* a sample at every step: accepted steps + the initial state */
    assert_int_equal(csv_rows(r.out), acc + 1);
    cli_free(&r);

    /* --times, and the grid of --step */
    r = cli("run robertson --method cvode --times 0,0.4,4,40 --rtol 1e-8 --atol 1e-14");
    CHECK(r.status == 0, "%s", r.err);
    double t[8];
    assert_int_equal(csv_times(r.out, t, 8), 4);
    assert_true(t[0] == 0.0 && t[1] == 0.4 && t[2] == 4.0 && t[3] == 40.0);
    const dyn_reference *r40 = dyn_reference_find("robertson-40");
    assert_int_equal(last_row(r.out, v, 4), 4);
    CHECK(rel_err(v + 1, r40->y, 3) < 1e-5, "at 40: %.3g", rel_err(v + 1, r40->y, 3));
    cli_free(&r);
    r = cli("run vanderpol --method cvode --step 0.5 --tspan 0:2 --rtol 1e-8 --atol 1e-10");
    CHECK(r.status == 0, "%s", r.err);
    assert_int_equal(csv_times(r.out, t, 8), 5);
    for (int k = 0; k < 5; k++)
        assert_true(t[k] == 0.5 * k);
    cli_free(&r);
    /* per-state relative tolerances: equal ones are the scalar run, a tighter one on y2
     * takes more steps; the stats line has jac= */
    r = cli("run vanderpol --method cvode --atol 1e-12 --rtol 1e-4 --final --stats");
    assert_int_equal(r.status, 0);
    long a1, a2;
    assert_int_equal(stats_of(r.err, &steps, &a1, &rej, &rhs, &jac), 0);
    assert_non_null(strstr(r.err, " jac="));
    char *scalar = strdup(r.out);
    cli_free(&r);
    r = cli("run vanderpol --method cvode --atol 1e-12 --rtol 1e-4,1e-4 --final --stats");
    assert_int_equal(r.status, 0);
    assert_string_equal(r.out, scalar);
    free(scalar);
    cli_free(&r);
    r = cli("run vanderpol --method cvode --atol 1e-12 --rtol 1e-4,1e-8 --final --stats");
    assert_int_equal(r.status, 0);
    assert_int_equal(stats_of(r.err, &steps, &a2, &rej, &rhs, &jac), 0);
    CHECK(a2 > 2 * a1, "tighter rtol on y2: %ld steps, before %ld", a2, a1);
    cli_free(&r);
}

static void test_cvode_refusals_and_listing(void **state)
{
    (void)state;
    cli_result r = cli("methods --help");
    assert_int_equal(r.status, 0);
    assert_non_null(strstr(r.out, "cvode"));
    assert_non_null(strstr(r.out, "SUNDIALS"));
    cli_free(&r);
    if (!cli_has_cvode())
        skip();
    r = cli("methods");
    const char *line = strstr(r.out, "\ncvode ");
    assert_non_null(line);
    char row[256];
    const char *nl = strchr(line + 1, '\n');
    size_t len = nl ? (size_t)(nl - line - 1) : strlen(line + 1);
    snprintf(row, sizeof row, "%.*s", (int)len, line + 1);
    assert_non_null(strstr(row, "BDF"));
    assert_non_null(strstr(row, "1-5"));
    assert_non_null(strstr(row, "adaptive"));
    assert_non_null(strstr(row, "yes"));
    cli_free(&r);
    r = cli("run pendulum --method cvode --event turn");
    assert_int_equal(r.status, 2);
    CHECK(strstr(r.err, "--event") && strstr(r.err, "cvode"), "%s", r.err);
    assert_int_equal(r.out_len, 0);
    cli_free(&r);
    r = cli("run pendulum --method cvode --trace 1");
    assert_int_equal(r.status, 2);
    CHECK(strstr(r.err, "--trace") && strstr(r.err, "cvode"), "%s", r.err);
    cli_free(&r);
    /* cvode as a --compare run of a plot */
    r = cli("plot vanderpol --set mu=1000 --tspan 0:3000 --method rodas4 --compare cvode "
            "--y y1 --output %s",
            cli_path("p.svg"));
    CHECK(r.status == 0, "%s", r.err);
    cli_free(&r);
    r = cli("plot vanderpol --y y1 --compare cvode --event turn --output %s", cli_path("p.svg"));
    assert_int_equal(r.status, 2);
    cli_free(&r);
}

/* ---- long spans ---- */

static void test_long_span_output(void **state)
{
    (void)state;
    /* Robertson to 1e11 with rodas4 and no --step: a sample at every step, not 2e14 */
    cli_result r = cli("run robertson --method rodas4 --tspan 0:1e11 --rtol 1e-6 --atol 1e-12 "
                       "--stats");
    CHECK(r.status == 0, "exit %d: %s", r.status, r.err);
    long steps, acc, rej, rhs, jac;
    assert_int_equal(stats_of(r.err, &steps, &acc, &rej, &rhs, &jac), 0);
    assert_int_equal(csv_rows(r.out), acc + 1);
    assert_true(acc < 10000);
    static double t[20000];
    long n = csv_times(r.out, t, 20000);
    for (long k = 1; k < n; k++)
        assert_true(t[k] > t[k - 1]);
    assert_true(t[0] == 0.0 && t[n - 1] == 1e11);
    cli_free(&r);
    /* a model on a grid by default: the note, then every step */
    r = cli("run vanderpol --method dp45 --tspan 0:2e4 --stats");
    CHECK(r.status == 0, "%s", r.err);
    CHECK(strstr(r.err, "every accepted step") != NULL, "no note: %s", r.err);
    assert_int_equal(stats_of(r.err, &steps, &acc, &rej, &rhs, &jac), 0);
    assert_int_equal(csv_rows(r.out), acc + 1);
    double v[3];
    assert_int_equal(last_row(r.out, v, 3), 3);
    assert_true(v[0] == 2e4);
    cli_free(&r);
    /* --quiet keeps the note off; --step gives the grid it asks for */
    r = cli("run vanderpol --method dp45 --tspan 0:1e5 --quiet --final");
    assert_int_equal(r.status, 0);
    assert_null(strstr(r.err, "every accepted step"));
    cli_free(&r);
    r = cli("run vanderpol --method dp45 --tspan 0:1e5 --step 50");
    assert_int_equal(r.status, 0);
    assert_int_equal(csv_rows(r.out), 2001);
    assert_null(strstr(r.err, "note"));
    cli_free(&r);
    /* within the limit the model's grid stays: 0:100 at 0.01 is 10001 samples */
    r = cli("run vanderpol --method dp45 --tspan 0:100");
    assert_int_equal(r.status, 0);
    assert_int_equal(csv_rows(r.out), 10001);
    cli_free(&r);
    /* help and docs state the rule */
    r = cli("run --help");
    assert_non_null(strstr(r.out, "every accepted"));
    assert_non_null(strstr(r.out, "1e6"));
    cli_free(&r);
}

/* Progress on a terminal when the samples of an adaptive run come from a long grid inside
 * few steps (the driver's own progress is per step); script(1) gives the terminal. */
static void test_progress_on_a_terminal(void **state)
{
    (void)state;
    if (system("command -v script >/dev/null 2>&1 && command -v timeout >/dev/null 2>&1") != 0)
        skip();
    char cmd[1024];
    snprintf(cmd, sizeof cmd,
             "timeout 60 script -qc \"'%s' run robertson --method rodas4 --tspan 0:1e11 "
             "--step 1000 --final >/dev/null\" /dev/null >'%s' 2>&1",
             DYNKIT_CLI, cli_path("tty"));
    int rc = system(cmd);
    (void)rc;
    char *text = cli_read_file(cli_path("tty"), NULL);
    CHECK(strstr(text, "elapsed") != NULL, "no progress on the terminal: %.300s", text);
    free(text);
}

/* ---- the stiff models' defaults ---- */

static void test_stiff_defaults(void **state)
{
    (void)state;
    cli_result r = cli("run robertson --stats");
    CHECK(r.status == 0, "%s", r.err);
    long steps, acc, rej, rhs, jac;
    assert_int_equal(stats_of(r.err, &steps, &acc, &rej, &rhs, &jac), 0);
    assert_true(jac == acc && acc < 100); /* rodas4: one Jacobian per step */
    assert_int_equal(csv_rows(r.out), acc + 1);
    assert_int_equal(rhs, 7 * acc + 5 * rej + 2);
    double v[4];
    assert_int_equal(last_row(r.out, v, 4), 4);
    assert_true(v[0] == 40.0);
    const dyn_reference *r40 = dyn_reference_find("robertson-40");
    CHECK(rel_err(v + 1, r40->y, 3) < 1e-3, "%.3g", rel_err(v + 1, r40->y, 3));
    cli_free(&r);
    r = cli("run hires --final --stats");
    assert_int_equal(r.status, 0);
    assert_non_null(strstr(r.err, " jac="));
    cli_free(&r);
    r = cli("info robertson");
    assert_non_null(strstr(r.out, "--method rodas4"));
    assert_non_null(strstr(r.out, "every accepted step"));
    cli_free(&r);
    r = cli("info hires");
    assert_non_null(strstr(r.out, "--method rodas4"));
    cli_free(&r);
    /* a fixed-step method keeps the model's step (RK4 stable at 5e-4) */
    r = cli("run robertson --method rk4 --final --stats");
    assert_int_equal(r.status, 0);
    assert_int_equal(stats_of(r.err, &steps, &acc, &rej, &rhs, &jac), 0);
    assert_int_equal(acc, 80000);
    cli_free(&r);
    /* pictures of the defaults */
    r = cli("plot robertson --y y2 --output %s", cli_path("p.svg"));
    CHECK(r.status == 0, "%s", r.err);
    cli_free(&r);
    r = cli("animate hires --output %s", cli_path("a.html"));
    CHECK(r.status == 0, "%s", r.err);
    char *page = cli_read_file(cli_path("a.html"), NULL);
    assert_non_null(strstr(page, "rodas4"));
    free(page);
    cli_free(&r);
    /* a long run in a picture is thinned as it comes: at most 2000 samples kept */
    r = cli("animate vanderpol --method dp45 --tspan 0:1e5 --quiet --output %s",
            cli_path("a.html"));
    CHECK(r.status == 0, "%s", r.err);
    page = cli_read_file(cli_path("a.html"), NULL);
    const char *t = strstr(page, "\"data\":[[");
    assert_non_null(t);
    long commas = 0;
    for (const char *p = t + 9; *p && *p != ']'; p++)
        commas += *p == ',';
    CHECK(commas + 1 <= 2000 && commas + 1 > 500, "%ld samples kept", commas + 1);
    free(page);
    cli_free(&r);
}

/* ---- tolerances with --compare ---- */

static void test_tolerances_with_compare(void **state)
{
    (void)state;
    cli_result r = cli("animate vanderpol --method rk4 --compare dp45 --rtol 1e-8 --output %s",
                       cli_path("a.html"));
    CHECK(r.status == 0, "%s", r.err);
    char *page = cli_read_file(cli_path("a.html"), NULL);
    assert_non_null(strstr(page, "rtol = 1e-08"));
    free(page);
    cli_free(&r);
    r = cli("plot vanderpol --method rk4 --compare heun --rtol 1e-8 --y y1 --output %s",
            cli_path("p.svg"));
    assert_int_equal(r.status, 2);
    CHECK(strstr(r.err, "--compare") != NULL && strstr(r.err, "adaptive") != NULL, "%s", r.err);
    cli_free(&r);
    r = cli("run vanderpol --method rk4 --rtol 1e-8");
    assert_int_equal(r.status, 2);
    assert_null(strstr(r.err, "--compare"));
    cli_free(&r);
}

static int teardown(void **state)
{
    (void)state;
    static const char *const files[] = {"p.svg", "a.html", "tty", NULL};
    return cli_teardown_files(files);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cvode_robertson),
        cmocka_unit_test(test_cvode_refusals_and_listing),
        cmocka_unit_test(test_long_span_output),
        cmocka_unit_test(test_progress_on_a_terminal),
        cmocka_unit_test(test_stiff_defaults),
        cmocka_unit_test(test_tolerances_with_compare),
        cmocka_unit_test(test_jacobian_not_finite_where_f_is),
    };
    return cmocka_run_group_tests(tests, cli_setup, teardown);
}
