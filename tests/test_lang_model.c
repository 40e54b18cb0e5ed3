/* SPDX-License-Identifier: BSD-3-Clause */
/* test_lang_model.c — .ode files translated (src/lang), compiled and loaded (src/jit), then
 * run: each operator and function gives XPPAUT's value (measured with xppaut 6.11 where
 * XPPAUT's meaning differs from C's: priorities, heav(0), sign(0), mod of negatives),
 * temporaries in dependency order, derived parameters, user functions, arrays, globals'
 * resets applied in sequence, the extensions in `#:` lines, the options as the model's
 * default run; the homework's van der Pol and pendulum written as .ode files reproduce the
 * built-in right-hand sides bit for bit; an exact solution; the analytic Jacobian against
 * finite differences on several files; and a band declared by @ bandlo, bandup. */
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
#include "dynkit/models.h"
#include "test_util.h"
#include "test_ode_load.h"

static void load(const char *text, loaded *L) { test_ode_load(text, "lang-jit-cache", L); }

static void unload(loaded *L) { dyn_jit_unload(&L->jm); }

static double output(const loaded *L, const char *name, double t, const double *y)
{
    double out[64];
    const int i = dyn_model_output_index(L->m, name);
    CHECK(i >= 0, "no output %s", name);
    assert_int_equal(L->m->compute_outputs(t, y, L->par, out), 0);
    return out[i];
}

static void test_operators_and_functions_give_xppauts_values(void **state)
{
    (void)state;
    loaded L;
    load("x'=0\ny'=0\n"
         /* priorities, as xppaut computes them */
         "aux p1=-2^2\naux p2=2^3^2\naux p3=1-2-3\naux p4=2**(-1)\naux p5=8/2/2\n"
         "aux p6=2*3^2\naux c1=1|1&0\naux c2=2*3>1\naux c3=3>1*2\naux c4=1+1==2\n"
         "aux c5=not 0+1\naux c6=not 0==2\naux c7=1+2&0\naux c8=3*0|1\naux c9=2^0&0\n"
         "aux d1=3>2>1\naux d2=2&3\naux d3=-2&3\naux d4=2^3>1\naux d5=if(0>1+5)then(7)else(8)\n"
         "aux d6=if(x>100)then(1)else(2)+5\naux d7=2*-3\naux d8=1<=1\naux d9=2!=2\n"
         "aux e1=1>=2\naux e2=.5e1+1e-1\n"
         /* XPPAUT's functions */
         "aux h0=heav(0)\naux h1=heav(-1e-300)\naux s0=sign(0)\naux s1=sign(-3)\n"
         "aux m1=mod(-7,3)\naux m2=mod(7,-3)\naux m3=mod(-7.5,2)\naux m4=mod(7.5,2)\n"
         "aux f1=flr(-1.5)\naux f2=ceil(-1.5)\naux x1=max(1,2)+min(1,2)\n"
         "aux l1=log(x)\naux l2=ln(x)\naux l3=log10(x)\naux a1=abs(-x)\naux a2=atan2(x,y)\n"
         /* C's values */
         "aux g1=sin(x)+cos(y)*tan(x)\naux g2=asin(x)-acos(x)/atan(y)\n"
         "aux g3=sinh(x)*cosh(y)-tanh(x)\naux g4=exp(x)*sqrt(y)\naux g5=x^y\naux g6=pi\n"
         "aux g7=erf(x)+erfc(y)\naux g8=t*2\ninit x=0.3, y=0.7\n",
         &L);
    const double y[2] = {0.3, 0.7};
    static const struct {
        const char *name;
        double v;
    } expect[] = {
        {"p1", -4},  {"p2", 64},  {"p3", -4}, {"p4", 0.5}, {"p5", 2},  {"p6", 18},
        {"c1", 1},   {"c2", 2},   {"c3", 2},  {"c4", 1},   {"c5", 2},  {"c6", 1},
        {"c7", 1},   {"c8", 1},   {"c9", 0},  {"d1", 0},   {"d2", 1},  {"d3", 1},
        {"d4", 1},   {"d5", 7},   {"d6", 7},  {"d7", -6},  {"d8", 1},  {"d9", 0},
        {"e1", 0},   {"e2", 5.1}, {"h0", 1},  {"h1", 0},   {"s0", 0},  {"s1", -1},
        {"m1", 2},   {"m2", 1},   {"m3", 0.5}, {"m4", 1.5}, {"f1", -2}, {"f2", -1},
        {"x1", 3},
    };
    for (size_t i = 0; i < sizeof expect / sizeof expect[0]; i++) {
        const double v = output(&L, expect[i].name, 0.25, y);
        CHECK(v == expect[i].v, "%s = %.17g, expected %.17g", expect[i].name, v,
              expect[i].v);
    }
    assert_true(same_bits(output(&L, "l1", 0, y), log(0.3)));
    assert_true(same_bits(output(&L, "l2", 0, y), log(0.3)));
    assert_true(same_bits(output(&L, "l3", 0, y), log10(0.3)));
    assert_true(same_bits(output(&L, "a1", 0, y), 0.3));
    assert_true(same_bits(output(&L, "a2", 0, y), atan2(0.3, 0.7)));
    assert_true(same_bits(output(&L, "g1", 0, y), sin(0.3) + cos(0.7) * tan(0.3)));
    assert_true(same_bits(output(&L, "g2", 0, y), asin(0.3) - acos(0.3) / atan(0.7)));
    assert_true(same_bits(output(&L, "g3", 0, y), sinh(0.3) * cosh(0.7) - tanh(0.3)));
    assert_true(same_bits(output(&L, "g4", 0, y), exp(0.3) * sqrt(0.7)));
    assert_true(same_bits(output(&L, "g5", 0, y), pow(0.3, 0.7)));
    assert_true(same_bits(output(&L, "g6", 0, y), 3.14159265358979323846));
    assert_true(same_bits(output(&L, "g7", 0, y), erf(0.3) + erfc(0.7)));
    assert_true(same_bits(output(&L, "g8", 0.25, y), 0.5));
    unload(&L);
}

