/* SPDX-License-Identifier: BSD-3-Clause */
/* test_lang.c — the .ode translator's front end (dynkit/lang.h, src/lang): every feature
 * XPPAUT has and dynkit does not is refused with its line, column and name; errors point
 * at the file's own line and column (also inside continued and expanded array lines) with
 * the line and a caret; unknown names suggest the nearest known one; circular definitions
 * name the cycle; the notes of ignored options; the limits; no input crashes it; and real
 * files from XPPAUT's examples translate. (The compiled models: test_lang_model.c.) */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/lang.h"
#include "test_util.h"

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
    if (n)
        memset(n, 0, sizeof *n);
    return dyn_ode_to_c("m.ode", text, strlen(text), out, d, n ? collect_note : NULL, n);
}

/* The translation of text fails at line:col with a message containing what. */
static void expect_error(const char *text, int line, int col, const char *what)
{
    char *out = (char *)1;
    dyn_lang_diag d;
    const int rc = translate(text, &out, &d, NULL);
    CHECK(rc == 2, "expected an error for:\n%s\n(rc %d)", text, rc);
    CHECK(out == NULL, "the C text is NULL on failure");
    CHECK(d.line == line && d.col == col, "%s\nerror at %d:%d, expected %d:%d: %s", text,
          d.line, d.col, line, col, d.message);
    CHECK(strstr(d.message, what) != NULL, "%s\nmessage '%s' lacks '%s'", text, d.message,
          what);
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

static void test_refused_features_name_line_and_feature(void **state)
{
    (void)state;
    static const struct {
        const char *text;
        int line, col;
        const char *what;
    } cases[] = {
        {"x'=-del_shft(x,0,1)\n", 1, 5, "delay-differential equations ('del_shft')"},
        /* Volterra integrals that XPPAUT's manual does not define */
        {"x'=-x+int[1.5]{exp(-t)#x}\n", 1, 11, "0 <= m < 1"},
        {"par a=.5\nx'=-x+int[a]{exp(-t)#x}\n", 2, 11, "not a parameter"},
        {"x'=-x+int{exp(-x)#x}\n", 1, 7, "the kernel K of int{K#u} reads a state"},
        {"x'=-x+int{exp(-t')#x}\n", 1, 16, "t' belongs to the integrand"},
        {"x'=-x+int{exp(-t)#x\n", 1, 7, "expected '}'"},
        {"x'=-x+int+1\n", 1, 7, "'int' begins a Volterra integral"},
        {"x'=1\nbdry 1+hom_bcs(0)\n", 2, 8, "hom_bcs(K) is a whole boundary condition"},
        {"x'=1\nbdry hom_bcs(0)\n", 2, 1, "one condition fewer than states"},
        {"x'=y\ny'=x\nc'=0\nbdry c\nbdry hom_bcs(-1)\n", 5, 14, "a whole number K from 0"},
        /* two flow states, one x'=0 state used: no equilibrium of the flow's size */
        {"x'=y\ny'=x\nxe'=0\nye'=0\nbdry xe\nbdry hom_bcs(0)\nbdry hom_bcs(1)\n", 6, 1,
         "the equilibria are not in the file's layout"},
        {"x'=y\ny'=-x\nbdry x\n", 3, 1, "1 boundary condition for 2 states"},
        {"par a=1\nx'=1\nbdry a'\n", 3, 6, "only a state's name takes a prime"},
        {"x'=w\nw=x*2\nbdry w\n", 3, 6, "a value along the run"},
        {"x'=1\nspecial k=fsparse(51,5,w,ind,u0,v0,f)\n", 2, 1,
         "network sums ('special' with fsparse)"},
        {"x'=1\nexport {x} {y}\n", 2, 1, "'export'"},
        {"x'=ishift(x,1)\n", 1, 4, "indirect addressing ('ishift')"},
        {"x'=besselj(0,x)\n", 1, 4, "Bessel functions ('besselj')"},
        {"x'=1\noptions my.opt\n", 2, 1, "option files"},
        {"x'=1\n@ dt=-0.1\n", 2, 6, "backwards in time"},
        /* a band of the Jacobian (@ bandlo, bandup) that does not fit the equations */
        {"x1'=x3-x1\nx2'=x1*x2\nx3'=-x3\n@ bandlo=1,bandup=1\n", 4, 3,
         "bandlo=1, bandup=1 do not hold: d(x1')/d(x3) is not zero, 2 places above the "
         "diagonal"},
        {"x1'=x2\nx2'=-x1\n@ bandlo=2\n", 3, 3,
         "a bandwidth of the Jacobian must be below the number of states, 2"},
        {"x'=1\n@ bandup=1.5\n", 2, 10, "bandup must be a whole number >= 0"},
        /* above 400 states (no analytic Jacobian): checked from the states each equation
         * reads, also through temporaries */
        {"x0'=-x0\nw[1..450]=x[j-1]\nx[1..450]'=w[j]-x[j]\n@ bandlo=0,bandup=3\n", 4, 3,
         "bandlo=0, bandup=3 do not hold: x1' reads x0, 1 place below the diagonal"},
        {"x0'=-x0\nx[1..450]'=x[j-1]-x[j]\nx451'=x0\n@ bandlo=1\n", 4, 3,
         "bandlo=1, bandup=0 do not hold: x451' reads x0, 451 places below the diagonal"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
        expect_error(cases[i].text, cases[i].line, cases[i].col, cases[i].what);
}

/* Differential-algebraic systems: as many 0= equations as solv variables, guesses and
 * derived parameters of the parameters only, 0= written so, not in maps. */
static void test_algebraic_equations_are_checked(void **state)
{
    (void)state;
    expect_error("x'=1\n0=x-1\n", 2, 1,
                 "1 algebraic equation (0=...) for 0 algebraic variables (solv): give as many of "
                 "each");
    expect_error("x'=1\nsolv y=-.5\n", 2, 6,
                 "0 algebraic equations (0=...) for 1 algebraic variable (solv)");
    expect_error("x'=-y\nsolv y\n0=y+exp(y)-x\n!a=2*y\n", 4, 6,
                 "a derived parameter cannot depend on the algebraic variable 'y'");
    expect_error("x'=-y\nsolv y=x\n0=y+exp(y)-x\n", 2, 8,
                 "the initial guess of an algebraic variable cannot depend on the state 'x'");
    expect_error("x'=1\n01=x\n", 2, 1, "an algebraic equation is written 0=expression");
    expect_error("x'=z\nsolv v, z\n0=z-x\n0=z+x-1\n", 2, 6,
                 "the algebraic variable 'v' appears in no algebraic equation");
    expect_error("solv y\nx(t+1)=y\n0=y-x\n", 1, 6, "not discrete maps");
    expect_error("x'=-y\nsolv y\n0=y-x\n@ xp=y\n", 4, 6,
                 "option 'xp': 'y' is an algebraic variable: name an aux output of it");
    char *out = expect_ok("x'=-y\nsolv y=-.5\n0=y+exp(y)-x\n", NULL);
    CHECK(strstr(out, "dk_alg_solve") && strstr(out, "w[0]"), "%s", out);
    free(out);
    /* read through a function only: the function is inlined where it is called */
    out = expect_ok("f(u)=u+v\nx'=v\nsolv v\n0=f(x)\n", NULL);
    CHECK(strstr(out, "w[0]"), "%s", out);
    free(out);
}

static void test_unknown_names_suggest_the_nearest(void **state)
{
    (void)state;
    expect_error("par omega=1\nx'=-omgea*x\n", 2, 5, "unknown name 'omgea' (did you mean "
                 "'omega'?)");
    expect_error("x'=-sinn(x)\n", 1, 5, "unknown function 'sinn' (did you mean 'sin'?)");
    expect_error("x'=zzzzzz\n", 1, 4, "unknown name 'zzzzzz'");
    expect_error("par a=1\nx'=1\ninit xx=2\n", 3, 6, "unknown name 'xx' (did you mean 'x'?)");
    {
        /* a global reads a parameter another assigns: XPPAUT sets it after the whole cycle
         * of a cascade, dynkit after each global, so the file gets a warning */
        notes n;
        char *out = expect_ok("par k=0\nx'=1\ny'=1\nglobal 1 x-1 {x=0;k=k+1}\n"
                              "global 1 y-1 {y=0;x=k}\n", &n);
        CHECK(strstr(n.text, "5: warning: this global reads 'k', which the global on line 4 "
                             "assigns") != NULL,
              "%s", n.text);
        free(out);
        out = expect_ok("par k=0\nx'=1\nglobal 1 x-1 {x=0;k=k+1}\n", &n);
        CHECK(strstr(n.text, "warning") == NULL, "%s", n.text);
        free(out);
    }
    {
        /* an aux named like a function and, declared before it, a state: a label only */
        notes n;
        char *out = expect_ok("f(u)=u^2\naux f=x+1\naux x=2*x\nx'=-f(x)\n", &n);
        CHECK(strstr(n.text, "2: aux 'f' shares its name with a function") &&
                  strstr(n.text, "4: aux 'x' shares its name with a state"),
              "%s", n.text);
        free(out);
    }
    {
        /* a plot option naming no variable: a warning, the option left out (XPPAUT runs the
         * file and ignores it) */
        notes n;
        char *out = expect_ok("x'=1\n@ xp=xx, yp=x\n", &n);
        CHECK(strstr(n.text, "2: warning: option 'xp': 'xx' is not a state or an aux output "
                             "(did you mean 'x'?); the option is ignored") != NULL,
              "%s", n.text);
        CHECK(strstr(out, ".phase_x = NULL") && strstr(out, ".phase_y = \"x\""), "%s", out);
        free(out);
    }
    expect_error("x'=1\n#: xq [m] position\n", 2, 4, "not a declared name");
    expect_error("x'=1\nsett a=2\n", 2, 1, "unknown statement 'sett' (did you mean 'set'?)");
    expect_error("x'=1\n@ meth=tk4\n", 2, 8, "unknown method 'tk4' (did you mean 'rk4'?)");
}

static void test_kinds_of_names_are_checked(void **state)
{
    (void)state;
    /* XPPAUT folds the case of names: A and a are one */
    expect_error("par a=1\npar A=2\nx'=a\n", 2, 5, "'A' is already declared as a parameter "
                 "on line 1");
    expect_error("x'=1\nx'=2\n", 2, 1, "already declared as a state");
    expect_error("x'=1\naux e=x\ny'=e\n", 3, 4, "'e' is an aux output");
    expect_error("f(a)=a\nx'=f\n", 2, 4, "'f' is a function");
    expect_error("x'=sin(x,1)\n", 1, 4, "'sin' takes 1 argument, not 2");
    expect_error("f(a,b)=a+b\nx'=f(x)\n", 2, 4, "function 'f' takes 2 arguments, not 1");
    expect_error("par a=1\n!b=a*x\nx'=b\n", 2, 6, "cannot depend on the state 'x'");
    expect_error("par a=t\nx'=1\n", 1, 7, "must be a number");
    expect_error("par a=1, b=a\nx'=1\n", 1, 12, "must be a number, not a formula of 'a'");
    expect_error("x'=1\ninit x=t\n", 2, 8, "cannot depend on the time t");
    expect_error("x'=1\nglobal 1 x-1 {a=0}\n", 2, 15, "unknown name 'a'");
    expect_error("number a=1\nx'=1\nglobal 1 x-1 {a=0}\n", 3, 15,
                 "a global assigns states and parameters; 'a' is a number");
    expect_error("sin=1\nx'=sin\n", 1, 1, "reserved word");
    expect_error("f(a)=f(a)+1\nx'=f(x)\n", 1, 1, "calls itself");
    expect_error("x'=1\nx(0)=y\n", 2, 6, "unknown name 'y'");
}

static void test_sums_and_shifts_are_checked(void **state)
{
    (void)state;
    expect_error("x'=sum(1,a)of(i')\npar a=2\n", 1, 10, "the last bound of sum must be a whole "
                 "number");
    expect_error("x'=sum(1,2)of(sum(1,2)of(i'))\n", 1, 15, "a sum inside a sum");
    expect_error("x'=i'\n", 1, 4, "i' is the index of a sum");
    expect_error("x'=shift(x,1)\n", 1, 4, "shift(x,1) is outside the 1 names of its kind");
    expect_error("x'=shift(x,x)\n", 1, 12, "the offset of shift must be a whole number");
    expect_error("x'=sum(1,10)(i')\n", 1, 13, "expected 'of'");
    expect_error("x'=sum(1,1000000)of(i')\n", 1, 4, "too long");
    /* a bound that is not whole is refused, not truncated as XPPAUT does */
    expect_error("x'=sum(0,1.5)of(1)\n", 1, 10,
                 "the last bound of sum must be a whole number, not 1.5");
    expect_error("x'=sum(0,3/2)of(1)\n", 1, 11,
                 "the last bound of sum must be a whole number, not 1.5");
}

static void test_circular_definitions_name_the_cycle(void **state)
{
    (void)state;
    expect_error("x'=a\na=b+1\nb=c*2\nc=a-x\n", 2, 1, "circular definition of fixed "
                 "quantities: a -> b -> c -> a");
    expect_error("x'=a\na=a+1\n", 2, 1, "a -> a");
    expect_error("par k=1\n!u=v*k\n!v=u+1\nx'=u\n", 2, 2, "circular definition of derived "
                 "parameters: u -> v -> u");
}

static void test_syntax_errors_point_at_the_place(void **state)
{
    (void)state;
    expect_error("x'=(1+x\n", 1, 8, "expected ')'");
    expect_error("x'=1+*x\n", 1, 6, "expected a number, a name or '('");
    expect_error("x'=2v\n", 1, 5, "missing operator after the number '2'");
    expect_error("x'=a b\npar a=1,b=1\n", 1, 6, "missing operator");
    expect_error("x'=1e\n", 1, 5, "exponent needs digits");
    expect_error("x'=if(x>1)then(1)\n", 1, 18, "expected 'else'");
    expect_error("x'=1\nglobal 2 x {x=0}\n", 2, 8, "1 (rising), -1 (falling) or 0 (when ");
    expect_error("x'=1\nglobal 1 x-1 {x=0\n", 2, 18, "missing '}'");
    expect_error("x'=1\n@ total=abc\n", 2, 9, "needs a number");
    expect_error("x'=1\n$\n", 2, 1, "unexpected '$'");
    expect_error("par a=1\n", 0, 0, "no differential or difference equation");
    expect_error("x'=1\n#: event hit = x-1, upward\n", 2, 21, "expected rising, falling or "
                 "both");
    expect_error("x'=1\n#: event hit\nx2'=1\n", 2, 1, "next line is not a global");
    /* a continued line: the second physical line's own column */
    expect_error("x'=1+\\\n   2*$\n", 2, 6, "expected a number");
    /* an expanded array line: the column in the file, whatever j is */
    expect_error("x[1..3]'=-x[j]+qq\n", 1, 16, "unknown name 'qq'");
    expect_error("x[1..3]'=-x[j-1]\n", 1, 11, "unknown name 'x0'");
    expect_error("x[0..2]'=x[j-1]\n", 1, 11, "negative");
    expect_error("x[1..2]'=x[k]\n", 1, 12, "unexpected 'k' in an index");
    expect_error("x'=y[j]\n", 1, 6, "[j] outside an array line");
    expect_error("%[1..2]\nx[j]'=1\n", 1, 1, "without its closing '%'");
}

static void test_diag_format_shows_the_line_and_a_caret(void **state)
{
    (void)state;
    char *out;
    dyn_lang_diag d;
    assert_int_equal(translate("par a=1\nx'=-a*bb\n", &out, &d, NULL), 2);
    char buf[1024];
    dyn_lang_diag_format(&d, buf, sizeof buf);
    assert_string_equal(buf, "m.ode:2:7: error: unknown name 'bb'\n"
                             "  x'=-a*bb\n"
                             "        ^\n");
    /* too small a buffer: truncated, terminated */
    char small[12];
    dyn_lang_diag_format(&d, small, sizeof small);
    assert_true(strlen(small) < sizeof small);
}

static void test_notes_tell_what_is_ignored(void **state)
{
    (void)state;
    notes n;
    char *out = expect_ok("x'=-x\n@ xlo=0, xhi=20, ylo=-2 maxstor=100000\n"
                          "@ ntst=50, meth=qualrk\nset hopf {a=1}\n",
                          &n);
    /* the window of the phase plane is the model's (an axis with lo < hi), not a note */
    CHECK(strstr(out, ".phase_window = {0.0, 20.0, (-2.0), 0.0}"), "%s", out);
    free(out);
    CHECK(!strstr(n.text, "option 'xlo'") && !strstr(n.text, "option 'ylo'"), "%s", n.text);
    CHECK(strstr(n.text, "2: option 'maxstor' is accepted and ignored"), "%s", n.text);
    CHECK(strstr(n.text, "3: option 'ntst' is AUTO's: dynkit continue reads it"), "%s", n.text);
    CHECK(strstr(n.text, "3: meth=qualrk runs as dynkit's dp45"), "%s", n.text);
    CHECK(strstr(n.text, "4: 'set'"), "%s", n.text);
    /* formulas as values: computed, and the difference from XPPAUT 6.11's atof said */
    out = expect_ok("par a=2*pi, b=-0.5\nx'=a\ny'=b\ny(0)=a\n", &n);
    CHECK(strstr(out, "{\"a\", \"\", \"\", 0 * sizeof(double), 6.2831853071795862}"), "%s", out);
    free(out);
    CHECK(strstr(n.text, "1: the value of 'a' is a formula, '2*pi': dynkit computes it; XPPAUT "
                         "6.11 reads only the number it starts with (2)"),
          "%s", n.text);
    CHECK(strstr(n.text, "4: the value of 'y' is a formula, 'a'"), "%s", n.text);
    CHECK(!strstr(n.text, "'b'"), "a signed number is a number: %s", n.text);
    /* an initial value given twice: the last one, as in XPPAUT 6.11, and said; nout with
     * an adaptive meth ignored, as XPPAUT does, and said */
    out = expect_ok("x'=-x\nx(0)=3\ninit x=1\n@ meth=cvode, nout=5\n", &n);
    free(out);
    CHECK(strstr(n.text, "3: the initial value of x is given again (before, on line 2): the "
                         "last one is used"),
          "%s", n.text);
    CHECK(strstr(n.text, "4: nout=5 is ignored with meth=cvode"), "%s", n.text);
    /* XPPAUT reads x>1+2 as (x>1)+2: said, not changed */
    out = expect_ok("x'=x>1+2\n", &n);
    free(out);
    CHECK(strstr(n.text, "a>b+c is read as (a>b)+c"), "%s", n.text);
    out = expect_ok("x'=(x>1)+2\n", &n);
    free(out);
    assert_int_equal(n.count, 0);
}

/* meth: XPPAUT's names, and their beginnings as XPPAUT takes them (measured with xppaut:
 * meth=r runs rungekutta, meth=8 83dp, meth=m modeuler), to dynkit's methods. */
static void test_meth_maps_to_dynkit_methods(void **state)
{
    (void)state;
    static const struct {
        const char *meth, *method;
    } cases[] = {
        {"euler", "euler"},   {"e", "euler"},       {"modeuler", "heun"},  {"m", "heun"},
        {"rungekutta", "rk4"}, {"r", "rk4"},        {"runge", "rk4"},      {"RK4", "rk4"},
        {"adams", "rk4"},     {"gear", "rodas4"},   {"stiff", "rodas4"},   {"cvode", "rodas4"},
        {"backeul", "rodas4"}, {"2rb", "rodas4"},   {"volterra", "rodas4"}, {"qualrk", "dp45"},
        {"q", "dp45"},        {"5dp", "dp45"},      {"dopri5", "dp45"},    {"83dp", "dop853"},
        {"8", "dop853"},      {"ymp", "rk4"},       {"heun", "heun"},      {"midpoint", "midpoint"},
        {"bs23", "bs23"},     {"rosen", "rodas4"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char text[128], want[64];
        snprintf(text, sizeof text, "x'=-x\n@ meth=%s\n", cases[i].meth);
        snprintf(want, sizeof want, ".method = \"%s\",", cases[i].method);
        char *out = expect_ok(text, NULL);
        CHECK(strstr(out, want), "meth=%s: expected %s", cases[i].meth, want);
        free(out);
    }
    /* no meth, no tolerances: none named, so that the model runs by the rule of every model
     * (DYN_MODEL_METHOD dp45, DYN_MODEL_RTOL 1e-6, DYN_MODEL_ATOL 1e-9); or the file's */
    char *out = expect_ok("x'=-x\n", NULL);
    CHECK(strstr(out, ".method = NULL,") && strstr(out, ".rtol = 0.0,") &&
              strstr(out, ".atol = 0.0,"),
          "%s", out);
    free(out);
    out = expect_ok("x'=-x\n@ tol=1e-4, atol=1e-5\n", NULL);
    CHECK(strstr(out, ".rtol = 0.0001,") && strstr(out, ".atol = 1.0000000000000001e-05,"),
          "%s", out);
    free(out);
    out = expect_ok("x'=-x\n@ meth=d\n", NULL); /* XPPAUT: any prefix of discrete */
    CHECK(strstr(out, ".method = \"discrete\","), "%s", out);
    free(out);
}

/* Lookup tables (XPPAUT's manual, "table"): a formula of t over npts abscissas, computed by
 * prepare with the parameters (so --set re-evaluates it) into the parameter array after the
 * derived parameters; a call interpolates linearly; its derivative is the segment's slope.
 * Mistakes are refused at their place. */
static void test_lookup_tables(void **state)
{
    (void)state;
    char *out = expect_ok("table w % 11 -5 5 a*t\npar a=2, b=1\n!c=a+b\nx'=-x+w(x)\n", NULL);
    CHECK(strstr(out, "for (long k = 0; k < 11; k++)") && strstr(out, "p[3 + k] = (p[0] * t)") &&
              strstr(out, "dk_table(p + 3, 11, (-5.0), 1.0, y[0])") &&
              strstr(out, "dk_table_slope(p + 3, 11, (-5.0), 1.0, y[0])") &&
              strstr(out, ".par_size = 14 * sizeof(double)"),
          "%s", out);
    free(out);
    /* XPPAUT reads any word that begins with tab as table (nnet2.ode's tabular), and takes
     * table % NAME ... too */
    out = expect_ok("tabular w % 25 -12 12 1/25\ntable % v 2 0 1 w(t)\nx'=v(x)\n", NULL);
    CHECK(strstr(out, "p[0 + k] = (1.0 / 25.0)") && strstr(out, "dk_table(p + 25, 2,"), "%s",
          out);
    free(out);
    expect_error("x'=w\ntable w % 3 0 1 t\n", 1, 4, "'w' is a table: look a value up with w(x)");
    expect_error("x'=w(1,2)\ntable w % 3 0 1 t\n", 1, 4, "takes 1 argument");
    expect_error("table w % 0 0 1 t\nx'=1\n", 1, 7, "0 points");
    expect_error("table w % 2.5 0 1 t\nx'=1\n", 1, 7, "2.5 points");
    expect_error("table w % 3 1 1 t\nx'=1\n", 1, 7, "must be above the first");
    expect_error("table w % 3 0\nx'=1\n", 1, 14, "the last abscissa");
    expect_error("table w % 3 0 1 x\nx'=1\n", 1, 17, "cannot depend on the state 'x'");
    expect_error("table w % 3 0 1 v(t)\ntable v % 3 0 1 t\nx'=1\n", 1, 17,
                 "uses table 'v', defined after it");
    expect_error("par a=1\n!b=w(a)\ntable w % 3 0 1 t\nx'=1\n", 2, 4,
                 "a derived parameter cannot use the table 'w'");
    expect_error("table w % 3 0 1 t\nf(u)=w(u)\ninit x=f(1)\nx'=1\n", 3, 8,
                 "cannot call 'f', which depends on a table");
    expect_error("table w no_such_file.tab\nx'=1\n", 1, 9, "cannot read 'no_such_file.tab'");
    expect_error("table w % 3 -1e308 1e308 t\nx'=1\n", 1, 7, "not finite numbers with a finite "
                 "span");
}

/* Network sums (XPPAUT's `special NAME=conv(...)`): computed after the fixed quantities
 * of the functions that use them (the block of fixed quantities it sums over with them),
 * element j as NAME(j); no analytic Jacobian (finite differences, with a note). Mistakes
 * are refused at their place. */
static void test_network_sums_translate(void **state)
{
    (void)state;
    notes n = {0};
    char *out = expect_ok("table w % 3 -1 1 1\nf[0..3]=heav(u[j])\nspecial z=conv(even,4,1,w,f0)\n"
                          "u[0..3]'=-u[j]+z([j])\n", &n);
    CHECK(strstr(out, "const double spu_0[4] = {v_0, v_1, v_2, v_3};") &&
              strstr(out, "dk_conv(sp_0, 4, 1, 1, p + 0, spu_0);") &&
              strstr(out, "dydt[3] = ((-y[3]) + sp_0[3]);") && !strstr(out, "dk_jacobian(double"),
          "%s", out);
    CHECK(strstr(n.text, "no analytic Jacobian: network sums"), "notes: %s", n.text);
    free(out);
    out = expect_ok("tab w % 3 -1 1 1\nspecial k=conv(period,2,1,w,x0)\nx[0..1]'=k([j])\n", NULL);
    CHECK(strstr(out, "dk_conv(sp_0, 2, 1, 2, p + 0, (y + 0));"), "%s", out);
    free(out);
    expect_error("table w % 3 -1 1 1\nspecial k=conv(even,2,1,w,x0)\nx[0..1]'=k(2)\n", 3, 12,
                 "from 0 to 1");
    expect_error("table w % 3 -1 1 1\nspecial k=conv(even,2,1,w,x0)\nx[0..1]'=k\n", 3, 10,
                 "'k' is a network sum");
    expect_error("table w % 3 -1 1 1\nspecial k=conv(even,3,1,w,x0)\nx[0..1]'=k(0)\n", 2, 27,
                 "sums 3 states from 'x0' on, and there are only 2");
    expect_error("table w % 3 -1 1 1\nspecial k=conv(odd,2,1,w,x0)\nx[0..1]'=k(0)\n", 2, 16,
                 "conv's type is even, periodic or 0");
    expect_error("special k=conv(even,2,1,v,x0)\nx[0..1]'=k(0)\n", 1, 25, "'v' is not declared");
    expect_error("par a=1,b=2\nspecial k=gill(0,a,b)\nx[0..1]'=0\n", 2, 9,
                 "draws one reaction per step of a discrete map");
    expect_error("table w % 3 -1 1 1\nspecial k=mmult(2,2,w,x0)\nx[0..1]'=0\n", 2, 21,
                 "mmult takes m n = 4 weights, and table 'w' has 3 points");
    expect_error("table w % 3 -1 1 1\nspecial a=conv(0,40000,1,w,x0)\n"
                 "special b=conv(0,40000,1,w,x0)\nx[0..39999]'=a([j])+b([j])\n", 3, 9,
                 "network sums of more than 65536 elements");
    expect_error("table w % 3 -1 1 1\nspecial k=conv(even,2,1,w,x0)\nf=k(0)\nx[0..1]'=f\n", 3, 1,
                 "uses a network sum");
}

/* Difference equations (XPPAUT's manual): x(t+1)= or meth=discrete make the file a map,
 * iterated by the method "discrete" one step per unit of time whatever dt says; what cannot
 * be a map is refused with its place. */
static void test_difference_equations(void **state)
{
    (void)state;
    char *out = expect_ok("z(t+1)=a*z*(1-z)\npar a=3.7\ninit z=0.2\n@ total=100, dt=0.5\n",
                          NULL);
    CHECK(strstr(out, ".method = \"discrete\",") && strstr(out, ".step = 1.0,") &&
              strstr(out, ".t1 = 100.0,"),
          "%s", out);
    free(out);
    /* x'= lines of a map are iterated too, as in XPPAUT */
    out = expect_ok("x(t+1)=x/2\ny'=y+1\n", NULL);
    CHECK(strstr(out, ".method = \"discrete\","), "%s", out);
    free(out);
    expect_error("x(t+2)=x\n", 1, 5, "steps by 1");
    /* as in XPPAUT: x(t+1)= makes a map whatever meth says; the last meth counts; a map's
     * total is its whole steps */
    notes n = {0};
    out = expect_ok("x(t+1)=x/2\n@ meth=rk4, total=4.5\n", &n);
    CHECK(strstr(out, ".method = \"discrete\",") && strstr(out, ".t1 = 4.0,") &&
              strstr(n.text, "meth=rk4 is ignored") && strstr(n.text, "total=4.5"),
          "%s\n%s", n.text, out);
    free(out);
    out = expect_ok("x'=-x\n@ meth=discrete\n@ meth=euler\n", NULL);
    CHECK(strstr(out, ".method = \"euler\","), "%s", out);
    free(out);
    expect_error("x(t+1)=x/2\nglobal 1 x-1 {x=0}\n", 2, 1, "events and globals are not supported "
                                                           "in a discrete map");
}

/* Files from other systems: a byte order mark, CRLF line ends, tabs. */
/* @ bandlo, bandup fill the model's band: with the analytic band Jacobian (up to 400
 * states) or, above, banded differences after the check of the states each equation
 * reads; only the band's entries are written */
static void test_band_options_fill_the_model(void **state)
{
    (void)state;
    char *small = expect_ok("x0'=x1-2*x0\nx[1..8]'=x[j-1]-2*x[j]+x[j+1]\nx9'=x8-2*x9\n"
                            "@ bandlo=1,bandup=1\n",
                            NULL);
    assert_non_null(strstr(small, ".jac_banded = 1"));
    assert_non_null(strstr(small, ".jac_lower = 1"));
    assert_non_null(strstr(small, ".jacobian_band = dk_jacobian_band"));
    free(small);
    char *big = expect_ok("x0'=-x0\nx[1..450]'=x[j-1]-x[j]\n@ bandlo=1,bandup=0\n", NULL);
    assert_non_null(strstr(big, ".jac_banded = 1"));
    assert_non_null(strstr(big, ".jac_upper = 0"));
    assert_non_null(strstr(big, ".jacobian_band = NULL"));
    assert_null(strstr(big, "dk_jacobian_band("));
    free(big);
}

static void test_bom_crlf_and_tabs(void **state)
{
    (void)state;
    char *out = expect_ok("\xef\xbb\xbfpar a=1\r\nx'=\t-a*x \\\r\n\t+ 1\r\n", NULL);
    CHECK(strstr(out, "dydt[0] = (((-p[0]) * y[0]) + 1.0);"), "%s", out);
    free(out);
    expect_error("\xef\xbb\xbfx'=qq\r\n", 1, 7, "unknown name 'qq'");
}

static void test_generated_c_conventions(void **state)
{
    (void)state;
    char *out = expect_ok("# decay\npar k=2\nw=k*x\nx'=-w\naux e=x^2\nf(a)=a+1\n"
                          "x(0)=f(k)\n",
                          NULL);
    /* fixed quantities, functions and arguments by their number, never by their name */
    CHECK(strstr(out, "#line 4 \"m.ode\"\n    dydt[0] = (-v_0);"), "%s", out);
    CHECK(strstr(out, "#line 3 \"m.ode\"\n    const double v_0 = (p[0] * y[0]);"), "%s", out);
    CHECK(strstr(out, "static double u_0(double a_0, double t, const double *y, const double "
                      "*p)"),
          "%s", out);
    CHECK(strstr(out, "const dyn_model *dynkit_model(void)"), "%s", out);
    CHECK(strstr(out, ".initial_state = dk_initial_state"), "%s", out);
    CHECK(strstr(out, ".jacobian = dk_jacobian"), "%s", out);
    CHECK(strstr(out, ".source = \"m.ode\""), "%s", out);
    CHECK(strstr(out, ".name = \"m\""), "%s", out);
    /* the path is escaped in strings and #line */
    free(out);
    char *o2 = NULL;
    dyn_lang_diag d;
    assert_int_equal(dyn_ode_to_c("a\"b\\c.ode", "x'=1\n", 5, &o2, &d, NULL, NULL), 0);
    CHECK(strstr(o2, "#line 1 \"a\\\"b\\\\c.ode\""), "%s", o2);
    free(o2);
}

static void test_limits_are_refused_with_a_message(void **state)
{
    (void)state;
    /* nesting */
    char *deep = malloc(20000);
    strcpy(deep, "x'=");
    for (int i = 0; i < 5000; i++)
        strcat(deep, "(");
    strcat(deep, "x");
    for (int i = 0; i < 5000; i++)
        strcat(deep, ")");
    char *out;
    dyn_lang_diag d;
    assert_int_equal(translate(deep, &out, &d, NULL), 2);
    CHECK(strstr(d.message, "nested too deeply"), "%s", d.message);
    strcpy(deep, "x'=");
    for (int i = 0; i < 5000; i++)
        strcat(deep, "-");
    strcat(deep, "x\n");
    assert_int_equal(translate(deep, &out, &d, NULL), 2);
    CHECK(strstr(d.message, "nested too deeply"), "%s", d.message);
    free(deep);
    /* functions that read a fixed quantity take it as an argument: 2^38 calls are 39 C
     * functions (and their partial derivatives), a text of linear size */
    char *bomb = malloc(4096);
    strcpy(bomb, "phi=2*x\nf1(a)=phi*a\n");
    for (int i = 2; i < 40; i++)
        sprintf(bomb + strlen(bomb), "f%d(a)=f%d(a)+f%d(a)\n", i, i - 1, i - 1);
    strcat(bomb, "x'=f39(x)\n");
    assert_int_equal(translate(bomb, &out, &d, NULL), 0);
    CHECK(strlen(out) < 100000 && strstr(out, ".jacobian = dk_jacobian"), "%zu bytes",
          strlen(out));
    free(out);
    /* with more than 20 arguments and fixed quantities together the calls are expanded
     * where they are called: 2^40 copies are refused */
    strcpy(bomb, "");
    for (int i = 0; i < 20; i++)
        sprintf(bomb + strlen(bomb), "q%d=x+%d\n", i, i);
    strcat(bomb, "f1(a)=a*(q0+q1+q2+q3+q4+q5+q6+q7+q8+q9+q10+q11+q12+q13+q14+q15+q16+q17+q18"
                 "+q19)\n");
    for (int i = 2; i < 40; i++)
        sprintf(bomb + strlen(bomb), "f%d(a)=f%d(a)+f%d(a)\n", i, i - 1, i - 1);
    strcat(bomb, "x'=f39(x)\n");
    assert_int_equal(translate(bomb, &out, &d, NULL), 2);
    CHECK(strstr(d.message, "too deeply to expand"), "%s", d.message);
    /* reading states, they are C functions, but differentiated inline: the Jacobian is left
     * out, the model stays */
    strcpy(bomb, "f1(a)=sin(a)*x\n");
    for (int i = 2; i < 40; i++)
        sprintf(bomb + strlen(bomb), "f%d(a)=f%d(a)*f%d(a)\n", i, i - 1, i - 1);
    strcat(bomb, "x'=f39(x)\n");
    notes n;
    assert_int_equal(translate(bomb, &out, &d, &n), 0);
    CHECK(strstr(out, ".jacobian = NULL"), "the Jacobian is left out");
    CHECK(strstr(n.text, "no analytic Jacobian"), "%s", n.text);
    free(out);
    free(bomb);
    expect_error("x[1..1000000]'=1\n", 1, 2, "too long");
    expect_error("x[5..1]'=1\n", 1, 2, "empty array range");
    /* NULL arguments */
    assert_int_equal(dyn_ode_to_c("m.ode", NULL, 5, &out, &d, NULL, NULL), 2);
    assert_int_equal(dyn_ode_to_c("m.ode", "x'=1", 4, NULL, &d, NULL, NULL), 2);
    assert_int_equal(dyn_ode_to_c(NULL, "x'=1", 4, &out, NULL, NULL, NULL), 0);
    free(out);
}

/* Every prefix of a file and a few byte flips translate or fail cleanly (the fuzzer does
 * more: fuzz/fuzz_ode.c). */
static void test_truncated_and_damaged_files_never_crash(void **state)
{
    (void)state;
    static const char text[] =
        "# bouncing\n#: title Ball\n#: y [m] height\npar g=9.81, e=.8\n!h=g/2\n"
        "f(a,b)=a*b+if(a>b)then(a)else(-b)\nw=f(y,v)\ny'=v\nv'=-g+0*w\n"
        "x[1..3]'=-x[j]+[j]\n%[1..2]\nz[j]'=z[j]\n%\n"
        "global -1 y {v=-e*v;y=0}\n#: event top = v, falling, stop -- apex\n"
        "init y=1,v=0\naux en=v^2/2+g*y\n@ dt=.01, total=3, meth=rk4, xp=y, yp=v\ndone\n";
    const size_t n = strlen(text);
    char *buf = malloc(n + 1);
    for (size_t len = 0; len <= n; len++) {
        char *out = NULL;
        dyn_lang_diag d;
        memcpy(buf, text, len);
        const int rc = dyn_ode_to_c("m.ode", buf, len, &out, &d, NULL, NULL);
        assert_true(rc == 0 || rc == 2);
        assert_true((rc == 0) == (out != NULL));
        free(out);
    }
    for (size_t at = 0; at < n; at += 3) {
        static const char flips[] = "([{}])=#'\\\n%!@,;.-0";
        for (const char *f = flips; *f; f++) {
            memcpy(buf, text, n);
            buf[at] = *f;
            char *out = NULL;
            dyn_lang_diag d;
            const int rc = dyn_ode_to_c("m.ode", buf, n, &out, &d, NULL, NULL);
            assert_true(rc == 0 || rc == 2);
            free(out);
        }
    }
    free(buf);
}

/* Real files of XPPAUT's examples (Debian's xppaut package) translate. */
static void test_xppaut_examples_translate(void **state)
{
    (void)state;
    static const char *const files[] = {"lorenz.ode", "fhn.ode",   "delta.ode", "tyson.ode",
                                        "hhred.ode",  "torus.ode", "pend.ode",  "doubpend.ode", "chemotax.ode", "waterwheel.ode", "wcring.ode",
                                        "rossler.ode", "angela.ode"};
    int found = 0;
    for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
        char path[512];
        snprintf(path, sizeof path, "/usr/share/doc/xppaut/examples/ode/%s", files[i]);
        FILE *f = fopen(path, "rb");
        if (!f)
            continue;
        found++;
        static char text[1 << 16];
        const size_t len = fread(text, 1, sizeof text, f);
        fclose(f);
        char *out = NULL;
        dyn_lang_diag d;
        const int rc = dyn_ode_to_c(path, text, len, &out, &d, NULL, NULL);
        char buf[2048];
        CHECK(rc == 0, "%s", dyn_lang_diag_format(&d, buf, sizeof buf));
        free(out);
    }
    if (!found)
        skip();
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_refused_features_name_line_and_feature),
        cmocka_unit_test(test_algebraic_equations_are_checked),
        cmocka_unit_test(test_unknown_names_suggest_the_nearest),
        cmocka_unit_test(test_kinds_of_names_are_checked),
        cmocka_unit_test(test_sums_and_shifts_are_checked),
        cmocka_unit_test(test_circular_definitions_name_the_cycle),
        cmocka_unit_test(test_syntax_errors_point_at_the_place),
        cmocka_unit_test(test_diag_format_shows_the_line_and_a_caret),
        cmocka_unit_test(test_notes_tell_what_is_ignored),
        cmocka_unit_test(test_meth_maps_to_dynkit_methods),
        cmocka_unit_test(test_difference_equations),
        cmocka_unit_test(test_lookup_tables),
        cmocka_unit_test(test_network_sums_translate),
        cmocka_unit_test(test_band_options_fill_the_model),
        cmocka_unit_test(test_bom_crlf_and_tabs),
        cmocka_unit_test(test_generated_c_conventions),
        cmocka_unit_test(test_limits_are_refused_with_a_message),
        cmocka_unit_test(test_truncated_and_damaged_files_never_crash),
        cmocka_unit_test(test_xppaut_examples_translate),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
