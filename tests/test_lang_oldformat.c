/* SPDX-License-Identifier: BSD-3-Clause */
/* test_lang_oldformat.c — XPPAUT's first .ode format (src/lang/ode_old.c): a file whose
 * first line is a positive number is read in it and one whose first line is not stays in
 * the current format; errors point at the file's own line and column (inside a right-hand
 * side, a function's formula, a declaration list); the counts of the first line are
 * checked; the line kinds dynkit does not support are refused by their letter; lines XPPAUT
 * ignores are ignored with a warning. (Agreement with XPPAUT: tests/xppaut/oldformat/.) */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/dynkit.h"
#include "dynkit/jit.h"
#include "dynkit/lang.h"
#include "test_util.h"
#include "test_ode_load.h"

typedef struct notes {
    int count;
    char text[4096];
} notes;

static void collect_note(const char *path, int line, const char *message, void *ctx)
{
    notes *n = ctx;
    (void)path;
    n->count++;
    const size_t used = strlen(n->text);
    snprintf(n->text + used, sizeof n->text - used, "%d: %s\n", line, message);
}

static int translate(const char *text, char **out, dyn_lang_diag *d, notes *n)
{
    memset(n, 0, sizeof *n);
    return dyn_ode_to_c("old.ode", text, strlen(text), out, d, collect_note, n);
}

static void expect_error(const char *text, int line, int col, const char *what)
{
    char *out = NULL;
    dyn_lang_diag d;
    notes n;
    const int rc = translate(text, &out, &d, &n);
    CHECK(rc == 2, "expected an error for:\n%s\n(rc %d)", text, rc);
    CHECK(d.line == line && d.col == col, "%s\nerror at %d:%d, expected %d:%d: %s", text,
          d.line, d.col, line, col, d.message);
    CHECK(strstr(d.message, what) != NULL, "%s\nmessage '%s' lacks '%s'", text, d.message,
          what);
    free(out);
}

static char *expect_ok(const char *text, notes *n)
{
    char *out = NULL;
    dyn_lang_diag d;
    const int rc = translate(text, &out, &d, n);
    char buf[2048];
    CHECK(rc == 0, "%s\n%s", text, dyn_lang_diag_format(&d, buf, sizeof buf));
    assert_non_null(out);
    return out;
}

/* The 'o' lines belong in order to the variables, the fixed quantities, then the auxiliary
 * quantities (named by the 'a' line, else AUX<k>): for u'' = -4 u - g u' at (u, u') = (1, 0)
 * the right-hand side is (0, -4), the energy 2 u^2 + u'^2/2 is 2 and twice it 4. */
static void test_o_lines_in_order(void **state)
{
    (void)state;
    loaded L;
    test_ode_load("4\nv u=1,v=0\nf energy\np g=0.1\no v\no -4*u-g*v\no 2*u^2+v^2/2\n"
                  "a e\no energy\no energy*2\nd\n", "lang-old-jit-cache", &L);
    assert_int_equal(L.m->n_states, 2);
    assert_true(L.m->y0[0] == 1.0 && L.m->y0[1] == 0.0);
    double f[2], out[8];
    L.m->rhs(0, L.m->y0, f, L.par);
    CHECK(f[0] == 0.0 && f[1] == -4.0, "f = (%g, %g)", f[0], f[1]);
    const int e = dyn_model_output_index(L.m, "e"), a2 = dyn_model_output_index(L.m, "AUX2");
    CHECK(e >= 0 && a2 >= 0, "outputs e %d, AUX2 %d", e, a2);
    assert_int_equal(L.m->compute_outputs(0, L.m->y0, L.par, out), 0);
    CHECK(out[e] == 2.0 && out[a2] == 4.0, "e = %g, AUX2 = %g", out[e], out[a2]);
    dyn_jit_unload(&L.jm);
}

/* Lotka–Volterra as XPPAUT's first format writes it (the run is compared with XPPAUT by
 * tests/xppaut/oldformat/). */
static void test_first_line_number_selects_the_old_format(void **state)
{
    (void)state;
    notes n;
    char *out = expect_ok("2\nv x=80,y=30\np a=.25,b=-.01,c=-1.0,d=.01\nox a*x+b*x*y\n"
                          "oy c*y+d*x*y\nd\n", &n);
    CHECK(strstr(n.text, "1: the first line is a number: the file is in XPPAUT's first "
                         "format, with 2 equations"), "%s", n.text);
    free(out);
    /* a first line that is not a positive number keeps the current format */
    expect_error("0\nv x=1\n", 1, 1, "a statement starts with a name");
    out = expect_ok("# 2\nx'=-x\n", &n);
    CHECK(!strstr(n.text, "first format"), "%s", n.text);
    free(out);
    /* a UTF-8 byte order mark before the first line (an editor's) is skipped */
    out = expect_ok("\xef\xbb\xbf" "2\nv x=80,y=30\np a=.25\nox a*x\noy -y\nd\n", &n);
    CHECK(strstr(n.text, "1: the first line is a number: the file is in XPPAUT's first "
                         "format, with 2 equations"), "%s", n.text);
    free(out);
}