/* The homework's van der Pol and pendulum as .ode files: the built-in right-hand sides bit
 * for bit, and so the same RK4 runs. */
static void test_homework_models_reproduce_the_built_in_ones(void **state)
{
    (void)state;
    loaded L;
    load("# van der Pol\npar mu=1\ny1'=y2\ny2'=mu*(1-y1^2)*y2-y1\ninit y1=2,y2=0\n"
         "@ meth=rk4, dt=0.01, total=15\n",
         &L);
    assert_int_equal(L.m->n_states, 2);
    assert_string_equal(L.m->method, "rk4");
    dyn_vanderpol_par vp = {.mu = 1.0};
    for (int k = 0; k < 50; k++) {
        const double y[2] = {-3 + 0.13 * k, 2.5 - 0.11 * k};
        double f1[2], f2[2];
        L.par[0] = vp.mu = 0.5 + 0.1 * k;
        L.m->rhs(0.1 * k, y, f1, L.par);
        dyn_vanderpol_rhs(0.1 * k, y, f2, &vp);
        assert_true(same_bits(f1[0], f2[0]) && same_bits(f1[1], f2[1]));
    }
    L.par[0] = vp.mu = 1.0;
    const dyn_tableau *rk4 = dyn_method_find("rk4");
    double y1[2], y2[2], work[64];
    dyn_system s1 = {L.m->rhs, 2, L.par}, s2 = {dyn_vanderpol_rhs, 2, &vp};
    dyn_result r;
    assert_int_equal(dyn_fixed_solve(rk4, &s1, L.m->t0, L.m->t1, L.m->step, L.m->y0, y1, work,
                                     NULL, &r),
                     0);
    const double y0[2] = {2, 0};
    assert_int_equal(dyn_fixed_solve(rk4, &s2, 0, 15, 0.01, y0, y2, work, NULL, &r), 0);
    assert_true(same_bits(y1[0], y2[0]) && same_bits(y1[1], y2[1]));
    unload(&L);

    load("par m=2, l=9.81, g=9.81\nphi'=dphi\ndphi'=-(g/l)*sin(phi)\n"
         "init phi=0, dphi=1.5707963267948966\n",
         &L);
    dyn_pendulum_par pp = {2.0, 9.81, 9.81};
    for (int k = 0; k < 50; k++) {
        const double y[2] = {-3 + 0.13 * k, 2.5 - 0.11 * k};
        double f1[2], f2[2];
        L.m->rhs(0, y, f1, L.par);
        dyn_pendulum_rhs(0, y, f2, &pp);
        assert_true(same_bits(f1[0], f2[0]) && same_bits(f1[1], f2[1]));
    }
    assert_true(same_bits(L.m->y0[1], DYN_PI / 2.0));
    unload(&L);
}

/* x' = -k x from x(0) = a: x(t) = a exp(-k t); the default run (no meth) names no method
 * and no tolerances (the rule of every model: dp45 at rtol 1e-6, atol 1e-9) on XPPAUT's span
 * 0..20 with dt 0.05. */
