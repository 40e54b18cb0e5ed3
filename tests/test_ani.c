/* SPDX-License-Identifier: BSD-3-Clause */
/* test_ani.c — XPPAUT's animation files (dynkit/ani.h, src/lang/ani_*.c), after XPPAUT's
 * manual ("Animation") and its reader aniparse.c: every command and its fields, colours by
 * name and by formula, array lines and blocks, permanent/transient, dimension, settext,
 * comets, end; errors at FILE:LINE:COL with the feature or the nearest name; the evaluator
 * against known values of XPPAUT's operators and functions and against the compiled model's
 * own outputs (the same formula in the .ode and in the .ani gives the same numbers); C
 * models by their names; limits; and Debian's shipped .ani files, each read with its .ode
 * file or refused with the feature named. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include "dynkit/ani.h"
#include "dynkit/dynkit.h"
#include "dynkit/jit.h"
#include "dynkit/lang.h"
#include "dynkit/mbs.h"
#include "test_util.h"

/* A model with one of each kind of name: states x, v; parameters k, a; a number c; a
 * derived parameter d2; a fixed quantity w; a function f; an aux output e. */
static const char *const MODEL = "# test model\n"
                                 "x'=v\n"
                                 "v'=-k*x\n"
                                 "par k=2, a=0.5\n"
                                 "number c=3\n"
                                 "!d2=2*k\n"
                                 "w=x*x+v\n"
                                 "f(u)=u*u+a\n"
                                 "g(u)=u+x\n"
                                 "aux e=x+2*v\n"
                                 "init x=1, v=0\n"
                                 "done\n";

static int notes;
static char last_note[600];

static void count_note(const char *path, int line, const char *message, void *ctx)
{
    (void)path;
    (void)line;
    (void)ctx;
    notes++;
    snprintf(last_note, sizeof last_note, "%s", message);
}

static int parse(const char *ode, const char *text, dyn_ani **ani, dyn_lang_diag *d)
{
    dyn_ani_model m;
    memset(&m, 0, sizeof m);
    m.ode_path = "m.ode";
    m.ode_text = ode;
    m.ode_len = ode ? strlen(ode) : 0;
    return dyn_ani_parse("a.ani", text, strlen(text), &m, ani, d, count_note, NULL);
}

static dyn_ani *parse_ok(const char *text)
{
    dyn_ani *a = NULL;
    dyn_lang_diag d;
    char buf[2048];
    const int rc = parse(MODEL, text, &a, &d);
    CHECK(rc == 0 && a, "%s", dyn_lang_diag_format(&d, buf, sizeof buf));
    return a;
}

/* The frame (t; x, v) of MODEL with its default parameters. */
static void eval_model(const dyn_ani *a, double t, double x, double v, double *out)
{
    const double y[2] = {x, v}, outputs[1] = {x + 2 * v}, par[3] = {2, 0.5, 4};
    const dyn_ani_frame fr = {t, y, outputs, par};
    int ns, no, np;
    dyn_ani_sizes(a, &ns, &no, &np);
    assert_int_equal(ns, 2);
    assert_int_equal(no, 1);
    assert_int_equal(np, 3);
    assert_int_equal(dyn_ani_eval(a, &fr, out), 0);
}

static void test_every_command(void **state)
{
    (void)state;
    notes = 0;
    dyn_ani *a = parse_ok("# a comment line\n"
                          "\n"
                          "line 0;.1;x;v;$RED;3\n"
                          "rline .1;-.2\n"
                          "RECT 0;0;1;1;$BLUE;2\n"
                          "frect .1;.2;.3;.4;$GREEN\n"
                          "circ .5;.5;.1;$PURPLE;2\n"
                          "fcircle .5;.5;.05\n"
                          "ellip .5;.5;.2;.1;$ORANGE;1\n"
                          "fellipse .5;.5;.2;.1;$YELLOW\n"
                          "text .1;.9;Hello world  \n"
                          "vtext .1;.8;t = ;t\n"
                          "comet x;v;-3;25;$BLUEGREEN\n"
                          "settext 3;symbol;$REDORANGE\n"
                          "PERmanent\n"
                          "li 0;0;1;1\n"
                          "transient\n"
                          "co x;v;2;5\n");
    assert_int_equal(dyn_ani_count(a), 14);
    static const struct {
        dyn_ani_kind kind;
        int line, n_values, color, thickness, permanent;
    } want[] = {
        {DYN_ANI_LINE, 3, 4, DYN_ANI_RED, 3, 0},       {DYN_ANI_RLINE, 4, 2, 0, 0, 0},
        {DYN_ANI_RECT, 5, 4, DYN_ANI_BLUE, 2, 0},      {DYN_ANI_FRECT, 6, 4, DYN_ANI_GREEN, 0, 0},
        {DYN_ANI_CIRCLE, 7, 3, DYN_ANI_PURPLE, 2, 0},  {DYN_ANI_FCIRCLE, 8, 3, 0, 0, 0},
        {DYN_ANI_ELLIPSE, 9, 4, DYN_ANI_ORANGE, 1, 0}, {DYN_ANI_FELLIPSE, 10, 4, DYN_ANI_YELLOW, 0, 0},
        {DYN_ANI_TEXT, 11, 2, 0, 0, 0},                {DYN_ANI_VTEXT, 12, 3, 0, 0, 0},
        {DYN_ANI_COMET, 13, 2, DYN_ANI_BLUEGREEN, 0, 0}, {DYN_ANI_SETTEXT, 14, 0, DYN_ANI_REDORANGE, 0, 0},
        {DYN_ANI_LINE, 16, 4, 0, 0, 1},                {DYN_ANI_COMET, 18, 2, 0, 0, 0},
    };
    int offset = 0;
    for (int i = 0; i < 14; i++) {
        const dyn_ani_prim *p = dyn_ani_at(a, i);
        CHECK(p->kind == want[i].kind && p->line == want[i].line && p->col == 1 &&
                  p->n_values == want[i].n_values && p->color == want[i].color &&
                  p->thickness == want[i].thickness && p->permanent == want[i].permanent &&
                  p->offset == offset,
              "primitive %d: kind %d line %d values %d colour %d thickness %d permanent %d "
              "offset %d",
              i, p->kind, p->line, p->n_values, p->color, p->thickness, p->permanent,
              p->offset);
        offset += p->n_values;
    }
    assert_int_equal(dyn_ani_n_values(a), offset);
    assert_string_equal(dyn_ani_at(a, 8)->text, "Hello world"); /* the line's end dropped */
    assert_string_equal(dyn_ani_at(a, 9)->text, "t = ");        /* blanks inside kept */
    assert_int_equal(dyn_ani_at(a, 10)->comet_type, -3);
    assert_int_equal(dyn_ani_at(a, 10)->comet_length, 25);
    assert_int_equal(dyn_ani_at(a, 11)->text_size, 3);
    assert_int_equal(dyn_ani_at(a, 11)->text_font, 1);
    assert_int_equal(dyn_ani_at(a, 13)->comet_type, 2);
    assert_null(dyn_ani_at(a, 14));
    assert_null(dyn_ani_at(a, -1));
    double win[4];
    dyn_ani_window(a, win);
    assert_true(win[0] == 0 && win[1] == 0 && win[2] == 1 && win[3] == 1);
    assert_int_equal(dyn_ani_speed(a), 10);
    assert_int_equal(notes, 0);
    /* the values of one frame */
    double v[64];
    eval_model(a, 1.5, 0.25, -0.5, v);
    const double *l = v + dyn_ani_at(a, 0)->offset;
    assert_true(l[0] == 0 && l[1] == 0.1 && l[2] == 0.25 && l[3] == -0.5);
    const double *vt = v + dyn_ani_at(a, 9)->offset;
    assert_true(vt[0] == 0.1 && vt[1] == 0.8 && vt[2] == 1.5);
    /* constant values: numbers; varying ones: the states and t */
    assert_true(dyn_ani_value_is_constant(a, 0, 0));
    assert_false(dyn_ani_value_is_constant(a, 0, 2));
    assert_false(dyn_ani_value_is_constant(a, 9, 2));
    dyn_ani_free(a);
}

