/* SPDX-License-Identifier: BSD-3-Clause */
/* Prints include/dynkit/erk_kernels.h: the step of the library's embedded pairs bs23, dp45
 * and dop853 written out with their coefficients as constants, from the library's own
 * tables (dyn_method_find), so that the kernels cannot drift from them.
 *
 * For each pair it emits
 * - the table (a, b, c, e, e3) as arrays, by which dyn_ek_match recognises a table;
 * - dyn_ek_<pair>_row(r, ...): stage r's state (y + h * (sum of row r's non-zero a_rj k_j
 *   but the last, left to right from the first)) + (h a_rl) k_l, or y_{n+1} for r = s (row
 *   b), exactly the arithmetic of the library's stage loop for embedded pairs
 *   (src/ode/rk_stages.h: the newest term apart, off the chain of the other terms);
 * - dyn_ek_<pair>_err(...): the sums of squares of Hairer's error norm (src/ode/step_erk.c,
 *   err_sums), every sum started from -0.0 as there (the same as from its first term).
 * Zero coefficients do not appear, so every compiler folds the whole step at any
 * optimisation level; a loop over a table known only at run time is what it replaces.
 *
 *     build/tests/gen_erk_kernels > include/dynkit/erk_kernels.h
 * CTest erk_kernels_current fails when the committed header differs from this output.
 */
#include <stdio.h>
#include <string.h>

#include "dynkit/ode.h"

/* v as a C array, rows of row_len values (wrapped at 4 a line) */
static void array(const char *pair, const char *what, const double *v, int count, int row_len)
{
    printf("static const double dyn_ek_%s_%s[%d] = {\n", pair, what, count);
    for (int i = 0; i < count; i++) {
        const int col = i % row_len;
        printf("%s%.17g,%s", col % 4 == 0 ? "    " : " ", v[i],
               col == row_len - 1 || col % 4 == 3 ? "\n" : "");
    }
    printf("};\n");
}

/* case r of dyn_ek_<pair>_row: the combination of one row of length len */
static void row_case(int r, const double *row, int len)
{
    int nt = 0;
    for (int j = 0; j < len; j++)
        nt += row[j] != 0.0;
    printf("    case %d:\n", r);
    if (nt == 0) {
        printf("        return 0;\n");
        return;
    }
    int jl = len - 1; /* the last term, added apart: (h a_l) k_l */
    while (row[jl] == 0.0)
        jl--;
    printf("        {\n            const double hc = h * %.17g;\n", row[jl]);
    if (nt == 1) {
        printf("            DYN_EK_LOOP(q) DYN_EK_PUT(q, y[q] + hc * k[%d * N + q]);\n", jl);
        printf("        }\n        return 1;\n");
        return;
    }
    printf("            DYN_EK_LOOP(q) DYN_EK_PUT(q, (y[q] + h * (");
    int t = 0;
    for (int j = 0; j < jl; j++) {
        if (row[j] == 0.0)
            continue;
        printf("%s%.17g * k[%d * N + q]",
               t ? "\n                                                    + " : "", row[j], j);
        t++;
    }
    printf("))\n                                          + hc * k[%d * N + q]);\n", jl);
    printf("        }\n        return %d;\n", nt);
}

/* the sum of one estimate's terms for component i, from -0.0 (the same as from its first) */
static void err_sum(const char *var, const double *e, int s)
{
    printf("        double %s = -0.0;\n", var);
    for (int j = 0; j < s; j++)
        if (e[j] != 0.0)
            printf("        %s += %.17g * k[%d * N + i];\n", var, e[j], j);
}