static void test_exact_solution_and_default_run(void **state)
{
    (void)state;
    loaded L;
    load("par k=0.5, a=3\n!k2=2*k\nx'=-k*x\nz'=-k2*z\nx(0)=a\ninit z=1\n", &L);
    assert_null(L.m->method);
    assert_true(L.m->rtol == 0 && L.m->atol == 0);
    assert_true(L.m->t0 == 0 && L.m->t1 == 20 && L.m->step == 0.05);
    assert_non_null(L.m->initial_state);
    double y0[2];
    dyn_model_initial_state(L.m, L.par, y0);
    assert_true(y0[0] == 3 && y0[1] == 1);
    assert_int_equal(L.m->n_params, 2); /* k2 is derived: not a parameter */
    assert_true(L.par[2] == 1.0);
    const dyn_tableau *dp45 = dyn_method_find("dp45");
    dyn_solve_opts o = {0};
    o.rtol = 1e-10;
    o.atol = 1e-12;
    const dyn_system sys = {L.m->rhs, 2, L.par};
    static double work[4096];
    assert_true(dyn_solve_work_size(dp45, 2, &o) <= 4096);
    double y[2];
    dyn_result r;
    assert_int_equal(dyn_solve(dp45, &sys, 0, 4, y0, y, work, &o, &r), 0);
    CHECK(fabs(y[0] - 3 * exp(-2.0)) < 1e-8, "x(4) = %.17g", y[0]);
    CHECK(fabs(y[1] - exp(-4.0)) < 1e-8, "z(4) = %.17g", y[1]);
    /* a new parameter: prepare computes the derived one and the initial state follows */
    L.par[0] = 1.5;
    L.par[1] = -2;
    char err[256];
    assert_int_equal(L.m->prepare(L.par, err, sizeof err), 0);
    assert_true(L.par[2] == 3.0);
    dyn_model_initial_state(L.m, L.par, y0);
    assert_true(y0[0] == -2);
    unload(&L);
}

static void test_temporaries_derived_and_functions(void **state)
{
    (void)state;
    loaded L;
    /* temporaries used before they are defined, computed in dependency order */
    load("par k=2, c=1\n!r=sqrt(k)/c\nx'=-b\nb=a*r\na=x+q(x,t)\nf(u)=u*u\n"
         "q(u,v)=f(u)+g(v)\ng(t)=3*t\nr2(x)=x+k\naux o=r2(b)\naux rr=r\n",
         &L);
    const double y[1] = {0.5};
    double dy[1];
    L.m->rhs(2.0, y, dy, L.par);
    const double r = sqrt(2.0) / 1.0, a = 0.5 + (0.25 + 6.0), b = a * r;
    CHECK(dy[0] == -b, "x' = %.17g, expected %.17g", dy[0], -b);
    assert_true(output(&L, "o", 2.0, y) == b + 2.0);
    assert_true(output(&L, "rr", 2.0, y) == r);
    /* derived parameters follow their parameters; a non-finite one is refused by prepare */
    L.par[1] = 0.0;
    char err[256];
    assert_int_not_equal(L.m->prepare(L.par, err, sizeof err), 0);
    CHECK(strstr(err, "derived parameter 'r' is not finite"), "%s", err);
    unload(&L);
}

static void test_arrays_expand_like_xppaut(void **state)
{
    (void)state;
    loaded L;
    load("x[1..3]'=-[j]*x[j]+x[j-1]\nx0=0.5\n%[1..2]\nu[j]'=v[j]\nv[j]'=-[j*j]*u[j]\n%\n"
         "init x[1..3]=[j]\naux s[2..3]=x[j]+10*[j]\n",
         &L);
    assert_int_equal(L.m->n_states, 7);
    static const char *const names[] = {"x1", "x2", "x3", "u1", "v1", "u2", "v2"};
    for (int i = 0; i < 7; i++)
        assert_string_equal(L.m->states[i].name, names[i]);
    assert_true(L.m->y0[0] == 1 && L.m->y0[1] == 2 && L.m->y0[2] == 3 && L.m->y0[3] == 0);
    const double y[7] = {1, 2, 3, 4, 5, 6, 7};
    double dy[7];
    L.m->rhs(0, y, dy, L.par);
    const double expect[7] = {-1 + 0.5, -4 + 1, -9 + 2, 5, -4, 7, -24};
    for (int i = 0; i < 7; i++)
        CHECK(dy[i] == expect[i], "dy[%d] = %g, expected %g", i, dy[i], expect[i]);
    assert_int_equal(L.m->n_outputs, 2);
    assert_true(output(&L, "s3", 0, y) == 33);
    unload(&L);
}