static void test_settext_sizes_fonts_and_thickness_as_xppaut(void **state)
{
    (void)state;
    /* sizes clamped to 0..4, a font starting with s is the symbol font, thickness whole
     * (atoi: 2.7 is 2), a negative thickness 0 */
    dyn_ani *a = parse_ok("settext 9;roman;$black\nsettext -1;Sym;$RED\n"
                          "line 0;0;1;1;$BLUE;2.7\nline 0;0;1;1;$BLUE;-4\n");
    assert_int_equal(dyn_ani_at(a, 0)->text_size, 4);
    assert_int_equal(dyn_ani_at(a, 0)->text_font, 0);
    assert_int_equal(dyn_ani_at(a, 0)->color, DYN_ANI_FOREGROUND);
    assert_int_equal(dyn_ani_at(a, 1)->text_size, 0);
    assert_int_equal(dyn_ani_at(a, 1)->text_font, 1);
    assert_int_equal(dyn_ani_at(a, 2)->thickness, 2);
    assert_int_equal(dyn_ani_at(a, 3)->thickness, 0);
    dyn_ani_free(a);
}

static void test_colour_names_and_formulas(void **state)
{
    (void)state;
    static const struct {
        const char *name;
        int color;
    } names[] = {
        {"$WHITE", DYN_ANI_FOREGROUND}, {"$RED", DYN_ANI_RED}, {"$REDORANGE", DYN_ANI_REDORANGE},
        {"$ORANGE", DYN_ANI_ORANGE}, {"$YELLOWORANGE", DYN_ANI_YELLOWORANGE},
        {"$YELLOW", DYN_ANI_YELLOW}, {"$YELLOWGREEN", DYN_ANI_YELLOWGREEN},
        {"$GREEN", DYN_ANI_GREEN}, {"$BLUEGREEN", DYN_ANI_BLUEGREEN}, {"$BLUE", DYN_ANI_BLUE},
        {"$PURPLE", DYN_ANI_PURPLE}, {"$BLACK", DYN_ANI_FOREGROUND}, {"$red", DYN_ANI_RED},
        {"$ Blue Green", DYN_ANI_BLUEGREEN}, /* XPPAUT removes the blanks */
    };
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        char text[128];
        snprintf(text, sizeof text, "fcircle .5;.5;.1;%s\n", names[i].name);
        dyn_ani *a = parse_ok(text);
        CHECK(dyn_ani_at(a, 0)->color == names[i].color && dyn_ani_at(a, 0)->n_values == 3,
              "%s: colour %d", names[i].name, dyn_ani_at(a, 0)->color);
        dyn_ani_free(a);
    }
    assert_string_equal(dyn_ani_color_name(DYN_ANI_FOREGROUND), "BLACK");
    assert_string_equal(dyn_ani_color_name(DYN_ANI_YELLOWGREEN), "YELLOWGREEN");
    /* a formula: its value clamped to [0, 1], as XPPAUT's eval_ani_color */
    dyn_ani *a = parse_ok("fcircle .5;.5;.1;x\nline 0;0;1;1;v/4;2\nfrect 0;0;1;1;.3\n"
                          "comet x;v;1;4;t\n");
    assert_int_equal(dyn_ani_at(a, 0)->color, -1);
    assert_int_equal(dyn_ani_at(a, 0)->n_values, 4);
    assert_int_equal(dyn_ani_at(a, 1)->n_values, 5);
    assert_int_equal(dyn_ani_at(a, 1)->thickness, 2);
    assert_int_equal(dyn_ani_at(a, 3)->n_values, 3);
    double v[32];
    eval_model(a, 0.75, -2.0, 8.0, v);
    assert_true(v[dyn_ani_at(a, 0)->offset + 3] == 0.0);
    assert_true(v[dyn_ani_at(a, 1)->offset + 4] == 1.0);
    assert_true(v[dyn_ani_at(a, 2)->offset + 4] == 0.3);
    assert_true(v[dyn_ani_at(a, 3)->offset + 2] == 0.75);
    eval_model(a, 0.75, 0.25, 2.0, v);
    assert_true(v[dyn_ani_at(a, 0)->offset + 3] == 0.25);
    assert_true(v[dyn_ani_at(a, 1)->offset + 4] == 0.5);
    dyn_ani_free(a);
}

static void test_array_lines_and_blocks(void **state)
{
    (void)state;
    dyn_ani *a = parse_ok("fcircle [0..3]/4;[j]*[j]/10;.1\n"
                          "%[1..2]\n"
                          "line [j];0;[j+1];\\\n"
                          "  1\n"
                          "%\n"
                          "end\n"
                          "this is not read\n");
    assert_int_equal(dyn_ani_count(a), 6);
    double v[64];
    eval_model(a, 0, 0, 0, v);
    for (int j = 0; j < 4; j++) {
        const double *c = v + dyn_ani_at(a, j)->offset;
        CHECK(c[0] == j / 4.0 && c[1] == j * j / 10.0 && c[2] == 0.1, "j = %d: %g %g", j, c[0],
              c[1]);
        assert_int_equal(dyn_ani_at(a, j)->line, 1);
    }
    for (int j = 1; j <= 2; j++) {
        const dyn_ani_prim *p = dyn_ani_at(a, 3 + j);
        const double *c = v + p->offset;
        assert_int_equal(p->kind, DYN_ANI_LINE);
        assert_int_equal(p->line, 3);
        CHECK(c[0] == j && c[1] == 0 && c[2] == j + 1 && c[3] == 1, "block j = %d", j);
    }
    dyn_ani_free(a);
}

/* XPPAUT's operators and functions, with its priorities, its fixed quantities, derived
 * parameters, numbers, functions and the aux outputs. */
static void test_evaluator_known_values(void **state)
{
    (void)state;
    dyn_ani *a = parse_ok("line heav(0);heav(-1e-300);sign(0);sign(-3)\n"
                          "line mod(-7,3);mod(7,-3);flr(-1.5);ceil(-1.5)\n"
                          "line 2^3^2;-2^2;not 0+1;2*3>1\n"
                          "line if(x>1)then(2)else(3);max(1,2)+min(1,2);1|1&0;2**(-1)\n"
                          "line k;d2;c;a\n"
                          "line w;f(v);g(1);e\n"
                          "line t;pi;atan2(1,-1);exp(ln(2))\n"
                          "line abs(-x);sqrt(4);log10(1000);1+1==2\n");
    double v[64];
    eval_model(a, 2.5, 3.0, -1.0, v);
    static const double want[] = {1, 0, 0, -1,
                                  2, 1, -2, -1,
                                  64, -4, 2, 2,
                                  2, 3, 1, 0.5,
                                  2, 4, 3, 0.5,
                                  3.0 * 3.0 - 1.0, 1.0 + 0.5, 1.0 + 3.0, 3.0 + 2.0 * -1.0,
                                  2.5, 3.14159265358979323846, 2.35619449019234492885, 2,
                                  3, 2, 3, 1};
    for (int i = 0; i < 32; i++)
        CHECK(fabs(v[i] - want[i]) <= 1e-15 * fmax(1.0, fabs(want[i])), "value %d: %.17g, not %.17g",
              i, v[i], want[i]);
    /* what changes from frame to frame */
    assert_true(dyn_ani_value_is_constant(a, 4, 0));  /* k */
    assert_true(dyn_ani_value_is_constant(a, 4, 1));  /* d2 */
    assert_false(dyn_ani_value_is_constant(a, 5, 0)); /* w, a fixed quantity */
    assert_false(dyn_ani_value_is_constant(a, 5, 1)); /* f(v) */
    assert_false(dyn_ani_value_is_constant(a, 5, 2)); /* g uses the state x */
    assert_false(dyn_ani_value_is_constant(a, 5, 3)); /* e, an output */
    assert_false(dyn_ani_value_is_constant(a, 6, 0)); /* t */
    assert_true(dyn_ani_value_is_constant(a, 6, 1));  /* pi */
    dyn_ani_free(a);
}

