/* SPDX-License-Identifier: BSD-3-Clause */
/* test_band.c — band matrices in the stiff method (src/ode/band_lu.c, jacobian_band.c, the
 * banded path of rodas4) on the Brusselator of Hairer & Wanner II, sec. IV.10:
 * - the band LU solves random band systems (pivoting forced by weak diagonals) like the
 *   dense LU, to rounding, for every shape (lower 0..3, upper 0..3, n from 1 to 40), and
 *   LAPACK's dgbtrf/dgbtrs (backend dynkit_lapack, when built) agree with both;
 * - the grouped difference Jacobian costs lower + upper + 1 calls and equals the analytic
 *   band to difference accuracy; the full analytic Jacobian is zero outside the declared
 *   band and equals the band inside (the model's band is right);
 * - rodas4 with band matrices gives the dense run's solution (same steps, rounding apart),
 *   with the analytic band and with grouped differences;
 * - the accuracy follows the tolerance against a reference of much tighter tolerance, and
 *   the sizes cost linear work: counts of f per step do not grow with N;
 * - against SciPy's independent reference (N = 20, t = 10) the band run is as accurate as
 *   its tolerance asks. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>

#include "dynkit/brusselator.h"
#include "dynkit/problems.h"
#include "dynkit/solve.h"
#include "ode/jacobian.h"
#include "ode/linalg.h"
#include "test_util.h"
#ifdef DYNKIT_HAVE_LAPACK
#include "dynkit/lapack.h"
#endif

/* Deterministic uniform numbers in [-1, 1) (xorshift64*). */
static double rnd(uint64_t *s)
{
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    return (double)((*s * 2685821657736338717ULL) >> 11) * 0x1.0p-52 - 1.0;
}

static double max_abs(const double *x, int n)
{
    double m = 0.0;
    for (int i = 0; i < n; i++)
        m = fmax(m, fabs(x[i]));
    return m;
}

/* One random band system of each shape solved three ways. */
static void test_band_lu_matches_dense(void **state)
{
    (void)state;
    enum { NMAX = 40 };
    static double A[NMAX * NMAX], LU[NMAX * NMAX], ab[NMAX * 10], ab2[NMAX * 10];
    double b[NMAX], x_dense[NMAX], x_band[NMAX], x_lapack[NMAX];
    int piv[NMAX], piv2[NMAX];
    uint64_t seed = 0x9e3779b97f4a7c15ULL;
    int cases = 0, pivoted = 0;
    for (int n = 1; n <= NMAX; n += (n < 8 ? 1 : 7))
        for (int kl = 0; kl <= 3; kl++)
            for (int ku = 0; ku <= 3; ku++) {
                if (kl >= n || ku >= n)
                    continue;
                const int ldab = 2 * kl + ku + 1;
                memset(A, 0, sizeof A);
                memset(ab, 0, sizeof ab);
                for (int i = 0; i < n; i++)
                    for (int j = i - kl; j <= i + ku; j++)
                        if (j >= 0 && j < n) {
                            /* weak diagonal every third row: partial pivoting must swap */
                            double v = rnd(&seed);
                            if (i == j)
                                v = (i % 3 == 0) ? 1e-3 * v : 2.0 + v;
                            A[i * n + j] = v;
                            ab[(size_t)j * ldab + (size_t)(kl + ku + i - j)] = v;
                        }
                for (int i = 0; i < n; i++)
                    b[i] = x_dense[i] = x_band[i] = x_lapack[i] = rnd(&seed);
                memcpy(LU, A, sizeof(double) * (size_t)(n * n));
                memcpy(ab2, ab, sizeof(double) * (size_t)(n * ldab));
                assert_int_equal(dyn_lu_factor(n, LU, piv), 0);
                dyn_lu_solve(n, LU, piv, x_dense);
                assert_int_equal(dyn_band_solver_builtin.factor(n, kl, ku, ab, ldab, piv2), 0);
                dyn_band_solver_builtin.solve(n, kl, ku, ab, ldab, piv2, x_band);
                for (int j = 0; j < n; j++)
                    pivoted += piv2[j] != j;
                /* the residual of the band solution and its distance to the dense one */
                double r[NMAX];
                for (int i = 0; i < n; i++) {
                    double s = -b[i];
                    for (int j = 0; j < n; j++)
                        s += A[i * n + j] * x_band[j];
                    r[i] = s;
                }
                const double scale = fmax(1.0, max_abs(x_dense, n));
                CHECK(max_abs(r, n) <= 1e-11 * scale, "n %d kl %d ku %d: residual %g", n, kl,
                      ku, max_abs(r, n));
                CHECK(max_abs_diff(x_band, x_dense, n) <= 1e-10 * scale,
                      "n %d kl %d ku %d: band and dense differ by %g", n, kl, ku,
                      max_abs_diff(x_band, x_dense, n));
#ifdef DYNKIT_HAVE_LAPACK
                assert_int_equal(dyn_band_solver_lapack.factor(n, kl, ku, ab2, ldab, piv2), 0);
                dyn_band_solver_lapack.solve(n, kl, ku, ab2, ldab, piv2, x_lapack);
                CHECK(max_abs_diff(x_lapack, x_dense, n) <= 1e-10 * scale,
                      "n %d kl %d ku %d: LAPACK and dense differ by %g", n, kl, ku,
                      max_abs_diff(x_lapack, x_dense, n));
#endif
                cases++;
            }
    test_note("%d band systems, %d row interchanges\n", cases, pivoted);
    assert_true(pivoted > 50);
}

