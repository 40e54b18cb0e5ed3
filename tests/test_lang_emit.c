/* SPDX-License-Identifier: BSD-3-Clause */
/* test_lang_emit.c — a model file is data: nothing from its path or its text becomes code
 * in the C the translator writes (src/lang/emit_out.c states the rule). The C text of
 * hostile paths, names, `#:` text and tables passes the token check of fuzz/emit_check.h
 * (the fuzz harness fuzz_emit's), compiles, and gives back every outside string byte for
 * byte as data; a directory whose name once closed the header comment and ran a
 * constructor runs nothing. Every shipped example and XPPAUT's examples pass the check. */
#define _GNU_SOURCE
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <dirent.h>
#include <ftw.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "../fuzz/emit_check.h"
#include "dynkit/jit.h"
#include "dynkit/lang.h"
#include "dynkit/mbs.h"
#include "lang/lang_internal.h"
#include "test_util.h"

/* The C text of text (named path), which must translate and pass the token check. */
static char *emit_checked(const char *path, const char *text)
{
    char *out = NULL;
    dyn_lang_diag d;
    const int rc = dyn_ode_to_c(path, text, strlen(text), &out, &d, NULL, NULL);
    CHECK(rc == 0, "%s: %s", path, d.message);
    char why[512];
    CHECK(emit_check(out, lang_alg_solver_text(), why, sizeof why) == 0, "%s: %s", path, why);
    return out;
}

static int remove_entry(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st, (void)flag, (void)ftw;
    return remove(path);
}

static char *read_all(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    const long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *s = malloc((size_t)n + 1);
    if (s && fread(s, 1, (size_t)n, f) != (size_t)n) {
        free(s);
        s = NULL;
    }
    if (s)
        s[n] = '\0';
    fclose(f);
    return s;
}

/* A directory named "a*\001" then one whose name is C code: the path once went into the
 * header comment with the control byte dropped after the check for the comment's end, so
 * the comment closed and the next name was compiled; its constructor ran system(). Now
 * the C text passes the check, and compiled and loaded (cc, and libtcc when built in) the
 * model runs while the marker file stays absent; its .source is the path, byte for byte. */
static void test_hostile_path_runs_nothing(void **state)
{
    (void)state;
    char root[] = "/tmp/dynkit emit test XXXXXX";
    assert_non_null(mkdtemp(root));
    char marker[512], dir[1024], path[1280], cache[600];
    /* the name of the directory that was code (a name holds no '/': it touches PWNED in
     * the working directory, root during the test) */
    snprintf(marker, sizeof marker, "%s/PWNED", root);
    snprintf(cache, sizeof cache, "%s/cache", root);
    snprintf(dir, sizeof dir, "%s/a*\001", root);
    assert_int_equal(mkdir(dir, 0700), 0);
    const size_t used = strlen(dir);
    snprintf(dir + used, sizeof dir - used,
             "/int system(const char *); __attribute__((constructor)) static void dk_x(void) "
             "{ system(\"touch PWNED\"); } ");
    assert_int_equal(mkdir(dir, 0700), 0);
    snprintf(path, sizeof path, "%s/*m.ode", dir);
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs("x'=-x\ninit x=1\ndone\n", f);
    fclose(f);
    char *text = read_all(path);
    assert_non_null(text);
    char *out = emit_checked(path, text);
    free(text);
    char here[1024];
    assert_non_null(getcwd(here, sizeof here));
    assert_int_equal(chdir(root), 0); /* where the code would touch PWNED */
    const dyn_jit_backend backends[2] = {DYN_JIT_CC, DYN_JIT_TCC};
    for (int b = 0; b < 2; b++) {
        if (!dyn_jit_backend_available(backends[b]))
            continue;
        dyn_jit_opts o = {.backend = backends[b], .cache_dir = cache};
        dyn_jit_model jm;
        char err[4096];
        const int rc = dyn_jit_load_source(out, strlen(out), path, &o, &jm, err, sizeof err);
        CHECK(rc == 0, "%s: %s", dyn_jit_backend_name(backends[b]), err);
        double y = 2.0, dy = 0.0;
        assert_int_equal(jm.model->rhs(0.0, &y, &dy, NULL), 0);
        CHECK(dy == -2.0, "x' = -x at x = 2 is %g", dy);
        CHECK(strcmp(jm.model->source, path) == 0, "the source is the path: %s",
              jm.model->source);
        dyn_jit_unload(&jm);
        CHECK(access(marker, F_OK) != 0, "%s: the path's code ran",
              dyn_jit_backend_name(backends[b]));
    }
    assert_int_equal(chdir(here), 0);
    free(out);
    nftw(root, remove_entry, 16, FTW_DEPTH | FTW_PHYS);
}