/* The same formulas compiled from the .ode file (its aux outputs) and evaluated from the
 * .ani file give the same numbers; the outputs named in the .ani are the compiled ones. */
static void test_evaluator_matches_the_compiled_model(void **state)
{
    (void)state;
    const char *ode = "# double pendulum\n"
                      "par m1=1.3, m2=0.7, l1=1.1, l2=0.9, g=9.81\n"
                      "init th1=2, th2=2.5, w1=0.3, w2=-0.2\n"
                      "d=th1-th2\n"
                      "den=2*m1+m2-m2*cos(2*d)\n"
                      "th1'=w1\nth2'=w2\n"
                      "w1'=(-g*(2*m1+m2)*sin(th1)-m2*g*sin(th1-2*th2)-2*sin(d)*m2*(w2^2*l2+"
                      "w1^2*l1*cos(d)))/(l1*den)\n"
                      "w2'=2*sin(d)*(w1^2*l1*(m1+m2)+g*(m1+m2)*cos(th1)+w2^2*l2*m2*cos(d))/"
                      "(l2*den)\n"
                      "aux x2=l1*sin(th1)+l2*sin(th2)\n"
                      "aux y2=-l1*cos(th1)-l2*cos(th2)\n"
                      "aux energy=0.5*m1*(l1*w1)^2+0.5*m2*((l1*w1)^2+(l2*w2)^2+2*l1*l2*w1*w2*"
                      "cos(d))-(m1+m2)*g*l1*cos(th1)-m2*g*l2*cos(th2)\n"
                      "aux odd=heav(w1)*mod(th2,1)+sign(w2)*flr(th1*3)/max(den,1)+"
                      "if(d>0)then(d^3)else(-d)\n"
                      "done\n";
    const char *ani = "line l1*sin(th1)+l2*sin(th2);-l1*cos(th1)-l2*cos(th2);"
                      "0.5*m1*(l1*w1)^2+0.5*m2*((l1*w1)^2+(l2*w2)^2+2*l1*l2*w1*w2*cos(d))-"
                      "(m1+m2)*g*l1*cos(th1)-m2*g*l2*cos(th2);"
                      "heav(w1)*mod(th2,1)+sign(w2)*flr(th1*3)/max(den,1)+"
                      "if(d>0)then(d^3)else(-d)\n"
                      "line x2;y2;energy;odd\n";
    char *c_src = NULL;
    dyn_lang_diag d;
    char buf[4096];
    CHECK(dyn_ode_to_c("dp.ode", ode, strlen(ode), &c_src, &d, NULL, NULL) == 0, "%s",
          dyn_lang_diag_format(&d, buf, sizeof buf));
    dyn_jit_opts opts;
    memset(&opts, 0, sizeof opts);
    opts.cache_dir = "ani-jit-cache";
    dyn_jit_model jm;
    char err[4096];
    CHECK(dyn_jit_load_source(c_src, strlen(c_src), "dp.ode", &opts, &jm, err, sizeof err) == 0,
          "%s", err);
    free(c_src);
    const dyn_model *m = jm.model;
    double par[16];
    assert_true(m->par_size <= sizeof par);
    CHECK(dyn_model_default_params(m, par, err, sizeof err) == 0, "%s", err);
    dyn_ani *a = NULL;
    dyn_ani_model am;
    memset(&am, 0, sizeof am);
    am.ode_path = "dp.ode";
    am.ode_text = ode;
    am.ode_len = strlen(ode);
    CHECK(dyn_ani_parse("dp.ani", ani, strlen(ani), &am, &a, &d, NULL, NULL) == 0, "%s",
          dyn_lang_diag_format(&d, buf, sizeof buf));
    /* along a run of the model: every sample */
    double y[4];
    memcpy(y, m->y0, sizeof y);
    int same = 0, total = 0;
    for (int k = 0; k < 400; k++) {
        const double t = 0.01 * k;
        double out[4], v[8];
        assert_int_equal(m->compute_outputs(t, y, par, out), 0);
        const dyn_ani_frame fr = {t, y, out, par};
        assert_int_equal(dyn_ani_eval(a, &fr, v), 0);
        for (int i = 0; i < 4; i++) {
            CHECK(fabs(v[i] - out[i]) <= 1e-14 * fmax(1.0, fabs(out[i])),
                  "sample %d, value %d: .ani %.17g, compiled %.17g", k, i, v[i], out[i]);
            same += same_bits(v[i], out[i]);
            total++;
            assert_true(same_bits(v[4 + i], out[i])); /* the outputs themselves */
        }
        double dy[4];
        assert_int_equal(m->rhs(t, y, dy, par), 0);
        for (int i = 0; i < 4; i++)
            y[i] += 0.01 * dy[i];
    }
    /* the same operations in the same order: the same bits (both ISO C, no contraction) */
    CHECK(same == total, "%d of %d values have the compiled model's bits", same, total);
    dyn_ani_free(a);
    dyn_jit_unload(&jm);
}

/* ---- the animation's numbers as outputs of the model's C (dyn_ani_ode_to_c) ---- */

/* The model of ode with the animation's numbers as outputs, compiled, against the evaluator
 * of a (read from the same files) at the model's initial state and at a state moved from it,
 * at t = 0.3: the outputs after the model's are the frame's numbers (a colour clamped to
 * [0, 1] as dyn_ani_eval does). 1 when compared (the values counted in *same and *total), 0
 * when the translation refuses the animation (diag in d). */
static int frames_as_outputs(const char *op, const char *ot, size_t olen, const char *ap,
                             const char *at, size_t alen, const dyn_ani *a, int *same,
                             int *total, dyn_lang_diag *d)
{
    char *c_src = NULL;
    if (dyn_ani_ode_to_c(op, ot, olen, NULL, 0, ap, at, alen, &c_src, d) != 0)
        return 0;
    dyn_jit_opts opts;
    memset(&opts, 0, sizeof opts);
    opts.cache_dir = "ani-jit-cache";
    dyn_jit_model jm;
    char err[4096];
    CHECK(dyn_jit_load_source(c_src, strlen(c_src), op, &opts, &jm, err, sizeof err) == 0,
          "%s: %s", ap, err);
    free(c_src);
    const dyn_model *m = jm.model;
    int ns, no, np;
    dyn_ani_sizes(a, &ns, &no, &np);
    const int nv = dyn_ani_n_values(a);
    CHECK(m->n_states == ns && m->n_outputs == no + nv, "%s: %d states, %d outputs; the .ani "
          "reads %d states, %d outputs and has %d numbers", ap, m->n_states, m->n_outputs, ns,
          no, nv);
    void *par = calloc(1, m->par_size + 1);
    double *y = calloc((size_t)ns + 1, sizeof *y), *out = calloc((size_t)no + nv + 1, 8);
    double *v = calloc((size_t)nv + 1, sizeof *v);
    assert_true(par && y && out && v);
    CHECK(dyn_model_default_params(m, par, err, sizeof err) == 0, "%s", err);
    assert_true((size_t)np * sizeof(double) <= m->par_size);
    for (int pass = 0; pass < 2; pass++) {
        for (int i = 0; i < ns; i++)
            y[i] = m->y0[i] + (pass ? 0.1 * (i + 1) : 0.0);
        assert_int_equal(m->compute_outputs(0.3, y, par, out), 0);
        const dyn_ani_frame fr = {0.3, y, out, par};
        assert_int_equal(dyn_ani_eval(a, &fr, v), 0);
        for (int i = 0; i < dyn_ani_count(a); i++) {
            const dyn_ani_prim *pr = dyn_ani_at(a, i);
            for (int k = 0; k < pr->n_values; k++) {
                const int K = pr->offset + k;
                double c = out[no + K];
                if (pr->color < 0 && k == pr->n_values - 1)
                    c = c > 1.0 ? 1.0 : c < 0.0 ? 0.0 : c;
                CHECK((isnan(c) && isnan(v[K])) || fabs(c - v[K]) <= 1e-13 * fmax(1.0, fabs(c)),
                      "%s:%d, number %d: compiled %.17g, evaluated %.17g", ap, pr->line, k, c,
                      v[K]);
                *same += same_bits(c, v[K]) || (isnan(c) && isnan(v[K]));
                (*total)++;
            }
        }
    }
    free(par);
    free(y);
    free(out);
    free(v);
    dyn_jit_unload(&jm);
    return 1;
}