/* A list statement (init, par, number, wiener) reads a range per item: `init
 * u[3..4]=1.05,v[3..4]=1.05` sets u3, u4, v3 and v4, each item over its own range with its
 * own [j]; items without a range between them as usual. */
static void test_list_ranges_per_item(void **state)
{
    (void)state;
    loaded L;
    load("u[1..4]'=-u[j]\nv[1..4]'=-v[j]\ninit u[3..4]=1.05,v[3..4]=[j]*10, u1=7\n"
         "par a[1..2]=3, k=0.5, b[1..3]=[j]*2\nnumber n[1..2]=[j]+0.25, m=1\n"
         "aux s=a1+a2+k+b1+b2+b3\naux sn=n1+n2+m\n",
         &L);
    assert_int_equal(L.m->n_states, 8);
    const double y0[8] = {7, 0, 1.05, 1.05, 0, 0, 30, 40};
    for (int i = 0; i < 8; i++)
        CHECK(L.m->y0[i] == y0[i], "%s(0) = %g, expected %g", L.m->states[i].name, L.m->y0[i],
              y0[i]);
    assert_int_equal(L.m->n_params, 6);
    const double y[8] = {0};
    assert_true(output(&L, "s", 0, y) == 3 + 3 + 0.5 + 2 + 4 + 6);
    assert_true(output(&L, "sn", 0, y) == 1.25 + 2.25 + 1);
    unload(&L);
}

/* sum(j1,j2)of(...i'...) and shift(name,k), unrolled: XPPAUT's manual gives sum(1,10)of(i')
 * = 55 and shift(u0,2) = u2. */
static void test_sums_and_shifts(void **state)
{
    (void)state;
    loaded L;
    load("par w0=0.5, w1=0.25, w2=0.125\nu[0..2]'=-u[j]+shift(w0,[j])\nu[3..4]'=-u[j]\n"
         "aux s55=sum(1,10)of(i')\naux su=sum(0,4)of(shift(u0,i'))\n"
         "aux sw=sum(0,2)of(shift(w0,i')*i')\naux ux2=shift(u0,2)\naux e=sum(3,2)of(i')\n"
         "c[0..2]=u[j]*[j]\naux sc=sum(0,2)of(shift(c0,i'))\n",
         &L);
    const double y[5] = {1, 2, 3, 4, 5};
    assert_true(output(&L, "s55", 0, y) == 55);
    assert_true(output(&L, "su", 0, y) == 15);
    assert_true(output(&L, "sw", 0, y) == 0.25 + 0.25);
    assert_true(output(&L, "ux2", 0, y) == 3);
    assert_true(output(&L, "e", 0, y) == 0); /* an empty sum */
    assert_true(output(&L, "sc", 0, y) == 0 * 1 + 1 * 2 + 2 * 3);
    double dy[5];
    L.m->rhs(0, y, dy, L.par);
    assert_true(dy[0] == -1 + 0.5 && dy[1] == -2 + 0.25 && dy[2] == -3 + 0.125);
    unload(&L);
}

/* The longest sum the manual allows (100000 terms, docs/model-files.md) is unrolled and
 * kept shallow: sum(0,99999)of(i') = 99999 * 100000 / 2, exact in doubles; a sum of 300
 * terms (past one left-to-right chunk) gives Gauss's n(n+1)/2 as well. */
static void test_the_longest_sum_is_read(void **state)
{
    (void)state;
    loaded L;
    load("x'=-x\naux big=sum(0,99999)of(i')\naux mid=sum(1,300)of(i')\n", &L);
    const double y[1] = {1};
    assert_true(output(&L, "big", 0, y) == 4999950000.0);
    assert_true(output(&L, "mid", 0, y) == 45150.0);
    unload(&L);
}

/* XPPAUT applies a global's assignments in sequence (xppaut 6.11: x=0;y=x+10;z=y gives
 * y = z = 10); the solver restarts from the reset state. */
