/* SPDX-License-Identifier: BSD-3-Clause */
/* test_lang_chain.c — the translator's work grows with the file, not with the ways calls
 * nest. A chain of user functions that each call the one before twice, f_k(u) =
 * f_{k-1}(f_{k-1}(u)), the first reading a fixed quantity (f_0(u) = w sin(u) + u/2,
 * w = a x), means 2^k calls of f_0: expanded where called (as it once was: k = 10 gave
 * 4.2 MB of C, k = 16 ran past 300 s) that is 2^k copies of the body and 4^k terms of the
 * Jacobian. Each function now takes the fixed quantity as an argument and stays one C
 * function: the text grows by the same amount per level and k = 20 translates in
 * milliseconds. Its values and Jacobian match a direct evaluation of the recursion (the
 * same operations in the same order, to the last bit for the values; the Jacobian
 * against central differences). */
#define _GNU_SOURCE
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <ftw.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "dynkit/jit.h"
#include "dynkit/lang.h"
#include "test_util.h"

#define A 0.5 /* the parameter a */

static char *chain_text(int k)
{
    char *text = malloc(4096);
    int n = sprintf(text, "par a=%g\nw=a*x\nf0(u)=w*sin(u)+u/2\n", A);
    for (int i = 1; i <= k; i++)
        n += sprintf(text + n, "f%d(u)=f%d(f%d(u))\n", i, i - 1, i - 1);
    sprintf(text + n, "x'=-f%d(x)\ninit x=1\ndone\n", k);
    return text;
}

static double seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The C text of chain k (and how long the translation took). */
static char *translate_chain(int k, double *took)
{
    char *text = chain_text(k), *out = NULL;
    dyn_lang_diag d;
    const double t0 = seconds();
    const int rc = dyn_ode_to_c("chain.ode", text, strlen(text), &out, &d, NULL, NULL);
    *took = seconds() - t0;
    free(text);
    CHECK(rc == 0, "k = %d: %s", k, d.message);
    return out;
}

/* Each level adds the same text within 2 % (the digits of its numbers), from k = 11 to 20,
 * and k = 20 translates in under 0.2 s to under 40 kB. */
static void test_the_text_grows_linearly(void **state)
{
    (void)state;
    size_t size[21];
    double took = 0.0;
    for (int k = 10; k <= 20; k++) {
        char *out = translate_chain(k, &took);
        size[k] = strlen(out);
        free(out);
    }
    const double step = (double)(size[12] - size[11]);
    for (int k = 11; k <= 20; k++) {
        const double grew = (double)(size[k] - size[k - 1]);
        CHECK(fabs(grew - step) <= 0.02 * step, "level %d adds %.0f bytes, level 12 %.0f", k,
              grew, step);
    }
    CHECK(took < 0.2 && size[20] < 40000, "k = 20: %.3f s, %zu bytes", took, size[20]);
}

static double f_direct(int k, double u, double w)
{
    return k == 0 ? w * sin(u) + u / 2 : f_direct(k - 1, f_direct(k - 1, u, w), w);
}

static int remove_entry(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st, (void)flag, (void)ftw;
    return remove(path);
}

/* Compiled (libtcc when built in, else cc): x' = -f_k(x) at x = 0.8 equals the direct
 * recursion bit for bit, for k = 3, 10 and 16; the Jacobian (through the fixed quantity
 * too: w = a x) agrees with central differences of the recursion within 1e-7. */
static void test_values_match_the_recursion(void **state)
{
    (void)state;
    char root[] = "/tmp/dynkit chain XXXXXX";
    assert_non_null(mkdtemp(root));
    char cache[600];
    snprintf(cache, sizeof cache, "%s/cache", root);
    const dyn_jit_opts o = {.backend = dyn_jit_backend_available(DYN_JIT_TCC) ? DYN_JIT_TCC
                                                                               : DYN_JIT_CC,
                            .cache_dir = cache};
    const int ks[3] = {3, 10, 16};
    for (int i = 0; i < 3; i++) {
        const int k = ks[i];
        double took;
        char *out = translate_chain(k, &took);
        dyn_jit_model jm;
        char err[4096];
        const int rc = dyn_jit_load_source(out, strlen(out), "chain.ode", &o, &jm, err,
                                           sizeof err);
        free(out);
        CHECK(rc == 0, "k = %d: %s", k, err);
        const dyn_model *m = jm.model;
        double *par = calloc(1, m->par_size);
        par[0] = A;
        char perr[256];
        assert_int_equal(m->prepare(par, perr, sizeof perr), 0);
        const double x = 0.8;
        double y = x, dy = 0.0, J = 0.0;
        assert_int_equal(m->rhs(0.0, &y, &dy, par), 0);
        const double want = -f_direct(k, x, A * x);
        CHECK(dy == want, "k = %d: x' = %.17g, the recursion %.17g", k, dy, want);
        CHECK(m->jacobian != NULL, "k = %d: an analytic Jacobian", k);
        assert_int_equal(m->jacobian(0.0, &y, &J, par), 0);
        const double h = 1e-6;
        const double fd = -(f_direct(k, x + h, A * (x + h)) - f_direct(k, x - h, A * (x - h))) /
                          (2 * h);
        CHECK(fabs(J - fd) <= 1e-7 * fmax(1.0, fabs(fd)), "k = %d: J = %.12g, differences %.12g",
              k, J, fd);
        free(par);
        dyn_jit_unload(&jm);
    }
    nftw(root, remove_entry, 16, FTW_DEPTH | FTW_PHYS);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_the_text_grows_linearly),
        cmocka_unit_test(test_values_match_the_recursion),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