/* Every kind of name (state, parameter, number, derived parameter, fixed quantity, function,
 * aux output, t), a colour formula beyond [0, 1], and a vtext; a function that reads a fixed
 * quantity refused at its place in the .ani. */
static void test_frames_as_outputs_of_the_model(void **state)
{
    (void)state;
    const char *ani = "line x;v;w+f(x);e+d2*c;x*4\n"
                      "fcircle g(v);t;.1;x/4+2\n"
                      "vtext .1;.2;x = ;x+c\n"
                      "settext 2;roman;$RED\n"
                      "rect 0;0;k;a;$BLUE\n";
    dyn_ani *a = NULL;
    dyn_lang_diag d;
    char buf[4096];
    CHECK(parse(MODEL, ani, &a, &d) == 0, "%s", dyn_lang_diag_format(&d, buf, sizeof buf));
    int same = 0, total = 0;
    CHECK(frames_as_outputs("m.ode", MODEL, strlen(MODEL), "a.ani", ani, strlen(ani), a, &same,
                            &total, &d),
          "refused: %s", dyn_lang_diag_format(&d, buf, sizeof buf));
    assert_int_equal(total, 2 * 16);
    CHECK(same == total, "%d of %d numbers have the evaluator's bits", same, total);
    dyn_ani_free(a);
    /* h reads the fixed quantity w, which the translator passes to h as an argument: refused
     * at the call, by the reader of the animation (it takes 2 arguments) or here */
    static const char *const with_h = "# h reads w\nx'=v\nv'=-x\nw=x*x+v\nh(u)=u*w\n"
                                      "init x=1, v=0\ndone\n";
    const char *bad = "line 0;0;x;v\nline 0;0;h(x);v\n";
    char *c_src = (char *)1;
    CHECK(dyn_ani_ode_to_c("h.ode", with_h, strlen(with_h), NULL, 0, "h.ani", bad, strlen(bad),
                           &c_src, &d) == 2 && c_src == NULL,
          "accepted: %s", bad);
    CHECK(strcmp(d.path, "h.ani") == 0 && d.line == 2 && d.col == 10 && strstr(d.message, "'h'"),
          "%s", dyn_lang_diag_format(&d, buf, sizeof buf));
    /* an error of the animation itself, at its place */
    CHECK(dyn_ani_ode_to_c("m.ode", MODEL, strlen(MODEL), NULL, 0, "a.ani", "line 0;0;zz;1\n",
                           14, &c_src, &d) == 2 &&
              strcmp(d.path, "a.ani") == 0 && d.line == 1 && d.col == 10,
          "%s", dyn_lang_diag_format(&d, buf, sizeof buf));
}

/* An error: its line, column and a part of its message. */
static void expect_error(const char *text, int line, int col, const char *part)
{
    dyn_ani *a = (dyn_ani *)1;
    dyn_lang_diag d;
    char buf[2048];
    const int rc = parse(MODEL, text, &a, &d);
    dyn_lang_diag_format(&d, buf, sizeof buf);
    CHECK(rc == 2 && a == NULL, "accepted: %s", text);
    CHECK(d.line == line && d.col == col && strstr(d.message, part),
          "%s\n  wanted %d:%d '%s', got:\n%s", text, line, col, part, buf);
    assert_string_equal(d.path, "a.ani");
}

static void test_errors_name_their_place(void **state)
{
    (void)state;
    expect_error("lien .5;.5;1;1\n", 1, 1, "unknown command 'lien' (did you mean 'line'?)");
    expect_error("# ok\nline .5;.5;1\n", 2, 13, "'line' takes x1;y1;x2;y2[;colour[;thickness]]");
    expect_error("line .5;.5;1;1;$RDE\n", 1, 16, "unknown colour '$RDE' (did you mean '$RED'?)");
    expect_error("line .5;;1;1\n", 1, 9, "empty field 2");
    expect_error("line .5;.5;1;1;$RED;2;3\n", 1, 22, "too many fields");
    expect_error("fcircle x;v;.1;$RED\nline x;vv;1;1\n", 2, 8,
                 "unknown name 'vv' (did you mean 'v'?)");
    expect_error("line x;v;1;1;$RED;2*x\n", 1, 19, "thickness must be a number");
    expect_error("settext 1;rom;0.5\n", 1, 15, "settext takes a named colour");
    expect_error("comet x;v;1;0\n", 1, 13, "comet's length");
    expect_error("comet x;v;1;1e9\n", 1, 13, "too large");
    expect_error("\n\n  xnull 0;0;1;1;$RED;1\n", 3, 3, "nullclines in animations ('xnull', "
                                                     "'ynull') are not supported");
    expect_error("grab x;v;.1\n{x=mouse_x}\n", 1, 1, "'grab' is followed by two lines");
    expect_error("grab x;v;.1\nline 0;0;1;1\n", 2, 1, "'grab' is followed by two lines");
    expect_error("line sin(x;0;1;1\n", 1, 11, "missing ')' before the ';' that ends the field");
    expect_error("line (x+1;0;1;1\n", 1, 10, "missing ')' before the ';' that ends the field");
    expect_error("line x;v;1;sin(x\n", 1, 17, "expected ',' or ')'");
    expect_error("line f(x,1);0;1;1\n", 1, 6, "function 'f' takes 1 argument, not 2");
    expect_error("line f;0;1;1\n", 1, 6, "'f' is a function");
    expect_error("line fx(1);0;1;1\n", 1, 6, "unknown function 'fx'");
    expect_error("line x+ran(1);0;1;1\n", 1, 8, "random numbers ('ran') are not supported");
    expect_error("line delay(x,1);0;1;1\n", 1, 6, "('delay') are not supported");
    expect_error("permanent x\n", 1, 11, "'permanent' takes nothing after it");
    expect_error("line .5;.5;1;1 # comment\n", 1, 16, "unexpected '#'");
    expect_error("text .1;.1;\n", 1, 12, "'text' takes x;y;string (2 fields given");
    expect_error("vtext .1;.1;t=\n", 1, 15, "'vtext' takes x;y;string;value");
    expect_error("line [1..3;0;1;1\n", 1, 6, "'['");
    expect_error("dimension 0;0;1;pi\n", 1, 17, "yhi must be a number");
    expect_error("line 2x;0;1;1\n", 1, 7, "missing operator");
    expect_error("\"quoted\n", 1, 1, "unknown command");
    expect_error("l 0;0;1;1\n", 1, 1, "unknown command 'l'");
    /* the algebraic variables of a model (0=...), and the fixed quantities that read them,
     * are solved for by the model, not by the animation's evaluator */
    static const char *const dae = "x'=-x\nsolv v\n0=v-2*x\nq=x+v\naux vv=v\ndone\n";
    dyn_ani *a;
    dyn_lang_diag d;
    assert_int_equal(parse(dae, "line 0;0;v;1\n", &a, &d), 2);
    CHECK(d.line == 1 && d.col == 10 && strstr(d.message, "'v' is an algebraic variable") &&
              strstr(d.message, "aux"),
          "%d:%d %s", d.line, d.col, d.message);
    assert_int_equal(parse(dae, "line 0;0;q;1\n", &a, &d), 2);
    CHECK(d.line == 1 && strstr(d.message, "'q' reads an algebraic variable"), "%s", d.message);
    assert_int_equal(parse(dae, "line 0;0;vv;1\n", &a, &d), 0);
    dyn_ani_free(a);
    /* the diagnostic's display: FILE:LINE:COL, the line and a caret under the column */
    char buf[2048];
    assert_int_equal(parse(MODEL, "line 0;0;1;1\nline x;omega;1;1\n", &a, &d), 2);
    dyn_lang_diag_format(&d, buf, sizeof buf);
    CHECK(strcmp(buf, "a.ani:2:8: error: unknown name 'omega': an animation's formulas use "
                      "the model's states, outputs, parameters, t and numbers\n"
                      "  line x;omega;1;1\n"
                      "         ^\n") == 0,
          "%s", buf);
}

