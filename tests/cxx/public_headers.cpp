// SPDX-License-Identifier: BSD-3-Clause
// Every public header compiled as C++11 (with -Wall -Wextra -pedantic -Werror under gcc and
// clang), and the header-only solvers run from C++: dyn_solve_inline (dynkit/solve_inline.h,
// the generated kernels of dynkit/erk_kernels.h) and dyn_fixed_solve_inline
// (dynkit/ode_inline.h) must give the C library's numbers bit for bit on van der Pol
// (mu = 1, y0 = (2, 0)): bs23, dp45 and dop853 at rtol = atol = 1e-9 over [0, 15], RK4 with
// 1500 steps of 0.01. Exit status 0 when every number agrees, 1 otherwise (CTest
// cxx_headers).
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "dynkit/analysis.h"
#include "dynkit/ani.h"
#include "dynkit/brusselator.h"
#include "dynkit/cart.h"
#include "dynkit/continuation.h"
#include "dynkit/delay.h"
#include "dynkit/dynkit.h"
#include "dynkit/equilibria.h"
#include "dynkit/erk_kernels.h"
#include "dynkit/io.h"
#include "dynkit/ivp.h"
#include "dynkit/jit.h"
#include "dynkit/lang.h"
#include "dynkit/lyapunov.h"
#include "dynkit/mbs.h"
#include "dynkit/mech.h"
#include "dynkit/model.h"
#include "dynkit/models.h"
#include "dynkit/ode.h"
#include "dynkit/ode_inline.h"
#include "dynkit/plane.h"
#include "dynkit/problems.h"
#include "dynkit/report.h"
#include "dynkit/report_studies.h"
#include "dynkit/run.h"
#include "dynkit/sde.h"
#include "dynkit/solve.h"
#include "dynkit/solve_inline.h"
#include "dynkit/steady.h"
#include "dynkit/sweep.h"
#include "dynkit/verify.h"
#include "dynkit/volterra.h"

// the library's van der Pol arithmetic (src/models/vanderpol.c), inlined
DYN_INLINE_RHS int vdp(double t, const double *y, double *dydt, void *par)
{
    (void)t;
    const double mu = *static_cast<const double *>(par);
    dydt[0] = y[1];
    dydt[1] = mu * (1.0 - y[0] * y[0]) * y[1] - y[0];
    return 0;
}

static int failures = 0;

static void check(bool ok, const char *what)
{
    std::printf("%s: %s\n", ok ? "ok" : "FAILED", what);
    if (!ok)
        failures++;
}

int main()
{
    double mu = 1.0;
    dyn_vanderpol_par lib_par;
    lib_par.mu = 1.0;
    const dyn_system in = {vdp, 2, &mu};
    const dyn_system lib = {dyn_vanderpol_rhs, 2, &lib_par};
    const double y0[2] = {2.0, 0.0};
    const char *pairs[] = {"bs23", "dp45", "dop853"};
    for (const char *name : pairs) {
        const dyn_tableau *m = dyn_method_find(name);
        dyn_solve_opts o;
        std::memset(&o, 0, sizeof o);
        o.rtol = o.atol = 1e-9;
        double *w =
            static_cast<double *>(std::calloc(dyn_solve_work_size(m, 2, &o), sizeof(double)));
        double ya[2], yb[2];
        dyn_result ra, rb;
        const int sa = dyn_solve_inline(m, &in, 0.0, 15.0, y0, ya, w, &o, &ra);
        const int sb = dyn_solve(m, &lib, 0.0, 15.0, y0, yb, w, &o, &rb);
        char what[96];
        std::snprintf(what, sizeof what, "dyn_solve_inline %s from C++ = dyn_solve, bit for bit",
                      name);
        check(sa == DYN_OK && sb == DYN_OK && std::memcmp(ya, yb, sizeof ya) == 0 &&
                  ra.stats.rhs_calls == rb.stats.rhs_calls && ra.stats.steps == rb.stats.steps,
              what);
        std::free(w);
    }
    const dyn_tableau *rk4 = dyn_method_find("rk4");
    double *w = static_cast<double *>(std::calloc(dyn_fixed_work_size(rk4, 2), sizeof(double)));
    double ya[2], yb[2];
    const int sa = dyn_fixed_solve_inline(rk4, &in, 0.0, 15.0, 0.01, y0, ya, w, NULL, NULL);
    const int sb = dyn_fixed_solve(rk4, &lib, 0.0, 15.0, 0.01, y0, yb, w, NULL, NULL);
    check(sa == DYN_OK && sb == DYN_OK && std::memcmp(ya, yb, sizeof ya) == 0,
          "dyn_fixed_solve_inline rk4 from C++ = dyn_fixed_solve, bit for bit");
    std::free(w);
    return failures ? 1 : 0;
}