static int pair(const char *name)
{
    const dyn_tableau *m = dyn_method_find(name);
    if (!m || m->kind != DYN_KIND_EMBEDDED_RK || !m->e) {
        fprintf(stderr, "gen_erk_kernels: %s is not an embedded pair of the library\n", name);
        return 1;
    }
    const int s = m->stages;
    printf("\n/* ---- %s: %s (%d stages%s) ---- */\n", m->name, m->title, s,
           m->fsal ? ", first same as last" : "");
    array(m->name, "a", m->a, s * s, s);
    array(m->name, "b", m->b, s, s);
    array(m->name, "c", m->c, s, s);
    array(m->name, "e", m->e, s, s);
    if (m->e3)
        array(m->name, "e3", m->e3, s, s);
    printf("\n/* Stage r < %d: out = y + h * (row r of a) . k; r = %d: y_{n+1} = y + h * b . k, with\n"
           " * the last term added apart: (y + h * (the others)) + (h a_l) k_l.\n"
           " * Returns the number of terms (0: out is not written, the stage state is y). */\n",
           s, s);
    printf("DYN_EK_FN int dyn_ek_%s_row(const int r, const int n, const double h,\n"
           "                             const double *DYN_EK_RESTRICT y,\n"
           "                             const double *DYN_EK_RESTRICT k,\n"
           "                             double *DYN_EK_RESTRICT out)\n{\n"
           "    const size_t N = (size_t)n;\n    switch (r) {\n",
           m->name);
    for (int r = 0; r < s; r++)
        row_case(r, m->a + (size_t)r * (size_t)s, r);
    row_case(s, m->b, s);
    printf("    default:\n        return 0;\n    }\n}\n");
    printf("\n/* Sum over the states of (err_i / sk_i)^2, err_i = sum_j e_j k_j,i, sk_i "
           "=\n * atol + rtol max(|y_i|, |ynew_i|)%s. */\n",
           m->e3 ? "; *s3 likewise for e3" : "");
    printf("DYN_EK_FN double dyn_ek_%s_err(const int n, const double rtol, const double atol,\n"
           "                                const double *DYN_EK_RESTRICT y,\n"
           "                                const double *DYN_EK_RESTRICT ynew,\n"
           "                                const double *DYN_EK_RESTRICT k, double *s3)\n{\n"
           "    const size_t N = (size_t)n;\n    double s5 = -0.0, s3_ = -0.0;\n"
           "    DYN_EK_LOOP(i)\n    {\n",
           m->name);
    err_sum("err", m->e, s);
    if (m->e3)
        err_sum("err3", m->e3, s);
    printf("        const double ay = fabs(y[i]), an = fabs(ynew[i]);\n"
           "        const double sk = atol + rtol * (ay > an ? ay : an);\n"
           "        const double r = err / sk;\n        s5 += r * r;\n");
    if (m->e3)
        printf("        const double r3 = err3 / sk;\n        s3_ += r3 * r3;\n");
    printf("    }\n    *s3 = s3_;\n    return s5;\n}\n");
    return 0;
}

int main(void)
{
    printf(
        "/* SPDX-License-Identifier: BSD-3-Clause */\n"
        "/* dynkit/erk_kernels.h — GENERATED by tools/gen_erk_kernels.c from the library's "
        "tables;\n"
        " * do not edit (CTest erk_kernels_current checks it).\n"
        " *\n"
        " * The steps of the embedded pairs bs23, dp45 and dop853 with their coefficients as\n"
        " * constants, for the header-only adaptive driver (dynkit/solve_inline.h) and the\n"
        " * library's fast path of dyn_solve: the same arithmetic as the library's stage loop\n"
        " * (src/ode/rk_stages.h) and error norm (src/ode/step_erk.c), term for term, so\n"
        " * results are bit for bit the same; only the zero terms and the loads of the\n"
        " * coefficients are gone. Internal to dynkit: names and signatures may change.\n"
        " */\n"
        "#ifndef DYNKIT_ERK_KERNELS_H\n#define DYNKIT_ERK_KERNELS_H\n\n"
        "#include <math.h>\n#include <stddef.h>\n\n"
        "#if defined(__GNUC__)\n"
        "#define DYN_EK_FN static inline __attribute__((always_inline, unused))\n"
        "#else\n#define DYN_EK_FN static inline\n#endif\n"
        "#ifdef __cplusplus\n#define DYN_EK_RESTRICT __restrict\n#else\n"
        "#define DYN_EK_RESTRICT restrict\n#endif\n"
        "/* loops over the states: unrolled for small constant n at any optimisation level (clang\n"
        " * does it by itself; its unroll_count pragma kept an indexed loop instead, see\n"
        " * DYN_INL_UNROLL in dynkit/ode_inline.h) */\n"
        "#if defined(__clang__)\n"
        "#define DYN_EK_LOOP(q) for (int q = 0; q < n; q++)\n"
        "#elif defined(__GNUC__)\n"
        "#define DYN_EK_LOOP(q) _Pragma(\"GCC unroll 4\") for (int q = 0; q < n; q++)\n"
        "#else\n#define DYN_EK_LOOP(q) for (int q = 0; q < n; q++)\n#endif\n"
        "/* a stage value pinned to a register (see DYN_RK_SCALAR in src/ode/rk_stages.h) */\n"
        "#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))\n"
        "#define DYN_EK_PUT(q, expr) do { double v_ = (expr); __asm__(\"\" : \"+x\"(v_)); "
        "out[q] = v_; } while (0)\n"
        "#elif defined(__GNUC__) && defined(__aarch64__)\n"
        "#define DYN_EK_PUT(q, expr) do { double v_ = (expr); __asm__(\"\" : \"+w\"(v_)); "
        "out[q] = v_; } while (0)\n"
        "#else\n#define DYN_EK_PUT(q, expr) (out[q] = (expr))\n#endif\n");
    if (pair("bs23") || pair("dp45") || pair("dop853"))
        return 1;
    printf("\n#endif /* DYNKIT_ERK_KERNELS_H */\n");
    return 0;
}