static void test_window_speed_grab_and_notes(void **state)
{
    (void)state;
    notes = 0;
    dyn_ani *a = parse_ok("dimension -1.25;-2;3.5;1e1\nspeed 75\n"
                          "grab x;v;.05\n{x=mouse_x}\n{x=mouse_x;runnow=1}\n"
                          "fcircle x;v;.1\n");
    double win[4];
    dyn_ani_window(a, win);
    assert_true(win[0] == -1.25 && win[1] == -2 && win[2] == 3.5 && win[3] == 10);
    assert_int_equal(dyn_ani_speed(a), 75);
    assert_int_equal(dyn_ani_count(a), 1);
    assert_int_equal(notes, 2); /* speed, grab */
    assert_non_null(strstr(last_note, "grab"));
    dyn_ani_free(a);
    /* an aux output is named with a note: XPPAUT's animator does not know them */
    notes = 0;
    a = parse_ok("line e;0;1;1\nline w;0;1;1\n");
    assert_int_equal(notes, 1);
    assert_non_null(strstr(last_note, "'e' is an aux output"));
    dyn_ani_free(a);
    /* a window with xlo >= xhi is ignored, as XPPAUT does, with a note */
    notes = 0;
    a = parse_ok("dimension 1;0;0;1\nspeed 5000\nline 0;0;1;1\n");
    dyn_ani_window(a, win);
    assert_true(win[0] == 0 && win[1] == 0 && win[2] == 1 && win[3] == 1);
    assert_int_equal(dyn_ani_speed(a), 1000);
    assert_int_equal(notes, 2);
    dyn_ani_free(a);
}

/* A C model (no .ode file): its states, outputs and parameters by name; parameters by
 * index in the frame. */
static void test_c_model_names(void **state)
{
    (void)state;
    static const char *const st[] = {"phi", "dphi"}, *const out[] = {"energy", "bad name"},
                             *const par[] = {"m", "l", "pi"}; /* pi cannot be declared */
    dyn_ani_model m;
    memset(&m, 0, sizeof m);
    m.n_states = 2;
    m.states = st;
    m.n_outputs = 2;
    m.outputs = out;
    m.n_params = 3;
    m.params = par;
    const char *text = "line .5;.5;.5+l*sin(phi);.5-l*cos(PHI)\nvtext 0;0;E=;energy*m+dphi\n";
    dyn_ani *a = NULL;
    dyn_lang_diag d;
    char buf[2048];
    CHECK(dyn_ani_parse("c.ani", text, strlen(text), &m, &a, &d, NULL, NULL) == 0, "%s",
          dyn_lang_diag_format(&d, buf, sizeof buf));
    const double y[2] = {0.5, 2.0}, o[2] = {3.0, 0.0}, p[3] = {2.0, 0.25, 7.0};
    const dyn_ani_frame fr = {0, y, o, p};
    double v[16];
    assert_int_equal(dyn_ani_eval(a, &fr, v), 0);
    assert_true(v[2] == 0.5 + 0.25 * sin(0.5) && v[3] == 0.5 - 0.25 * cos(0.5));
    assert_true(v[6] == 3.0 * 2.0 + 2.0);
    dyn_ani_free(a);
    /* the evaluated text of a vtext: the string and %g */
    assert_string_equal(dyn_ani_vtext("t=", 0.5, buf, sizeof buf), "t=0.5");
    assert_string_equal(dyn_ani_vtext("E = ", 123456789.0, buf, sizeof buf), "E = 1.23457e+08");
    assert_string_equal(dyn_ani_vtext("", -1e-5, buf, sizeof buf), "-1e-05");
    /* a name that is not the model's */
    assert_int_equal(dyn_ani_parse("c.ani", "line x;0;1;1\n", 13, &m, &a, &d, NULL, NULL), 2);
    assert_int_equal(d.col, 6);
}

static void test_limits_and_damaged_input(void **state)
{
    (void)state;
    dyn_ani *a;
    dyn_lang_diag d;
    /* too many primitives */
    assert_int_equal(parse(MODEL, "fcircle [1..20000]/20000;.5;.01\n", &a, &d), 2);
    assert_non_null(strstr(d.message, "too many commands"));
    /* a text too long */
    char text[600] = "text 0;0;";
    memset(text + 9, 'a', 300);
    text[309] = '\0';
    assert_int_equal(parse(MODEL, text, &a, &d), 2);
    assert_non_null(strstr(d.message, "text too long"));
    /* formulas nested deeply */
    char deep[2000] = "line ";
    for (int i = 0; i < 600; i++)
        strcat(deep, "(");
    assert_int_equal(parse(MODEL, deep, &a, &d), 2);
    /* a NUL byte */
    const char nul[] = "line 0;0;1;1\nli\0ne 0;0;1;1\n";
    dyn_ani_model m;
    memset(&m, 0, sizeof m);
    assert_int_equal(dyn_ani_parse("n.ani", nul, sizeof nul - 1, &m, &a, &d, NULL, NULL), 2);
    assert_int_equal(d.line, 2);
    /* an empty file: nothing to draw */
    a = parse_ok("");
    assert_int_equal(dyn_ani_count(a), 0);
    assert_int_equal(dyn_ani_n_values(a), 0);
    dyn_ani_free(a);
    /* NULL arguments */
    assert_int_equal(dyn_ani_parse("x", NULL, 3, &m, &a, &d, NULL, NULL), 2);
    assert_int_equal(dyn_ani_parse("x", "", 0, &m, NULL, &d, NULL, NULL), 2);
    assert_int_equal(dyn_ani_count(NULL), 0);
    dyn_ani_free(NULL);
    /* an .ode file with an error: reported at its own place */
    assert_int_equal(parse("x'=y\n", "line 0;0;1;1\n", &a, &d), 2);
    assert_string_equal(d.path, "m.ode");
    assert_int_equal(d.line, 1);
    /* every prefix of a valid file, and each byte replaced by others: no crash, a clean
     * answer (the fuzz harness fuzz/fuzz_ani.c does this at length) */
    const char *good = "dimension -1;-1;1;1\nPERMANENT\nline 0;0;x;v;$RED;2\nTRANSIENT\n"
                       "fcircle [1..3]/4;w;.1;e/2\nvtext 0;0;t=;t\ncomet x;v;-2;9;f(t)\n"
                       "settext 2;sym;$BLUE\ntext .1;.2;abc\nend\n";
    const size_t n = strlen(good);
    char *buf = malloc(n + 1);
    static const char bytes[] = ";$[].\\%#(\n -0e{";
    for (size_t cut = 0; cut <= n; cut++) {
        if (parse(MODEL, "", &a, &d) == 0)
            dyn_ani_free(a);
        memcpy(buf, good, n);
        buf[cut] = '\0';
        if (parse(MODEL, buf, &a, &d) == 0)
            dyn_ani_free(a);
        for (size_t b = 0; b < sizeof bytes - 1 && cut < n; b++) {
            memcpy(buf, good, n + 1);
            buf[cut] = bytes[b];
            if (parse(MODEL, buf, &a, &d) == 0) {
                double v[256];
                assert_true(dyn_ani_n_values(a) <= 256);
                eval_model(a, 1, 2, 3, v);
                dyn_ani_free(a);
            } else {
                assert_true(d.message[0] != '\0');
            }
        }
    }
    free(buf);
}