/* A zero column is reported with its (1-based) index, as dgbtrf's info. */
static void test_band_lu_singular(void **state)
{
    (void)state;
    const int n = 5, kl = 1, ku = 1, ldab = 2 * kl + ku + 1;
    double ab[5 * 4] = {0};
    int piv[5];
    for (int j = 0; j < n; j++)
        if (j != 2)
            ab[(size_t)j * ldab + (size_t)(kl + ku)] = 1.0; /* diagonal, column 2 empty */
    assert_int_equal(dyn_band_lu_factor(n, kl, ku, ab, ldab, piv), 3);
}

typedef struct counted {
    dyn_brusselator_par p;
    long calls;
} counted;

static int counted_rhs(double t, const double *y, double *dydt, void *par)
{
    counted *c = par;
    c->calls++;
    return dyn_brusselator_rhs(t, y, dydt, &c->p);
}

static dyn_model *bruss(int N, dyn_brusselator_par *p, double *y0)
{
    char err[128];
    dyn_model *m = dyn_brusselator_new(N, err, sizeof err);
    assert_non_null(m);
    assert_int_equal(dyn_model_default_params(m, p, err, sizeof err), 0);
    dyn_model_initial_state(m, p, y0);
    return m;
}

static void test_difference_band_matches_analytic(void **state)
{
    (void)state;
    enum { N = 20, n = 2 * N, W = 5 };
    counted c = {{0}, 0};
    double y[n], f0[n], Jfd[n * W], Jan[n * W], Jfull[n * n], work[2 * n];
    dyn_model *m = bruss(N, &c.p, y);
    uint64_t seed = 7;
    for (int i = 0; i < n; i++)
        y[i] += 0.3 * rnd(&seed); /* off the initial profile: u v and u^2 terms matter */
    const dyn_system sys = {counted_rhs, n, &c};
    counted_rhs(0.0, y, f0, &c);
    c.calls = 0;
    long calls = 0;
    assert_int_equal(dyn_fd_jacobian_band(&sys, 0.0, y, f0, NULL, 2, 2, Jfd, work, &calls), 0);
    assert_int_equal(calls, W);
    assert_int_equal(c.calls, W);
    dyn_brusselator_jac_band(0.0, y, Jan, &c.p);
    dyn_brusselator_jac(0.0, y, Jfull, &c.p);
    double worst = 0.0, big = 0.0;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            const double full = Jfull[i * n + j];
            if (abs(i - j) > 2) {
                CHECK(full == 0.0, "J(%d, %d) = %g outside the declared band", i, j, full);
                continue;
            }
            const double an = DYN_BAND_AT(Jan, 2, 2, i, j), fd = DYN_BAND_AT(Jfd, 2, 2, i, j);
            CHECK(an == full, "band and full Jacobian differ at (%d, %d)", i, j);
            worst = fmax(worst, fabs(fd - an));
            big = fmax(big, fabs(an));
        }
    test_note("grouped differences: %d calls for %d states, max error %.3g of max |J| %.3g\n",
              W, n, worst, big);
    /* forward differences: about sqrt(eps) relative (the diagonal holds -2 alpha (N+1)^2) */
    assert_true(worst <= 1e-6 * big);
    dyn_brusselator_free(m);
}