/* Names that are C keywords, libc functions or the translator's own locals, `#:` text
 * with comment ends, quotes, backslashes, trigraphs, control and non-ASCII bytes: the C
 * text passes the check, compiles, and its strings are the file's bytes; x' = -k x with
 * double = 2 (a parameter) at system = 3 is -6. */
static void test_hostile_names_and_text(void **state)
{
    (void)state;
    const char *model =
        "#: title T */ int evil; /* ?\?/ \" \\ \x01 \xc3\xa9\n"
        "#: description D */ #include <stdlib.h> ?\?= \\ x\n"
        "par double=2\n"
        "#: double [m*/s\"\\?\?/] it */ system(\"id\"); /*\n"
        "v_0=double*system\n"
        "system'=-v_0\n"
        "init system=3\n"
        "#: system [*/] state */\n"
        "u_0(dk_rhs)=dk_rhs*double\n"
        "aux main=u_0(system)\n"
        "#: main [?\?/] out */\n"
        "#: event return = system-1, falling -- */ evil ?\?/\n"
        "global 1 {system-0.5} {system=3}\n"
        "table static % 3 0 2 t*double\n"
        "aux y=static(system)\n"
        "done\n";
    const char *hostile_path = "s*/p\\a\"c e?\?/\"?\?/\n\x7f.ode";
    char *out = emit_checked(hostile_path, model);
    char root[] = "/tmp/dynkit emit names XXXXXX";
    assert_non_null(mkdtemp(root));
    char cache[600];
    snprintf(cache, sizeof cache, "%s/cache", root);
    const dyn_jit_backend backends[2] = {DYN_JIT_CC, DYN_JIT_TCC};
    for (int b = 0; b < 2; b++) {
        if (!dyn_jit_backend_available(backends[b]))
            continue;
        /* -std=c11 reads trigraphs: the jit's #line of the path once turned ??/ and the
         * quote after it into an escaped backslash and the end of the name (with -Werror:
         * "extra tokens at end of #line directive") */
        dyn_jit_opts o = {.backend = backends[b], .cache_dir = cache, .cflags = "-std=c11 -Werror"};
        dyn_jit_model jm;
        char err[4096];
        const int rc = dyn_jit_load_source(out, strlen(out), hostile_path, &o, &jm, err,
                                           sizeof err);
        CHECK(rc == 0, "%s: %s", dyn_jit_backend_name(backends[b]), err);
        const dyn_model *m = jm.model;
        CHECK(strcmp(m->title, "T */ int evil; /* ?\?/ \" \\ \x01 \xc3\xa9") == 0, "title %s",
              m->title);
        CHECK(strstr(m->description, "D */ #include <stdlib.h> ?\?= \\ x") != NULL, "%s",
              m->description);
        CHECK(strcmp(m->params[0].name, "double") == 0 &&
                  strcmp(m->params[0].unit, "m*/s\"\\?\?/") == 0 &&
                  strcmp(m->params[0].description, "it */ system(\"id\"); /*") == 0,
              "%s [%s] %s", m->params[0].name, m->params[0].unit, m->params[0].description);
        CHECK(strcmp(m->states[0].name, "system") == 0 && strcmp(m->states[0].unit, "*/") == 0,
              "%s [%s]", m->states[0].name, m->states[0].unit);
        CHECK(strcmp(m->outputs[0].name, "main") == 0 && strcmp(m->outputs[0].unit, "?\?/") == 0,
              "%s [%s]", m->outputs[0].name, m->outputs[0].unit);
        CHECK(strcmp(m->source, hostile_path) == 0, "source %s", m->source);
        CHECK(strcmp(m->events[0].name, "return") == 0 &&
                  strcmp(m->events[0].description, "*/ evil ?\?/") == 0,
              "%s -- %s", m->events[0].name, m->events[0].description);
        double *par = calloc(1, m->par_size);
        memcpy(par, &(double){2.0}, sizeof(double));
        char perr[256];
        assert_int_equal(m->prepare(par, perr, sizeof perr), 0);
        double y = 3.0, dy = 0.0, o2[2];
        assert_int_equal(m->rhs(0.0, &y, &dy, par), 0);
        CHECK(dy == -6.0, "system' = -v_0 = -double * system = -6 at 3, got %g", dy);
        assert_int_equal(m->compute_outputs(0.0, &y, par, o2), 0);
        CHECK(o2[0] == 6.0 && o2[1] == 6.0, "main = 2 * 3 = %g, the table 2 t at 3: %g",
              o2[0], o2[1]);
        free(par);
        dyn_jit_unload(&jm);
    }
    free(out);
    nftw(root, remove_entry, 16, FTW_DEPTH | FTW_PHYS);
}