/* ---- Debian's shipped examples ---- */

#define XPP_DIR "/usr/share/doc/xppaut/examples/ode/"

static char *read_file(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    char *b = malloc(1 << 20);
    *len = fread(b, 1, (1 << 20) - 1, f);
    b[*len] = '\0';
    fclose(f);
    return b;
}

static void test_debian_examples(void **state)
{
    (void)state;
    struct stat st;
    if (stat(XPP_DIR "pend.ani", &st) != 0) {
        printf("skipped: Debian's xppaut examples are not installed (%s)\n", XPP_DIR);
        return;
    }
    /* each .ani with the .ode it belongs to: the commands it has when read, or the feature
     * that refuses it; a model the translator refuses is refused with the translator's
     * message (its features grow: then the .ani is read) */
    static const struct {
        const char *ani, *ode, *refused;
        int prims;
    } ex[] = {
        {"6x6.ani", "6x6.ode", NULL, 36},
        {"acoaster.ani", "acoaster.ode", NULL, 55},
        {"atcoaster.ani", "atcoaster.ode", NULL, 55},
        {"chemo.ani", "chemotax.ode", NULL, 202}, /* its model uses sums */
        {"coaster2D.ani", "coaster2D.ode", NULL, 5},
        {"doubpend.ani", "doubpend.ode", NULL, 5},
        {"duck.ani", "duckx.ode", NULL, 7},
        {"duck2.ani", "duckx.ode", NULL, 9},
        {"duck3.ani", "duckx.ode", NULL, 10},
        {"elaspen.ani", "elaspen.ode", NULL, 3},
        {"fish.ani", "lamprey.ode", NULL, 20},
        {"idoubpend.ani", "idoubpend.ode", NULL, 5},
        {"ielaspen.ani", "ielaspen.ode", NULL, 7},
        {"invpend.ani", "invpend.ode", NULL, 3},
        {"itoy.ani", "itoy.ode", NULL, 12},
        {"jcoaster.ani", "jcoaster.ode", NULL, 205},
        {"jcoaster.old.ani", "jcoaster.ode", NULL, 145},
        {"jcoaster1.ani", "jcoaster1.ode", NULL, 205},
        {"lorenz.ani", "lorenz2.ode", NULL, 11},
        {"nc.ani", "pend.ode", "nullclines in animations ('xnull', 'ynull') are not supported", 0},
        {"osc.ani", "osc.ode", NULL, -1}, /* its model has noise (wiener) */
        {"osc1.ani", "osc.ode", NULL, -1},
        {"pend.ani", "pend.ode", NULL, 2},
        {"pend2.ani", "pend.ode", NULL, 9},
        {"pendx.ani", "pendx.ode", NULL, 2},
        {"toy.ani", "toy_ok.ode", NULL, 12},
        {"waterwheel.ani", "waterwheel.ode", "random numbers ('ran') are not supported", 0},
        {"wave.ani", "wave.ode", NULL, 21},
        {"wavepp.ani", "wave.ode", NULL, 21},
        {"wcstim.ani", "wcstim.ode", "nullclines in animations ('xnull', 'ynull') are not "
                                     "supported", 0},
    };
    int read = 0, refused = 0, model_refused = 0, compiled = 0, same = 0, total = 0;
    for (size_t i = 0; i < sizeof ex / sizeof ex[0]; i++) {
        char ap[256], op[256], buf[4096];
        snprintf(ap, sizeof ap, XPP_DIR "%s", ex[i].ani);
        snprintf(op, sizeof op, XPP_DIR "%s", ex[i].ode);
        size_t alen = 0, olen = 0;
        char *at = read_file(ap, &alen), *ot = read_file(op, &olen);
        CHECK(at && ot, "%s or %s missing", ap, op);
        /* the model as the translator takes it */
        char *c_src = NULL;
        dyn_lang_diag md;
        const int mrc = dyn_ode_to_c(op, ot, olen, &c_src, &md, NULL, NULL);
        free(c_src);
        dyn_ani_model m;
        memset(&m, 0, sizeof m);
        m.ode_path = op;
        m.ode_text = ot;
        m.ode_len = olen;
        dyn_ani *a = NULL;
        dyn_lang_diag d;
        const int rc = dyn_ani_parse(ap, at, alen, &m, &a, &d, NULL, NULL);
        dyn_lang_diag_format(&d, buf, sizeof buf);
        if (mrc != 0 && !(ex[i].refused && strstr(ex[i].refused, "nullclines"))) {
            /* refused with the translator's own message, at the .ode file's place */
            CHECK(rc == 2 && strcmp(d.message, md.message) == 0 && strcmp(d.path, op) == 0 &&
                      d.line == md.line && strstr(d.message, "not supported"),
                  "%s: %s (the model: %s)", ex[i].ani, rc ? buf : "read", md.message);
            printf("%-17s refused: its model %s: %s\n", ex[i].ani, ex[i].ode, d.message);
            model_refused++;
        } else if (ex[i].refused) {
            CHECK(rc == 2 && strstr(d.message, ex[i].refused) && strcmp(d.path, ap) == 0,
                  "%s: %s", ex[i].ani, rc ? buf : "read");
            printf("%-17s refused: %s\n", ex[i].ani, d.message);
            refused++;
        } else {
            CHECK(rc == 0, "%s: %s", ex[i].ani, buf);
            CHECK(ex[i].prims < 0 || dyn_ani_count(a) == ex[i].prims, "%s: %d commands",
                  ex[i].ani, dyn_ani_count(a));
            read++;
            /* every value of a frame evaluates */
            int ns, no, np;
            dyn_ani_sizes(a, &ns, &no, &np);
            double *y = calloc((size_t)ns + 1, sizeof *y), *o = calloc((size_t)no + 1, 8);
            double *p = calloc((size_t)np + 1, sizeof *p);
            double *v = calloc((size_t)dyn_ani_n_values(a) + 1, sizeof *v);
            const dyn_ani_frame fr = {0, y, o, p};
            assert_int_equal(dyn_ani_eval(a, &fr, v), 0);
            free(y);
            free(o);
            free(p);
            free(v);
            /* its numbers as outputs of the model's C (a live page's module) */
            if (mrc == 0) {
                dyn_lang_diag od;
                if (frames_as_outputs(op, ot, olen, ap, at, alen, a, &same, &total, &od)) {
                    compiled++;
                } else {
                    printf("%-17s not compiled: %s\n", ex[i].ani,
                           dyn_lang_diag_format(&od, buf, sizeof buf));
                    CHECK(strstr(od.message, "reads fixed quantities"), "%s: %s", ex[i].ani,
                          buf);
                }
            }
            dyn_ani_free(a);
        }
        free(at);
        free(ot);
    }
    printf("Debian's .ani files: %d read, %d refused, %d refused for their model; %d compiled "
           "as outputs of their model (%d of %d numbers with the evaluator's bits)\n", read,
           refused, model_refused, compiled, same, total);
    assert_true(compiled >= 20);
    assert_int_equal(read + refused + model_refused, 30);
    assert_true(read >= 22);
    assert_true(refused >= 2);
}