/* rodas4 on the Brusselator of size N: dense or band matrices, analytic or differences. */
typedef struct run_out {
    double y[400];
    dyn_result res;
} run_out;

static void run_rodas(int N, int banded, int analytic, double rtol, run_out *out)
{
    dyn_brusselator_par p;
    const int n = 2 * N;
    assert_true(n <= 400);
    double y0[400];
    dyn_model *m = bruss(N, &p, y0);
    const dyn_tableau *meth = dyn_method_find("rodas4");
    dyn_solve_opts o = {0};
    o.rtol = rtol;
    o.atol = rtol;
    o.jacobian = analytic ? dyn_brusselator_jac : NULL;
    o.jac_banded = banded;
    o.jac_lower = o.jac_upper = 2;
    o.jacobian_band = analytic ? dyn_brusselator_jac_band : NULL;
    const size_t size = dyn_solve_work_size(meth, n, &o);
    double *work = malloc(size * sizeof *work);
    int *iwork = malloc(dyn_solve_iwork_size(meth, n) * sizeof *iwork);
    assert_non_null(work);
    assert_non_null(iwork);
    o.iwork = iwork;
    const dyn_system sys = {dyn_brusselator_rhs, n, &p};
    assert_int_equal(dyn_solve(meth, &sys, 0.0, 10.0, y0, out->y, work, &o, &out->res), DYN_OK);
    free(work);
    free(iwork);
    dyn_brusselator_free(m);
}

static void test_rodas_band_equals_dense(void **state)
{
    (void)state;
    enum { N = 10, n = 2 * N };
    static run_out dense, band, dense_fd, band_fd;
    run_rodas(N, 0, 1, 1e-6, &dense);
    run_rodas(N, 1, 1, 1e-6, &band);
    run_rodas(N, 0, 0, 1e-6, &dense_fd);
    run_rodas(N, 1, 0, 1e-6, &band_fd);
    /* the same analytic J: only the rounding of the factorisation differs */
    assert_int_equal(band.res.stats.accepted, dense.res.stats.accepted);
    assert_int_equal(band.res.stats.rejected, dense.res.stats.rejected);
    CHECK(max_abs_diff(band.y, dense.y, n) <= 1e-12, "band vs dense: %g",
          max_abs_diff(band.y, dense.y, n));
    /* differences: the grouped ones give the same columns as one-by-one (same increments,
     * other rows unperturbed), so the two runs agree to rounding, at 5 calls instead of 20 */
    CHECK(max_abs_diff(band_fd.y, dense_fd.y, n) <= 1e-10, "band vs dense differences: %g",
          max_abs_diff(band_fd.y, dense_fd.y, n));
    const long jac_fd_dense = dense_fd.res.stats.rhs_calls - dense.res.stats.rhs_calls;
    const long jac_fd_band = band_fd.res.stats.rhs_calls - band.res.stats.rhs_calls;
    test_note("N = %d: %ld steps; calls of f for Jacobians: %ld dense, %ld grouped\n", N,
              dense.res.stats.accepted, jac_fd_dense, jac_fd_band);
    assert_true(jac_fd_band * 3 < jac_fd_dense);
}

/* The error of the band run follows the tolerance (against a run 1e4 times tighter), and
 * the work per step of the analytic band does not grow with N. */