static void test_globals_reset_in_sequence(void **state)
{
    (void)state;
    loaded L;
    load("x'=1\ny'=0\nz'=0\n#: event wrap -- x back to 0\nglobal 1 x-1.05 {x=0;y=x+10;z=y}\n"
         "global -1 y+1 {y=0}\n",
         &L);
    assert_int_equal(L.m->n_events, 2);
    const dyn_event *ev = &L.m->events[0];
    assert_string_equal(ev->name, "wrap");
    assert_string_equal(ev->description, "x back to 0");
    assert_int_equal(ev->direction, 1);
    assert_int_equal(ev->terminal, 0);
    assert_non_null(ev->reset);
    assert_string_equal(L.m->events[1].name, "global2");
    assert_int_equal(L.m->events[1].direction, -1);
    double y[3] = {1.05, 7, 7};
    assert_true(ev->g(1.05, y, L.par) == 0.0);
    assert_int_equal(ev->reset(1.05, y, L.par), 0);
    assert_true(y[0] == 0 && y[1] == 10 && y[2] == 10);
    /* a run: x wraps at 1.05 and 2.1, so x(2.5) = 0.4 */
    const dyn_tableau *dp45 = dyn_method_find("dp45");
    dyn_solve_opts o = {0};
    o.rtol = 1e-10;
    o.atol = 1e-12;
    o.events = L.m->events;
    o.n_events = 1;
    static double work[8192];
    assert_true(dyn_solve_work_size(dp45, 3, &o) <= 8192);
    const double y0[3] = {0, 0, 0};
    dyn_result r;
    const dyn_system sys = {L.m->rhs, 3, L.par};
    assert_int_equal(dyn_solve(dp45, &sys, 0, 2.5, y0, y, work, &o, &r), 0);
    CHECK(fabs(y[0] - 0.4) < 1e-9 && y[1] == 10, "x(2.5) = %.17g, y = %g", y[0], y[1]);
    assert_int_equal(r.events, 2);
    unload(&L);
}

static void test_extensions_and_options_fill_the_model(void **state)
{
    (void)state;
    loaded L;
    load("# A ball on a spring\n# with damping\n#: title Damped spring\n"
         "#: x [m] position of the ball\n#: v [m/s] its velocity\n#: k [N/m] stiffness\n"
         "#: e [J] energy\n#: description Hooke's law.\n"
         "par k=4, c=0.1\nx'=v\nv'=-k*x-c*v\naux e=(v^2+k*x^2)/2\ninit x=1\n"
         "#: event turn = v, falling, stop -- the ball turns back\n"
         "#: event cross = x, both\n"
         "@ total=10, t0=1, dt=0.02, meth=rungekutta, xp=x, yp=V, nout=5, trans=2,\\\n"
         "  bound=1000, tol=1e-7, atol=1e-8, xlo=-2\ndone\nthis line is not read\n",
         &L);
    const dyn_model *m = L.m;
    assert_string_equal(m->name, "m");
    assert_string_equal(m->title, "Damped spring");
    assert_string_equal(m->description, "A ball on a spring\nwith damping\nHooke's law.");
    assert_string_equal(m->states[0].unit, "m");
    assert_string_equal(m->states[0].description, "position of the ball");
    assert_string_equal(m->states[1].unit, "m/s");
    assert_string_equal(m->params[0].unit, "N/m");
    assert_string_equal(m->params[1].unit, ""); /* not given */
    assert_string_equal(m->outputs[0].unit, "J");
    assert_true(m->t0 == 1 && m->t1 == 11 && m->step == 0.02);
    assert_string_equal(m->method, "rk4");
    assert_true(m->rtol == 1e-7 && m->atol == 1e-8);
    assert_true(m->every == 5 && m->t_trans == 2 && m->bound == 1000);
    assert_string_equal(m->phase_x, "x");
    assert_string_equal(m->phase_y, "v"); /* the declared spelling */
    assert_string_equal(m->source, "m.ode");
    assert_int_equal(m->n_events, 2);
    assert_string_equal(m->events[0].name, "turn");
    assert_int_equal(m->events[0].direction, -1);
    assert_int_equal(m->events[0].terminal, 1);
    assert_null(m->events[0].reset);
    assert_string_equal(m->events[0].description, "the ball turns back");
    assert_int_equal(m->events[1].direction, 0);
    assert_int_equal(m->events[1].terminal, 0);
    const double y[2] = {0.5, -0.25};
    assert_true(m->events[0].g(0, y, L.par) == -0.25);
    unload(&L);
}

/* nout as XPPAUT 6.11 reads it: with its adaptive methods (gear, qualrk, stiff, cvode, 5dp,
 * 83dp, 2rb) it writes a sample every dt and ignores nout (`@ dt=.1,total=10,nout=10`: 101
 * rows, 11 with euler, rungekutta, backeul ...), whichever of meth and nout comes first. */