/* The shipped examples: examples/models/double_pendulum.ani and pendulum.ani. */
static void test_shipped_examples(void **state)
{
    (void)state;
    static const char *const names[] = {"double_pendulum", "pendulum"};
    for (int i = 0; i < 2; i++) {
        char ap[512], op[512], buf[4096];
        snprintf(ap, sizeof ap, "%s/examples/models/%s.ani", DYNKIT_SOURCE_DIR, names[i]);
        snprintf(op, sizeof op, "%s/examples/models/%s.ode", DYNKIT_SOURCE_DIR, names[i]);
        size_t alen = 0, olen = 0;
        char *at = read_file(ap, &alen), *ot = read_file(op, &olen);
        CHECK(at && ot, "%s or %s missing", ap, op);
        dyn_ani_model m;
        memset(&m, 0, sizeof m);
        m.ode_path = op;
        m.ode_text = ot;
        m.ode_len = olen;
        dyn_ani *a = NULL;
        dyn_lang_diag d;
        notes = 0;
        CHECK(dyn_ani_parse(ap, at, alen, &m, &a, &d, count_note, NULL) == 0, "%s",
              dyn_lang_diag_format(&d, buf, sizeof buf));
        assert_int_equal(notes, 0);
        int has_comet = 0, has_vtext = 0;
        for (int k = 0; k < dyn_ani_count(a); k++) {
            has_comet |= dyn_ani_at(a, k)->kind == DYN_ANI_COMET;
            has_vtext |= dyn_ani_at(a, k)->kind == DYN_ANI_VTEXT;
        }
        assert_true(has_vtext);
        assert_true(has_comet || i == 1);
        dyn_ani_free(a);
        free(at);
        free(ot);
    }
}

/* ---- the command line: dynkit animate MODEL.ode with MODEL.ani beside it ---- */

static void write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

/* Run the tool in the directory ani-cli; its exit status, standard error into err. */
static int animate(const char *args, char *err, size_t size)
{
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "cd ani-cli && DYNKIT_CACHE_DIR=../ani-jit-cache '%s' animate %s "
             "2> err.txt", DYNKIT_CLI, args);
    const int st = system(cmd);
    size_t n = 0;
    char *e = read_file("ani-cli/err.txt", &n);
    snprintf(err, size, "%s", e ? e : "");
    free(e);
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

/* examples/mechanisms/double_pendulum.mech with its .ani (dyn_mech_ani_to_c): compiled, its
 * outputs after the model's and the scene's inputs (scene:K) are the frame's numbers the
 * evaluator gives for the animation read with the model's names (a C model's way, as
 * `dynkit animate` reads it beside a mechanism), at the initial state and a state moved from
 * it; an error of the animation is reported at its place */
static void test_mechanism_animation(void **state)
{
    (void)state;
    char mp[1024], ap[1024], err[4096], buf[2048];
    snprintf(mp, sizeof mp, "%s/examples/mechanisms/double_pendulum.mech", DYNKIT_SOURCE_DIR);
    snprintf(ap, sizeof ap, "%s/examples/mechanisms/double_pendulum.ani", DYNKIT_SOURCE_DIR);
    size_t mlen = 0, alen = 0;
    char *mt = read_file(mp, &mlen), *at = read_file(ap, &alen), *c_src = NULL;
    assert_true(mt && at);
    dyn_lang_diag d;
    CHECK(dyn_mech_ani_to_c(mp, mt, mlen, NULL, 0, 0, ap, at, alen, &c_src, &d) == 0, "%s",
          dyn_lang_diag_format(&d, buf, sizeof buf));
    dyn_jit_opts opts;
    memset(&opts, 0, sizeof opts);
    opts.cache_dir = "ani-jit-cache";
    dyn_jit_model jm;
    CHECK(dyn_jit_load_source(c_src, strlen(c_src), mp, &opts, &jm, err, sizeof err) == 0, "%s",
          err);
    free(c_src);
    const dyn_model *m = jm.model;
    int no = 0, nscene = 0, nani = 0; /* the model's outputs, then scene:K, then ani:K */
    for (int i = 0; i < m->n_outputs; i++) {
        const char *name = m->outputs[i].name;
        if (strncmp(name, "scene:", 6) == 0)
            nscene++;
        else if (strncmp(name, "ani:", 4) == 0)
            CHECK(atoi(name + 4) == nani++, "output %d is %s", i, name);
        else
            CHECK(nscene == 0 && nani == 0 && i == no++, "output %d is %s", i, name);
    }
    const char *sn[16], *on[16], *pn[32];
    assert_true(m->n_states <= 16 && no <= 16 && m->n_params <= 32);
    for (int i = 0; i < m->n_states; i++)
        sn[i] = m->states[i].name;
    for (int i = 0; i < no; i++)
        on[i] = m->outputs[i].name;
    for (int i = 0; i < m->n_params; i++)
        pn[i] = m->params[i].name;
    const dyn_ani_model names = {mp, NULL, 0, m->n_states, no, m->n_params, sn, on, pn};
    dyn_ani *a = NULL;
    CHECK(dyn_ani_parse(ap, at, alen, &names, &a, &d, NULL, NULL) == 0, "%s",
          dyn_lang_diag_format(&d, buf, sizeof buf));
    const int nv = dyn_ani_n_values(a);
    CHECK(nv == nani && nscene > 0, "%d numbers in a frame, %d ani outputs, %d scene inputs", nv,
          nani, nscene);
    void *par = calloc(1, m->par_size + 1);
    double *y = calloc((size_t)m->n_states + 1, sizeof *y), *p = calloc(32, sizeof *p);
    double *out = calloc((size_t)m->n_outputs + 1, sizeof *out), *v = calloc((size_t)nv + 1, 8);
    assert_true(par && y && p && out && v);
    CHECK(dyn_model_default_params(m, par, err, sizeof err) == 0, "%s", err);
    for (int i = 0; i < m->n_params; i++)
        p[i] = dyn_model_get_param(m, par, i);
    int same = 0;
    for (int pass = 0; pass < 2; pass++) {
        for (int i = 0; i < m->n_states; i++)
            y[i] = m->y0[i] + (pass ? 0.1 * (i + 1) : 0.0);
        assert_int_equal(m->compute_outputs(0.3, y, par, out), 0);
        const dyn_ani_frame fr = {0.3, y, out, p};
        assert_int_equal(dyn_ani_eval(a, &fr, v), 0);
        for (int K = 0; K < nv; K++) {
            const double c = out[no + nscene + K];
            CHECK(fabs(c - v[K]) <= 1e-13 * fmax(1.0, fabs(c)),
                  "number %d: compiled %.17g, evaluated %.17g", K, c, v[K]);
            same += same_bits(c, v[K]);
        }
    }
    CHECK(same > 0, "no number of %d has the evaluator's bits", 2 * nv);
    dyn_ani_free(a);
    free(par);
    free(y);
    free(p);
    free(out);
    free(v);
    dyn_jit_unload(&jm);
    c_src = (char *)1;
    CHECK(dyn_mech_ani_to_c(mp, mt, mlen, NULL, 0, 0, "a.ani", "line 0;0;zz;1\n", 14, &c_src,
                            &d) == 2 &&
              c_src == NULL && strcmp(d.path, "a.ani") == 0 && d.line == 1 && d.col == 10,
          "%s", dyn_lang_diag_format(&d, buf, sizeof buf));
    free(mt);
    free(at);
}