/* Every .ode and .mech file of dir that translates passes the check; returns how many
 * did. */
static int check_dir(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d)
        return 0;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        const size_t l = strlen(e->d_name);
        const int mech = l > 5 && strcmp(e->d_name + l - 5, ".mech") == 0;
        if (!mech && (l < 5 || strcasecmp(e->d_name + l - 4, ".ode") != 0))
            continue;
        char path[1024];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        char *text = read_all(path);
        if (!text)
            continue;
        char *out = NULL;
        dyn_lang_diag dg;
        const int rc = mech ? dyn_mech_to_c(path, text, strlen(text), NULL, 0, &out, &dg,
                                            NULL, NULL)
                            : dyn_ode_to_c(path, text, strlen(text), &out, &dg, NULL, NULL);
        if (rc == 0) {
            char why[512];
            CHECK(emit_check(out, lang_alg_solver_text(), why, sizeof why) == 0, "%s: %s",
                  path, why);
            n++;
            free(out);
        }
        free(text);
    }
    closedir(d);
    return n;
}

/* The shipped examples (all 8 translate; 4 or more of the mechanisms without their table
 * files) and XPPAUT's own (Debian's package, when
 * installed: 65 or more translate) pass the check: the token rule fits real models. */
static void test_examples_pass_the_check(void **state)
{
    (void)state;
    const int shipped = check_dir(DYNKIT_SOURCE_DIR "/examples/models");
    CHECK(shipped >= 8, "%d shipped examples translated", shipped);
    const int mechanisms = check_dir(DYNKIT_SOURCE_DIR "/examples/mechanisms");
    CHECK(mechanisms >= 4, "%d mechanisms translated", mechanisms);
    const int debian = check_dir("/usr/share/doc/xppaut/examples/ode");
    if (access("/usr/share/doc/xppaut/examples/ode", F_OK) == 0)
        CHECK(debian >= 65, "%d of XPPAUT's examples translated", debian);
    /* the features the examples may miss: network sums, algebraic equations, a band,
     * tables from a formula, partial derivatives of functions */
    const char *more[] = {
        "table w % 3 -1 1 1\nf[0..3]=heav(u[j])\nspecial z=conv(even,4,1,w,f0)\n"
        "u[0..3]'=-u[j]+z([j])\n",
        "table w % 4 0 3 1\nspecial k=mmult(2,2,w,x0)\nx[0..1]'=k([j])\n",
        "f(a,b)=a*b\ntable w % 3 -1 1 1\nspecial k=fconv(period,2,1,w,x0,x0,f)\nx[0..1]'=k([j])\n",
        "solv w=1\n0=w^3+w-x\nx'=-w\ninit x=1\n",
        "@ bandlo=1, bandup=1\nx0'=-x0\nx[1..3]'=-x[j]+0.5*x[j-1]\n",
        "g(a)=sin(a)*a^3/(1+a^2)\npar q=1\nx'=g(x*q)+max(x,q)+mod(x,2)+sign(x)+abs(x)\n"
        "y'=if(x>1)then(x)else(-y)+atan2(x,y)+erf(y)+flr(x)+ceil(y)+not(x)+(x>=y)+(x<=y)\n"
        "init x=0.5\nglobal 1 {x-1} {x=0;y=y+1}\naux e=x^2+y^2\n",
        "x(t+1)=x*(1-x)\ninit x=0.1\n"};
    for (size_t i = 0; i < sizeof more / sizeof *more; i++)
        free(emit_checked("more.ode", more[i]));
}

/* The check itself: a name of the file as an identifier, the path in a comment, an
 * unescaped byte in a literal, a trigraph, a stray byte are each refused. */
static void test_the_check_refuses(void **state)
{
    (void)state;
    char why[512];
    const char *ok = "static double u_0(double a_0) { return \"a\\001\" [0] + 1e-05; }\n";
    CHECK(emit_check(ok, NULL, why, sizeof why) == 0, "%s", why);
    const char *bad[] = {"static double u_speed(double a_0);\n", "/* m.ode */\n",
                         "const char *s = \"a\001\";\n", "const char *s = \"?\?/\";\n",
                         "x = y @ 2;\n", "#include <stdlib.h>\n", "// m.ode\n",
                         "int system;\n"};
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++)
        CHECK(emit_check(bad[i], NULL, why, sizeof why) != 0, "accepted: %s", bad[i]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_the_check_refuses),
        cmocka_unit_test(test_hostile_path_runs_nothing),
        cmocka_unit_test(test_hostile_names_and_text),
        cmocka_unit_test(test_examples_pass_the_check),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