static void test_nout_is_ignored_with_an_adaptive_meth(void **state)
{
    (void)state;
    static const struct {
        const char *options;
        long every;
    } cases[] = {
        {"meth=qualrk, dt=.1, nout=10", 1}, {"nout=10, meth=cvode", 1},
        {"meth=83dp, nout=10", 1},          {"meth=gear, njmp=3", 1},
        {"meth=2rb, nout=4", 1},            {"meth=dopri5, nout=4", 1},
        {"meth=rungekutta, nout=10", 10},   {"meth=backeul, nout=10", 10},
        {"meth=euler, nout=7", 7},          {"nout=10", 10},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char text[200];
        snprintf(text, sizeof text, "x'=-x\ninit x=1\n@ %s\ndone\n", cases[i].options);
        loaded L;
        load(text, &L);
        CHECK(L.m->every == cases[i].every, "@ %s: every %ld, expected %ld", cases[i].options,
              (long)L.m->every, cases[i].every);
        unload(&L);
    }
}

/* Names that are C keywords or libm functions, and case folding, compile and mean the file's
 * names. */
static void test_names_cannot_clash_with_c(void **state)
{
    (void)state;
    loaded L;
    load("par y=2, p=3, double=5, DYDT=7\nwhile'=-Y*while\npow'=P*pow+double\nJ=dydt+1\n"
         "aux return=J\nmain(struct)=struct+1\naux out=main(while)\n",
         &L);
    const double y[2] = {1.5, 2};
    double dy[2];
    L.m->rhs(0, y, dy, L.par);
    assert_true(dy[0] == -3 && dy[1] == 11);
    assert_true(output(&L, "return", 0, y) == 8);
    assert_true(output(&L, "out", 0, y) == 2.5);
    assert_string_equal(L.m->states[0].name, "while");
    unload(&L);
}

/* The analytic Jacobian against central differences at several points, where f is smooth
 * (the one-sided differences agree; piecewise functions jump elsewhere). */
static void check_jacobian(const char *text)
{
    loaded L;
    load(text, &L);
    const dyn_model *m = L.m;
    const int n = m->n_states;
    assert_non_null(m->jacobian);
    assert_true(n <= 8);
    int checked = 0, entries = 0;
    for (int pt = 0; pt < 6; pt++) {
        double y[8], J[64], f1[8], f2[8], f0[8];
        const double t = 0.3 + 0.7 * pt;
        for (int i = 0; i < n; i++)
            y[i] = 0.37 + 0.21 * i - 0.13 * pt + 0.05 * i * pt;
        assert_int_equal(m->jacobian(t, y, J, L.par), 0);
        for (int j = 0; j < n; j++) {
            const double h = 1e-6 * fmax(1.0, fabs(y[j]));
            double yp[8], ym[8];
            memcpy(yp, y, sizeof y);
            memcpy(ym, y, sizeof y);
            yp[j] += h;
            ym[j] -= h;
            m->rhs(t, yp, f1, L.par);
            m->rhs(t, ym, f2, L.par);
            m->rhs(t, y, f0, L.par);
            for (int i = 0; i < n; i++) {
                const double fd = (f1[i] - f2[i]) / (2 * h);
                const double dp = (f1[i] - f0[i]) / h, dm = (f0[i] - f2[i]) / h;
                entries++;
                if (fabs(dp - dm) > 1e-3 * fmax(1.0, fabs(dp)))
                    continue; /* a jump or a kink between y - h and y + h */
                checked++;
                CHECK(fabs(fd - J[i * n + j]) <= 1e-6 * fmax(1.0, fabs(fd)),
                      "%s\npoint %d: J[%d][%d] = %.12g, differences %.12g", text, pt, i, j,
                      J[i * n + j], fd);
            }
        }
    }
    CHECK(checked >= entries * 3 / 4, "%s\nonly %d of %d entries where f is smooth", text,
          checked, entries);
    unload(&L);
}