static void test_command_line(void **state)
{
    (void)state;
    mkdir("ani-cli", 0777);
    write_text("ani-cli/m.ode", MODEL);
    remove("ani-cli/out.html");
    char err[4096];
    /* an error in m.ani: exit status 2, the place and a caret, nothing written */
    write_text("ani-cli/m.ani", "fcircle x;v;.1;$RED\nline x;vv;1;1\n");
    int rc = animate("m.ode --output out.html", err, sizeof err);
    CHECK(rc == 2 && strstr(err, "m.ani:2:8: error: unknown name 'vv' (did you mean 'v'?)") &&
              strstr(err, "       ^"),
          "status %d: %s", rc, err);
    struct stat st;
    assert_int_not_equal(stat("ani-cli/out.html", &st), 0);
    /* --no-ani leaves it out */
    rc = animate("m.ode --no-ani --output out.html", err, sizeof err);
    CHECK(rc == 0, "status %d: %s", rc, err);
    size_t n = 0;
    char *page = read_file("ani-cli/out.html", &n);
    assert_non_null(page);
    assert_null(strstr(page, "\"ani\":"));
    free(page);
    /* a good one, read beside the model file; --ani names another */
    write_text("ani-cli/m.ani", "PERMANENT\nline 0;0;x;1;$BLUE;2\nTRANSIENT\n"
                                "fcircle x;v;k/10;e\nvtext 0;0;x=;x\ncomet x;v;-2;5\n");
    rc = animate("m.ode --tspan 0:1 --step 0.5 --method rk4 --output out.html", err, sizeof err);
    CHECK(rc == 0, "status %d: %s", rc, err);
    page = read_file("ani-cli/out.html", &n);
    assert_non_null(page);
    /* per run and primitive: one number for a constant, samples (t = 0, 0.5, 1) else; a
     * permanent primitive has the first frame's place */
    CHECK(strstr(page, "\"ani\":{\"file\":\"m.ani\",\"window\":[0,0,1,1]") &&
              strstr(page, "{\"kind\":\"line\",\"line\":2,\"permanent\":true,"
                           "\"color\":\"BLUE\",\"thickness\":2}") &&
              strstr(page, "{\"kind\":\"fcircle\",\"line\":4,\"color\":null,"
                           "\"thickness\":0}") &&
              strstr(page, "{\"kind\":\"comet\",\"line\":6,\"color\":\"BLACK\","
                           "\"type\":-2,\"length\":5}") &&
              strstr(page, "\"runs\":[[{\"v\":[0,0,1,1]},{\"v\":[[1,"), /* x(0) = 1 */
          "%.3000s", strstr(page, "\"ani\":") ? strstr(page, "\"ani\":") : page);
    CHECK(strstr(page, ",0.2,") && strstr(page, "\"s\":[\"x=1\",\"x="), "%.2000s",
          strstr(page, "\"ani\":"));
    free(page);
    write_text("ani-cli/other.ani", "circle .5;.5;.25\n");
    rc = animate("m.ode --ani other.ani --output out.html", err, sizeof err);
    CHECK(rc == 0, "status %d: %s", rc, err);
    page = read_file("ani-cli/out.html", &n);
    assert_non_null(strstr(page, "\"file\":\"other.ani\""));
    free(page);
    /* a missing --ani file, and --ani with --no-ani */
    rc = animate("m.ode --ani none.ani --output out.html", err, sizeof err);
    CHECK(rc == 2 && strstr(err, "none.ani"), "status %d: %s", rc, err);
    rc = animate("m.ode --ani other.ani --no-ani --output out.html", err, sizeof err);
    CHECK(rc == 2 && strstr(err, "contradict"), "status %d: %s", rc, err);
    /* a built-in model with --ani: its states, outputs and parameters by name */
    write_text("ani-cli/p.ani", "line .5;.5;.5+.4*sin(phi);.5-.4*cos(phi)\nvtext 0;0;E=;energy*l\n");
    rc = animate("pendulum --ani p.ani --output out.html", err, sizeof err);
    CHECK(rc == 0, "status %d: %s", rc, err);
    page = read_file("ani-cli/out.html", &n);
    assert_non_null(strstr(page, "\"file\":\"p.ani\""));
    free(page);
    /* NAME.ani beside a C model belongs to the model it was written for: one that names
     * other quantities (a top's theta) is a warning and a page without animation, and one
     * beside NAME.ode is the .ode file's, even when its names fit the C model */
    write_text("ani-cli/top.c",
               "#include <dynkit/model.h>\n"
               "static int rhs(double t, const double *y, double *f, void *p)\n"
               "{ (void)t; (void)p; f[0] = y[1]; f[1] = -y[0]; return 0; }\n"
               "static const dyn_var st[] = {{\"x\", \"m\", \"\"}, {\"v\", \"m/s\", \"\"}};\n"
               "static const double init[] = {1.0, 0.0};\n"
               "static const dyn_model model = {.name = \"top\", .n_states = 2, .states = st,\n"
               "  .y0 = init, .rhs = rhs, .t0 = 0, .t1 = 1, .step = 0.5};\n"
               "const dyn_model *dynkit_model(void) { return &model; }\n");
    write_text("ani-cli/top.ani", "line .5;.5;.5+.4*sin(theta);.5-.4*cos(theta)\n");
    remove("ani-cli/top.ode");
    remove("ani-cli/out.html");
    rc = animate("top.c --output out.html", err, sizeof err);
    CHECK(rc == 0 && strstr(err, "warning: top.ani, found beside the model, does not fit it") &&
              strstr(err, "unknown name 'theta'"),
          "status %d: %s", rc, err);
    page = read_file("ani-cli/out.html", &n);
    assert_non_null(page);
    assert_null(strstr(page, "\"ani\":{"));
    free(page);
    write_text("ani-cli/top.ani", "line .5;.5;.5+.4*sin(x);.5-.4*cos(x)\n");
    rc = animate("top.c --output out.html", err, sizeof err);
    page = read_file("ani-cli/out.html", &n);
    CHECK(rc == 0 && page && strstr(page, "\"file\":\"top.ani\""), "status %d: %s", rc, err);
    free(page);
    write_text("ani-cli/top.ode", "x'=v\nv'=-x\ninit x=1\ndone\n");
    rc = animate("top.c --output out.html", err, sizeof err);
    page = read_file("ani-cli/out.html", &n);
    CHECK(rc == 0 && strstr(err, "warning: top.ani belongs to top.ode, not to top.c") && page &&
              !strstr(page, "\"ani\":{"),
          "status %d: %s", rc, err);
    free(page);
    remove("ani-cli/top.ode");
    /* --help says it */
    rc = animate("--help > help.txt", err, sizeof err);
    char *help = read_file("ani-cli/help.txt", &n);
    assert_true(rc == 0 && help && strstr(help, "--ani FILE.ani") && strstr(help, "--no-ani"));
    free(help);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_command),
        cmocka_unit_test(test_settext_sizes_fonts_and_thickness_as_xppaut),
        cmocka_unit_test(test_colour_names_and_formulas),
        cmocka_unit_test(test_array_lines_and_blocks),
        cmocka_unit_test(test_evaluator_known_values),
        cmocka_unit_test(test_evaluator_matches_the_compiled_model),
        cmocka_unit_test(test_frames_as_outputs_of_the_model),
        cmocka_unit_test(test_errors_name_their_place),
        cmocka_unit_test(test_window_speed_grab_and_notes),
        cmocka_unit_test(test_c_model_names),
        cmocka_unit_test(test_limits_and_damaged_input),
        cmocka_unit_test(test_debian_examples),
        cmocka_unit_test(test_shipped_examples),
        cmocka_unit_test(test_mechanism_animation),
        cmocka_unit_test(test_command_line),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