static void test_rodas_band_accuracy(void **state)
{
    (void)state;
    enum { N = 100, n = 2 * N };
    static run_out ref, loose, tight;
    run_rodas(N, 1, 1, 1e-11, &ref);
    run_rodas(N, 1, 1, 1e-5, &loose);
    run_rodas(N, 1, 1, 1e-7, &tight);
    const double e5 = max_abs_diff(loose.y, ref.y, n), e7 = max_abs_diff(tight.y, ref.y, n);
    test_note("N = %d: error at t = 10 %.3g (tol 1e-5), %.3g (tol 1e-7); %ld and %ld steps\n",
              N, e5, e7, loose.res.stats.accepted, tight.res.stats.accepted);
    assert_true(e5 < 1e-3);
    assert_true(e7 < 1e-5);
    assert_true(e7 < e5 / 10.0);
    /* the solution is the known one qualitatively: u stays positive and near its
     * boundary value by t = 10 (the sine profile has diffused and reacted away) */
    for (int i = 0; i < N; i++)
        assert_true(ref.y[2 * i] > 0.0 && ref.y[2 * i + 1] > 0.0);
    static run_out small;
    run_rodas(10, 1, 1, 1e-7, &small);
    const double per_step_small = (double)small.res.stats.rhs_calls / small.res.stats.steps;
    const double per_step_big = (double)tight.res.stats.rhs_calls / tight.res.stats.steps;
    test_note("calls of f per step: %.2f (N = 10), %.2f (N = 100)\n", per_step_small,
              per_step_big);
    assert_true(fabs(per_step_small - per_step_big) < 1.0);
}

/* Against an independent reference: SciPy's DOP853 and Radau at 1e-13 (N = 20, t = 10;
 * references.c), rodas4 with band matrices and LAPACK's or the built-in LU, and with
 * grouped differences, reaches the tolerance's accuracy. */
static void test_rodas_band_against_scipy(void **state)
{
    (void)state;
    const dyn_reference *r = dyn_reference_find("brusselator-20-10");
    assert_non_null(r);
    assert_int_equal(r->n, 40);
    static run_out analytic, differences;
    run_rodas(20, 1, 1, 1e-10, &analytic);
    run_rodas(20, 1, 0, 1e-10, &differences);
    const double ea = max_abs_diff(analytic.y, r->y, 40), ed = max_abs_diff(differences.y, r->y, 40);
    test_note("N = 20 at rtol = atol = 1e-10 against SciPy: %.2e (analytic band), %.2e "
              "(grouped differences)\n", ea, ed);
    assert_true(ea < 1e-9);
    assert_true(ed < 1e-9);
}

static void test_band_refused_when_wrong(void **state)
{
    (void)state;
    dyn_brusselator_par p;
    double y0[6], y[6];
    dyn_model *m = bruss(3, &p, y0);
    const dyn_tableau *meth = dyn_method_find("rodas4");
    dyn_solve_opts o = {0};
    o.jac_banded = 1;
    o.jac_lower = 6;
    o.jac_upper = 2;
    double work[4096];
    int iwork[6];
    o.iwork = iwork;
    const dyn_system sys = {dyn_brusselator_rhs, 6, &p};
    dyn_result res;
    assert_int_equal(dyn_solve_work_size(meth, 6, &o), 0);
    assert_int_equal(dyn_solve(meth, &sys, 0.0, 1.0, y0, y, work, &o, &res), DYN_ERR_ARG);
    assert_non_null(strstr(res.message, "band of the Jacobian (lower 6, upper 2)"));
    char err[128];
    assert_null(dyn_brusselator_new(0, err, sizeof err));
    assert_non_null(strstr(err, "N must be an integer in [1, "));
    dyn_brusselator_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_band_lu_matches_dense),
        cmocka_unit_test(test_band_lu_singular),
        cmocka_unit_test(test_difference_band_matches_analytic),
        cmocka_unit_test(test_rodas_band_equals_dense),
        cmocka_unit_test(test_rodas_band_accuracy),
        cmocka_unit_test(test_rodas_band_against_scipy),
        cmocka_unit_test(test_band_refused_when_wrong),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