static void test_jacobian_matches_finite_differences(void **state)
{
    (void)state;
    check_jacobian("par mu=3\ny1'=y2\ny2'=mu*(1-y1^2)*y2-y1\n");
    check_jacobian("par s=10, r=28, b=2.667\nx'=s*(y-x)\ny'=x*(r-z)-y\nz'=x*y-b*z\n");
    check_jacobian("par k=2\nw=k*x*y\nu=sin(w)+x^3\nx'=u*y-exp(-w)\ny'=-w/(1+u^2)+sqrt(x+2)\n");
    check_jacobian("f(a,b)=a*b^2+sin(a)\ng(c)=f(c,c)+tanh(c)\nx'=g(x*y)+f(y,t)\n"
                   "y'=ln(x+3)-log10(y+4)*atan(x)\n");
    check_jacobian("x'=abs(x-0.11)+max(x,y)-min(x*y,0.2)+heav(x)+sign(y)+flr(x)\n"
                   "y'=if(x>y)then(x^2)else(y^3)+mod(x+5,0.7)+mod(3,y+1)\n"
                   "z'=atan2(x,z+2)+(x+2)^y+2^z+(z+2)^2.5+asin(x/3)+acos(z/4)+cosh(y)+sinh(z)\n");
    check_jacobian("h(x)=x*k1\nk1=y*2\nx'=h(x)+y\ny'=cos(x)*tan(y/3)+erf(x)+erfc(y)\n");
    check_jacobian("x[1..4]'=x[j-1]-2*x[j]+x[j+1]+x[j]^2\nx0=0\nx5=1\n");
    check_jacobian("x[0..3]'=sum(0,3)of(cos(i'-[j])*shift(x0,i'))*x[j]\n");
}

/* XPPAUT's @ bandlo, bandup: a 1-D reaction-diffusion chain like Debian's schnak2.ode (20
 * points, states interleaved, two diagonals below and above). The model declares the band;
 * the generated band Jacobian holds the dense analytic Jacobian's entries in the band, the
 * dense one is zero outside it; rodas4 with band matrices ends where rodas4 with dense ones
 * does (1e-10), and cvode likewise when built. A band that misses an entry, or is as wide
 * as the system, is an error that names them (tests/test_lang.c has the messages). */
static void test_declared_band(void **state)
{
    (void)state;
    static const char text[] =
        "f(u,v)=-u+v*u^2\ng(u,v)=a-v*u^2\n"
        "u0'=f(u0,v0)+duh*(u1-u0)\nv0'=g(u0,v0)+dvh*(v1-v0)\n"
        "%[1..18]\nu[j]'=f(u[j],v[j])+duh*(u[j+1]-2*u[j]+u[j-1])\n"
        "v[j]'=g(u[j],v[j])+dvh*(v[j+1]-2*v[j]+v[j-1])\n%\n"
        "u19'=f(u19,v19)+duh*(u18-u19)\nv19'=g(u19,v19)+dvh*(v18-v19)\n"
        "par a=1.05,du=5,dv=75,h=1\n!duh=du/(h*h)\n!dvh=dv/(h*h)\n"
        "init u0=1.5,u1=1.3,u2=1.1,v0=1.05,v1=1.05,v2=1.05\n"
        "init u[3..19]=1.05,v[j]=1.05\n"
        "@ total=5,meth=stiff,tol=1e-10,atol=1e-10\n@ bandlo=2,bandup=2\ndone\n";
    loaded L;
    load(text, &L);
    const dyn_model *m = L.m;
    const int n = m->n_states, ld = 5;
    assert_int_equal(n, 40);
    assert_int_equal(m->jac_banded, 1);
    assert_int_equal(m->jac_lower, 2);
    assert_int_equal(m->jac_upper, 2);
    assert_non_null(m->jacobian);
    assert_non_null(m->jacobian_band);
    double y[40], J[1600], B[200];
    for (int i = 0; i < n; i++)
        y[i] = 1.0 + 0.37 * sin(1.3 * i); /* a state with every entry non-zero */
    assert_int_equal(m->jacobian(0.0, y, J, L.par), 0);
    assert_int_equal(m->jacobian_band(0.0, y, B, L.par), 0);
    int inside = 0;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            if (i - j > 2 || j - i > 2) {
                CHECK(J[i * n + j] == 0.0, "J[%d][%d] = %g outside the band", i, j,
                      J[i * n + j]);
                continue;
            }
            const double b = DYN_BAND_AT(B, 2, 2, i, j);
            CHECK(b == J[i * n + j], "band (%d, %d) = %.17g, dense %.17g", i, j, b,
                  J[i * n + j]);
            inside += J[i * n + j] != 0.0;
        }
    assert_true(inside > 3 * n); /* the band is used, not empty */
    (void)ld;
    /* rodas4: band matrices against dense ones */
    const dyn_tableau *r4 = dyn_method_find("rodas4");
    double y0[40], ya[40], yb[40];
    memcpy(y0, m->y0, sizeof y0);
    const dyn_system sys = {m->rhs, n, L.par};
    dyn_solve_opts o = {0};
    o.rtol = o.atol = 1e-10;
    o.jacobian = m->jacobian;
    int *iw = calloc((size_t)dyn_solve_iwork_size(r4, n) + 1, sizeof *iw);
    o.iwork = iw;
    double *wa = calloc(dyn_solve_work_size(r4, n, &o), sizeof *wa);
    dyn_result ra, rb;
    assert_int_equal(dyn_solve(r4, &sys, 0.0, 5.0, y0, ya, wa, &o, &ra), DYN_OK);
    dyn_solve_opts ob = o;
    ob.jac_banded = 1;
    ob.jac_lower = ob.jac_upper = 2;
    ob.jacobian_band = m->jacobian_band;
    double *wb = calloc(dyn_solve_work_size(r4, n, &ob), sizeof *wb);
    assert_int_equal(dyn_solve(r4, &sys, 0.0, 5.0, y0, yb, wb, &ob, &rb), DYN_OK);
    double worst = 0.0;
    for (int i = 0; i < n; i++)
        worst = fmax(worst, fabs(ya[i] - yb[i]));
    CHECK(worst < 1e-10, "band and dense rodas4 differ by %g", worst);
    CHECK(fabs(ya[0] - m->y0[0]) > 0.1, "the solution moved (u0 %g -> %g)", m->y0[0], ya[0]);
    free(wa);
    free(wb);
    free(iw);
    unload(&L);
}