static void test_errors_point_at_the_file(void **state)
{
    (void)state;
    /* inside a right-hand side, after the first word */
    expect_error("1\nv x=1\nodex -x*undefined\nd\n", 3, 9, "unknown name 'undefined'");
    /* inside a function's formula: its arguments are arg1 ... argN */
    expect_error("1\nv x=1\nuser f 1 arg2+1\no -f(x)\nd\n", 3, 10, "unknown name 'arg2'");
    expect_error("1\nv x=1\nu f 0 2\no -x\nd\n", 3, 5,
                 "the number of arguments of 'f' must be a whole number from 1 to 20");
    /* a parameter's value */
    expect_error("1\nv x=1\np a=1,b=*2\no -a*x\nd\n", 3, 9, "expected a number");
    expect_error("1\nv x=1\no\nd\n", 3, 2, "expected a right-hand side after 'o'");
    /* inside an integral of an integral equation ('i' line) */
    expect_error("1\nv u=1\ni 1-int{exp(-t)#uu}\nd\n", 3, 17, "unknown name 'uu'");
    /* inside a kernel's formula, where a right-hand side names the kernel */
    expect_error("1\nv u=1\nk kk 0 exp(-t)#uu\ni 1-kk\nd\n", 3, 16, "unknown name 'uu'");
    expect_error("1\nv u=1\nk kk 0\ni 1-kk\nd\n", 3, 7, "expected 'k NAME MU FORMULA'");
    expect_error("1\nv x=1\na e=2\no -x\nd\n", 3, 4, "an 'a' line names the auxiliary");
}

/* The first line counts the variables and the auxiliary quantities; the 'o' lines are as
 * many plus one per fixed quantity. */
static void test_counts_of_the_first_line(void **state)
{
    (void)state;
    expect_error("2\nv x=1,y\no -x\nd\n", 1, 1, "the file needs 2 'o' lines, and has 1");
    expect_error("1\nv x=1\nf w\no -x\nd\n", 1, 1,
                 "with 1 fixed quantity the file needs 2 'o' lines, and has 1");
    expect_error("2\nv x,y,z\no -x\no x\nd\n", 1, 1,
                 "the first line gives 2 equations, fewer than the 3 variables");
    /* an 'o' line beyond the count ends the file, as in XPPAUT: the next line is not read */
    notes n;
    char *out = expect_ok("1\nv x=1\no -x\no x\nthis line is not read: *(\n", &n);
    CHECK(strstr(n.text, "4: " DYN_LANG_WARNING "an 'o' line beyond the first line's count "
                         "(1 equation, 0 fixed quantities)"), "%s", n.text);
    free(out);
}

static void test_line_kinds_refused_or_ignored(void **state)
{
    (void)state;
    static const struct {
        const char *line;
        const char *what;
    } refused[] = {
        {"markov z 0 2", "'m' lines of XPPAUT's first format (Markov states)"},
        {"bndry x-1", "'b' lines of XPPAUT's first format (boundary conditions"},
        {"change my.opt", "'c' lines of XPPAUT's first format (an option file"},
    };
    for (size_t i = 0; i < sizeof refused / sizeof refused[0]; i++) {
        char text[256];
        snprintf(text, sizeof text, "1\nv x=1\n%s\no -x\nd\n", refused[i].line);
        expect_error(text, 3, 1, refused[i].what);
    }
    /* comments, XPPAUT's help lines and an unknown letter: ignored (the letter with a
     * warning), as XPPAUT ignores them; an '@' line counts only in the first column */
    notes n;
    char *out = expect_ok("1\n% comment\n# comment\nshow\nhelp\nv x=1\ne not a kind\n"
                          " @ total=5\no -x\nd\n", &n);
    CHECK(strstr(n.text, "7: " DYN_LANG_WARNING "'e': XPPAUT's first format has no 'e' "
                         "lines"), "%s", n.text);
    CHECK(strstr(n.text, "8: " DYN_LANG_WARNING "an '@' line of XPPAUT's first format starts "
                         "in the first column"), "%s", n.text);
    CHECK(n.count == 3, "%s", n.text); /* and the note of the format */
    free(out);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_first_line_number_selects_the_old_format),
        cmocka_unit_test(test_o_lines_in_order),
        cmocka_unit_test(test_errors_point_at_the_file),
        cmocka_unit_test(test_counts_of_the_first_line),
        cmocka_unit_test(test_line_kinds_refused_or_ignored),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