/* The C text is clean C11: no warning with -Wall -Wextra -Wshadow -pedantic (unused
 * helpers, functions and temporaries are not written), for the seed files of the fuzzer and
 * the example models. */
static void test_generated_c_compiles_without_warnings(void **state)
{
    (void)state;
    static const char *const files[] = {
        "fuzz/corpus/ode/arrays.ode",        "fuzz/corpus/ode/ball.ode",
        "fuzz/corpus/ode/functions.ode",     "fuzz/corpus/ode/vanderpol.ode",
        "fuzz/corpus/ode/band.ode",
        "examples/models/double_pendulum.ode", "examples/models/elastic_pendulum.ode",
        "examples/models/bouncing_ball.ode", "examples/models/lorenz.ode",
    };
    if (system("cc --version > /dev/null 2>&1") != 0)
        skip();
    for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
        char path[1024], cmd[2048];
        snprintf(path, sizeof path, "%s/%s", DYNKIT_SOURCE_DIR, files[i]);
        FILE *f = fopen(path, "rb");
        CHECK(f != NULL, "cannot open %s", path);
        static char text[1 << 16];
        const size_t len = fread(text, 1, sizeof text, f);
        fclose(f);
        char *c_src = NULL;
        dyn_lang_diag d;
        char buf[2048];
        CHECK(dyn_ode_to_c(path, text, len, &c_src, &d, NULL, NULL) == 0, "%s",
              dyn_lang_diag_format(&d, buf, sizeof buf));
        FILE *o = fopen("lang-warnings.c", "wb");
        assert_non_null(o);
        fputs(c_src, o);
        fclose(o);
        free(c_src);
        snprintf(cmd, sizeof cmd,
                 "cc -std=c11 -Wall -Wextra -Wshadow -pedantic -Werror -fsyntax-only -I'%s/include' "
                 "lang-warnings.c",
                 DYNKIT_SOURCE_DIR);
        CHECK(system(cmd) == 0, "%s: the C text does not compile cleanly", files[i]);
    }
    remove("lang-warnings.c");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_operators_and_functions_give_xppauts_values),
        cmocka_unit_test(test_homework_models_reproduce_the_built_in_ones),
        cmocka_unit_test(test_exact_solution_and_default_run),
        cmocka_unit_test(test_temporaries_derived_and_functions),
        cmocka_unit_test(test_arrays_expand_like_xppaut),
        cmocka_unit_test(test_list_ranges_per_item),
        cmocka_unit_test(test_sums_and_shifts),
        cmocka_unit_test(test_the_longest_sum_is_read),
        cmocka_unit_test(test_globals_reset_in_sequence),
        cmocka_unit_test(test_extensions_and_options_fill_the_model),
        cmocka_unit_test(test_nout_is_ignored_with_an_adaptive_meth),
        cmocka_unit_test(test_names_cannot_clash_with_c),
        cmocka_unit_test(test_jacobian_matches_finite_differences),
        cmocka_unit_test(test_declared_band),
        cmocka_unit_test(test_generated_c_compiles_without_warnings),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
